"""The span model's cost against the link model's real-time method, both through ChainDrive.fmu in
the same run on one core: the ratio the fidelity ladder promises.

    python -m harness bench-fidelity [--rpm 1000 3000 6000] [--cycles 8] [--repeats 3]
                                     [--drive FILE] [--out results/benchmark_fidelity_cost.md]

Per speed and communication step (0.1 ms, the main job's, and 1 ms, an engine simulator's), the
main job's scene (harness/job.py: closed loop with the measured-torque tables, the run-in and
--cycles counted cycles) runs once per model through fmpy, its inputs recorded: the link model
with the real-time method (job.REALTIME_METHOD at job.REALTIME_STEP) and the span model with its
defaults (harness/defaults.py). Then a C master (harness/package/fmi2_master.c, built here with
the system's compiler) replays each run's inputs --repeats times, by turns, and sums the thread's
CPU time inside fmi2DoStep; its outputs must have the bits of the fmpy run's (checked). A model's
RTF is that CPU time per simulated second, the smallest of the repeats (the run the machine
disturbed least): the FMU's own cost as a compiled master sees it. fmpy's RTF, measured around
its fmi2DoStep calls from Python, is printed beside it; it adds the interpreter's call overhead,
about 2-4 us per call, which outweighs the span model's own cost at 0.1 ms steps. Printed per
speed and communication step: both models' RTFs and their ratio (span / link; target at most
TARGET_RATIO). The machine heads the report. Run nothing else meanwhile.
"""
import pathlib
import re
import tempfile

import numpy as np

from .. import job, paths, runs
from ..fmu import export, fmu
from ..package import compare

TARGET_RATIO = 1.0 / 20.0  # span / link real-time method, CPU inside fmi2DoStep
COMMUNICATION_STEPS = (1e-4, 1e-3)  # [s] the main job's, and an engine simulator's


def add_arguments(ap):
    ap.add_argument("--rpm", type=float, nargs="+", default=[1000.0, 3000.0, 6000.0], help="engine speeds [rpm]")
    ap.add_argument("--cycles", type=int, default=8, help="engine cycles counted after the run-in")
    ap.add_argument("--repeats", type=int, default=3, help="C-master replays per run, by turns (the smallest counts)")
    ap.add_argument("--drive", help="drive description (docs/drive_schema.md; default: the default drive), "
                    "both models of it (a span model with its dynamics calibrated: its description's spanModel)")
    ap.add_argument("--out", default=str(paths.RESULTS / "benchmark_fidelity_cost.md"))


def check(ap, args):
    if args.cycles < 1:
        ap.error(f"--cycles {args.cycles}: at least 1 counted cycle")
    if args.repeats < 1:
        ap.error(f"--repeats {args.repeats}: at least 1 replay per run")
    return args


def config_of(args, rpm, fidelity, step):
    """The run of a fidelity at one speed, its run-in fixed (the replays run the same duration)."""
    run_in = job.run_in_cycles(rpm)
    if fidelity == "link":
        return job.run_config(rpm=rpm, cycles=args.cycles, step=step, method=job.REALTIME_METHOD,
                              solver_step=job.REALTIME_STEP, run_in=run_in, drive=args.drive)
    return job.run_config(rpm=rpm, cycles=args.cycles, step=step, fidelity=fidelity, run_in=run_in,
                          drive=args.drive)


class Replayer:
    """The C master on the drive's FMU (the one the fmpy runs use), in a work folder."""

    def __init__(self, work, drive=None):
        self.work = pathlib.Path(work)
        self.master = compare.build_linux_master(self.work)
        self.fmu_dir = pathlib.Path(fmu.unpacked(export.fmu_for(drive))[1])
        self.binary = self.fmu_dir / "binaries" / "linux64" / f"{compare.model_identifier(self.fmu_dir)}.so"
        self.uri = (self.fmu_dir / "resources").resolve().as_uri()

    def cpu(self, run, step):
        """[s] CPU inside fmi2DoStep of one replay; an error if its outputs differ from the run's."""
        replayed = compare.replay([str(self.master)], self.binary, self.uri, self.fmu_dir, run, self.work, step)
        same = compare.compare(run, replayed)
        if not same.identical:
            raise RuntimeError(f"the C master's replay differs from fmpy's run: {same.first}")
        found = re.search(r"([0-9.]+) s CPU inside fmi2DoStep", replayed.log[-1])
        return float(found.group(1))


def measure(args, replayer, rpm, step):
    """{fidelity: (C master's RTF, fmpy's RTF, config)} at one speed and communication step."""
    recorded = {}
    for fidelity in ("link", "span"):
        config = config_of(args, rpm, fidelity, step)
        duration = job.duration_of(config)
        run, step_cpus = compare.run_recorded(config, duration)
        recorded[fidelity] = (run, duration, float(np.sum(step_cpus)) / duration, config)
    cpus = {fidelity: [] for fidelity in recorded}
    for _ in range(args.repeats):
        for fidelity, (run, duration, _, _) in recorded.items():
            cpus[fidelity].append(replayer.cpu(run, step) / duration)
    return {f: (min(cpus[f]), fmpy_rtf, config) for f, (_, _, fmpy_rtf, config) in recorded.items()}


def lines_of(step, found):
    (link, link_fmpy, config), (span, span_fmpy, _) = found["link"], found["span"]
    ratio, ratio_fmpy = span / link, span_fmpy / link_fmpy
    return [f"- {step * 1e3:g} ms communication steps: link model ({config.method} at "
            f"{config.solver_step * 1e6:.4g} us) RTF **{link:.3g}**, span model RTF **{span:.3g}**: ratio "
            f"**1/{1.0 / ratio:.1f}** (target at most 1/{1.0 / TARGET_RATIO:g}: "
            f"{'meets' if ratio <= TARGET_RATIO else 'MISSES'}); through fmpy {link_fmpy:.3g} and "
            f"{span_fmpy:.3g}, 1/{1.0 / ratio_fmpy:.1f}"]


def run(args):
    lines = ["# Fidelity cost: the span model against the link model's real-time method", "",
             f"Machine: {runs.machine()}; command: python -m harness bench-fidelity {' '.join(args.argv)}", "",
             f"Drive: {args.drive or 'the default drive'}.", "",
             f"Scene: the main job (closed loop with the torque tables of harness/tables/data), run-in and "
             f"{args.cycles} counted cycles, recorded through fmpy and replayed by a C master "
             f"(harness/package/fmi2_master.c) with the same output bits. RTF: CPU s of the thread inside "
             f"fmi2DoStep per simulated s, the smallest of {args.repeats} replays by turns; through fmpy: "
             f"measured around its calls from Python (the interpreter's call overhead included).", ""]
    print("\n".join(lines))
    with tempfile.TemporaryDirectory() as work:
        replayer = Replayer(work, args.drive)
        for rpm in args.rpm:
            part = [f"## {rpm:g} rpm", ""]
            for step in COMMUNICATION_STEPS:
                part += lines_of(step, measure(args, replayer, rpm, step))
            part.append("")
            print("\n".join(part))
            lines += part
    runs.write_lines(args.out, lines)
    return 0
