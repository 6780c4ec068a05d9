"""Speed against accuracy: work-precision charts on cycle statistics and a stability map of every
method.

    python -m harness study [--quick] [--out DIR] [--jobs N] [--scenes 1000,3000,6000]
    python -m harness study --scene cvt [--quick] [--out DIR]     the chain CVT's section (harness/study/cvt.py)

Scenes: the default drive at 1000, 3000 and 6000 rpm, open loop with the measured-torque tables
(harness/tables/tables.py: crankshaft speed fluctuation and camshaft torques over crank angle).

Why statistics: the link-level dynamics of the drive is chaotic (impacts of rollers on teeth and
of link plates on guides): two runs that differ by one rounding grow apart exponentially
(docs/study/chaos.md), so after a few milliseconds any two solutions, the reference's among them,
differ at the level of the signal itself. What a method can get right, and what engineers compare,
are the statistics over engine cycles: means, peak-to-peak values and engine-order amplitudes, each
known only to within the scatter of the cycles (harness/cycle_stats.py).

1. Start transient: from the pre-loaded state, fixed-verlet at 1 us over the main job's run-in
   (whole engine cycles, at least 2 and at least 0.15 s); its final state is saved at t0 and every
   run below starts from it (chaindrive-run --initial-state). Every run then settles for one engine
   cycle (in which the rigid-contact models find their own equilibrium: with ideal joints the chain
   cannot stretch) and is measured over the next N whole engine cycles (N: about 0.8 s of engine
   time, CYCLES_TIME, or --cycles-time; a quarter of that for the costly rigid-contact methods).
2. Reference ensemble: arkode-erk at rtol 1e-8 over three times as many cycles; for each headline
   quantity the mean over its cycles with the 95 % confidence half-width, and the cycle-to-cycle
   standard deviation (the reference's own scatter). Its convergence is checked by a second, very
   different accurate method (fixed-verlet at 0.25 us) over the same cycles: their statistics must
   agree within their intervals.
3. Every method (contact method x integrator) over a geometric sweep of its step or tolerance:
   CPU seconds per simulated second (median of up to 3 runs; repeated runs are also checked to be
   bit-identical) and, per headline quantity, its error: the difference of its cycle mean from
   the reference's, in % (levels) or dB (order amplitudes) and in units of the reference's
   cycle-to-cycle scatter, with z = difference / sqrt(ci_method^2 + ci_reference^2). A statistic
   is consistent with the reference when |z| <= 1 (within the 95 % interval of the difference); a
   method is as accurate as the physics allows when all its headline statistics are consistent,
   jointly at 95 % (Bonferroni: each |z| <= the (1 - 0.05/K) quantile over 1.96 for K statistics).
   A run that fails is a failure marker with the kind the solver reports.
4. Convergence order: the short-horizon trajectory error over the first 1 ms after t0 (before the
   chaotic growth: methods.SHORT_HORIZON), against arkode-erk at rtol 1e-11, checked at 1e-12.
5. Stability map: each method at its default setting over engine speed, over its step or
   tolerance, and over joint and contact stiffness (factors on the default drive), from the
   pre-loaded state over 20 ms: ok, or the failure detected by the solver (blow-up, non-finite
   state, tunnelling, LCP ray termination or numerical failure, Newton failure, step-size
   collapse, runaway events) or the wall-time budget.
6. Real time: CPU time per fmi2DoStep of ChainDrive.fmu through fmpy's FMU2Slave at fixed
   communication steps of 100 us and 1 ms, for the fixed-step methods (median, 99th percentile,
   maximum).

Every run writes outputs every 60 us (OUTPUT_STEP): a whole number of steps of every fixed step
of the sweeps, so that all runs share their output times on the time grid (src/integrators/time_grid.h).

--quick: 6000 rpm (the shortest cycle), a 2-cycle run-in, 2 measured cycles, a reference at rtol 1e-6 over 3 cycles, one or two points per method, a reduced
stability map and short real-time timings: a smoke test of the whole chain (each method gives a
point or a reported failure) for CI.

Outputs in DIR (default results/study): report.md, results.json, work-precision charts
wp_<rpm>rpm.png, stability_<axis>.png, and the CSV of every run under runs/ (not for the
repository). The report is written by harness/study/report.py.
"""
import datetime
import json
import pathlib
import shutil
import time

from .. import paths, runs
from . import cvt, report
from .methods import CYCLES_TIME, MIN_CYCLES
from .realtime import realtime
from .scenes import Study
from .stability import stability

CHAOS_RESULTS = paths.ROOT / "docs" / "study" / "chaos" / "results.json"  # divergence rates, for the report


def add_arguments(ap):
    ap.add_argument("--scene", choices=("timing", "cvt"), default="timing",
                    help="timing: the timing drive (default); cvt: the chain CVT's work-precision section "
                         "(harness/study/cvt.py), which report.md includes")
    ap.add_argument("--quick", action="store_true", help="the reduced variant (CI)")
    ap.add_argument("--out", default=None, help="output directory (default results/study or results/study-quick)")
    ap.add_argument("--scenes", default=None, help="engine speeds [rpm], comma separated (default 1000,3000,6000)")
    ap.add_argument("--jobs", type=int, default=1, help="runs in parallel (timings are cleaner with 1)")
    ap.add_argument("--cycles-time", type=float, default=CYCLES_TIME,
                    help=f"engine time measured per point [s] (whole cycles, at least {MIN_CYCLES}; "
                         f"default {CYCLES_TIME})")
    ap.add_argument("--repeats", type=int, default=3, help="runs per point for the median CPU time")
    ap.add_argument("--repeat-below", type=float, default=20.0,
                    help="repeat a point only if one run takes less than this many CPU seconds")
    ap.add_argument("--timeout", type=float, default=3600.0, help="wall-time budget of one measured run [s]")
    ap.add_argument("--keep-csv", action="store_true", help="keep the output CSV of every point")
    ap.add_argument("--skip", default="", help="parts to skip: comma separated of wp, stability, realtime")
    ap.add_argument("--resume", action="store_true",
                    help="reuse the scenes already finished in --out (scene_<rpm>rpm.json)")
    ap.add_argument("--chaos", default=str(CHAOS_RESULTS),
                    help="results of python -m harness chaos for the report's last section (default %(default)s)")
    ap.add_argument("--report-only", metavar="RESULTS_JSON",
                    help="only rewrite the report and charts into --out from the results of an earlier run")


def check(ap, args):
    if args.out is None:
        args.out = (str(pathlib.Path(args.report_only).parent) if args.report_only else
                    str(paths.RESULTS / ("study-quick" if args.quick else "study")))
    return args


def chaos_results(path):
    """The divergence-rate study's results (its JSON at path) for the report (None if it has not been run)."""
    path = pathlib.Path(path)
    return json.loads(path.read_text()) if path.exists() else None


def rewrite_report(args):
    r = json.loads(pathlib.Path(args.report_only).read_text())
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if pathlib.Path(args.report_only).resolve() != (out / "results.json").resolve():
        (out / "results.json").write_text(json.dumps(r, indent=1))
    report.write(out, r, chaos_results(args.chaos))
    print(f"written: {out / 'report.md'}")
    return 0


def run(args):
    if args.scene == "cvt":
        return cvt.run(args)
    if args.report_only:
        return rewrite_report(args)
    scenes_rpm = [6000.0] if args.quick else [1000.0, 3000.0, 6000.0]
    if args.scenes:
        scenes_rpm = [float(x) for x in args.scenes.split(",")]
    skip = set(filter(None, args.skip.split(",")))
    study = Study(args)
    out = pathlib.Path(args.out)
    if not args.resume:
        shutil.rmtree(out / "runs", ignore_errors=True)
        for f in out.glob("scene_*rpm.json"):
            f.unlink()
    out.mkdir(parents=True, exist_ok=True)
    started = datetime.datetime.now()
    w0 = time.monotonic()
    study.log(f"study{' (quick)' if args.quick else ''}: {runs.machine()}")
    scenes = [study.scene(rpm) for rpm in scenes_rpm] if "wp" not in skip else []
    stab = stability(study) if "stability" not in skip else dict(duration=0.0, runs=[])
    rt = realtime(study) if "realtime" not in skip else []
    wall = time.monotonic() - w0
    command = " ".join(["python -m harness study"] + args.argv)
    results = dict(machine=runs.machine(), started=started.isoformat(timespec="seconds"), wall_seconds=wall,
                   quick=args.quick, command=command, scenes=scenes, stability=stab, realtime=rt, log=study.log_lines,
                   settings=dict(repeats=args.repeats, repeat_below=args.repeat_below, jobs=args.jobs,
                                 timeout=args.timeout))
    (out / "results.json").write_text(json.dumps(results, indent=1))
    report.write(out, results, chaos_results(args.chaos))
    if not args.keep_csv and not args.quick:
        shutil.rmtree(out / "runs", ignore_errors=True)
    print(f"\nwritten: {out / 'report.md'} ({wall / 60:.1f} min)")
    return 0
