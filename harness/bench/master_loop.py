"""The main job's closed loop in C against the same loop through fmpy's calls: what each costs
beyond the FMU, on the main job's scene, by turns in one run.

    python -m harness bench-loop [--rpm 1000 3000 6000] [--fidelities link span] [--cycles 8]
                                 [--repeats 7] [--out results/benchmark_master_loop.md]

Per speed and fidelity, the main job's closed loop (harness/job.py run_closed: the tables looked
up at the FMU's angles, the inputs set, fmi2DoStep, the outputs recorded) runs a fixed run-in and
--cycles counted cycles once compiled and once through fmpy, by turns, --repeats times; their
records must have the same bits (checked). Each run's loop CPU is the thread's from its first
fmi2DoStep to its last, its FMU CPU the sum inside fmi2DoStep; printed: the median over the repeats
of loop CPU / FMU CPU for each loop (the target for the compiled one: at most TARGET_RATIO), the
CPU per simulated second of each, and the model's median and worst step under each loop (each
step's least CPU over the repeats: what the loop between the steps does to the FMU's caches
shows there). The machine heads the report.
"""
import statistics

import numpy as np

from .. import job, paths, runs
from ..drive.description import elements as drive_elements
from ..tables import tables

TARGET_RATIO = 1.15  # the compiled loop's CPU from its first fmi2DoStep to its last over that inside them


def add_arguments(ap):
    ap.add_argument("--rpm", type=float, nargs="+", default=[1000.0, 3000.0, 6000.0], help="engine speeds [rpm]")
    ap.add_argument("--fidelities", nargs="+", choices=job.FIDELITIES, default=list(job.FIDELITIES))
    ap.add_argument("--cycles", type=int, default=8, help="engine cycles after the run-in")
    ap.add_argument("--repeats", type=int, default=7,
                    help="runs of each loop, by turns (the worst step's least CPU needs about 7 on a shared host)")
    ap.add_argument("--out", default=str(paths.RESULTS / "benchmark_master_loop.md"))


def check(ap, args):
    if args.cycles < 1:
        ap.error(f"--cycles {args.cycles}: at least 1 engine cycle")
    if args.repeats < 1:
        ap.error(f"--repeats {args.repeats}: at least 1 run of each loop")
    return args


def one_run(config, compiled):
    """(record, CPU inside each fmi2DoStep, loop CPU) [s] of the scene's closed loop."""
    elements = drive_elements(config.drive)
    inputs = job.table_inputs(job.drive_loads(config, elements), tables.crankshaft_speed(config.rpm), elements)
    record, step_cpus, loop_cpu = job.run_closed(config, job.duration_of(config), inputs, progress=False,
                                                 compiled=compiled)
    return record, np.array(step_cpus), loop_cpu


def measure(args, rpm, fidelity):
    """{loop: [(CPU inside each fmi2DoStep, loop CPU)] over the repeats}, and the simulated duration [s]."""
    config = job.run_config(rpm=rpm, fidelity=fidelity, cycles=args.cycles, run_in=job.run_in_cycles(rpm))
    found, reference = {"compiled": [], "python": []}, None
    for _ in range(args.repeats):
        for loop in found:
            record, step_cpus, loop_cpu = one_run(config, loop == "compiled")
            if reference is None:
                reference = record
            elif any(not np.array_equal(record[c], reference[c]) for c in reference):
                raise RuntimeError(f"{fidelity} at {rpm:g} rpm: the {loop} loop's record differs from the first run's")
            found[loop].append((step_cpus, loop_cpu))
    return found, float(reference["time"][-1])


def model_steps(runs_):
    """[us] median and max over the steps (the first, the start's, left out) of each step's least
    CPU inside fmi2DoStep over the runs: the model's own step cost, the machine's interruptions
    left in one run's step, not in the same step of every run."""
    least = np.min([cpus[1:] for cpus, _ in runs_], axis=0) * 1e6
    return float(np.median(least)), float(least.max())


def line_of(rpm, fidelity, found, duration):
    """One row: per loop the CPU inside fmi2DoStep and from the first to the last per simulated s
    and their ratio (medians over the repeats), and the model's median and worst step."""
    ratio = {loop: statistics.median(c / f.sum() for f, c in runs_) for loop, runs_ in found.items()}
    per_s = {loop: statistics.median(c for _, c in runs_) / duration for loop, runs_ in found.items()}
    fmu_per_s = {loop: statistics.median(f.sum() for f, _ in runs_) / duration for loop, runs_ in found.items()}
    steps = {loop: "%.1f / %.1f" % model_steps(runs_) for loop, runs_ in found.items()}
    verdict = "meets" if ratio["compiled"] <= TARGET_RATIO else "MISSES"
    return (f"| {rpm:g} | {fidelity} | {fmu_per_s['compiled']:.3g} | {per_s['compiled']:.3g} | "
            f"**{ratio['compiled']:.3f}** ({verdict}) | {steps['compiled']} | {fmu_per_s['python']:.3g} | "
            f"{per_s['python']:.3g} | {ratio['python']:.2f} | {steps['python']} |")


def run(args):
    lines = ["# The main job's master loop: compiled against fmpy's calls", "",
             f"Machine: {runs.machine()}; command: python -m harness bench-loop {' '.join(args.argv)}", "",
             f"The main job's closed loop, a fixed run-in and {args.cycles} counted cycles, each loop run "
             f"{args.repeats} times by turns with the same record bits. CPU of the thread from the first fmi2DoStep "
             f"to the last per simulated s, and over that inside fmi2DoStep (median of the repeats; target for "
             f"the compiled loop at most {TARGET_RATIO}). The model's step: each step's least CPU inside fmi2DoStep "
             f"over the repeats (the first step left out), its median and maximum over the steps.", "",
             "| rpm | fidelity | compiled loop: inside fmi2DoStep [CPU s/s] | first to last fmi2DoStep | ratio | "
             "model's step: median / worst [us] | fmpy's loop: inside fmi2DoStep | first to last | ratio | "
             "model's step: median / worst [us] |", "|---|---|---|---|---|---|---|---|---|---|"]
    print("\n".join(lines), flush=True)
    for rpm in args.rpm:
        for fidelity in args.fidelities:
            lines.append(line_of(rpm, fidelity, *measure(args, rpm, fidelity)))
            print(lines[-1], flush=True)
    runs.write_lines(args.out, lines)
    return 0
