"""The fidelity ladder: is the span model good enough for the quantities asked, and what does it save?

    python -m harness fidelity [--drive FILE] [--rpm 3000] [--tolerance KEY=X% | KEY=XdB | orders=XdB ...]
                               [--cycles N] [--link-cycles M] [--link-summary FILE] [--tables DIR]
                               [--out DIR]
    python -m harness fidelity --report DIR [DIR ...] [--out FILE.md] [--study DIR]

Runs the span model over many engine cycles (--cycles, cheap) and a short check of the link model
(--link-cycles), both through the main job's machinery (harness/job.py: ChainDrive.fmu in closed
loop with the measured-torque tables, the same run-in), and compares their cycle statistics
(harness/cycle_stats.py). Per quantity with a tolerance it prints the link value with its 95 %
confidence half-width, the span value with its own, their difference (% for levels, dB for order
amplitudes), the tolerance, whether the span model meets it (|difference| <= tolerance) and whether
the difference lies within the scatter of both runs (their combined 95 % interval); then the cost
of each (CPU s per simulated s inside fmi2DoStep) and the recommendation: the cheapest fidelity
that meets every tolerance (the link model is the reference and meets them by definition).

Tolerances (--tolerance, repeated; harness/study/ladder.py): KEY=X% for a level of the summary
(tensioner.F.mean=2%), KEY=XdB for one order amplitude, orders=XdB for every order amplitude of at
least 10 % of the largest of its signal. Without --tolerance: the acceptance set, span forces
(tensioner.F.mean, chain.Ftight.mean, chain.Fslack.mean) within 3 %, tension-guide angle and
camshaft timing peak-to-peak within 10 %, orders within 3 dB; with a hydraulic tensioner (the
default drive's) also its chamber's mean pressure within 3 % (the plunger force's share).

--link-summary FILE takes the link model's statistics from an earlier `python -m harness run --out
DIR` (DIR/summary.json; its cost from DIR/run.json when present) instead of running the check.
--out DIR (default results/fidelity) receives fidelity.json (the comparison) and the summary.json
and run.json of each run that was made (DIR/span, DIR/link).

--report: the accuracy table at several speeds from the fidelity.json of earlier runs (one DIR per
speed), as the Markdown section "Fidelity ladder: span model against link model" written to --out
(default results/fidelity.md); with --study DIR the comparisons also go into that study's
results.json, and its report.md and work-precision charts are rewritten with the section and with
the span model as one point per speed (harness/study/report.py). For example:

    python -m harness run --rpm 1000 --out results/link-1000        # likewise at 3000 and 6000 rpm
    python -m harness fidelity --rpm 1000 --link-summary results/link-1000/summary.json \\
                               --out results/fidelity-1000
    python -m harness fidelity --report results/fidelity-1000 results/fidelity-3000 results/fidelity-6000 \\
                               --out docs/study/fidelity.md --study docs/study
"""
import json
import pathlib

from .. import cycle_stats, job, paths, runs
from ..drive.description import drive_json, elements, is_hydraulic
from . import ladder

# the main job's cycles: the span model itself is cheap, but the Python master loop costs about
# 0.3 ms CPU per 100 us step (3 s per simulated s), more than the span model inside fmi2DoStep
DEFAULT_SPAN_CYCLES = 120
DEFAULT_LINK_CYCLES = 24   # a short check: intervals of about 2 % on the tensioner-force mean


def add_arguments(ap):
    ap.add_argument("--drive", help="drive description (default: the FMU's default drive)")
    ap.add_argument("--rpm", type=float, default=3000.0, help="mean engine speed [rpm], 1000-6000 (tables)")
    forms = (f"repeated: {ladder.FORMS}; default: " + " ".join(ladder.DEFAULT_TOLERANCES) + " and, for a hydraulic "
             "tensioner, " + " ".join(ladder.HYDRAULIC_TOLERANCES))
    # argparse formats help with %
    ap.add_argument("--tolerance", action="append", metavar="SPEC", help=forms.replace("%", "%%"))
    ap.add_argument("--cycles", type=int, default=DEFAULT_SPAN_CYCLES,
                    help=f"counted engine cycles of the span model (default {DEFAULT_SPAN_CYCLES})")
    ap.add_argument("--link-cycles", type=int, default=DEFAULT_LINK_CYCLES,
                    help=f"counted engine cycles of the link-model check (default {DEFAULT_LINK_CYCLES})")
    ap.add_argument("--link-summary", metavar="FILE",
                    help="summary.json of an earlier link-model run (python -m harness run --out DIR) instead "
                         "of the check")
    ap.add_argument("--tables", help="directory of the torque/speed tables (default harness/tables/data)")
    ap.add_argument("--out", help="output directory (default results/fidelity); with --report the Markdown file "
                                  "(default results/fidelity.md)")
    ap.add_argument("--report", nargs="+", metavar="DIR",
                    help="write the accuracy table of earlier runs (their DIR/fidelity.json, one per speed)")
    ap.add_argument("--study", metavar="DIR",
                    help="with --report: add the section and the span points to this study's results.json, "
                         "report.md and charts")


def check(ap, args):
    if args.report:
        args.comparisons = [load_comparison(ap, p) for p in args.report]
        args.out = args.out or str(paths.RESULTS / "fidelity.md")
        if args.study and not (pathlib.Path(args.study) / "results.json").exists():
            ap.error(f"--study {args.study}: no results.json there (the output of python -m harness study)")
        return args
    if args.study:
        ap.error("--study goes with --report")
    for option, cycles in (("--cycles", args.cycles), ("--link-cycles", args.link_cycles)):
        if cycles < 2:
            ap.error(f"{option} {cycles}: at least 2 counted cycles are needed for a confidence interval")
    drive = drive_json(args.drive)
    keys = cycle_stats.headline_keys(elements(drive))
    specs = args.tolerance or list(ladder.default_tolerances(is_hydraulic(drive), keys))
    args.tolerances = [parse_tolerance(ap, spec, keys) for spec in specs]
    args.out = args.out or str(paths.RESULTS / "fidelity")
    if args.link_summary:
        args.link = load_link_summary(ap, args.link_summary, keys, args.rpm)
    return args


def parse_tolerance(ap, spec, keys):
    try:
        return ladder.parse_tolerance(spec, keys)
    except ValueError as e:
        ap.error(f"--tolerance {spec!r}: {e}; allowed forms: {ladder.FORMS}")


def load_link_summary(ap, path, keys, rpm):
    """The link reference of --link-summary: {summary, cost (run.json beside it, or None), source}."""
    path = pathlib.Path(path)
    try:
        summary = json.loads(path.read_text())
    except (OSError, ValueError) as e:
        ap.error(f"--link-summary {path}: not readable as JSON ({e})")
    missing = [k for k in keys if k not in summary]
    if missing:
        ap.error(f"--link-summary {path}: not a summary of python -m harness run (missing {', '.join(missing)})")
    run_json = path.parent / "run.json"
    cost = json.loads(run_json.read_text()) if run_json.exists() else None
    if cost and (cost.get("fidelity") != "link" or abs(cost.get("rpm", rpm) - rpm) > 1e-9):
        ap.error(f"--link-summary {path}: a run of the {cost.get('fidelity')} fidelity at {cost.get('rpm'):g} rpm "
                 f"({run_json}); the reference is the link fidelity at --rpm {rpm:g}")
    return dict(summary=summary, cost=cost, source=str(path))


def load_comparison(ap, path):
    """A fidelity.json (given as the file or the directory holding it)."""
    path = pathlib.Path(path)
    path = path / "fidelity.json" if path.is_dir() else path
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError) as e:
        ap.error(f"--report {path}: not readable as the JSON of python -m harness fidelity ({e})")


def job_config(args, fidelity, cycles):
    """The main job's configuration for one fidelity (the main job's defaults otherwise)."""
    return job.run_config(rpm=args.rpm, fidelity=fidelity, cycles=cycles, drive=args.drive or None,
                          tables=args.tables or None)


def run_fidelity(args, fidelity, cycles):
    """One fidelity through the main job (closed loop, no plots): {summary, cost, source}; its
    summary.json and run.json go to OUT/<fidelity>."""
    config = job_config(args, fidelity, cycles)
    scene_run = job.simulate(config)
    _, summary = job.cycle_statistics(config, scene_run)
    cost = scene_run.cost(config)
    job.write_summary(pathlib.Path(args.out) / fidelity, summary, cost)
    print(f"  {fidelity}: {cost['doStepCpuPerSimulatedSecond']:.3g} CPU s per simulated s inside fmi2DoStep "
          f"({cost['cpuPerSimulatedSecond']:.3g} with the master loop)\n")
    return dict(summary=summary, cost=cost, source="run")


def cpu_per_simulated_second(cost):
    """The FMU's own cost of a run (CPU s per simulated s inside fmi2DoStep; that of the whole loop
    when the run did not tell it), None when unknown."""
    if cost is None:
        return None
    return cost.get("doStepCpuPerSimulatedSecond") or cost.get("cpuPerSimulatedSecond")


def comparison(args, link, span):
    """The content of fidelity.json: the rows of every quantity with a tolerance, each fidelity's
    cycles and cost, and the recommendation."""
    rows = ladder.compare(link["summary"], span["summary"], args.tolerances)
    meets_all = all(r["meets"] for r in rows)
    sides = {name: dict(source=side["source"], cycles=side["summary"]["tensioner.F.mean"]["cycles"],
                        cpuPerSimulatedSecond=cpu_per_simulated_second(side["cost"]), run=side["cost"])
             for name, side in (("link", link), ("span", span))}
    candidates = [dict(fidelity="link", cost=sides["link"]["cpuPerSimulatedSecond"], meetsAll=True),
                  dict(fidelity="span", cost=sides["span"]["cpuPerSimulatedSecond"], meetsAll=meets_all)]
    return dict(rpm=args.rpm, drive=args.drive, command=" ".join(["python -m harness fidelity"] + args.argv),
                machine=runs.machine(), tolerances=[f"{t.key}={t.limit:g}{t.unit}" for t in args.tolerances],
                rows=rows, spanMeetsAll=meets_all, recommendation=ladder.recommend(candidates),
                summaries={"link": link["summary"], "span": span["summary"]}, **sides)


def print_comparison(c):
    print(f"fidelity ladder at {c['rpm']:g} rpm, {c['drive'] or 'default drive'}: span model ({c['span']['cycles']} "
          f"cycles) against the link model ({c['link']['cycles']} cycles, {c['link']['source']}); means over engine "
          f"cycles +- 95 % half-widths")
    print(f"  {'quantity':<40} {'link':>24} {'span':>24} {'difference':>11} {'tolerance':>9}  span meets  "
          f"within scatter")
    for r in c["rows"]:
        value = "{mean:11.4g} +- {ci95:<8.2g}".format
        print(f"  {r['key']:<40} {value(**r['link'])} {r['unit']:<3} {value(**r['span'])} {r['unit']:<3} "
              f"{r['difference']:+8.2f} {r['differenceUnit']:<2} {r['tolerance']:6g} {r['differenceUnit']:<2}  "
              f"{'yes' if r['meets'] else 'NO':<10}  {'yes' if r['withinScatter'] else 'no'} (z {r['z']:+.2f})")
    link, span = c["link"]["cpuPerSimulatedSecond"], c["span"]["cpuPerSimulatedSecond"]
    ratio = f" ({link / span:.0f} times cheaper)" if link and span else ""
    print(f"cost, CPU s per simulated s inside fmi2DoStep: link {ladder.number(link)}, span {ladder.number(span)}"
          f"{ratio}")
    missed = [r["key"] for r in c["rows"] if not r["meets"]]
    why = (f"the span model meets all {len(c['rows'])} tolerances" if not missed else
           f"the span model misses {', '.join(missed)}")
    print(f"recommendation: {c['recommendation']} ({why})")


def write_report(args):
    """--report: the accuracy table of the comparisons, and with --study the study's report."""
    comparisons = sorted(args.comparisons, key=lambda c: c["rpm"])
    runs.write_lines(args.out, ladder.report_lines(comparisons))
    if args.study:
        from . import report, study  # the study's report and charts: needed only here
        study_dir = pathlib.Path(args.study)
        results = json.loads((study_dir / "results.json").read_text())
        # the rows hold what the report draws; the full summaries stay in each fidelity.json
        results["fidelity"] = [{k: v for k, v in c.items() if k != "summaries"} for c in comparisons]
        (study_dir / "results.json").write_text(json.dumps(results, indent=1))
        # the report's last section, as python -m harness study writes it by default
        chaos = study.chaos_results(study.CHAOS_RESULTS)
        report.write(study_dir, results, chaos)
        print(f"written: {study_dir / 'report.md'} and its charts, with the span model")
    return 0


def run(args):
    if args.report:
        return write_report(args)
    span = run_fidelity(args, "span", args.cycles)
    link = args.link if args.link_summary else run_fidelity(args, "link", args.link_cycles)
    c = comparison(args, link, span)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "fidelity.json").write_text(json.dumps(c, indent=1) + "\n")
    print_comparison(c)
    print(f"written: {out / 'fidelity.json'}")
    return 0
