"""Divergence rate and the chaos floor, measured with twin runs that differ by one rounding.

    python -m harness chaos [--quick] [--out DIR] [--report FILE] [--jobs N] [--rpm 3000]
                            [--settings default,both4,...] [--pairs N] [--cycles N] [--max-cycles N]
                            [--verlet-steps 2.5e-6,...] [--keep-runs] [--report-only RESULTS_JSON]

Scene: the default drive at --rpm (3000), open loop with the measured-torque tables
(harness/tables/tables.py: crankshaft speed fluctuation and camshaft torques over crank angle, as
the --inputs time series of chaindrive-run).

Damping settings (--settings, all by default): the default drive; joint damping
(chain.joint.damping) and contact damping (contact.rollerSprocket.dampingFactor and
contact.plateGuide.dampingFactor) both raised 4x and 10x; each of them alone 4x and 10x (which
damping matters); and a method check on the default damping from the same start states
(adaptive arkode-erk at rtol 1e-8 instead of fixed-step Verlet).

Per setting:
1. Run-in from the pre-loaded state, the run-in of harness/job.py (whole engine cycles, at least
   2 and at least 0.15 s: 4 cycles at 3000 rpm), with fixed-verlet at the first step of
   --verlet-steps (2.5, 2, 1.25, 1, 0.625, 0.5, 0.4, 0.25 us) below the explicit-damping bound
   (step_bound: h c / m < 2 for a link with its joint dampers and with a contact damper at an
   impact peak, times 0.8) that completes it; the steps that failed are reported with the
   failure the solver detected (blow-up, ...). Explicit --verlet-steps are tried as given.
2. Step check: the damping forces are explicit in Verlet. Too much joint damping for the step
   blows up; too much contact damping does not: the contact force, clamped at zero, chatters,
   and the run goes on with wrong dynamics and a wrong divergence rate (contact damping 10x at
   2.5 us diverges at several times the rate it has at 1 us or 0.5 us). So the rate lambda of
   the tensioner force is measured on PROBE_PAIRS (4) pairs at the run-in's step and at half of
   it, and the step is halved until the pairs' log rates at the two steps no longer differ
   significantly (Welch's t-test at the 1 % level: the rate of a pair changes with any change
   of step, as every trajectory does) or differ by less than a factor STEP_TOLERANCE (1.25),
   down to MIN_STEP (0.2 us). Every step checked is reported.
3. Start states S_0 ... S_(N-1): the run-in's final state (again at the accepted step if the
   check went below the run-in's step), then the run continued one engine cycle at a time, so
   that pair k starts at a cycle boundary k cycles after S_0 (the ensemble samples different
   states on the same engine phase).
4. Twin pairs k = 0 .. N-1 (--pairs, 12): twin A runs from S_k, twin B from S_k with one state
   component multiplied by 1 + 1e-12 (a different component per pair: x or y of links spread
   along the chain, or a rotor angle), outputs every 20 us. Their length: the latest
   saturation time (b) of any pair and signal in the accepted step check plus AFTER_SATURATION
   (3) engine cycles, at least --cycles (5), at most --max-cycles (15). A twin that fails is a
   reported failure, not a number; the other pairs still count.

Measures, per setting and per signal (tensioner force, tension-guide angle), on the difference
B - A as RMS over 1 ms windows, time counted from the perturbation:
(a) divergence rate lambda [1/ms]: least-squares slope of ln(windowed difference) between its
    first crossing of FIT_LOW (1e-6) and of FIT_HIGH (1e-2) times the independent level (below),
    and at least 100 times its first window (the output's print floor, or the adaptive method's
    own error level); median and range over the pairs, and the e-folding time 1/lambda.
(b) saturation time: the first window in which the difference reaches half the independent
    level: the RMS difference of two unrelated runs with the same inputs, measured between twin
    A runs that start at least two engine cycles apart (the same engine phase, unrelated
    states). In ms and in engine cycles; median and range over the pairs.
(c) cycle independence: the per-cycle statistics of harness/cycle_stats.per_cycle (tensioner
    force mean, peak-to-peak and order 2, tight-span force mean, tension-guide angle
    peak-to-peak) of twin A and twin B, cycle by cycle (cycle 0 starts at the perturbation).
    r_j = median over the pairs of |x_B - x_A| in cycle j, divided by the median |x - x'| over
    all pairs of distinct engine cycles of the twin A runs (the difference of unrelated
    cycles): about 1 once the twins are independent. Medians, not RMS: the per-cycle values
    have heavy tails (a peak-to-peak is set by the largest impact of its cycle). The bound is
    the 2.5 % quantile of the same ratio for N random pairs of those unrelated cycles (4000
    draws): independent twins fall below it with 2.5 % probability. A statistic counts as
    independent from the first cycle j whose r_j reaches its bound (the report also counts
    later cycles below it), the twins' cycle statistics from the largest such j over the
    statistics; the report adds the rank correlation of x_A and x_B over the pairs.

--quick: the default setting only, a 1-cycle run-in, no step check, 3 pairs of QUICK_CYCLES (6) cycles: a
smoke test (about 10 s on 2 cores; run by tests/python/study/test_chaos.py).

Outputs in DIR (default results/chaos): results.json, divergence.png (windowed twin difference
over time per setting with the fitted slopes), cycles.png (per-cycle twin statistics),
lambda.png (divergence rate per setting with its spread), and the report (markdown; default
DIR/report.md); run files under DIR/runs (removed unless --keep-runs). At most 2 runs at a time
(--jobs 1 or 2: the machine's cores are shared).
"""

import datetime
import json
import pathlib
import shutil
import time

import numpy as np

from ... import paths, runs
from .analysis import FIT_HIGH, FIT_LOW, SATURATION, WINDOW, analyse, fmt, fmt_spread, measured
from .charts import chart_cycles, chart_divergence, chart_lambda
from .damping import damping_measures
from .report import write_report
from .steps import AFTER_SATURATION, setting_states, twin_cycles
from .twins import OUTPUT_STEP, PERTURBATION, Context, damped_drive, failure_of, method_label, run_twins

MAX_JOBS = 2            # never more runs at a time (shared machine)
VERLET_STEPS = (2.5e-6, 2e-6, 1.25e-6, 1e-6, 6.25e-7, 5e-7, 4e-7, 2.5e-7)  # all divide the output step

SETTINGS = [
    dict(id="default", label="default damping", joint=1.0, contact=1.0),
    dict(id="both4", label="joint + contact damping x4", joint=4.0, contact=4.0),
    dict(id="both10", label="joint + contact damping x10", joint=10.0, contact=10.0),
    dict(id="joint4", label="joint damping x4", joint=4.0, contact=1.0),
    dict(id="joint10", label="joint damping x10", joint=10.0, contact=1.0),
    dict(id="contact4", label="contact damping x4", joint=1.0, contact=4.0),
    dict(id="contact10", label="contact damping x10", joint=1.0, contact=10.0),
    # method check: the default drive from the default setting's start states, adaptive ERK
    dict(id="erk", label="default, arkode-erk rtol 1e-8", joint=1.0, contact=1.0, states_from="default",
         pairs=6, cycles=2, method=dict(contact="compliant", integrator="arkode-erk", option="rtol", value=1e-8)),
]


def run_setting(ctx, s):
    """One damping setting: run-in, start states, twins, measures; failures are reported as such."""
    sd = ctx.runs_dir / s["id"]
    drive = damped_drive(sd / "drive.json", s["joint"], s["contact"])
    res = setting_record(s, drive)
    ctx.log(f"\n## {s['label']} ({s['id']}): joint damping {res['jointDamping']:g} N s/m, contact damping factors "
            f"{res['rollerAlpha']:g} / {res['guideAlpha']:g} s/m")
    states, state_method, choice = setting_states(ctx, s, drive, sd, res)
    if states is None:
        return res
    m = ensemble_method(ctx, s, res, choice, state_method)
    ctx.log(f"  ensemble: {len(states)} pairs of {res['twinCycles']} engine cycles, {method_label(m)}")
    pairs = run_twins(ctx, m, drive, states, sd, res["twinCycles"])
    done = pair_outcomes(res, pairs)
    if len(done) < 2:
        res["status"] = "failed"
        res["failure"] = f"{len(pairs) - len(done)} of {len(pairs)} pairs failed"
        return res
    res.update(analyse(ctx, done))
    res["status"] = "ok" if len(done) == len(pairs) else "partial"
    ctx.log(setting_line(res))
    return res


def setting_record(s, drive):
    """The result of a setting before its runs: its damping factors and values."""
    d = json.loads(drive.read_text())
    return dict(id=s["id"], label=s["label"], jointFactor=s["joint"], contactFactor=s["contact"],
                jointDamping=d["chain"]["joint"]["damping"],
                rollerAlpha=d["contact"]["rollerSprocket"]["dampingFactor"],
                guideAlpha=d["contact"]["plateGuide"]["dampingFactor"], runIn=[])


def ensemble_method(ctx, s, res, choice, state_method):
    """The twins' method (the setting's own, else the one that made the start states) and their
    length, recorded in res with the step checks; returns the method."""
    res["stepChecks"] = choice["checks"]
    res["stepConverged"] = choice["converged"]
    res["stepBound"] = choice.get("bound")
    m = s.get("method") or state_method
    res["method"] = dict(m, label=method_label(m))
    res["statesMethod"] = method_label(state_method)
    accepted = next((c for c in choice["checks"] if c["step"] == m.get("value")), None)
    res["twinCycles"] = twin_cycles(ctx, s, accepted)
    return m


def pair_outcomes(res, pairs):
    """Records the failed pairs and the cost of the others in res; returns the completed pairs."""
    res["pairFailures"] = [dict(start=p["start"], perturbation=p["perturbation"],
                                **failure_of(p["A"] if p["A"]["kind"] != "ok" else p["B"]))
                           for p in pairs if p["kind"] != "ok"]
    done = [p for p in pairs if p["kind"] == "ok"]
    cpu = [p[t]["cpuSeconds"] for p in done for t in "AB"]
    sim = [p[t]["simulated"] for p in done for t in "AB"]
    res["cpuPerSimulatedSecond"] = float(np.sum(cpu) / np.sum(sim)) if done else None
    return done


def setting_line(r):
    if r["status"] == "failed":
        return f"  {r['label']}: FAILED: {r.get('failure')}"
    F, P = r["signals"]["tensioner.F"], r["signals"]["tensionGuide.phi"]
    j = r["cycles"]["firstIndependent"]
    return (f"  {r['label']} [{r['method']['label']}]: lambda F {fmt_spread(F['rate_per_ms'])} 1/ms "
            f"(e-folding {fmt(F['efold_ms'])} ms), angle {fmt_spread(P['rate_per_ms'])} 1/ms; saturated after "
            f"{fmt(F['saturation_ms']['median'])} ms ({fmt(F['saturation_cycles']['median'])} cycles), angle "
            f"{fmt(P['saturation_ms']['median'])} ms; cycle statistics independent from cycle "
            f"{j if j is not None else 'none of those run'} ({r['twinCycles']} cycles run)")


def write_outputs(results, out, report):
    out.mkdir(parents=True, exist_ok=True)
    (out / "results.json").write_text(json.dumps(results, indent=1))
    if measured(results):
        chart_divergence(out / "divergence.png", results)
        chart_cycles(out / "cycles.png", results)
    chart_lambda(out / "lambda.png", results)
    write_report(results, report, out)


def add_arguments(ap):
    ap.add_argument("--quick", action="store_true", help="the smoke variant (default setting, 3 short pairs)")
    ap.add_argument("--out", default=None, help="output directory (default results/chaos or results/chaos-quick)")
    ap.add_argument("--report", default=None, help="report file (default OUT/report.md)")
    ap.add_argument("--jobs", type=int, default=1, help=f"runs at a time, at most {MAX_JOBS}")
    ap.add_argument("--rpm", type=float, default=3000.0, help="mean engine speed [rpm]")
    ap.add_argument("--settings", default=None,
                    help="damping settings, comma separated, of: " + ", ".join(s["id"] for s in SETTINGS))
    ap.add_argument("--pairs", type=int, default=None, help="twin pairs per setting (default 12; method checks 6)")
    ap.add_argument("--cycles", type=int, default=None,
                    help="engine cycles of the step check's twins and the least of the ensemble's (default 5; "
                         "the method check 2)")
    ap.add_argument("--max-cycles", type=int, default=15,
                    help=f"longest twin of the ensemble [engine cycles]: saturation + {AFTER_SATURATION} cycles, up "
                         "to this")
    ap.add_argument("--verlet-steps", default=None,
                    help="Verlet steps to try for the run-in [s], comma separated, largest first")
    ap.add_argument("--timeout", type=float, default=3600.0, help="wall-time budget of one run [s]")
    ap.add_argument("--keep-runs", action="store_true", help="keep the run files (states, CSV) under OUT/runs")
    ap.add_argument("--report-only", metavar="RESULTS_JSON", help="only rewrite the charts and the report")


def check(ap, args):
    if not 1 <= args.jobs <= MAX_JOBS:
        ap.error(f"--jobs {args.jobs}: between 1 and {MAX_JOBS} (the machine's cores are shared)")
    known = {s["id"]: s for s in SETTINGS}
    ids = args.settings.split(",") if args.settings else (["default"] if args.quick else list(known))
    unknown = [i for i in ids if i not in known]
    if unknown:
        ap.error(f"unknown settings {unknown}; known: {list(known)}")
    args.selected = [known[i] for i in ids]
    args.explicit_steps = bool(args.verlet_steps)
    args.verlet_steps = tuple(float(x) for x in args.verlet_steps.split(",")) if args.verlet_steps else VERLET_STEPS
    if args.out is None:
        args.out = str(paths.RESULTS / ("chaos-quick" if args.quick else "chaos"))
    return args


def run(args):
    out = pathlib.Path(args.out)
    report = pathlib.Path(args.report) if args.report else out / "report.md"
    if args.report_only:
        results = json.loads(pathlib.Path(args.report_only).read_text())
        results["damping"] = damping_measures()
        write_outputs(results, out, report)
        return 0
    shutil.rmtree(out / "runs", ignore_errors=True)
    started = datetime.datetime.now()
    w0 = time.monotonic()
    ctx = Context(args, args.selected)
    ctx.log(f"chaos study{' (quick)' if args.quick else ''}: {runs.machine()}")
    ctx.log(f"{args.rpm:g} rpm, engine cycle {ctx.cycle * 1e3:g} ms, run-in {ctx.run_in_cycles} cycles, output step "
            f"{OUTPUT_STEP * 1e6:g} us, perturbation {PERTURBATION:g} relative, runs at a time {args.jobs}")
    settings = [run_setting(ctx, s) for s in args.selected]
    command = " ".join(["python -m harness chaos"] + args.argv)
    results = dict(machine=runs.machine(), command=command, started=started.isoformat(timespec="seconds"),
                   wall_seconds=time.monotonic() - w0, quick=args.quick, rpm=args.rpm, cycle=ctx.cycle,
                   runInCycles=ctx.run_in_cycles, outputStep=OUTPUT_STEP, window=WINDOW, perturbation=PERTURBATION,
                   fitLow=FIT_LOW, fitHigh=FIT_HIGH, saturation=SATURATION, settings=settings,
                   damping=damping_measures(), log=ctx.log_lines)
    write_outputs(results, out, report)
    if not args.keep_runs:
        shutil.rmtree(out / "runs", ignore_errors=True)
    print(f"\nwritten: {out / 'results.json'}, {report} ({results['wall_seconds'] / 60:.1f} min)")
    return 0
