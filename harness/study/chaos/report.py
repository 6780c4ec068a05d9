"""The report of the divergence-rate study (markdown): results, integrators and steps, per-cycle
twin statistics, the verdict, the damping values against the literature."""
import math
import pathlib

from ... import runs
from .analysis import CYCLE_KEYS, fmt, fmt_spread, measured
from .damping import damping_section
from .steps import PROBE_PAIRS


def by_id(results, key):
    return next((r for r in results["settings"] if r["id"] == key and r["status"] != "failed"), None)


def rate(r, name="tensioner.F"):
    return r["signals"][name]["rate_per_ms"]["median"] if r else None


def results_table(results):
    lines = ["| setting | integrator | lambda tensioner force [1/ms] | e-folding [ms] | lambda guide angle [1/ms] | "
             "e-folding [ms] | force saturated after [ms] (cycles) | angle saturated after [ms] (cycles) | cycle "
             "statistics independent from cycle |", "|---|---|---|---|---|---|---|---|---|"]
    for r in results["settings"]:
        if r["status"] == "failed":
            tried = "; ".join(f"{t['step'] * 1e6:g} us: {t['kind']}" for t in r["runIn"])
            lines.append(f"| {r['label']} | FAILED: {r.get('failure')} ({tried}) | - | - | - | - | - | - | - |")
            continue
        F, P = r["signals"]["tensioner.F"], r["signals"]["tensionGuide.phi"]
        j = r["cycles"]["firstIndependent"]
        lines.append(
            f"| {r['label']} | {r['method']['label']} | {fmt_spread(F['rate_per_ms'])} | {fmt(F['efold_ms'])} | "
            f"{fmt_spread(P['rate_per_ms'])} | {fmt(P['efold_ms'])} | {saturation_cell(F)} | {saturation_cell(P)} | "
            f"{independence_cell(r)} |")
    return lines


def independence_cell(r):
    j = r["cycles"]["firstIndependent"]
    if j is not None:
        return str(j)
    return f"not within the {r['twinCycles']} cycles run" + (" (lambda check only)" if r["id"] == "erk" else "")


def saturation_cell(sig):
    s = sig["saturation_ms"]
    if s["median"] is None:
        return "not within the run"
    missing = len(sig["pairs"]) - s["n"]
    return (f"{fmt(s['median'])} [{fmt(s['min'])}, {fmt(s['max'])}] ({fmt(sig['saturation_cycles']['median'], 2)})"
            + (f", {missing} pairs not within the run" if missing else ""))


def steps_table(results):
    lines = ["| setting | Verlet steps tried for the run-in | step check: median lambda of the tensioner force "
             f"[1/ms] over {PROBE_PAIRS} pairs (p: Welch's t-test against the step before) | twins | twin length [cycles] | CPU s per simulated s | pairs (failed) |",
             "|---|---|---|---|---|---|---|"]
    for r in results["settings"]:
        tried = ", ".join(f"{t['step'] * 1e6:g} us {'ok' if t['kind'] == 'ok' else t['kind']}" for t in r["runIn"])
        n_fail = len(r.get("pairFailures", []))
        twins = r["method"]["label"] if "method" in r else "-"
        pairs = "-" if "cycles" not in r else f"{r['cycles']['pairs'] + n_fail} ({n_fail})"
        lines.append(f"| {r['label']} | {tried or 'start states of the default setting'} | {step_check_cell(r)} | "
                     f"{twins} | {r.get('twinCycles', '-')} | {fmt(r.get('cpuPerSimulatedSecond'))} | {pairs} |")
        for f in r.get("pairFailures", []):
            lines.append(f"| | pair {f['start']} ({f['perturbation']}): {f['kind']} at {fmt(f['failureTime'], 6)} s: "
                         f"{f['failure']} | | | | | |")
    return lines


def step_check_cell(r):
    checks = r.get("stepChecks") or []
    if not checks:
        return "-"
    cell = ", ".join(f"{c['step'] * 1e6:g} us: {fmt(c['rate_per_ms'])}"
                     + (f" (p {c['pValue']:.2g})" if c.get("pValue") is not None else "") for c in checks)
    verdict = {True: "converged", False: "NOT converged down to the smallest step", None: ""}[r.get("stepConverged")]
    return f"{cell} ({verdict})"


def cycles_table(results):
    keys = CYCLE_KEYS
    lines = ["| setting | statistic | r_j for cycles 0, 1, 2, ... | bound | rank correlation A-B over the pairs | "
             "s.d. between cycles | lag-1 autocorr. (cycles) | independent from cycle |",
             "|---|---|---|---|---|---|---|---|"]
    for r in measured(results):
        for key in keys:
            c = r["cycles"]["keys"][key]
            corr = ", ".join(fmt(x, 2) for x in c["correlation"])
            lines.append(f"| {r['label']} | {key} | {', '.join(f'{x:.2f}' for x in c['ratio'])} | {c['bound']:.2f} | "
                         f"{corr} | {c['betweenCycles']:.3g} | {c['lag1']:.2f} ({c['distinctCycles']}) | "
                         f"{first_cell(c)} |")
    return lines


def first_cell(c):
    if c["firstIndependent"] is None:
        return "not within the run"
    return f"{c['firstIndependent']} ({c['laterBelowBound']} later cycles below the bound)"


def ratio_to_default(results, key):
    d, r = by_id(results, "default"), by_id(results, key)
    return rate(r) / rate(d) if r and d and rate(r) and rate(d) else None


def verdict_lines(results):
    """The verdict, argued from the measured rates; settings missing or failed are said so."""
    d = by_id(results, "default")
    if not d or rate(d) is None:
        return ["The default setting has no measured divergence rate: no verdict."]
    lam = rate(d)
    F = d["signals"]["tensioner.F"]
    out = [f"- Default damping: the tensioner force of twin runs diverges at lambda = {lam:.2g} 1/ms, a factor e "
           f"every {1 / lam:.2g} ms (pairs: {fmt_spread(F['rate_per_ms'], 2)} 1/ms); 1e-12 grows to the level of "
           f"unrelated runs in {fmt(F['saturation_ms']['median'], 2)} ms, and a difference of one rounding (1e-16) "
           f"would take about {math.log(1e4) / lam:.0f} ms more."]
    erk = by_id(results, "erk")
    if erk and rate(erk):
        out.append(f"- The rate is the model's, not the integrator's: adaptive arkode-erk (rtol 1e-8) from the same "
                   f"start states gives {fmt_spread(erk['signals']['tensioner.F']['rate_per_ms'], 2)} 1/ms; the step "
                   "checks of every setting (table above) agree too.")
    for key, name in (("both4", "4x"), ("both10", "10x")):
        r = by_id(results, key)
        if r is None:
            out.append(f"- Joint and contact damping {name}: not measured (failed or not run).")
        elif rate(r) is None:
            out.append(f"- Joint and contact damping {name}: no exponential divergence found within "
                       f"{r['twinCycles']} engine cycles.")
        else:
            rf = r["signals"]["tensioner.F"]
            out.append(f"- Joint and contact damping {name}: lambda = {rate(r):.2g} 1/ms ({rate(r) / lam:.2f} of the "
                       f"default, e-folding {1 / rate(r):.2g} ms); the twins still reach the level of unrelated runs "
                       f"after {fmt(rf['saturation_ms']['median'], 2)} ms ({fmt(rf['saturation_cycles']['median'], 2)} "
                       f"engine cycles), and their cycle statistics are independent from cycle "
                       f"{fmt(r['cycles']['firstIndependent'])} on.")
    parts = [f"{by_id(results, k)['label']}: {ratio_to_default(results, k):.2f}" for k in
             ("joint4", "joint10", "contact4", "contact10") if ratio_to_default(results, k)]
    if parts:
        out.append("- Each damping alone, lambda relative to the default: " + "; ".join(parts) + ".")
    return out + verdict_conclusion(results)


def verdict_conclusion(results):
    """The judgement: which damping sets the rate, and whether any removes the divergence."""
    joint = [ratio_to_default(results, k) for k in ("joint4", "joint10")]
    out = [""]
    if all(joint) and all(0.7 <= x <= 1.4 for x in joint):
        out.append("Joint damping does not set the rate: ten times the default joint damping, which overdamps every "
                   "link mode, leaves lambda within the spread of the default.")
    return out + contact_conclusion(results) + tenfold_conclusion(results)


def contact_conclusion(results):
    """Whether contact damping sets the rate (it falls below half the default's)."""
    contact = [ratio_to_default(results, k) for k in ("contact4", "contact10", "both4", "both10")]
    if not (any(contact) and min(x for x in contact if x) < 0.5):
        return []
    r4, r10 = ratio_to_default(results, "both4"), ratio_to_default(results, "both10")
    trend = ("it falls little more from 4x to 10x" if r4 and r10 and r10 / r4 > 0.5 else
             "it keeps falling from 4x to 10x")
    return ["Contact damping does: it makes the roller and plate impacts less elastic, and lambda falls with "
            f"it; {trend}."]


def tenfold_conclusion(results):
    """Whether joint and contact damping raised tenfold remove the divergence."""
    b10 = by_id(results, "both10")
    out = []
    if b10 and rate(b10):
        out.append("No damping tried removes the divergence: with both raised tenfold, far beyond what the "
                   "literature supports for oil-wetted steel impacts (below), twin runs still separate "
                   "exponentially and their cycle statistics decorrelate within a few engine cycles. The chaos is "
                   "a property of the physics, the unilateral contacts with their impacts (rollers seating in "
                   "tooth gaps at the polygon frequency, link plates meeting the guides), not of too little "
                   "damping; damping sets its rate. Realistic damping, the defaults or less for the impacts, keeps "
                   "the rate at about the default's: pointwise agreement of two runs is lost within about one "
                   "engine cycle, and what a run predicts is its statistics over cycles.")
    elif b10:
        out.append("With both raised tenfold no divergence is measurable: at that damping the chaos is removed.")
    return out


def write_report(results, report_path, chart_dir):
    rel = pathlib.Path(chart_dir).resolve().relative_to(pathlib.Path(report_path).resolve().parent) \
        if pathlib.Path(chart_dir).resolve().is_relative_to(pathlib.Path(report_path).resolve().parent) \
        else pathlib.Path(chart_dir).resolve()
    L = [f"# Divergence rate and the chaos floor, measured ({results['rpm']:g} rpm)", "",
         f"`{results['command']}` on {results['machine']}; {results['started']}, "
         f"{results['wall_seconds'] / 60:.1f} min wall time{' (quick smoke variant)' if results['quick'] else ''}.",
         "Method, criteria and options: the docstring of `harness/study/chaos/chaos.py`. Results: "
         f"[`results.json`]({rel / 'results.json'}).", ""]
    L += ["## Results", ""] + results_table(results) + [""]
    L += [f"![twin difference]({rel / 'divergence.png'})", "", f"![divergence rate]({rel / 'lambda.png'})", ""]
    L += ["Integrators, steps and failures:", ""] + steps_table(results) + [""]
    L += ["### Per-cycle statistics of the twins", "",
          "r_j = median over the pairs of |x_B - x_A| in engine cycle j after the perturbation, divided by the median "
          "|x - x'| over all pairs of distinct engine cycles of the twin A runs (unrelated cycles): about 1 for "
          "independent twins, below the bound (the 2.5 % quantile of the same ratio for as many random pairs of "
          "unrelated cycles, 4000 draws) by chance in 2.5 % of the cycles. Medians, because the per-cycle values "
          "have heavy tails. Correlation: Spearman's rank correlation of x_A and x_B over the pairs.", ""]
    L += cycles_table(results) + [""]
    L += [f"![per-cycle statistics]({rel / 'cycles.png'})", ""]
    L += ["## Verdict: physics, not too little damping", ""] + verdict_lines(results) + [""]
    L += damping_section(results["damping"])
    runs.write_lines(report_path, L)
