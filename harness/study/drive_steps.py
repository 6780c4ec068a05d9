"""A step that fits the drive, measured: every test drive at its own default step against half that
step, closed loop with its own tables, the evidence behind the per-drive steps (docs/defaults.md).

    python -m harness drive-steps [--drives FILE ...] [--rpm 1000 6000] [--cycles 120] [--replicas 2]
                                  [--workers N] [--out docs/study/drive_steps]

Per drive and speed, the main job (closed loop, the drive's own tables from tests/drives/tables/<drive>/
or the shipped ones for the default drive, run-in until the tensioner has settled, --cycles counted
cycles) as an ensemble of --replicas runs (harness/replicas.py: the crankshaft speed perturbed by
1e-9 per replica, unrelated after the run-in) at the drive's default step, and a reference ensemble
at half that step. Checked: no blow-up, every run's energy balance within the main job's limit
(harness/checks.py), and per cycle statistic the difference of the two ensembles' means against
their combined 95 % interval (z); the statistics agree jointly at 95 % when every |z| lies within
the Bonferroni limit for their number (harness/study/errors.py). Written: OUT/drive_steps.json
(every ensemble's summary, energy balances, CPU) and OUT/drive_steps.md. The points (drive x
speed) run side by side in --workers processes (default: one per core), each point's runs in turn.
"""
import argparse
import concurrent.futures
import dataclasses
import json
import math
import os
import pathlib
import time

from .. import checks, job, paths, replicas, runs
from ..drive import description
from .errors import joint_limit, z_score

TEST_DRIVES = paths.ROOT / "tests" / "drives"


def add_arguments(ap):
    default_drives = [str(paths.ROOT / "src" / "drives" / "default_drive.json")] + \
        [str(p) for p in sorted(TEST_DRIVES.glob("*.json"))]
    ap.add_argument("--drives", nargs="+", default=default_drives, help="drive description files")
    ap.add_argument("--rpm", type=float, nargs="+", default=[1000.0, 6000.0], help="engine speeds [rpm]")
    ap.add_argument("--cycles", type=int, default=job.DEFAULT_CYCLES, help="engine cycles counted after the run-in")
    ap.add_argument("--replicas", type=int, default=2, help="runs per ensemble")
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="points run side by side")
    ap.add_argument("--out", default=str(paths.ROOT / "docs" / "study" / "drive_steps"))


def check(ap, args):
    if args.cycles < 2:
        ap.error(f"--cycles {args.cycles}: at least 2 counted cycles are needed for a confidence interval")
    if args.replicas < 1:
        ap.error(f"--replicas {args.replicas}: at least 1")
    if args.workers < 1:
        ap.error(f"--workers {args.workers}: at least 1")
    return args


def tables_of(drive):
    """The drive's own tables (tests/drives/tables/<stem>/), None for the shipped ones."""
    own = TEST_DRIVES / "tables" / pathlib.Path(drive).stem
    return str(own) if own.is_dir() else None


def ensemble(config, count):
    """count replicas of config: {summary, energyBalance (per replica), runIn, cpu} or {failed}."""
    summaries, energy, run_ins, cpu = [], [], [], 0.0
    for k in range(count):
        replica = replicas.replica_config(config, k)
        try:
            scene_run = job.simulate(replica, progress=False)
        except job.RunFailed as failure:
            return dict(failed=str(failure), replica=k)
        summaries.append(job.cycle_statistics(replica, scene_run)[1])
        found, _, _ = job.run_checks(replica, scene_run, job.counted_spans(replica, scene_run))
        energy.append(found["energyBalanceError"])
        run_ins.append(scene_run.run_in)
        cpu += scene_run.cpu
    return dict(summary=replicas.combine(summaries), energyBalance=energy, runIn=run_ins, cpu=cpu)


def agreement(found, reference):
    """Per statistic of both ensembles: z of the difference against the combined interval; the
    joint limit for their number, and the statistics beyond it."""
    keys = [k for k in reference if k in found and math.isfinite(reference[k]["ci95"])]
    z = {k: z_score(found[k]["mean"], found[k]["ci95"], reference[k]["mean"], reference[k]["ci95"]) for k in keys}
    limit = joint_limit(len(keys))
    outside = [k for k in keys if not abs(z[k]) <= limit]
    return dict(z=z, limit=limit, outside=outside, maxAbsZ=max((abs(v) for v in z.values()), default=math.nan))


def study_point(args, drive, rpm):
    """One drive at one speed: the default step's ensemble against the half step's."""
    base = job.run_config(drive=drive, tables=tables_of(drive), rpm=rpm, cycles=args.cycles,
                          out=pathlib.Path(args.out) / "runs")
    half = dataclasses.replace(base, solver_step=base.solver_step / 2)
    point = dict(drive=drive, rpm=rpm, method=base.method, step=base.solver_step, reason=job.step_text(base))
    point["default"] = ensemble(base, args.replicas)
    point["reference"] = ensemble(half, args.replicas)
    if "summary" in point["default"] and "summary" in point["reference"]:
        point["agreement"] = agreement(point["default"]["summary"], point["reference"]["summary"])
    return point


def verdict(point):
    """One line: blow-up, energy balance and agreement of a point."""
    if "failed" in point["default"]:
        return "**blow-up** at the default step: " + point["default"]["failed"]
    worst = max(point["default"]["energyBalance"], key=abs)
    energy_ok = abs(worst) <= checks.ENERGY_BALANCE_LIMIT
    parts = [f"energy balance {100 * worst:+.2f} %" + ("" if energy_ok else " (**beyond the limit**)")]
    if "failed" in point["reference"]:
        parts.append("the half step failed: " + point["reference"]["failed"])
    else:
        parts[0] += f" (half step {100 * max(point['reference']['energyBalance'], key=abs):+.2f} %)"
        a = point["agreement"]
        parts.append(f"max |z| {a['maxAbsZ']:.2f} (joint limit {a['limit']:.2f})" +
                     ("" if not a["outside"] else ", **outside**: " + ", ".join(a["outside"])))
    return "; ".join(parts)


def table(points):
    lines = ["| drive | rpm | step | run-in cycles | CPU s (default, half) | result |", "|---|---|---|---|---|---|"]
    for p in points:
        name = description.drive_json(p["drive"]).get("name", pathlib.Path(p["drive"]).stem)
        cpu = " / ".join(f"{p[e].get('cpu', math.nan):.0f}" for e in ("default", "reference"))
        run_in = ", ".join(str(c) for c in p["default"].get("runIn", []))
        lines.append(f"| {name} | {p['rpm']:g} | {p['step'] * 1e6:.4g} us | {run_in} | {cpu} | {verdict(p)} |")
    return lines


def run(args):
    out = pathlib.Path(args.out)
    started = time.time()
    cases = [(drive, rpm) for drive in args.drives for rpm in args.rpm]
    with concurrent.futures.ProcessPoolExecutor(min(args.workers, len(cases))) as pool:
        # (what a point reads of the arguments: the namespace itself holds modules, which do not pickle)
        settings = argparse.Namespace(cycles=args.cycles, replicas=args.replicas, out=args.out)
        futures = [pool.submit(study_point, settings, drive, rpm) for drive, rpm in cases]
        points = [f.result() for f in futures]  # (in the order of the cases)
    for (drive, rpm), point in zip(cases, points):
        print(f"\n{drive} at {rpm:g} rpm: {verdict(point)}")
    lines = ["# A step that fits the drive, measured", "",
             f"Machine: {runs.machine()}; command: python -m harness drive-steps {' '.join(args.argv)}; "
             f"{(time.time() - started) / 60:.0f} minutes.", "",
             f"Each drive closed loop with its own tables at its default step (`chaindrive-info --defaults --drive`), "
             f"{args.replicas} replicas of {args.cycles} counted cycles after the run-in, against {args.replicas} "
             f"replicas at half the step. The energy balance is the worst replica's (limit "
             f"{100 * checks.ENERGY_BALANCE_LIMIT:g} %); z is the difference of the ensembles' means over their "
             f"combined 95 % interval, within the joint (Bonferroni) limit for the number of statistics.", ""]
    lines += table(points) + ["", "The steps and their reasons:", ""]
    lines += sorted({f"- {pathlib.Path(p['drive']).name}: {p['reason']}" for p in points})
    out.mkdir(parents=True, exist_ok=True)
    runs.write_json(out / "drive_steps.json", dict(cycles=args.cycles, replicas=args.replicas, points=points))
    runs.write_lines(out / "drive_steps.md", lines)
    failed = [p for p in points if "failed" in p["default"] or "beyond" in verdict(p) or p.get("agreement", {}).get("outside")]
    return 1 if failed else 0
