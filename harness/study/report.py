"""The study's charts and report (harness/study/study.py runs it, `--report-only` rewrites it)."""
import datetime
import math

from ..plots import plt
from .chaos import report as chaos_report
from . import ladder
from .errors import joint_limit
from .methods import HORIZON_LABEL, KIND_CODES, METHODS, THRESHOLD_RMS, VERDICT_KEYS, is_rigid, setting_label

MARKERS = dict(zip([m["id"] for m in METHODS], "osD^v<>XpPh*"))
COLORS = dict(zip([m["id"] for m in METHODS], plt.rcParams["axes.prop_cycle"].by_key()["color"] + ["k", "0.5"]))
assert len(MARKERS) == len(COLORS) == len(METHODS), "a marker and a colour for every method"
RIGID = {m["id"] for m in METHODS if is_rigid(m)}
SPAN_LABEL = "span model against the link model (closed loop, FMU)"

# the panels of a scene's work-precision chart: cycle statistics, then the short horizon
PANELS = [("tensioner.F.mean", "tensioner force: mean"), ("tensioner.F.peakToPeak", "tensioner force: peak-to-peak"),
          ("chain.Ftight.mean", "tight span force: mean"), ("tensionGuide.phi.peakToPeak_deg",
                                                            "tension-guide angle: peak-to-peak"),
          ("tensioner.F.order2", "tensioner force: order 2"), ("tensioner.F.order8", "tensioner force: order 8"),
          ("tensioner.F.order{mesh}", "tensioner force: meshing order {mesh}"),
          ("tensionGuide.phi.order2_deg", "tension-guide angle: order 2"),
          ("short_F_rms_pct", f"tensioner force: RMS error over the first {HORIZON_LABEL} [%]")]


def mesh_of(scene):
    return next(int(k.split("order")[1]) for k in scene["reference"]["statistics"] if k.startswith("tensioner.F.order")
                and int(k.split("order")[1]) not in (2, 4, 6, 8))


def reference_band(ref, key):
    """The reference's 95 % interval as an error band (% or dB) around 0."""
    r = ref[key]
    if ".order" in key:  # down to -20 dB at most (an interval reaching zero amplitude)
        lo = 20.0 * math.log10(max(r["mean"] - r["ci95"], 0.1 * r["mean"]) / r["mean"])
        return lo, 20.0 * math.log10((r["mean"] + r["ci95"]) / r["mean"])
    half = 100.0 * r["ci95"] / abs(r["mean"])
    return -half, half


def compliant_range(scene, key, lo, hi, extra=()):
    """The error axis spans the reference band, the compliant methods' intervals and the extra
    points (the span model): the few cycles of the rigid-contact runs give intervals of hundreds
    of percent, which would squash the comparison this chart is for; rigid points beyond it are
    clipped (their figures are in the tables)."""
    ends = [lo, hi] + [v for p in extra for v in (p["errorLow"], p["errorHigh"])]
    for p in scene["points"]:
        if p["kind"] == "ok" and p["method"] not in RIGID:
            ends += [p["errors"][key]["errorLow"], p["errors"][key]["errorHigh"]]
    a, b = min(ends), max(ends)
    pad = 0.15 * (b - a) if b > a else 1.0
    return a - pad, b + pad


def statistic_panel(ax, scene, key, failures, span=None):
    """One statistic's errors over cost; span: the span model's point (ladder.span_point), drawn
    on the tensioner-force mean's panel."""
    ref = scene["reference"]["statistics"]
    lo, hi = reference_band(ref, key)
    ax.axhspan(lo, hi, color="0.85", lw=0, label="reference 95 % interval")
    ax.axhline(0.0, color="0.5", lw=0.8)
    for m in METHODS:
        ok = [p for p in scene["points"] if p["method"] == m["id"] and p["kind"] == "ok"]
        if not ok:
            continue
        x = [p["cpu_per_s"] for p in ok]
        e = [p["errors"][key] for p in ok]
        y = [v["error"] for v in e]
        yerr = [[v["error"] - v["errorLow"] for v in e], [v["errorHigh"] - v["error"] for v in e]]
        ax.errorbar(x, y, yerr=yerr, marker=MARKERS[m["id"]], color=COLORS[m["id"]], lw=0.8, ms=4, capsize=2,
                    label=m["label"])
    extra = [span] if span is not None and key == "tensioner.F.mean" else []
    for p in extra:
        ax.errorbar([p["cpu_per_s"]], [p["error"]], yerr=[[p["error"] - p["errorLow"]], [p["errorHigh"] - p["error"]]],
                    marker="*", color="k", ms=9, capsize=3, ls="", label=SPAN_LABEL)
    ax.set_ylim(*compliant_range(scene, key, lo, hi, extra))
    mark_failures(ax, failures, labelled=True)
    ax.set_ylabel("error [dB]" if ".order" in key else "error [%]", fontsize=8)


def short_panel(ax, scene, failures):
    for m in METHODS:
        ok = [p for p in scene["points"] if p["method"] == m["id"] and p["kind"] == "ok"]
        if ok:
            ax.plot([p["cpu_per_s"] for p in ok], [max(p["errors"]["short_F_rms_pct"], 1e-16) for p in ok],
                    marker=MARKERS[m["id"]], color=COLORS[m["id"]], lw=1, ms=4)
    c = max(scene["reference"]["short"]["change"]["short_F_rms_pct"], 1e-16)
    ax.axhline(c, ls="--", color="0.4", lw=1)
    ax.text(0.01, c, " reference change", transform=ax.get_yaxis_transform(), fontsize=7, va="bottom", color="0.3")
    ax.axhline(THRESHOLD_RMS, ls=":", color="r", lw=1)
    ax.set_yscale("log")
    mark_failures(ax, failures, labelled=False)


def mark_failures(ax, failures, labelled):
    """A failed run as a cross at its cost on the top edge (with the failure's code if labelled)."""
    top = ax.get_ylim()[1]
    for x, mid, kind in failures:
        ax.plot([x], [top], marker="x", color=COLORS[mid], ms=7, mew=2, clip_on=False)
        if labelled:
            ax.annotate(KIND_CODES.get(kind, kind), (x, top), fontsize=6, xytext=(3, 3), textcoords="offset points",
                        color=COLORS[mid])


def chart_scene(path, scene, span=None):
    """The work-precision chart of a scene; span: the span model's point (ladder.span_point) or None."""
    mesh = mesh_of(scene)
    fig, axes = plt.subplots(3, 3, figsize=(16, 13))
    F = scene["reference"]["statistics"]["tensioner.F.mean"]
    fig.suptitle(f"Work-precision on cycle statistics, default drive at {scene['rpm']:g} rpm with the torque tables\n"
                 f"error of each method's mean over {scene['plan']['cycles']} engine cycles ({scene['plan']['rigid']} "
                 f"for rigid contacts; bars: its 95 % interval) against the reference ensemble ({F['cycles']} cycles; "
                 f"grey band: its 95 % interval)\nerror axes span the compliant methods; rigid-contact points "
                 f"beyond them are clipped", fontsize=10)
    failures = [(p["cpu_per_s"], p["method"], p["kind"]) for p in scene["points"] if p["kind"] != "ok"]
    for ax, (key, label) in zip(axes.flat, PANELS):
        key, label = key.format(mesh=mesh), label.format(mesh=mesh)
        if key == "short_F_rms_pct":
            short_panel(ax, scene, failures)
        else:
            statistic_panel(ax, scene, key, failures, span)
        ax.set_xscale("log")
        ax.set_title(label, fontsize=9)
        ax.set_xlabel("CPU s per simulated s", fontsize=8)
        ax.grid(True, which="both", alpha=0.25)
        ax.tick_params(labelsize=7)
    handles, labels = axes.flat[0].get_legend_handles_labels()  # the first panel is the tensioner-force mean
    fail_handle = plt.Line2D([], [], marker="x", ls="", color="k", mew=2, label="failure (x at its cost; code)")
    fig.legend(handles + [fail_handle], labels + [fail_handle.get_label()], loc="lower center", ncol=5, fontsize=8)
    fig.tight_layout(rect=(0, 0.05, 1, 0.96))
    fig.savefig(path, dpi=80)
    plt.close(fig)


def stability_grid(stab, axis):
    """The runs along one axis of the stability map, the methods with runs on it and its values."""
    rs = [r for r in stab["runs"] if r["axis"] == axis]
    methods = [m for m in METHODS if any(r["method"] == m["id"] for r in rs)]
    if axis in ("step [us]", "rtol"):
        methods = [m for m in methods if (m["option"] == "step") == (axis == "step [us]")]
    xs = sorted({r["x"] for r in rs if any(r["method"] == m["id"] for m in methods)})
    return rs, methods, xs


def stability_cell(r):
    """Colour and text of a run in the stability chart."""
    if r["kind"] == "ok":
        return "#9be39b", f"{r['cpu_per_s']:.3g}"
    if r["kind"] == "timeout":
        return "#f2d16b", "TIME"
    return "#f08080", f"{KIND_CODES.get(r['kind'], r['kind'])} {1e3 * (r['failureTime'] or 0):.2g}ms"


def chart_stability(path, stab, axis):
    rs, methods, xs = stability_grid(stab, axis)
    if not methods or not xs:
        return False
    fig, ax = plt.subplots(figsize=(1.3 * len(xs) + 3.5, 0.55 * len(methods) + 1.4))
    for i, m in enumerate(methods):
        for j, x in enumerate(xs):
            r = next((r for r in rs if r["method"] == m["id"] and r["x"] == x), None)
            if r is None:
                continue
            color, text = stability_cell(r)
            ax.add_patch(plt.Rectangle((j, i), 1, 1, color=color, ec="white"))
            ax.text(j + 0.5, i + 0.5, text, ha="center", va="center", fontsize=7)
    ax.set_xlim(0, len(xs))
    ax.set_ylim(0, len(methods))
    ax.invert_yaxis()
    ax.set_xticks([j + 0.5 for j in range(len(xs))])
    ax.set_xticklabels([f"{x * 1e6:g}" if axis == "step [us]" else f"{x:g}" for x in xs], fontsize=8)
    ax.set_yticks([i + 0.5 for i in range(len(methods))])
    ax.set_yticklabels([m["label"] for m in methods], fontsize=8)
    ax.set_xlabel(axis, fontsize=9)
    ax.set_title(f"stability over {axis.split(' [')[0]}: green = ok (CPU s per simulated s), red = failure "
                 f"detected (code, time), yellow = over the time budget", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return True


# ---------------------------------------------------------------------------------------------
# text

def cheapest(points, accept):
    ok = sorted([p for p in points if p["kind"] == "ok" and accept(p)], key=lambda p: p["cpu_per_s"])
    return ok[0] if ok else None


def describe(p):
    return f"{p['label']} at {setting_label(p, p['value'])}, {p['cpu_per_s']:.3g} CPU s per simulated s"


def rigid_error_text(e, name):
    """An error with its 95 % interval and cycle count: the costly rigid-contact runs cover few
    cycles, and an interval over 2 cycles (Student's t with 1 degree of freedom, 12.7) is too wide
    to tell even a large error from the reference's scatter."""
    return (f"{name} {e['error']:+.1f} {e['errorUnit']}, interval {e['errorLow']:+.3g} to {e['errorHigh']:+.3g} "
            f"{e['errorUnit']} over {e['cycles']} cycles")


def verdicts(scene):
    return compliant_verdicts(scene) + rigid_verdicts(scene["points"])


def compliant_verdicts(scene):
    """The cheapest compliant method of the sweep that is as accurate as the physics allows, that
    is consistent in a few headline statistics, and that keeps the trajectory within 1 %."""
    pts = scene["points"]
    compliant = [p for p in pts if p["kind"] == "ok" and p["method"] not in RIGID]
    ref = scene["reference"]["statistics"]
    lines = []
    p = cheapest(compliant, lambda p: p["consistent"])
    lines.append("- As accurate as the physics allows (all of " + ", ".join(VERDICT_KEYS) + " within the "
                 "reference's interval, jointly at 95 %): " + (f"cheapest is {describe(p)}." if p else
                                                               "no compliant method of the sweep."))
    for key in ("tensioner.F.mean", "tensioner.F.order2", "tensioner.F.order8"):
        p = cheapest(compliant, lambda p, key=key: abs(p["errors"][key]["z"]) <= 1.0)
        r = ref[key]
        lines.append(f"- {key} (reference {r['mean']:.4g} +- {r['ci95']:.2g} {r['unit']}, cycle scatter "
                     f"{r['sd']:.2g}): " + (f"cheapest consistent is {describe(p)}." if p else "no method consistent."))
    p = cheapest(compliant, lambda p: p["errors"]["short_F_rms_pct"] <= THRESHOLD_RMS)
    lines.append(f"- Trajectory fidelity (tensioner force within 1 % RMS over the first {HORIZON_LABEL}): "
                 + (f"cheapest is {describe(p)}." if p else "no method of the sweep reaches it."))
    return lines


def rigid_verdicts(pts):
    """The rigid-contact points: statistics outside the reference's interval, and the failures."""
    lines = []
    rigid = [p for p in pts if p["method"] in RIGID]
    rigid_ok = [p for p in rigid if p["kind"] == "ok"]
    fails = sorted({p["kind"] for p in rigid if p["kind"] != "ok"})
    for p in rigid_ok:
        zs = {k: p["errors"][k]["z"] for k in VERDICT_KEYS}
        wrong = [k for k, z in zs.items() if abs(z) > joint_limit(len(VERDICT_KEYS))]
        unknown = all(not math.isfinite(z) for z in zs.values())
        lines.append(f"- Rigid contacts, {describe(p)}: a different contact model; statistics outside the reference's "
                     f"interval: {'unknown (one cycle, no interval)' if unknown else ', '.join(wrong) or 'none'} "
                     f"({rigid_error_text(p['errors']['tensioner.F.mean'], 'tensioner-force mean')}, "
                     f"{rigid_error_text(p['errors']['tensioner.F.order2'], 'order 2')}).")
    if fails:
        lines.append(f"- Rigid-contact failures: {', '.join(fails)}.")
    return lines


def reference_section(sc):
    ref = sc["reference"]
    st, chk, short = ref["statistics"], ref["check"], ref["short"]
    F = st["tensioner.F.mean"]
    L = [f"Run-in {sc['plan']['run_in']} engine cycles to t0 = {sc['t0'] * 1e3:.1f} ms; every run then settles "
         f"1 cycle and is measured over {sc['plan']['cycles']} cycles ({sc['plan']['rigid']} for rigid contacts). "
         f"Reference ensemble: arkode-erk at rtol {ref['rtol']:g} ({ref['cpu_per_s']:.0f} CPU s/s) over "
         f"{F['cycles']} cycles. Check: fixed-verlet at {chk['step'] * 1e6:g} us over the same cycles "
         f"({chk['cpu_per_s']:.0f} CPU s/s): "
         + ("consistent with the reference in every headline statistic (jointly at 95 %)." if chk["consistent"] else
            "NOT consistent with the reference: see the table."),
         "", "| statistic | reference mean | 95 % half-width | cycle scatter (sd) | check: error | check: z |",
         "|---|---|---|---|---|---|"]
    for key, r in st.items():
        c = chk["errors"][key]
        L.append(f"| {key} | {r['mean']:.4g} {r['unit']} | {r['ci95']:.2g} | {r['sd']:.2g} | {c['error']:+.2f} "
                 f"{c['errorUnit']} | {c['z']:+.2f} |")
    L += ["", f"Short horizon: arkode-erk at rtol {short['rtol']:g}; tightened to {short['check_rtol']:g} it changes "
              f"by {short['change']['short_F_rms_pct']:.2g} % RMS in tensioner force and "
              f"{short['change']['short_phi_rms_rad']:.2g} rad in tension-guide angle over the first {HORIZON_LABEL}.",
          ""]
    return L


def points_table(sc):
    mesh = mesh_of(sc)
    keys = ["tensioner.F.mean", "tensioner.F.peakToPeak", "chain.Ftight.mean", "tensionGuide.phi.peakToPeak_deg",
            "tensioner.F.order2", "tensioner.F.order4", "tensioner.F.order6", "tensioner.F.order8",
            f"tensioner.F.order{mesh}"]
    L = ["Errors against the reference: % or dB (z = error over the combined 95 % interval; |z| <= 1: "
         "consistent). Consistent = every statistic of the verdict consistent jointly at 95 %.", "",
         "| method | setting | CPU s/s | cycles | " + " | ".join(keys) + f" | consistent | {HORIZON_LABEL}: F RMS % | "
         "counters |",
         "|---|---|---|---|" + "---|" * len(keys) + "---|---|---|"]
    for p in sc["points"]:
        if p["kind"] != "ok":
            L.append(f"| {p['label']} | {setting_label(p, p['value'])} | fails | {KIND_CODES.get(p['kind'], '')} "
                     f"{p['kind']} at t = {(p['failureTime'] or 0) * 1e3:.3f} ms: {p['failure']} |" + "|" * (len(keys) + 3))
            continue
        e = p["errors"]
        cells = [f"{e[k]['error']:+.2f} ({e[k]['z']:+.1f})" for k in keys]
        cnt = f"{p.get('steps', 0)} steps"
        if "lcpSolves" in p:
            cnt += f", {p['lcpSolves']} LCPs (mean size {p['lcpSizeMean']:.0f}), {p.get('regularizedLcps', 0)} regularized"
        if not p["repeatsIdentical"]:
            cnt += ", REPEATS DIFFER"
        L.append(f"| {p['label']} | {setting_label(p, p['value'])} | {p['cpu_per_s']:.3g} | "
                 f"{e['tensioner.F.mean']['cycles']} | " + " | ".join(cells)
                 + f" | {'yes' if p['consistent'] else 'no'} | {e['short_F_rms_pct']:.3g} | {cnt} |")
    return L + [""]


def stability_section(out, stab):
    L = ["## Stability map", "",
         f"Each run: {stab['duration'] * 1e3:g} ms from the pre-loaded state with the torque tables; the failure kind "
         "is what the solver detected and reported (codes: " + ", ".join(f"{v} {k}" for k, v in KIND_CODES.items())
         + ").", ""]
    for axis in ("speed [rpm]", "step [us]", "rtol", "joint stiffness factor", "contact stiffness factor"):
        name = "stability_" + axis.split(" [")[0].replace(" ", "_") + ".png"
        if chart_stability(out / name, stab, axis):
            L += [f"![stability over {axis}]({name})", ""]
    L += ["| method | axis | value | setting | outcome |", "|---|---|---|---|---|"]
    for r in stab["runs"]:
        oc = (f"ok, {r['cpu_per_s']:.3g} CPU s/s" if r["kind"] == "ok" else
              f"**{r['kind']}** at t = {(r['failureTime'] or 0) * 1e3:.3f} ms: {r['failure']}")
        x = r["x"] * 1e6 if r["axis"] == "step [us]" else r["x"]
        L.append(f"| {r['label']} | {r['axis']} | {x:g} | {r['setting']} | {oc} |")
    return L + [""]


def realtime_section(rt):
    L = ["## Real time: CPU time per fmi2DoStep (ChainDrive.fmu through fmpy FMU2Slave, 3000 rpm)", "",
         "| method | communication step | steps | median ms | p99 ms | max ms | median / step | wall max ms | "
         "deadline misses |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rt:
        if "median" in r:
            L.append(f"| {r['label']} | {r['step'] * 1e3:g} ms | {r['steps']} | {r['median'] * 1e3:.3f} | "
                     f"{r['p99'] * 1e3:.3f} | {r['max'] * 1e3:.3f} | {r['ratio']:.2f} | {r['wall_max'] * 1e3:.3f} | "
                     f"{r['misses']} |" + (f" failed after: {r['failure']}" if r["failure"] else ""))
        else:
            L.append(f"| {r['label']} | {r['step'] * 1e3:g} ms | 0 | fails: {r['failure']} ||||||")
    timed = [r for r in rt if "median" in r]
    if timed:
        f = min(timed, key=lambda r: r["ratio"])
        L += ["", f"Verdict: the cheapest fixed-step method is {f['label']} ({f['median'] * 1e3:.3g} ms CPU per "
                  f"{f['step'] * 1e3:g} ms step, {f['ratio']:.2f} times the step): "
                  + ("real time on this machine." if f["ratio"] < 1.0 else
                     "not real time on this machine; hardware-in-the-loop use needs a faster machine or a cheaper "
                     "model.")]
    return L + [""]


def chaos_section(chaos_results):
    """The divergence rates and the damping verdict of the twin study (harness/study/chaos): why the
    errors above are judged against the reference's scatter."""
    L = ["## The chaos floor: divergence rates and damping", ""]
    if not chaos_results:
        return L + ["No results of `python -m harness chaos` were found: run it (see chaos.md).", ""]
    L += [f"From [chaos.md](chaos.md) (`{chaos_results['command']}`, {chaos_results['rpm']:g} rpm): twin runs that "
          "differ by 1e-12 in one initial value, per damping setting; median and [range] over the pairs.", ""]
    return (L + chaos_report.results_table(chaos_results) + ["", "Verdict:", ""]
            + chaos_report.verdict_lines(chaos_results) + [""])


def write(out, r, chaos_results=None):
    """Charts and report.md in out from the study's results (the content of results.json) and, if
    given, the results of the divergence-rate study (docs/study/chaos/results.json)."""
    started = datetime.datetime.fromisoformat(r["started"])
    L = ["# Speed against accuracy: work-precision on cycle statistics and stability of every method", "",
         f"Generated by `{r['command']}` on {started:%Y-%m-%d %H:%M} in {r['wall_seconds'] / 60:.1f} min wall time "
         f"(runs in parallel: {r['settings']['jobs']}).", f"Machine: {r['machine']}.", ""]
    if r["quick"]:
        L += ["**Quick variant**: 6000 rpm, 2 measured cycles, reference rtol 1e-6; a smoke test of the study, "
              "not its result.", ""]
    L += ["Method and measures: see the docstring of `harness/study/study.py`. Every run starts from the same state "
          f"after the run-in; CPU time is the median of up to {r['settings']['repeats']} runs (runs above "
          f"{r['settings']['repeat_below']:g} s CPU are not repeated); repeated runs are bit-identical unless marked. "
          "Why statistics and not trajectories: [chaos.md](chaos.md) and the last section.", ""]
    ladder_comparisons = r.get("fidelity", [])
    for sc in r["scenes"]:
        comparison = next((c for c in ladder_comparisons if c["rpm"] == sc["rpm"]), None)
        chart_scene(out / f"wp_{sc['rpm']:g}rpm.png", sc, comparison and ladder.span_point(comparison))
        L += [f"## {sc['rpm']:g} rpm", ""] + reference_section(sc)
        L += [f"![work-precision {sc['rpm']:g} rpm](wp_{sc['rpm']:g}rpm.png)", ""] + points_table(sc)
        L += ["Verdict:", ""] + verdicts(sc) + [""]
    if ladder_comparisons:
        L += ladder.report_lines(ladder_comparisons)
    L += stability_section(out, r["stability"]) + realtime_section(r["realtime"]) + chaos_section(chaos_results)
    # the chain CVT's section, from its own run (python -m harness study --scene cvt --out the same folder)
    if (out / "cvt.md").exists():
        L += (out / "cvt.md").read_text().splitlines() + [""]
    L += ["## Log", "", "```"] + r["log"] + ["```"]
    (out / "report.md").write_text("\n".join(L) + "\n")
