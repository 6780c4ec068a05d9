"""Real-time benchmark of the link model through ChainDrive.fmu: the CPU time inside fmi2DoStep per
simulated second (the real-time factor a hardware-in-the-loop rig sees), its spread over the
communication steps, and the accuracy of the same runs against a reference, at each speed.

    python -m harness bench-realtime [--rpm 3000 6000] [--cycles 24] [--repeats 2]
                                     [--method fixed-verlet-implicit-joint-damping] [--solver-step 3.5714e-6]
                                     [--newmark-gamma G] [--reference RPM=SUMMARY.json ...] [--replicas K]
                                     [--out results/benchmark_realtime.md]

The default is the real-time method: fixed-verlet-implicit-joint-damping at 1e-4 / 28 s (3.57 us,
28 steps per 0.1 ms communication step), about three quarters of its stable step (about 4.6 us
in closed loop at 6000 rpm; plain fixed-verlet's is 3.1-3.2 us).

Each speed runs the main job (harness/job.py: ChainDrive.fmu in closed loop with the measured-torque
tables at 0.1 ms communication steps, after its run-in) and reads the CPU time of every
fmi2DoStep; the master's own Python loop is not counted (a rig's master is not Python). Each
speed runs --repeats times; the runs must give the same bits (checked: a difference is an error),
so a step costs the model the same in each, and the smallest of a step's CPU times over the runs is
the model's cost of that step: an interruption of the machine (another process, the hypervisor)
lands on one run's step, not on the same step of every run. Printed per speed: the real-time
factor RTF = CPU s inside fmi2DoStep per simulated s (of each run; the target is judged on the
slowest), and the CPU time per fmi2DoStep (median, p99, max; p99 / median and max / median) of the
model (the per-step minimum; judged against the targets, TARGETS) and of the first run as measured
(the machine's interruptions included). With a reference for the speed (the summary.json of
`python -m harness run --out DIR`, for example a long run at a small step), the accuracy table: per quantity the reference and this
run with their 95 % half-widths over engine cycles, the difference and the tolerance (TOLERANCES).
With --replicas K the accuracy is that of an ensemble (harness/replicas.py): the first timed run
and K - 1 runs with the crankshaft-speed input perturbed, each interval from the spread between
their means (at 6000 rpm with the hydraulic tensioner, one run's intervals understate the guide's
peak-to-peak's; compare with a reference made the same way, `python -m harness run --replicas K`).
The machine heads the report, which is also written as Markdown to --out, and its figures as JSON
beside it (the same name, .json; `python -m harness realtime-chart` draws them). Run nothing else on
the machine meanwhile: CPU timings of shared cores are noisy (compare medians and ratios of one run).

Hosts differ: the same build, the same instructions per link and step, has run 2.9 times as fast on
one host as on another. The report therefore starts with the host's speed on a fixed workload (HOST_WORKLOAD:
the solver alone, plain Verlet at 2.5 us, 3000 rpm; the CPU of a 0.3 s run minus that of a 0.1 s
run, so the start drops out; median of HOST_REPEATS), as CPU s per simulated s and ns per link and step: RTFs
of different hosts compare through it.
"""
import json
import math
import pathlib
import tempfile

import numpy as np

from .. import job, paths, replicas, runs
from ..drive.description import drive_json
from ..study import ladder

# real-time factor targets per speed [CPU s inside fmi2DoStep per simulated s]: a quarter of real time
# at 3000 rpm and about a third at 6000 rpm, a hardware-in-the-loop rig's budget for one model in its
# frame (room for I/O, the rest of the plant and several drives per core); spread targets
RTF_TARGET = {3000.0: 0.25, 6000.0: 0.35}
P99_TARGET, MAX_TARGET = 1.5, 3.0  # p99 / median and max / median of the CPU per fmi2DoStep
# [s] the model's worst fmi2DoStep of 0.1 ms (each step's least CPU over the runs): well inside a
# 10 kHz hardware-in-the-loop frame, room left for the rig's own I/O
WORST_STEP_TARGET = 60e-6
# the host's speed: the solver alone on the default drive, plain Verlet at 2.5 us
HOST_WORKLOAD = dict(rpm=3000.0, integrator="fixed-verlet", step=2.5e-6, output_step=1e-3)
HOST_DURATIONS, HOST_REPEATS = (0.1, 0.3), 3
# the accuracy a real-time method must keep against the reference
TOLERANCES = ("tensioner.F.mean=2%", "chain.Ftight.mean=2%", "chain.Fslack.mean=2%",
              "tensionGuide.phi.peakToPeak_deg=10%", "tensioner.F.order2=3dB", "tensioner.F.order4=3dB",
              "tensioner.F.order6=3dB", "tensioner.F.order8=3dB")


def add_arguments(ap):
    ap.add_argument("--rpm", type=float, nargs="+", default=[3000.0, 6000.0], help="engine speeds [rpm]")
    ap.add_argument("--cycles", type=int, default=24, help="engine cycles counted after the run-in")
    ap.add_argument("--replicas", type=int, default=1, metavar="K",
                    help="the accuracy over K runs: the first timed run and K - 1 with the crankshaft-speed input "
                    "perturbed (harness/replicas.py; default 1)")
    ap.add_argument("--repeats", type=int, default=2,
                    help="runs per speed (bit-identical; their per-step minimum is the model's cost per step)")
    ap.add_argument("--method", default=job.REALTIME_METHOD, help="FMU parameter solver.method")
    ap.add_argument("--solver-step", type=float,
                    help="FMU parameter solver.step [s] (default: the drive's own step of the method, 1e-4 / 28 for the "
                    "default drive's real-time method)")
    ap.add_argument("--newmark-gamma", type=float, default=0.5, help="FMU parameter solver.newmarkGamma (fixed-newmark)")
    ap.add_argument("--reference", action="append", default=[], metavar="RPM=SUMMARY",
                    help="summary.json of a reference run at that speed (repeatable)")
    ap.add_argument("--drive", help="drive description (default: the default drive; another runs its own export)")
    ap.add_argument("--tables", help="directory of the torque/speed tables (default harness/tables/data)")
    ap.add_argument("--load", action="append", default=[], metavar="NAME=VALUE",
                    help="a constant load torque [N m] on the loaded sprocket NAME instead of its table (repeatable)")
    ap.add_argument("--threads", type=int, default=1,
                    help="FMU parameter solver.threads; more than 1: every step timed by the wall clock")
    ap.add_argument("--master-loop", choices=job.MASTER_LOOPS, default=job.MASTER_LOOPS[0],
                    help="the closed loop compiled (default) or through fmpy's calls (the same bits; the model's CPU "
                    "differs with what the loop does to the caches between the steps)")
    ap.add_argument("--out", default=str(paths.RESULTS / "benchmark_realtime.md"))


def check(ap, args):
    args.loads = tuple(job.constant_load(ap, text) for text in args.load)
    args.references = {}
    for spec in args.reference:
        rpm, sep, path = spec.partition("=")
        try:
            args.references[float(rpm)] = json.loads(pathlib.Path(path).read_text())
        except ValueError:
            ap.error(f"--reference {spec!r}: not RPM=SUMMARY.json with a number and a summary of python -m harness run")
        except OSError as e:
            ap.error(f"--reference {spec!r}: {e}")
        if not sep:
            ap.error(f"--reference {spec!r}: not of the form RPM=SUMMARY.json")
    if args.cycles < 2:
        ap.error(f"--cycles {args.cycles}: at least 2 counted cycles are needed for a confidence interval")
    if args.repeats < 1:
        ap.error(f"--repeats {args.repeats}: at least 1 run per speed")
    if args.replicas < 1:
        ap.error(f"--replicas {args.replicas}: at least 1 run per speed")
    return args


def scene_config(args, rpm):
    """The main job's configuration at one speed (no --solver-step: the fidelity's default)."""
    return job.run_config(rpm=rpm, cycles=args.cycles, method=args.method, newmark_gamma=args.newmark_gamma,
                          solver_step=args.solver_step or None, drive=getattr(args, "drive", None),
                          tables=getattr(args, "tables", None), loads=getattr(args, "loads", ()),
                          master_loop=getattr(args, "master_loop", None), threads=getattr(args, "threads", None))


def spread(cpu):
    """Median, p99 and max of CPU times per step."""
    return dict(median=float(np.median(cpu)), p99=float(np.percentile(cpu, 99)), max=float(cpu.max()))


def timing(scene_runs, steps_per_cycle):
    """RTF of each run and of the model (rtfModel: each step's minimum over the runs, summed), and the
    spread of the CPU per fmi2DoStep (the first step, which carries the start, left out): of the
    model and of the first run as measured; and the spread the model itself makes over the crank
    angle: the median of the model's step costs over the cycles at each crank angle, its largest
    over its smallest."""
    all_steps = np.array([r.step_cpus for r in scene_runs])
    per_run = all_steps[:, 1:]
    model = per_run.min(axis=0)
    cycles = len(model) // steps_per_cycle
    by_angle = np.median(model[:cycles * steps_per_cycle].reshape(cycles, steps_per_cycle), axis=0)
    return dict(rtf=[r.step_cpu / r.duration for r in scene_runs], steps=len(model), runs=len(scene_runs),
                rtfModel=math.fsum(all_steps.min(axis=0)) / scene_runs[0].duration,
                model=spread(model), measured=spread(per_run[0]), by_angle=float(by_angle.max() / by_angle.min()),
                cycles=cycles, first=float(all_steps[:, 0].min()))


def host_speed():
    """HOST_WORKLOAD without its start, the median over HOST_REPEATS: CPU s per simulated s and
    CPU s per link and step (the steps as the runs count them, the links of the default drive)."""
    links = drive_json()["chain"]["numberOfLinks"]
    per_s, per_link_step = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(HOST_REPEATS):
            short, long = (runs.run(pathlib.Path(tmp) / "host.csv", duration=d, **HOST_WORKLOAD)[2]
                           for d in HOST_DURATIONS)
            cpu = long["cpu"] - short["cpu"]
            per_s.append(cpu / (long["simulated"] - short["simulated"]))
            per_link_step.append(cpu / (long["steps"] - short["steps"]) / links)
    return float(np.median(per_s)), float(np.median(per_link_step))


def host_line(cpu_per_s, cpu_per_link_step):
    return (f"Host speed: the solver alone (chaindrive-run, fixed-verlet at 2.5 us, 3000 rpm, outputs every 1 ms, "
            f"the start left out) {cpu_per_s:.3g} CPU s per simulated s, "
            f"{cpu_per_link_step * 1e9:.1f} ns per link and step (median of {HOST_REPEATS})")


def verdict(ok):
    return "meets" if ok else "MISSES"


def spread_text(sp):
    return (f"median {sp['median'] * 1e6:.0f} us, p99 {sp['p99'] * 1e6:.0f} us, max {sp['max'] * 1e6:.0f} us; "
            f"p99 / median {sp['p99'] / sp['median']:.2f}, max / median {sp['max'] / sp['median']:.2f}")


def timing_lines(rpm, t, step):
    target = RTF_TARGET.get(rpm)
    rtf = max(t["rtf"])
    model = t["model"]
    p99, mx = model["p99"] / model["median"], model["max"] / model["median"]
    rtf_verdict = f" (target <= {target:g}: {verdict(rtf <= target)})" if target else ""
    runs = ", ".join(f"{x:.3g}" for x in t["rtf"])
    return [f"- RTF (CPU s inside fmi2DoStep per simulated s): **{rtf:.3g}**{rtf_verdict}"
            + (f" (the slowest of {t['runs']} bit-identical runs: {runs}; the model's, each step's minimum over "
               f"the runs: {t['rtfModel']:.3g})" if t["runs"] > 1 else ""),
            f"- CPU per fmi2DoStep of {step * 1e3:g} ms over {t['steps']} steps, the model's (each step's minimum over "
            f"the {t['runs']} runs): {spread_text(model)} (targets: p99 / median <= {P99_TARGET:g}: "
            f"{verdict(p99 <= P99_TARGET)}; max / median <= {MAX_TARGET:g}: {verdict(mx <= MAX_TARGET)}; max <= "
            f"{WORST_STEP_TARGET * 1e6:g} us: {verdict(model['max'] <= WORST_STEP_TARGET)})",
            f"- the same as measured in the first run (the machine's interruptions included): "
            f"{spread_text(t['measured'])}; the first step after the initialization (left out above): "
            f"{t.get('first', math.nan) * 1e6:.0f} us",
            f"- the model's own spread: the median over {t['cycles']} cycles at each crank angle varies by a factor "
            f"{t['by_angle']:.2f} over the cycle"]


def cycles_cell(stat):
    """The cycles a statistic is over: "480 cycles", or "4 x 480 cycles" of an ensemble."""
    k = stat.get("replicas", 1)
    return f"{stat['cycles']} cycles" if k == 1 else f"{k} x {stat['cycles'] // k} cycles"


def accuracy_rows(reference, summary):
    """ladder.compare's rows of the quantities with a tolerance (TOLERANCES)."""
    # (the tension guide by the drive's name: the summary's guide key)
    guide = next((k[:-len(".phi.peakToPeak_deg")] for k in summary if k.endswith(".phi.peakToPeak_deg")), "tensionGuide")
    tolerances = [ladder.parse_tolerance(t.replace("tensionGuide", guide), list(summary)) for t in TOLERANCES]
    return ladder.compare(reference, summary, tolerances)


def accuracy_lines(reference, summary, rows):
    lines = ["| quantity | reference | this run | difference | tolerance | meets | within scatter |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        ref, run = r["link"], r["span"]
        ref_cycles, run_cycles = cycles_cell(reference[r["key"]]), cycles_cell(summary[r["key"]])
        lines.append(f"| {r['key']} | {ref['mean']:.4g} +- {ref['ci95']:.2g} {r['unit']} ({ref_cycles}) | "
                     f"{run['mean']:.4g} +- {run['ci95']:.2g} {r['unit']} ({run_cycles}) | "
                     f"{r['difference']:+.2f} {r['differenceUnit']} | {r['tolerance']:g} {r['differenceUnit']} | "
                     f"{'yes' if r['meets'] else 'NO'} | {'yes' if r['withinScatter'] else 'no'} (z {r['z']:+.2f}) |")
    return lines


def ensemble_summary(config, first, count):
    """The ensemble's summary of the first run's (first) and count - 1 perturbed replicas'."""
    summaries = [first] + [job.cycle_statistics(c, job.simulate(c))[1]
                           for c in (replicas.replica_config(config, k) for k in range(1, count))]
    return replicas.combine(summaries)


def difference(scene_runs):
    """None when the repeated runs' records agree bit for bit (their step costs are then compared
    step by step), else what differs."""
    first = scene_runs[0].record
    for k, r in enumerate(scene_runs[1:], 2):
        differing = [c for c in first if np.asarray(first[c]).tobytes() != np.asarray(r.record[c]).tobytes()]
        if differing:
            return f"run {k} differs from run 1 in {', '.join(differing[:5])}: repeated runs must give the same bits"
    return None


# what every speed of a report's JSON holds (speed_record), and the report itself
SPEED_KEYS = ("rpm", "method", "step", "rtf", "p99OverMedian", "accuracy")
REPORT_KEYS = ("host", "speeds")


def load_report(ap, path):
    """A JSON report of this benchmark read for another command (its parser ap reports a file that
    is not one, naming the file and what is missing)."""
    try:
        report = json.loads(pathlib.Path(path).read_text())
    except (OSError, ValueError) as e:
        ap.error(f"{path}: not a readable JSON report of bench-realtime ({e})")
    missing = [k for k in REPORT_KEYS if not isinstance(report, dict) or k not in report]
    if not missing:
        missing = [f"speeds[{i}].{k}" for i, s in enumerate(report["speeds"]) for k in SPEED_KEYS
                   if not isinstance(s, dict) or k not in s]
    if missing:
        ap.error(f"{path}: not a report of bench-realtime (no {', '.join(missing[:3])}; reports written before "
                 f"bench-realtime wrote JSON have only their Markdown)")
    return report


def model_rtf(speed):
    """A report's speed's RTF for comparing methods: the model's (each step's minimum over the
    repeated runs, summed: the machine's interruptions left out) where the report has it, else the
    slowest run's (reports written before it had it)."""
    return speed.get("rtfModel", speed["rtf"])


def speed_record(rpm, config, t, rows):
    """One speed of the report's JSON: the method, its timing (t: timing()) and its accuracy rows
    (empty without a reference)."""
    return dict(rpm=rpm, method=config.method, step=config.solver_step, cycles=config.cycles,
                rtf=max(t["rtf"]), rtfRuns=t["rtf"], rtfModel=t["rtfModel"], rtfTarget=RTF_TARGET.get(rpm),
                model=t["model"], firstStep=t["first"], masterLoop=config.master_loop,
                p99OverMedian=t["model"]["p99"] / t["model"]["median"], accuracy=rows)


def run(args):
    command, machine = f"python -m harness bench-realtime {' '.join(args.argv)}", runs.machine()
    host = host_speed()
    lines = ["# Real-time benchmark: the link model through ChainDrive.fmu", "",
             f"Machine: {machine}; command: {command}", "", host_line(*host), ""]
    record = dict(machine=machine, command=command, replicas=args.replicas,
                  host=dict(cpuPerSimulatedSecond=host[0], cpuPerLinkStep=host[1]), speeds=[])
    print("\n".join(lines))
    for rpm in args.rpm:
        config = scene_config(args, rpm)
        scene_runs = [job.simulate(config) for _ in range(args.repeats)]
        if (message := difference(scene_runs)) is not None:
            print(f"error at {rpm:g} rpm: {message}")
            return 1
        scene_run = scene_runs[0]
        _, summary = job.cycle_statistics(config, scene_run)
        section = [f"## {rpm:g} rpm: {config.method} at {config.solver_step * 1e6:g} us, closed loop "
                   f"({config.master_loop} master loop), {args.cycles} cycles after {scene_run.run_in} run-in", ""]
        if config.threads > 1:
            section += [f"On {config.threads} threads (solver.threads): every time below is the wall clock's, not "
                        "the calling thread's CPU time", ""]
        steps_per_cycle = round(120.0 / rpm / config.step)  # (an engine cycle: two crank revolutions)
        t = timing(scene_runs, steps_per_cycle)
        section += timing_lines(rpm, t, config.step) + [""]
        reference, rows = args.references.get(rpm), []
        if reference:
            if args.replicas > 1:
                summary = ensemble_summary(config, summary, args.replicas)
                section.append(f"Accuracy over {args.replicas} replicas (harness/replicas.py):")
            rows = accuracy_rows(reference, summary)
            section += accuracy_lines(reference, summary, rows) + [""]
        print("\n".join(section))
        lines += section
        record["speeds"].append(speed_record(rpm, config, t, rows))
    runs.write_lines(args.out, lines)
    runs.write_json(pathlib.Path(args.out).with_suffix(".json"), record)
    return 0
