"""The hydraulic tensioner against the spring-damper law: what the default drive's hydraulic
tensioner changes in the cycle statistics.

    python -m harness tensioner-study [--rpm 1000,3000,6000] [--cycles 120] [--drive FILE] [--out DIR]

Runs the main job's closed loop (harness/job.py: ChainDrive.fmu with the measured-torque tables,
its run-in, the oil at the main job's defaults, 3 bar and 90 degC) with the drive (default: the
default drive, whose tensioner is hydraulic) and with its spring-damper variant
(harness/drive/design.py: spring_damper_variant, the law the default drive had before) at every
speed, and compares every headline statistic of the two laws (harness/cycle_stats.py): the
difference hydraulic minus spring-damper (% for levels, dB for order amplitudes) and whether it
exceeds the scatter of both runs, |z| > 1 with z the difference over the combined 95 % half-width
(harness/study/errors.py). Writes to --out (default results/tensioner): tensioner.json (per speed
and law every headline statistic with its interval, the hydraulic chamber pressure's among them,
the highest tensioner force over the counted cycles, the cost) and tensioner.md, generated from
it (the committed one: --out docs/study).
"""
import json
import math
import os
import pathlib
import tempfile

import numpy as np

from .. import cycle_stats, job, paths, runs
from ..drive import design
from ..drive.description import drive_json, is_hydraulic
from ..tables import tables
from .errors import is_order, relative_error, z_score

DEFAULT_RPM = "1000,3000,6000"
LAWS = ("springDamper", "hydraulic")  # the reference first
LAW_NAMES = {"springDamper": "spring-damper", "hydraulic": "hydraulic"}
# the quantities of the report's tables, in its order (the chamber pressure: the hydraulic law's alone)
REPORTED = ("tensioner.F.mean", "tensioner.F.peakToPeak", "tensioner.F.order2", "tensioner.F.order4",
            "tensioner.F.order6", "tensioner.F.order8", "tensioner.F.order21", "tensionGuide.phi.peakToPeak_deg",
            "tensionGuide.phi.order8_deg", "chain.Ftight.mean", "chain.Fslack.mean",
            "camshaftIntake.timing.peakToPeak_degCA")
# typical values of the engineering literature on timing-chain drives, for comparison [N]
QUASI_STATIC_FORCE = (100.0, 400.0)   # the tensioner's quasi-static force
DYNAMIC_PEAK_FORCE = (1000.0, 3000.0)  # its dynamic peaks at resonance


def add_arguments(ap):
    ap.add_argument("--rpm", default=DEFAULT_RPM, help=f"engine speeds [rpm], a comma list within the tables' "
                    f"1000-6000 (default {DEFAULT_RPM})")
    ap.add_argument("--cycles", type=int, default=job.DEFAULT_CYCLES,
                    help=f"engine cycles counted per run after the run-in (default {job.DEFAULT_CYCLES})")
    ap.add_argument("--drive", help="drive description with a hydraulic tensioner (default: the default drive)")
    ap.add_argument("--out", default=str(paths.RESULTS / "tensioner"),
                    help="output directory of tensioner.json and tensioner.md (the committed: docs/study)")


def check(ap, args):
    try:
        args.speeds = [float(x) for x in args.rpm.split(",")]
    except ValueError:
        ap.error(f"--rpm {args.rpm}: expected a comma list of engine speeds [rpm]")
    if args.cycles < 2:
        ap.error(f"--cycles {args.cycles}: at least 2 counted cycles are needed for a confidence interval")
    if not is_hydraulic(drive_json(args.drive)):
        ap.error(f"--drive {args.drive}: its tensioner is not hydraulic (tensioner.model); the study compares a "
                 f"hydraulic tensioner with its spring-damper variant")
    for rpm in args.speeds:
        problem = tables.speed_problem(rpm, None)
        if problem:
            ap.error(problem)
    return args


def run_law(rpm, cycles, drive_file):
    """One run of the main job's closed loop: {summary, tensionerForceMax_N, cost}."""
    config = job.run_config(rpm=rpm, cycles=cycles, drive=drive_file)
    scene_run = job.simulate(config, progress=False)
    _, summary = job.cycle_statistics(config, scene_run)
    spans = cycle_stats.counted_spans(scene_run.record["crankshaft.phi"], scene_run.run_in, cycles)
    counted = slice(spans[0][0], spans[-1][1])
    cost = scene_run.cost(config)
    cost["drive"] = None if drive_file is None else "spring-damper variant of the drive"
    return dict(summary=summary, tensionerForceMax_N=float(np.max(scene_run.record["tensioner.F"][counted])),
                cost=cost)


def compare(reference, other):
    """Rows of the headline quantities both summaries have: each law's mean and interval, the
    difference (% or dB) and z (beyond the combined scatter when |z| > 1)."""
    rows = []
    for key in reference:
        if key not in other:
            continue
        ref, val = reference[key], other[key]
        z = z_score(val["mean"], val["ci95"], ref["mean"], ref["ci95"])
        rows.append(dict(key=key, unit=ref["unit"], springDamper=ref, hydraulic=val,
                         difference=relative_error(key, val["mean"], ref["mean"]),
                         differenceUnit="dB" if is_order(key) else "%", z=z, beyondScatter=bool(abs(z) > 1.0)))
    return rows


def study(args, variant_file):
    """The content of tensioner.json."""
    speeds = []
    for rpm in args.speeds:
        laws = {}
        for law, drive_file in (("springDamper", variant_file), ("hydraulic", args.drive)):
            print(f"{rpm:g} rpm, {LAW_NAMES[law]} tensioner:")
            laws[law] = run_law(rpm, args.cycles, drive_file)
        speeds.append(dict(rpm=rpm, **laws, rows=compare(laws["springDamper"]["summary"],
                                                         laws["hydraulic"]["summary"])))
    return dict(command=" ".join(["python -m harness tensioner-study"] + list(getattr(args, "argv", []))),
                machine=runs.machine(), cycles=args.cycles, drive=args.drive or "default drive",
                literature=dict(quasiStaticForce_N=list(QUASI_STATIC_FORCE), dynamicPeakForce_N=list(DYNAMIC_PEAK_FORCE)),
                speeds=speeds)


def figure(s):
    """mean ± half-width of a summary entry, both to the half-width's second significant digit."""
    half = s["ci95"]
    if not (math.isfinite(half) and half > 0.0):
        return f"{s['mean']:.4g}"
    decimals = max(0, 1 - math.floor(math.log10(half)))
    return f"{s['mean']:.{decimals}f} ± {half:.{decimals}f}"


def table_lines(speed):
    """The Markdown table of one speed's comparison."""
    lines = [f"### {speed['rpm']:g} rpm", "",
             "| quantity | spring-damper | hydraulic | difference | beyond the scatter |", "|---|---|---|---|---|"]
    rows = {r["key"]: r for r in speed["rows"]}
    for key in REPORTED:
        r = rows.get(key)
        if r:
            lines.append(f"| `{key}` | {figure(r['springDamper'])} {r['unit']} | {figure(r['hydraulic'])} {r['unit']} | "
                         f"{r['difference']:+.1f} {r['differenceUnit']} | {'yes' if r['beyondScatter'] else 'no'} "
                         f"(z {r['z']:+.1f}) |")
    chamber = speed["hydraulic"]["summary"]
    lines += ["", "The hydraulic chamber (gauge): " + ", ".join(
        f"{what} {figure(chamber[cycle_stats.CHAMBER + suffix])} bar" for what, suffix in
        (("mean", ".mean_bar"), ("peak-to-peak", ".peakToPeak_bar"), ("minimum per cycle", ".min_bar"))
        if cycle_stats.CHAMBER + suffix in chamber) + ". Highest tensioner force over the counted cycles: "
        + ", ".join(f"{LAW_NAMES[law]} {speed[law]['tensionerForceMax_N']:.0f} N" for law in LAWS) + ".", ""]
    return lines


def findings(result):
    """The report's summary sentences, from the figures."""
    lines = []
    for speed in result["speeds"]:
        rows = {r["key"]: r for r in speed["rows"]}
        beyond = [k for k in REPORTED if k in rows and rows[k]["beyondScatter"]]
        F = rows["tensioner.F.mean"]
        lines.append(f"- {speed['rpm']:g} rpm: tensioner-force mean {figure(F['springDamper'])} N with the "
                     f"spring-damper law, {figure(F['hydraulic'])} N hydraulic ({F['difference']:+.0f} %); "
                     f"{len(beyond)} of {sum(k in rows for k in REPORTED)} reported quantities differ beyond the "
                     f"combined scatter" + (f" ({', '.join(f'`{k}`' for k in beyond)})" if beyond else "") + ".")
    return lines


def literature_lines(result):
    """The comparison with the typical values of the literature."""
    lo, hi = QUASI_STATIC_FORCE
    plo, phi = DYNAMIC_PEAK_FORCE

    def inside(x, a, b):
        return "within" if a <= x <= b else "below" if x < a else "above"
    lines = [f"Typical values of the engineering literature on timing-chain drives (not measurements of this "
             f"drive): a quasi-static tensioner force of {lo:.0f}-{hi:.0f} N and dynamic peaks of "
             f"{plo / 1e3:g}-{phi / 1e3:g} kN at resonance. Here:", ""]
    for speed in result["speeds"]:
        for law in LAWS:
            mean = speed[law]["summary"]["tensioner.F.mean"]["mean"]
            peak = speed[law]["tensionerForceMax_N"]
            lines.append(f"- {speed['rpm']:g} rpm, {LAW_NAMES[law]}: mean {mean:.0f} N ({inside(mean, lo, hi)} the "
                         f"quasi-static range), highest {peak:.0f} N ({inside(peak, plo, phi)} the range of peaks)")
    return lines + [""]


def report_lines(result):
    """tensioner.md, generated from tensioner.json."""
    return ["# The hydraulic tensioner against the spring-damper law", "",
            f"<!-- generated by `{result['command']}` from tensioner.json; do not edit -->", "",
            "The default drive's hydraulic tensioner ([hydraulic_tensioner.md](../hydraulic_tensioner.md)) against "
            "the spring-damper law the drive had before (`harness/drive/design.py`: `spring_damper_variant`), both "
            f"through the main job's closed loop ({result['cycles']} engine cycles counted after the run-in, oil at "
            f"{job.SUPPLY_PRESSURE / job.BAR:g} bar and {job.OIL_TEMPERATURE - job.ZERO_CELSIUS:g} degC). Every "
            "figure is the mean over engine cycles ± its 95 % confidence half-width; the difference is hydraulic "
            "minus spring-damper (% for levels, dB for order amplitudes); it exceeds the scatter when |z| > 1, z "
            "the difference over the combined half-width of both runs. Figures: "
            "[tensioner.json](tensioner.json); the command: `python -m harness tensioner-study --out docs/study`.",
            "", "## Findings", ""] + findings(result) + ["", "## Against typical values", ""] + \
        literature_lines(result) + ["## Per speed", ""] + [line for s in result["speeds"] for line in table_lines(s)]


def run(args):
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fd, variant_file = tempfile.mkstemp(suffix=".json", prefix="spring_damper_")
    try:
        with os.fdopen(fd, "w") as f:
            json.dump(design.spring_damper_variant(drive_json(args.drive)), f)
        result = study(args, variant_file)
    finally:
        os.unlink(variant_file)
    (out / "tensioner.json").write_text(json.dumps(result, indent=1, allow_nan=True) + "\n")
    runs.write_lines(out / "tensioner.md", report_lines(result))
    print("\n".join(findings(result)))
    return 0
