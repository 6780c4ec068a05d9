"""The main job: a scene run through ChainDrive.fmu with the measured-torque tables.

Runs a drive (default: the FMU's default drive) at a mean engine speed, driven by the
camshaft-torque and crankshaft-speed tables of harness/tables/data (synthesized, see
harness/tables/data/README.md), writes all outputs as CSV, makes the plots engineers read and reports
every headline quantity as a mean over engine cycles with its 95 % confidence half-width
(harness/cycle_stats.py), printed and written to summary.json.

Run-in: the run starts from the kinetostatic preload; the first engine cycles carry the start
transient and the creep of the tension guide from the static to the dynamic mean of the chain
forces (set by the tensioner's retraction damping: about 50 ms at 3000 rpm, 100 ms at 6000
rpm). The run-in, the smallest whole number of engine cycles that is at least 2 cycles and at
least 0.15 s long (4 cycles at 3000 rpm, 8 at 6000 rpm, 2 at 1000 rpm), is discarded; the
counted cycles (--cycles) follow.

Two fidelities (--fidelity, the FMU parameter `fidelity`): link (default), the link-by-link model,
and span, the span model (rotors and longitudinal spans, src/span/, about 80 times cheaper inside
fmi2DoStep, not as accurate: python -m harness fidelity compares them). Both give the same
outputs, so the same cycle statistics, plots and summary; the fidelity is named in the header line
and the plot titles. The solver step defaults to each fidelity's own (SOLVER_STEP).

Two couplings:
  closed (default)  the way an engine simulator couples: a master loop (fmpy FMU2Slave) looks the
                    camshaft torques up at the FMU's own camshaft angles and the crankshaft speed
                    at its crankshaft angle, at every communication step;
  open              the tables turned into time series at the mean speed and passed to
                    fmpy.simulate_fmu as input.

The chain CVT (--scene cvt, paper example 4.1) has a main job of its own: harness/cvt/job.py.

    python -m harness run [--rpm 3000] [--fidelity link|span] [--cycles N] [--run-in S]
                          [--coupling closed|open] [--step 1e-4] [--method fixed-verlet]
                          [--solver-step S] [--newmark-gamma G] [--drive FILE] [--out results]
    python -m harness run --scene cvt [--rpm 2000] [--load-torque 80] [--revolutions 8] [--cvt FILE]

Writes to --out: outputs.csv, summary.json (the cycle statistics), run.json (what ran and its
cost: fidelity, speed, cycles, CPU seconds of the loop and of fmi2DoStep alone) and the plots.
"""
import contextlib
import dataclasses
import json
import math
import pathlib
import sys
import time

import numpy as np

from . import cycle_stats, paths
from .cvt import job as cvt_job
from .drive.description import drive_json, meshing_order
from .fmu import fmu
from .plots import drive_picture, plots
from .tables import tables

RUN_IN_CYCLES = 2          # the run-in: at least this many engine cycles ...
RUN_IN_TIME = 0.15         # [s] ... and at least this long
DEFAULT_CYCLES = 120       # counted engine cycles of the default run (see README: 1 % confidence)
# the tables' mean speed over time (the harmonic mean of the speed over crank angle) lies up to
# 0.2 % below the nominal speed (at 1000 rpm): 120 cycles then take a quarter of a cycle longer
SPEED_MARGIN = 0.005
FIDELITIES = ("link", "span")  # values of the FMU parameter `fidelity`: the reference, then the cheaper
# [s] default FMU parameter solver.step per fidelity (fixed-verlet): the link model is stable below
# about 3.5 us; the span model (no link masses: rotors on span springs) runs at 100 us and blows up
# at 200 us on the default drive, so 20 us keeps a factor 5 and divides the communication step
SOLVER_STEP = {"link": 2.5e-6, "span": 2e-5}
# the real-time method of the link fidelity: Verlet with the joints' damping implicit, 28 steps per
# 0.1 ms communication step (about three quarters of its stable step; docs/benchmark_realtime.md)
REALTIME_METHOD, REALTIME_STEP = "fixed-verlet-implicit-joint-damping", 1e-4 / 28

class Progress:
    """A text progress bar on stderr."""

    def __init__(self, total, label):
        self.total, self.label, self.last = total, label, -1
        self.t0 = time.time()

    def update(self, t):
        pct = int(100 * t / self.total + 1e-9)
        tty = sys.stderr.isatty()
        if pct != self.last and (tty or pct % 10 == 0):
            self.last = pct
            bar = "#" * (pct // 4) + "." * (25 - pct // 4)
            sys.stderr.write(f"{chr(13) if tty else ''}{self.label} [{bar}] {pct:3d} %  t = {t * 1e3:7.2f} ms  "
                             f"({time.time() - self.t0:5.1f} s){'' if tty else chr(10)}")
            sys.stderr.flush()
        return True

    def done(self):
        if sys.stderr.isatty():
            sys.stderr.write("\n")


def parameters_of(args):
    p = {"fidelity": args.fidelity, "solver.method": args.method, "solver.step": args.solver_step,
         "solver.tolerance": args.rtol, "solver.newmarkGamma": args.newmark_gamma}
    if args.drive:
        p["driveFile"] = str(pathlib.Path(args.drive).resolve())
    return p


def table_inputs(torque, speed):
    """The closed loop's inputs from the tables of one engine speed: a function of (time, crank
    angle, intake and exhaust camshaft angles in crank degrees) giving the FMU's inputs."""
    def inputs(t, crank_deg, intake_deg, exhaust_deg):
        return {"crankshaft.w": speed_at(speed, crank_deg),
                "camshaftIntake.tau": float(tables.lookup(torque, "camshaftIntake.tau", intake_deg)),
                "camshaftExhaust.tau": float(tables.lookup(torque, "camshaftExhaust.tau", exhaust_deg))}
    return inputs


def run_closed(args, duration, inputs, progress=True, fmu_file=None):
    """Master loop: inputs (table_inputs) looked up at the FMU's own angles before every step.
    fmu_file: the FMU (a file or an unpacked folder; default the build's). Returns (record, CPU
    seconds spent inside each fmi2DoStep)."""
    s = fmu.Slave("chaindrive", fmu=fmu_file, parameters=parameters_of(args))
    n = int(round(duration / args.step))
    u0 = inputs(0.0, 0.0, 0.0, 0.0)
    with fmu_messages(s):
        s.initialize(inputs=u0)
    names = s.outputs
    rows = [[0.0] + [s.get(names)[k] for k in names] + [u0["crankshaft.w"], np.nan, np.nan]]
    prog = Progress(duration, "closed loop") if progress else None
    for k in range(n):
        o = s.get(["crankshaft.phi", "camshaftIntake.phi", "camshaftExhaust.phi"])
        # camshafts turn at half the crankshaft speed; the tables are over crank angle
        u = inputs(k * args.step, math.degrees(o["crankshaft.phi"]), 2.0 * math.degrees(o["camshaftIntake.phi"]),
                   2.0 * math.degrees(o["camshaftExhaust.phi"]))
        with fmu_messages(s):
            s.step(args.step, inputs=u, t=k * args.step)
        v = s.get(names)
        rows.append([(k + 1) * args.step] + [v[x] for x in names] + [u["crankshaft.w"], u["camshaftIntake.tau"],
                                                                    u["camshaftExhaust.tau"]])
        if prog:
            prog.update((k + 1) * args.step)
    if prog:
        prog.done()
    s.close()
    cols = ["time"] + names + ["input.crankshaft.w", "input.camshaftIntake.tau", "input.camshaftExhaust.tau"]
    return {c: np.array([r[i] for r in rows]) for i, c in enumerate(cols)}, s.step_cpus


@contextlib.contextmanager
def fmu_messages(slave):
    """A failing FMI call's exception (the same object) with the errors the FMU logged (the
    reason: a parameter out of range, a method failure) appended to its message."""
    try:
        yield
    except Exception as e:
        errors = slave.errors()
        if errors:
            e.args = (f"{e} ChainDrive.fmu: {'; '.join(errors)}",)
        raise


def speed_at(speed, crank_deg):
    col = "crankshaft.speed_rpm" if "crankshaft.speed_rpm" in speed.columns else "crankshaft.w"
    v = float(tables.lookup(speed, col, crank_deg))
    return v * 2.0 * math.pi / 60.0 if col.endswith("_rpm") else v


def run_open(args, duration, torque, speed):
    """fmpy.simulate_fmu with the tables as time series. Returns (record, None): fmpy's loop does
    not tell the time spent inside fmi2DoStep."""
    from fmpy import simulate_fmu
    ts = tables.time_series(args.rpm, duration, min(2e-5, args.step), torque_table=torque, speed_table=speed)
    names = ["crankshaft.w", "camshaftIntake.tau", "camshaftExhaust.tau"]
    arr = np.zeros(len(ts["time"]), dtype=[("time", float)] + [(n, float) for n in names])
    arr["time"] = ts["time"]
    for n in names:
        arr[n] = ts[n]
    prog = Progress(duration, "open loop")
    res = simulate_fmu(str(fmu.fmu_path()), stop_time=duration, output_interval=args.step, input=arr,
                       start_values=parameters_of(args), step_finished=lambda t, rec: prog.update(t))
    prog.done()
    out = {n: np.asarray(res[n], dtype=float) for n in res.dtype.names}
    for n in names:
        out["input." + n] = np.interp(out["time"], ts["time"], ts[n])
    return out, None


def write_csv(path, d):
    cols = list(d)
    with open(path, "w") as f:
        f.write(",".join(cols) + "\n")
        np.savetxt(f, np.column_stack([d[c] for c in cols]), delimiter=",", fmt="%.10g")


SCENES = ("timing", "cvt")  # the roller-chain timing drive (this module), the chain CVT (harness/cvt/job.py)


def add_arguments(ap):
    ap.add_argument("--scene", choices=SCENES, default="timing",
                    help="timing: the roller-chain timing drive through ChainDrive.fmu (default); cvt: the chain CVT "
                    "(paper example 4.1, harness/cvt/job.py)")
    ap.add_argument("--drive", help="drive description (default: the FMU's default drive)")
    ap.add_argument("--rpm", type=float, help="mean engine speed [rpm], 1000-6000 (tables; default 3000); cvt: the "
                    f"driving-pulley speed (default {cvt_job.DEFAULT_RPM:g})")
    ap.add_argument("--cvt", help="cvt: the CVT description (default: the embedded default CVT)")
    ap.add_argument("--load-torque", type=float, default=cvt_job.DEFAULT_LOAD,
                    help=f"cvt: the load torque on the driven pulley [N m] (default {cvt_job.DEFAULT_LOAD:g})")
    ap.add_argument("--revolutions", type=int, default=cvt_job.DEFAULT_REVOLUTIONS,
                    help=f"cvt: chain revolutions counted after the run-in (default {cvt_job.DEFAULT_REVOLUTIONS})")
    ap.add_argument("--run-in-revolutions", type=int, default=cvt_job.RUN_IN_REVOLUTIONS,
                    help=f"cvt: chain revolutions discarded first (default {cvt_job.RUN_IN_REVOLUTIONS})")
    ap.add_argument("--fidelity", choices=FIDELITIES, default="link",
                    help="FMU parameter fidelity: link (link-by-link model, default) or span (span model)")
    ap.add_argument("--cycles", type=int, default=DEFAULT_CYCLES,
                    help=f"engine cycles (720 deg crank) counted after the run-in (default {DEFAULT_CYCLES})")
    ap.add_argument("--run-in", type=int, help=f"engine cycles discarded before the first counted one (default: "
                    f"at least {RUN_IN_CYCLES} and at least {RUN_IN_TIME:g} s)")
    ap.add_argument("--coupling", choices=("closed", "open"), default="closed")
    ap.add_argument("--tables", help="directory of the torque/speed tables (default harness/tables/data)")
    ap.add_argument("--step", type=float, default=1e-4, help="communication step [s]")
    ap.add_argument("--method", default="fixed-verlet", help="FMU parameter solver.method")
    ap.add_argument("--solver-step", type=float, help="FMU parameter solver.step [s] (default: "
                    + ", ".join(f"{f} {h:g}" for f, h in SOLVER_STEP.items()) + ")")
    ap.add_argument("--rtol", type=float, default=1e-5, help="FMU parameter solver.tolerance")
    ap.add_argument("--newmark-gamma", type=float, default=0.5, help="FMU parameter solver.newmarkGamma (fixed-newmark)")
    ap.add_argument("--out", default=str(paths.RESULTS), help="output directory")


def check(ap, args):
    if args.scene == "cvt":
        return check_cvt(ap, args)
    if args.rpm is None:
        args.rpm = 3000.0
    if args.cycles < 2:
        ap.error(f"--cycles {args.cycles}: at least 2 counted cycles are needed for a confidence interval")
    if args.run_in is not None and args.run_in < 0:
        ap.error(f"--run-in {args.run_in}: must be >= 0 cycles")
    if args.solver_step is None:
        args.solver_step = SOLVER_STEP[args.fidelity]
    return args


def check_cvt(ap, args):
    """The CVT's options: the timing drive's that do not apply are refused, the defaults its own."""
    for option, value, default in (("--drive", args.drive, None), ("--fidelity", args.fidelity, "link"),
                                   ("--coupling", args.coupling, "closed"), ("--tables", args.tables, None)):
        if value != default:
            ap.error(f"{option} {value}: does not apply to the CVT scene (solver alone, link fidelity)")
    if args.revolutions < 2:
        ap.error(f"--revolutions {args.revolutions}: at least 2 counted revolutions are needed for a confidence interval")
    if args.run_in_revolutions < 0:
        ap.error(f"--run-in-revolutions {args.run_in_revolutions}: must be >= 0")
    if args.rpm is None:
        args.rpm = cvt_job.DEFAULT_RPM
    if not 0.0 < args.rpm <= 10000.0:
        ap.error(f"--rpm {args.rpm:g}: the driving speed must lie in (0, 10000] rpm")
    if args.solver_step is None:
        args.solver_step = cvt_job.DEFAULT_STEP
    return args


SHOWN_CYCLES = 4  # counted cycles shown in the time histories after the run-in
CYCLE_PLOT_KEYS = ("tensioner.F.mean", "tensioner.F.peakToPeak", "tensionGuide.phi.peakToPeak_deg",
                   "tensioner.F.order2", "tensioner.F.order8")


def write_plots(out, d, args, t0, per_cycle, summary):
    title = f"{args.rpm:g} rpm, {args.fidelity} fidelity, {args.coupling} loop, {args.method}"
    drive_picture.drive_picture(out / "drive.png", args.drive)
    plots.time_histories(out / "time_histories.png", d, args.rpm, title + f" (run-in and {SHOWN_CYCLES} cycles)",
                         t_end=t0 + SHOWN_CYCLES * 120.0 / args.rpm, t_counted=t0)
    plots.cycle_statistics(out / "cycle_statistics.png", per_cycle, summary, title + ", per engine cycle",
                           CYCLE_PLOT_KEYS)
    plots.spectra(out / "spectra.png", d, args.rpm, t0, title + " (counted cycles)")
    plots.link_cycle(out / "link_cycle.png", d, args.rpm, title + ", one cycle of the monitored link", t0=t0,
                     drive=args.drive)
    return [out / n for n in ("drive.png", "time_histories.png", "cycle_statistics.png", "spectra.png",
                              "link_cycle.png")]


def run_in_cycles(rpm):
    """The default run-in: whole engine cycles, at least RUN_IN_CYCLES and at least RUN_IN_TIME."""
    return max(RUN_IN_CYCLES, math.ceil(RUN_IN_TIME * rpm / 120.0 - 1e-9))


@dataclasses.dataclass
class SceneRun:
    """A scene run through the FMU: its record and what it cost."""
    record: dict            # output and input columns over time
    run_in: int             # engine cycles discarded before the counted ones
    duration: float         # [s] simulated
    cpu: float              # [s] CPU time of the whole loop (FMU and master)
    step_cpus: list | None  # [s] CPU time inside each fmi2DoStep (closed loop only)

    @property
    def step_cpu(self):
        """[s] CPU time inside fmi2DoStep over the run (None in open loop)."""
        return None if self.step_cpus is None else math.fsum(self.step_cpus)

    def cost(self, args):
        """What ran and its cost (run.json): CPU seconds per simulated second of the loop and of
        fmi2DoStep alone (the FMU's own cost; None in open loop)."""
        per_s = None if self.step_cpu is None else self.step_cpu / self.duration
        return {"fidelity": args.fidelity, "rpm": args.rpm, "drive": args.drive, "coupling": args.coupling,
                "method": args.method, "solverStep_s": args.solver_step, "communicationStep_s": args.step,
                "runInCycles": self.run_in, "cycles": args.cycles, "simulated_s": self.duration, "cpu_s": self.cpu,
                "doStepCpu_s": self.step_cpu, "cpuPerSimulatedSecond": self.cpu / self.duration,
                "doStepCpuPerSimulatedSecond": per_s}


def simulate(args, progress=True):
    """Runs the scene of args (the options of this command, checked) through ChainDrive.fmu over
    the run-in and the counted cycles; prints what runs (and a progress bar when progress)."""
    cycle = 2.0 * 60.0 / args.rpm
    run_in = args.run_in if args.run_in is not None else run_in_cycles(args.rpm)
    # a tenth of a cycle and SPEED_MARGIN more, so that the last counted cycle is complete with the
    # speed fluctuation
    duration = ((run_in + args.cycles) * (1.0 + SPEED_MARGIN) + 0.1) * cycle
    torque = tables.camshaft_torque(args.rpm, args.tables)
    speed = tables.crankshaft_speed(args.rpm, args.tables)
    print(f"ChainDrive.fmu, {args.fidelity} fidelity: {args.drive or 'default drive'}, {args.rpm:g} rpm, run-in "
          f"{run_in} + {args.cycles} engine cycles ({duration * 1e3:.1f} ms), {args.coupling}-loop coupling, "
          f"communication step {args.step * 1e6:g} us, {args.method} at {args.solver_step * 1e6:g} us")
    print(f"tables: {torque.path} ({torque.provenance})")
    cpu0 = time.process_time()
    if args.coupling == "closed":
        d, step_cpus = run_closed(args, duration, table_inputs(torque, speed), progress)
    else:
        d, step_cpus = run_open(args, duration, torque, speed)
    return SceneRun(d, run_in, duration, time.process_time() - cpu0, step_cpus)


def cycle_statistics(args, scene_run):
    """(per-cycle values, summary) of the counted cycles of a scene run (harness/cycle_stats.py)."""
    per_cycle = cycle_stats.per_cycle(scene_run.record, scene_run.run_in, meshing_order(drive_json(args.drive)),
                                      args.cycles)
    return per_cycle, cycle_stats.summarize(per_cycle)


def write_summary(out, summary, cost):
    """summary.json (the cycle statistics) and run.json (what ran, its cost) in out."""
    out.mkdir(parents=True, exist_ok=True)
    (out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    (out / "run.json").write_text(json.dumps(cost, indent=1) + "\n")


def report(summary, scene_run):
    """Prints the cycle statistics and the cost; says so when the confidence half-width of the
    tensioner-force mean exceeds 1 %, with the number of cycles that would bring it to 1 %."""
    print(f"\nsummary: mean over engine cycles after a run-in of {scene_run.run_in} cycles, +- the 95 % confidence "
          f"half-width")
    for key, s in summary.items():
        print(cycle_stats.format_line(key, s))
    F = summary["tensioner.F.mean"]
    rel = F["ci95"] / abs(F["mean"])
    if rel > 0.01:
        need = math.ceil(F["cycles"] * (rel / 0.01) ** 2)
        print(f"  note: the tensioner-force mean is known to {100 * rel:.2f} %; about {need} cycles give 1 %")
    cpu, duration = scene_run.cpu, scene_run.duration
    print(f"  CPU time {cpu:.2f} s for {duration * 1e3:.1f} ms simulated: {cpu / duration:.3g} CPU s per simulated s "
          f"(real-time factor, FMU and master loop)")
    if scene_run.step_cpu is not None:
        print(f"  of which inside fmi2DoStep {scene_run.step_cpu:.2f} s: {scene_run.step_cpu / duration:.3g} CPU s per "
              f"simulated s (the FMU alone)")


def run(args):
    if args.scene == "cvt":
        args.out_path = pathlib.Path(args.out)
        return cvt_job.run(args)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    scene_run = simulate(args)
    csv = out / "outputs.csv"
    write_csv(csv, scene_run.record)
    per_cycle, summary = cycle_statistics(args, scene_run)
    write_summary(out, summary, scene_run.cost(args))
    d = scene_run.record
    t0 = d["time"][cycle_stats.cycle_spans(d["crankshaft.phi"], scene_run.run_in)[0][0]]
    pictures = write_plots(out, d, args, t0, per_cycle, summary)
    report(summary, scene_run)
    print(f"  outputs: {csv}, {out / 'summary.json'}, {out / 'run.json'}")
    print("  plots: " + ", ".join(str(p) for p in pictures))
