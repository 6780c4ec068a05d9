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

Two couplings:
  closed (default)  the way an engine simulator couples: a master loop (fmpy FMU2Slave) looks the
                    camshaft torques up at the FMU's own camshaft angles and the crankshaft speed
                    at its crankshaft angle, at every communication step;
  open              the tables turned into time series at the mean speed and passed to
                    fmpy.simulate_fmu as input.

    python -m harness run [--rpm 3000] [--cycles N] [--run-in S] [--coupling closed|open] [--step 1e-4]
                          [--method fixed-verlet] [--solver-step 2.5e-6] [--drive FILE] [--out results]
"""
import json
import math
import pathlib
import sys
import time

import numpy as np

from . import cycle_stats, paths
from .drive.description import drive_json, meshing_order
from .fmu import fmu
from .plots import drive_picture, plots
from .tables import tables

RUN_IN_CYCLES = 2          # the run-in: at least this many engine cycles ...
RUN_IN_TIME = 0.15         # [s] ... and at least this long
DEFAULT_CYCLES = 120       # counted engine cycles of the default run (see README: 1 % confidence)

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
    p = {"solver.method": args.method, "solver.step": args.solver_step, "solver.tolerance": args.rtol}
    if args.drive:
        p["driveFile"] = str(pathlib.Path(args.drive).resolve())
    return p


def run_closed(args, duration, torque, speed):
    """Master loop: inputs looked up at the FMU's own angles before every step."""
    s = fmu.Slave("chaindrive", parameters=parameters_of(args))
    n = int(round(duration / args.step))
    w0 = speed_at(speed, 0.0)
    s.initialize(inputs={"crankshaft.w": w0,
                         "camshaftIntake.tau": float(tables.lookup(torque, "camshaftIntake.tau", 0.0)),
                         "camshaftExhaust.tau": float(tables.lookup(torque, "camshaftExhaust.tau", 0.0))})
    names = s.outputs
    rows = [[0.0] + [s.get(names)[k] for k in names] + [w0, np.nan, np.nan]]
    prog = Progress(duration, "closed loop")
    for k in range(n):
        o = s.get(["crankshaft.phi", "camshaftIntake.phi", "camshaftExhaust.phi"])
        crank_deg = math.degrees(o["crankshaft.phi"])
        # camshafts turn at half the crankshaft speed; the tables are over crank angle
        u = {"crankshaft.w": speed_at(speed, crank_deg),
             "camshaftIntake.tau": float(tables.lookup(torque, "camshaftIntake.tau", 2.0 * math.degrees(o["camshaftIntake.phi"]))),
             "camshaftExhaust.tau": float(tables.lookup(torque, "camshaftExhaust.tau", 2.0 * math.degrees(o["camshaftExhaust.phi"])))}
        s.step(args.step, inputs=u, t=k * args.step)
        v = s.get(names)
        rows.append([(k + 1) * args.step] + [v[x] for x in names] + [u["crankshaft.w"], u["camshaftIntake.tau"],
                                                                    u["camshaftExhaust.tau"]])
        prog.update((k + 1) * args.step)
    prog.done()
    s.close()
    cols = ["time"] + names + ["input.crankshaft.w", "input.camshaftIntake.tau", "input.camshaftExhaust.tau"]
    return {c: np.array([r[i] for r in rows]) for i, c in enumerate(cols)}


def speed_at(speed, crank_deg):
    col = "crankshaft.speed_rpm" if "crankshaft.speed_rpm" in speed.columns else "crankshaft.w"
    v = float(tables.lookup(speed, col, crank_deg))
    return v * 2.0 * math.pi / 60.0 if col.endswith("_rpm") else v


def run_open(args, duration, torque, speed):
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
    return out


def write_csv(path, d):
    cols = list(d)
    with open(path, "w") as f:
        f.write(",".join(cols) + "\n")
        np.savetxt(f, np.column_stack([d[c] for c in cols]), delimiter=",", fmt="%.10g")


def add_arguments(ap):
    ap.add_argument("--drive", help="drive description (default: the FMU's default drive)")
    ap.add_argument("--rpm", type=float, default=3000.0, help="mean engine speed [rpm], 1000-6000 (tables)")
    ap.add_argument("--cycles", type=int, default=DEFAULT_CYCLES,
                    help=f"engine cycles (720 deg crank) counted after the run-in (default {DEFAULT_CYCLES})")
    ap.add_argument("--run-in", type=int, help=f"engine cycles discarded before the first counted one (default: "
                    f"at least {RUN_IN_CYCLES} and at least {RUN_IN_TIME:g} s)")
    ap.add_argument("--coupling", choices=("closed", "open"), default="closed")
    ap.add_argument("--tables", help="directory of the torque/speed tables (default harness/tables/data)")
    ap.add_argument("--step", type=float, default=1e-4, help="communication step [s]")
    ap.add_argument("--method", default="fixed-verlet", help="FMU parameter solver.method")
    ap.add_argument("--solver-step", type=float, default=2.5e-6, help="FMU parameter solver.step [s]")
    ap.add_argument("--rtol", type=float, default=1e-5, help="FMU parameter solver.tolerance")
    ap.add_argument("--out", default=str(paths.RESULTS), help="output directory")


def check(ap, args):
    if args.cycles < 2:
        ap.error(f"--cycles {args.cycles}: at least 2 counted cycles are needed for a confidence interval")
    if args.run_in is not None and args.run_in < 0:
        ap.error(f"--run-in {args.run_in}: must be >= 0 cycles")
    return args


SHOWN_CYCLES = 4  # counted cycles shown in the time histories after the run-in
CYCLE_PLOT_KEYS = ("tensioner.F.mean", "tensioner.F.peakToPeak", "tensionGuide.phi.peakToPeak_deg",
                   "tensioner.F.order2", "tensioner.F.order8")


def write_plots(out, d, args, t0, per_cycle, summary):
    title = f"{args.rpm:g} rpm, {args.coupling} loop, {args.method}"
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


def report(summary, run_in, cpu, duration):
    """Prints the cycle statistics and the cost; says so when the confidence half-width of the
    tensioner-force mean exceeds 1 %, with the number of cycles that would bring it to 1 %."""
    print(f"\nsummary: mean over engine cycles after a run-in of {run_in} cycles, +- the 95 % confidence "
          f"half-width")
    for key, s in summary.items():
        print(cycle_stats.format_line(key, s))
    F = summary["tensioner.F.mean"]
    rel = F["ci95"] / abs(F["mean"])
    if rel > 0.01:
        need = math.ceil(F["cycles"] * (rel / 0.01) ** 2)
        print(f"  note: the tensioner-force mean is known to {100 * rel:.2f} %; about {need} cycles give 1 %")
    print(f"  CPU time {cpu:.2f} s for {duration * 1e3:.1f} ms simulated: {cpu / duration:.2f} CPU s per simulated s "
          f"(real-time factor, FMU and master loop)")


def run(args):
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    cycle = 2.0 * 60.0 / args.rpm
    run_in = args.run_in if args.run_in is not None else run_in_cycles(args.rpm)
    # a tenth of a cycle more, so that the last counted cycle is complete with the speed fluctuation
    duration = (run_in + args.cycles + 0.1) * cycle
    torque = tables.camshaft_torque(args.rpm, args.tables)
    speed = tables.crankshaft_speed(args.rpm, args.tables)
    print(f"ChainDrive.fmu: {args.drive or 'default drive'}, {args.rpm:g} rpm, run-in {run_in} + "
          f"{args.cycles} engine cycles ({duration * 1e3:.1f} ms), {args.coupling}-loop coupling, communication "
          f"step {args.step * 1e6:g} us, {args.method}")
    print(f"tables: {torque.path} ({torque.provenance})")
    cpu0 = time.process_time()
    d = run_closed(args, duration, torque, speed) if args.coupling == "closed" else run_open(args, duration, torque, speed)
    cpu = time.process_time() - cpu0
    csv = out / "outputs.csv"
    write_csv(csv, d)
    per_cycle = cycle_stats.per_cycle(d, run_in, meshing_order(drive_json(args.drive)))
    summary = cycle_stats.summarize(per_cycle)
    (out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    t0 = d["time"][cycle_stats.cycle_spans(d["crankshaft.phi"], run_in)[0][0]]
    pictures = write_plots(out, d, args, t0, per_cycle, summary)
    report(summary, run_in, cpu, duration)
    print(f"  outputs: {csv}, {out / 'summary.json'}")
    print("  plots: " + ", ".join(str(p) for p in pictures))
