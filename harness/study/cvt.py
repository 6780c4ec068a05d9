"""The chain CVT on the work-precision chart (`python -m harness study --scene cvt`): the compliant
methods a CVT runs with, each over a sweep of its step or tolerance, on the default CVT at 2000 rpm
driving and 100 N m output torque (about 60 % of its torque capacity), stationary.

Accuracy as for the timing drive (harness/study/study.py): per chain revolution the headline
quantities (harness/cvt/job.py: slip, driven speed, strand forces, clamping forces, power loss) over
the counted revolutions after the main job's run-in (the pins' radial settling), each a mean with its 95 % confidence half-width; against a
reference (fixed-verlet at 0.25 us over REFERENCE_FACTOR times the revolutions; its convergence
checked by arkode-erk at rtol 1e-8 over the same revolutions) the difference in % and
z = difference / sqrt(ci^2 + ci_ref^2). A point is accurate when every statistic is
within its engineering tolerance (TOLERANCES: forces 2 %, slip and power loss 5 %, driven speed
0.05 %) or consistent with the reference jointly at 95 % (Bonferroni), and the checks of a
stationary state hold: (F_tight - F_slack) r2 within 2 % of the driven torque, the energy balance
within 1 % of the dissipated energy. A run that fails is a failure marker with the solver's
message (blow-up: a joint stretched beyond a quarter pitch). Cost: CPU seconds per chain revolution
(the goal: under one CPU minute; the paper's stationary case took about 8 hours).

Time stepping (Moreau-Jean, Lemke per step: the compliant pins' friction as complementarity on a
linearized friction cone of 4 or 8 facets per pin, or rigid pins closing with Newton impacts;
TS_POINTS) costs tens of CPU seconds per revolution, so its points
do not run the run-in themselves: they continue from the state a handover run (the reference's
method and step) reaches at the end of the run-in, with TS_RUN_IN revolutions of their own before
the counted ones (TS_REVOLUTIONS). Its friction is exact Coulomb, the compliant methods' a
regularized law (the sliding speed vReg of src/drives/default_cvt.json's frictionRegularization):
the FRICTION_LIMIT points run the reference's method from the same handover state with a smaller
vReg, the regularized model approaching Coulomb's law, to tell the regularization's share of the
difference from the method's.

Writes to --out: cvt.md (the report's CVT section), cvt_results.json and wp_cvt.png; the study's
report.md links them (harness/study/report.py).
"""
import json
import math
import pathlib
import shutil

from scipy import stats as scistats

from .. import cycle_stats, paths, runs
from ..cvt import job as cvt_job
from ..plots import plt

RPM = 2000.0
LOAD = 100.0                 # [N m]
REVOLUTIONS = 6              # counted chain revolutions per point
RUN_IN = cvt_job.RUN_IN_REVOLUTIONS  # chain revolutions discarded (the pins' radial settling)
QUICK_RUN_IN = 2
REFERENCE_FACTOR = 3         # the reference counts this many times the revolutions
REFERENCE = ("fixed-verlet", 2.5e-7)
CHECK = ("arkode-erk", 1e-8)
KEYS = ("slip", "drivenSpeed", "tightStrandForce", "slackStrandForce", "clampingForceDriven", "powerLoss")
# [% of the reference] what a transmission engineer reads these to: a statistic is accurate
# within its tolerance or within the scatter (|z|). The settled CVT runs periodically, not
# chaotically: its scatter over revolutions is about 0.1 %, far below what matters, so the scatter
# alone would ask every method to converge to the reference's last digits.
TOLERANCES = {"slip": 5.0, "drivenSpeed": 0.05, "tightStrandForce": 2.0, "slackStrandForce": 2.0,
              "clampingForceDriven": 2.0, "powerLoss": 5.0}
# method: the steps [s] (fixed-step) or tolerances (arkode-erk) of its sweep
SWEEPS = {"fixed-verlet": (5e-7, 1e-6, 1.5e-6, 2e-6, 3e-6, 5e-6, 1e-5),
          "fixed-verlet-implicit-joint-damping": (1e-6, 2e-6, 3e-6, 5e-6),
          "arkode-erk": (1e-4, 1e-5, 1e-6)}
QUICK_SWEEPS = {"fixed-verlet": (1e-6, 1e-5), "arkode-erk": (1e-5,)}
# time stepping from the handover state: (method, step [s], facets of the friction polygon or None)
TS_POINTS = (("time-stepping", 1e-5, 4), ("time-stepping", 5e-6, 4), ("time-stepping", 5e-6, 8),
             ("time-stepping", 2e-6, 4), ("time-stepping", 1e-6, 4), ("time-stepping-rigid-pins", 1e-5, None),
             ("time-stepping-rigid-pins", 5e-6, None), ("time-stepping-rigid-pins", 2e-6, None),
             ("time-stepping-rigid-pins", 1e-6, None))
QUICK_TS_POINTS = (("time-stepping", 5e-6, 4), ("time-stepping-rigid-pins", 5e-6, None))
TS_RUN_IN, TS_REVOLUTIONS = 1, 3
QUICK_TS_RUN_IN, QUICK_TS_REVOLUTIONS = 0, 1
# the regularized friction toward Coulomb's law: (vReg [m/s], fixed-verlet step [s]); the
# regularized friction is stiff, c = mu F / vReg, so its stable step shrinks with vReg
FRICTION_LIMIT = ((0.005, 2.5e-7), (0.002, 1e-7), (0.001, 5e-8))
TORQUE_LIMIT, ENERGY_LIMIT = 0.02, 0.01


def point_config(method, setting, revolutions, run_in, out, **extra):
    """The CVT job's configuration of one point (harness/cvt/job.py) at the study's speed and load,
    with the study's own extras (time stepping's facets, a handover state to start from or to
    write, another CVT file). setting: the step, or the tolerance of an adaptive method."""
    adaptive = method.startswith("arkode-erk") and method != "arkode-erk-fixed"
    return cvt_job.CVTConfig(rpm=RPM, load_torque=LOAD, revolutions=revolutions, run_in_revolutions=run_in,
                             method=method, solver_step=1e-4 if adaptive else setting,  # (arkode-erk: its largest)
                             rtol=setting if adaptive else 1e-5, cvt=extra.get("cvt"), out=out,
                             friction_facets=extra.get("facets"), state_in=extra.get("state_in"),
                             state_out=extra.get("state_out"))


def run_point(method, setting, revolutions, run_in, out, counted_from=None, **extra):
    """One run: {method, setting, cpuPerRevolution, statistics, checks} or {..., failure}. The
    counted revolutions start at revolution `counted_from` (default: run_in) from time 0."""
    config = point_config(method, setting, revolutions, run_in, out, **extra)
    point = {"method": method, "setting": setting}
    point.update({k: extra[k] for k in ("facets", "vReg") if k in extra})
    try:
        record, result = cvt_job.simulate(config, quiet=True)
    except RuntimeError as e:
        point["failure"] = str(e).removeprefix("chaindrive-cvt: ")
        return point
    first = run_in if counted_from is None else counted_from
    spans = cvt_job.revolution_spans(record["time"], result["run"]["chainRevolution"], first)
    point["statistics"] = cycle_stats.summarize(cvt_job.per_revolution(record, spans))
    point["checks"] = cvt_job.checks(point["statistics"], result)
    point["cpuPerRevolution"] = result["run"]["cpuPerChainRevolution"]
    if "lcpSolves" in result["run"]:
        point["lcp"] = {k: result["run"][k] for k in ("lcpSizeMean", "pivots", "lcpSolves", "impacts")}
    return point


def handover_points(out, run_in, quick, log):
    """The points that continue from the handover state: time stepping, and the regularized
    friction toward Coulomb's law."""
    state = out / "cvt_handover_state.json"
    method, step = REFERENCE[0], (1e-6 if quick else REFERENCE[1])
    log(f"CVT handover state: {method} at {step:g} over the run-in of {run_in} revolutions")
    cvt_job.simulate(point_config(method, step, 0, run_in, out, state_out=state), quiet=True)
    cvt_file = json.loads((paths.ROOT / "src" / "drives" / "default_cvt.json").read_text())
    own_run_in, counted = (QUICK_TS_RUN_IN, QUICK_TS_REVOLUTIONS) if quick else (TS_RUN_IN, TS_REVOLUTIONS)
    points = []
    for method, step, facets in QUICK_TS_POINTS if quick else TS_POINTS:
        extra = {"facets": facets} if facets else {}
        points.append(run_point(method, step, counted, own_run_in, out, counted_from=run_in + own_run_in,
                                state_in=state, **extra))
    for v_reg, step in () if quick else FRICTION_LIMIT:
        cvt_file["contact"]["frictionRegularization"] = v_reg
        path = out / f"cvt_vreg_{v_reg:g}.json"
        path.write_text(json.dumps(cvt_file))
        points.append(run_point(REFERENCE[0], step, counted, own_run_in, out, counted_from=run_in + own_run_in,
                                vReg=v_reg, cvt=str(path), state_in=state))
    return points


def compare(point, ref):
    """Per statistic: difference in % of the reference and z; and whether the point is as
    accurate as the physics allows (every |z| within the Bonferroni bound, the checks held)."""
    if "failure" in point:
        return
    bound = float(scistats.norm.ppf(1.0 - 0.025 / len(KEYS))) / 1.96  # |z| <= this, jointly at 95 %
    errors = {}
    for key in KEYS:
        s, r = point["statistics"][key], ref["statistics"][key]
        diff = s["mean"] - r["mean"]
        errors[key] = {"percent": 100.0 * diff / abs(r["mean"]), "z": diff / math.hypot(s["ci95"], r["ci95"])}
    point["errors"] = errors
    c = point["checks"]
    point["checksHold"] = abs(c["torqueBalanceError"]) <= TORQUE_LIMIT and abs(c["energyBalanceError"]) <= ENERGY_LIMIT
    point["consistent"] = point["checksHold"] and all(
        abs(e["z"]) <= bound or abs(e["percent"]) <= TOLERANCES[key] for key, e in errors.items())


def study(out, quick=False, log=print):
    """The reference, its check and every method's sweep; returns the results."""
    revolutions = 2 if quick else REVOLUTIONS
    run_in = QUICK_RUN_IN if quick else RUN_IN
    run_dir = out / "cvt_runs"
    run_dir.mkdir(parents=True, exist_ok=True)
    factor = 1 if quick else REFERENCE_FACTOR
    ref_setting = 1e-6 if quick else REFERENCE[1]
    log(f"CVT reference: {REFERENCE[0]} at {ref_setting:g} over {factor * revolutions} revolutions")
    ref = run_point(REFERENCE[0], ref_setting, factor * revolutions, run_in, run_dir)
    if "failure" in ref:
        raise RuntimeError(f"the CVT reference failed: {ref['failure']}")
    check = None if quick else run_point(CHECK[0], CHECK[1], factor * revolutions, run_in, run_dir)
    if check:
        compare(check, ref)
    points = []
    for method, settings in (QUICK_SWEEPS if quick else SWEEPS).items():
        for setting in settings:
            points.append(run_point(method, setting, revolutions, run_in, run_dir))
            compare(points[-1], ref)
            log(f"  {describe(points[-1])}")
    for p in handover_points(run_dir, run_in, quick, log):
        compare(p, ref)
        log(f"  {describe(p)}")
        points.append(p)
    return {"machine": runs.machine(), "rpm": RPM, "loadTorque": LOAD, "revolutions": revolutions, "runIn": run_in,
            "handoverRunIn": QUICK_TS_RUN_IN if quick else TS_RUN_IN,
            "handoverRevolutions": QUICK_TS_REVOLUTIONS if quick else TS_REVOLUTIONS,
            "reference": ref, "referenceCheck": check, "points": points, "quick": quick}


def label(p):
    """The point's series: its method, time stepping's facets, a regularization of its own."""
    if "facets" in p:
        return f"{p['method']} ({p['facets']} facets)"
    return f"{p['method']} (vReg {p['vReg']:g} m/s)" if "vReg" in p else p["method"]


def describe(p):
    head = f"{label(p)} {p['setting']:g}"
    if "failure" in p:
        return f"{head}: FAILED ({p['failure']})"
    worst = max(p["errors"].values(), key=lambda e: abs(e["z"]))
    return (f"{head}: {p['cpuPerRevolution']:.3g} CPU s/revolution, largest |z| {abs(worst['z']):.2f}, torque balance "
            f"{100 * p['checks']['torqueBalanceError']:+.2f} %, energy {100 * p['checks']['energyBalanceError']:+.2f} %"
            f"{', accurate' if p['consistent'] else ''}")


def chart(path, r):
    """Work-precision: |error| of each statistic (% of the reference) over CPU per revolution."""
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5), sharex=True)
    series = list(dict.fromkeys(label(p) for p in r["points"]))
    for ax, key in zip(axes.flat, KEYS):
        ref = r["reference"]["statistics"][key]
        band = 100.0 * ref["ci95"] / abs(ref["mean"])
        ax.axhline(band, color="grey", ls=":", lw=0.8, label="reference's 95 % half-width")
        for name, marker in zip(series, "os^DvP<>*hXd"):
            pts = [p for p in r["points"] if label(p) == name and "failure" not in p]
            if pts:
                ax.loglog([p["cpuPerRevolution"] for p in pts],
                          [max(abs(p["errors"][key]["percent"]), 1e-4) for p in pts], marker=marker, label=name)
                for p in pts:
                    if not p["consistent"]:
                        ax.plot(p["cpuPerRevolution"], max(abs(p["errors"][key]["percent"]), 1e-4), "x", color="red",
                                ms=9)
        ax.set_title(key, fontsize=10)
        ax.set_ylabel("|error| [% of the reference]")
    for ax in axes[1]:
        ax.set_xlabel("CPU s per chain revolution")
    axes[0, 0].legend(fontsize=7)
    failed = [f"{label(p)} at {p['setting']:g}" for p in r["points"] if "failure" in p]
    fig.suptitle(f"Chain CVT, {r['rpm']:g} rpm, {r['loadTorque']:g} N m: work-precision (red x: not accurate: "
                 "a statistic beyond its tolerance and the scatter, or a check off)" +
                 ("\nfailed (named blow-ups, see the table): " + "; ".join(failed) if failed else ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def section(r):
    """The report's CVT section (Markdown)."""
    ref = r["reference"]
    lines = [f"## The chain CVT (paper example 4.1)\n",
             f"Default CVT, {r['rpm']:g} rpm driving, {r['loadTorque']:g} N m output torque, stationary; run-in "
             f"{r['runIn']} chain revolutions, then {r['revolutions']} counted per point (the reference "
             f"{ref['method']} at {ref['setting']:g} s over {ref['statistics']['slip']['cycles']} revolutions). Machine: "
             f"{r['machine']}. Method: harness/study/cvt.py; a point is accurate when every statistic is within "
             "its tolerance (" + ", ".join(f"{k} {v:g} %" for k, v in TOLERANCES.items()) + ") or within the "
             "reference's scatter, and the torque and energy balances hold (2 %, 1 %).\n",
             "| quantity | reference, mean +- 95 % |", "|---|---|"]
    for key in KEYS:
        s = ref["statistics"][key]
        lines.append(f"| {key} | {s['mean']:.6g} +- {s['ci95']:.3g} {s['unit']} |")
    c = ref["checks"]
    lines.append(f"\nChecks of the reference: speed ratio {1 + c['speedRatioError']:.5f} x the geometric; "
                 f"(F_tight - F_slack) r2 off the driven torque by {100 * c['torqueBalanceError']:+.2f} % (limit 2 %); "
                 f"energy balance {100 * c['energyBalanceError']:+.3f} % of the dissipated energy (limit 1 %).")
    if r.get("referenceCheck"):
        k = r["referenceCheck"]
        lines.append(f"Its convergence check, {k['method']} at {k['setting']:g}: " + (
            f"FAILED ({k['failure']})" if "failure" in k else
            f"largest |z| {max(abs(e['z']) for e in k['errors'].values()):.2f} over the statistics "
            f"({'accurate' if k['consistent'] else 'NOT accurate'})."))
    lines += ["\n![CVT work-precision](wp_cvt.png)\n",
              "| method | step or rtol | CPU s per chain revolution | slip error | F_tight error | largest abs(z) | "
              "torque balance | energy balance | verdict |", "|---|---|---|---|---|---|---|---|---|"]
    for p in r["points"]:
        if "failure" in p:
            lines.append(f"| {label(p)} | {p['setting']:g} | | | | | | | failed: {p['failure']} |")
            continue
        e, c = p["errors"], p["checks"]
        lines.append(f"| {label(p)} | {p['setting']:g} | {p['cpuPerRevolution']:.3g} | "
                     f"{e['slip']['percent']:+.2f} % | {e['tightStrandForce']['percent']:+.2f} % | "
                     f"{max(abs(x['z']) for x in e.values()):.2f} | {100 * c['torqueBalanceError']:+.2f} % | "
                     f"{100 * c['energyBalanceError']:+.2f} % | {'accurate' if p['consistent'] else 'off'} |")
    good = [p for p in r["points"] if p.get("consistent")]
    if good:
        best = min(good, key=lambda p: p["cpuPerRevolution"])
        lines.append(f"\nCheapest accurate point: {best['method']} at {best['setting']:g}, "
                     f"{best['cpuPerRevolution']:.3g} CPU s per chain revolution (the goal: under one CPU minute).")
    return "\n".join(lines + friction_law_lines(r)) + "\n"


def friction_law_lines(r):
    """The friction law's share: the means of the reference (regularized, vReg of the CVT file), the
    regularized model with smaller vReg and time stepping (Coulomb), all after the same run-in."""
    rows = [p for p in r["points"] if ("vReg" in p or p["method"].startswith("time-stepping")) and "failure" not in p]
    if not rows:
        return []
    lines = ["\nThe friction law: time stepping solves Coulomb's law exactly (up to its polygon of facets; with "
             "rigid pins circumferentially, the pins closing with Newton impacts at pulley entry), the "
             "compliant methods a regularized one (full friction beyond the sliding speed vReg = 0.02 m/s, "
             "src/drives/default_cvt.json); the wrap's sliding speeds (slip times chain speed, a few cm/s) are of "
             "that order. The points below continue from the reference's state at the end of the run-in "
             f"({r.get('handoverRunIn', TS_RUN_IN)} revolution(s) of their own, "
             f"{r.get('handoverRevolutions', TS_REVOLUTIONS)} counted); the regularized model with smaller "
             "vReg (fixed-verlet, with the smaller step its stiffer friction needs) moves toward time stepping's "
             "Coulomb values, so that the difference between the two is the regularization's more than the method's.\n",
             "| friction law, method | slip [%] | F_tight [N] | driven clamping force [N] | power loss [W] | "
             "CPU s per revolution |", "|---|---|---|---|---|---|"]
    ref = r["reference"]
    for p in [ref] + rows:
        st = p["statistics"]
        name = "reference, vReg 0.02 m/s" if p is ref else label(p)
        lines.append(f"| {name} {p['setting']:g} | {100 * st['slip']['mean']:.3f} +- {100 * st['slip']['ci95']:.3f} | "
                     f"{st['tightStrandForce']['mean']:.0f} | {st['clampingForceDriven']['mean']:.0f} | "
                     f"{st['powerLoss']['mean']:.1f} | {p['cpuPerRevolution']:.3g} |")
    return lines


def rejudge(r):
    """The comparisons of saved results again (the tolerances may have changed)."""
    for p in [r.get("referenceCheck")] + r["points"]:
        if p:
            compare(p, r["reference"])
    return r


def run(args):
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.report_only:
        r = rejudge(json.loads(pathlib.Path(args.report_only).read_text()))
    else:
        r = study(out, quick=args.quick)
    (out / "cvt_results.json").write_text(json.dumps(r, indent=1))
    chart(out / "wp_cvt.png", r)
    (out / "cvt.md").write_text(section(r))
    if not args.keep_csv:
        shutil.rmtree(out / "cvt_runs", ignore_errors=True)
    print(f"written: {out / 'cvt.md'}, {out / 'wp_cvt.png'}, {out / 'cvt_results.json'}")
    return 0

