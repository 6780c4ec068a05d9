"""The span model's own step convergence: its cycle statistics at each fixed step against those of
the finest, per speed. The evidence behind its default step (harness/defaults.py, docs/defaults.md).

    python -m harness span-steps [--rpm 1000 3000 6000] [--steps 5e-6 2.5e-5 3.3333333333333335e-5 5e-5 1e-4]
                                 [--cycles 20] [--out docs/study/span_steps]

Each run is the main job with the span fidelity (closed loop with the measured-torque tables,
run-in, --cycles counted cycles) at one solver.step of its default method. Per speed and step,
for the levels of the fidelity ladder's acceptance set (harness/study/ladder.py): the difference
from the finest step's run and whether it lies within the combined 95 % interval of both
(*within scatter*). A step is accurate at a speed when every such difference lies within the
scatter; the default is the largest step dividing the 0.1 ms communication step that is accurate
at every speed. Written: OUT/steps.json (every summary and comparison) and OUT/steps.md.
"""
import json
import pathlib

from .. import job, paths, runs
from . import ladder

LEVELS = [t for t in ladder.default_tolerances(True) if not t.startswith(ladder.ORDERS)]


def add_arguments(ap):
    ap.add_argument("--rpm", type=float, nargs="+", default=[1000.0, 3000.0, 6000.0], help="engine speeds [rpm]")
    ap.add_argument("--steps", type=float, nargs="+", default=[5e-6, 2.5e-5, 1e-4 / 3, 5e-5, 1e-4],
                    help="solver steps [s], the first the reference")
    ap.add_argument("--cycles", type=int, default=20, help="engine cycles counted after the run-in")
    ap.add_argument("--out", default=str(paths.RESULTS / "span_steps"))


def check(ap, args):
    if args.cycles < 2:
        ap.error(f"--cycles {args.cycles}: at least 2 counted cycles are needed for a confidence interval")
    if len(args.steps) < 2 or any(not (0.0 < s <= 1e-3) for s in args.steps):
        ap.error(f"--steps {args.steps}: a reference and at least one more, each in (0, 1e-3] s")
    return args


def summary_at(rpm, step, cycles):
    config = job.run_config(rpm=rpm, cycles=cycles, fidelity="span", solver_step=step)
    scene_run = job.simulate(config, progress=False)
    return job.cycle_statistics(config, scene_run)[1], scene_run.step_cpu / scene_run.duration


def study_speed(args, rpm):
    """{step: {summary, cpuPerSimulatedSecond, rows (against the reference), accurate}} at one speed."""
    found = {}
    for step in args.steps:
        summary, cost = summary_at(rpm, step, args.cycles)
        found[step] = dict(summary=summary, cpuPerSimulatedSecond=cost)
    reference = found[args.steps[0]]["summary"]
    tolerances = [ladder.parse_tolerance(t, list(reference)) for t in LEVELS]
    for step in args.steps[1:]:
        rows = ladder.compare(reference, found[step]["summary"], tolerances)
        found[step].update(rows=rows, accurate=all(r["withinScatter"] for r in rows))
    return found


def table(rpm, reference_step, found):
    steps = [s for s in found if s != reference_step]
    keys = [r["key"] for r in found[steps[0]]["rows"]]
    lines = [f"## {rpm:g} rpm (reference: {reference_step * 1e6:.4g} us)", "",
             "| quantity | reference | " + " | ".join(f"{s * 1e6:.4g} us" for s in steps) + " |",
             "|---|---|" + "---|" * len(steps)]
    for i, key in enumerate(keys):
        ref = found[steps[0]]["rows"][i]["link"]
        cells = [f"{r['difference']:+.2f} %{'' if r['withinScatter'] else ' (outside)'}"
                 for r in (found[s]["rows"][i] for s in steps)]
        lines.append(f"| {key} | {ref['mean']:.4g} +- {ref['ci95']:.2g} | " + " | ".join(cells) + " |")
    lines.append("| accurate (every difference within the scatter) | | " +
                 " | ".join("yes" if found[s]["accurate"] else "**no**" for s in steps) + " |")
    lines.append("| CPU s per simulated s inside fmi2DoStep | "
                 f"{found[reference_step]['cpuPerSimulatedSecond']:.3g} | " +
                 " | ".join(f"{found[s]['cpuPerSimulatedSecond']:.3g}" for s in steps) + " |")
    return lines + [""]


def run(args):
    out = pathlib.Path(args.out)
    lines = ["# The span model's step convergence", "",
             f"Machine: {runs.machine()}; command: python -m harness span-steps {' '.join(args.argv)}", "",
             f"The main job with the span fidelity (closed loop with the torque tables, {args.cycles} counted "
             f"cycles) at each step of its default method; per quantity the difference from the reference "
             f"step's run, *(outside)* when it lies outside the combined 95 % interval of both.", ""]
    results = {}
    for rpm in args.rpm:
        found = study_speed(args, rpm)
        results[f"{rpm:g}"] = {f"{s!r}": v for s, v in found.items()}
        part = table(rpm, args.steps[0], found)
        print("\n".join(part))
        lines += part
    out.mkdir(parents=True, exist_ok=True)
    (out / "steps.json").write_text(json.dumps(dict(steps=args.steps, cycles=args.cycles, speeds=results),
                                               indent=1) + "\n")
    runs.write_lines(out / "steps.md", lines)
    return 0
