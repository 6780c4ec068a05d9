"""Work-precision of the real-time candidates: the reports of `python -m harness bench-realtime`
(their JSON, written beside the Markdown) drawn as one chart, a panel per engine speed, and listed
as one table.

    python -m harness realtime-chart REPORT.json [REPORT.json ...] [--timing TIMING.json ...]
                                     [--out results/realtime_work_precision.png]

Each report's speed is a point: its cost, the real-time factor through ChainDrive.fmu (RTF: CPU s
inside fmi2DoStep per simulated s, the model's: each step's minimum over the report's bit-identical
runs, summed; realtime.model_rtf), against its error, the
largest difference of its accuracy table over that quantity's tolerance (1: at the tolerance; the
quantity is named in the table). The marker says the verdict: filled, every tolerance met and every
difference within the combined scatter of the run and the reference; open, every tolerance met but
not every difference within scatter; a cross, a tolerance missed. The RTF targets (bench-realtime's
RTF_TARGET) are the dashed lines. A report without a reference (no accuracy table) is listed, not
drawn.

The ensembles behind the accuracy take long, and a long run shares the machine with whatever else
runs meanwhile; their RTFs are then too high. A --timing report (bench-realtime without a reference,
run alone, with repeats: the minimum per step over bit-identical runs) gives the RTF of every point
of the same speed, method and step instead (a timing speed that matches no point is an error); the
table says where each RTF comes from. A difference that is not a number (a statistic the run could
not form) counts as missed, drawn at the chart's top edge. Hosts differ
in speed: the table gives the host speed (bench-realtime's fixed workload) of each RTF's report.

Writes the chart to --out and the table, as Markdown, beside it (the same name, .md).
"""
import math
import pathlib

from .. import paths, runs
from ..errors import UserError
from ..plots import plt
from .realtime import RTF_TARGET, load_report, model_rtf

# short names of the methods in the chart's labels
SHORT = {"fixed-verlet-implicit-joint-damping": "RT", "fixed-verlet": "Verlet",
         "fixed-newmark": "Newmark"}


def add_arguments(ap):
    ap.add_argument("reports", nargs="+", metavar="REPORT.json",
                    help="JSON reports of python -m harness bench-realtime")
    ap.add_argument("--timing", action="append", default=[], metavar="TIMING.json",
                    help="a report of bench-realtime whose RTFs replace those of the same speed, method and step "
                    "(repeatable)")
    ap.add_argument("--out", default=str(paths.RESULTS / "realtime_work_precision.png"), help="the chart (.png)")


def check(ap, args):
    args.loaded = [(pathlib.Path(path), load_report(ap, path)) for path in args.reports]
    args.timings = [(pathlib.Path(path), load_report(ap, path)) for path in args.timing]
    if not args.out.endswith(".png"):
        ap.error(f"--out {args.out}: the chart is a .png")
    return args


def share(row):
    """A row's difference over its tolerance (infinite when the difference is not a number)."""
    return abs(row["difference"]) / row["tolerance"] if math.isfinite(row["difference"]) else math.inf


def point(report, speed, source):
    """A speed of a report (from the file source) as a point: its cost, its largest difference over
    its tolerance (and the quantity), its verdict: 'within scatter', 'met' (every tolerance, not
    every difference within scatter), 'missed' or None (no accuracy table), and the files its
    accuracy and its RTF come from."""
    rows = speed["accuracy"]
    worst = max(rows, key=share, default=None)
    verdict = None
    if rows:
        verdict = ("missed" if not all(r["meets"] for r in rows)
                   else "within scatter" if all(r["withinScatter"] for r in rows) else "met")
    return dict(rpm=speed["rpm"], method=speed["method"], step=speed["step"], rtf=model_rtf(speed),
                rtfTarget=RTF_TARGET.get(speed["rpm"]), p99OverMedian=speed["p99OverMedian"],
                worst=share(worst) if worst else None,
                worstKey=worst["key"] if worst else None, verdict=verdict,
                withinScatter=sum(r["withinScatter"] for r in rows), met=sum(r["meets"] for r in rows),
                quantities=len(rows), hostCpuPerSimulatedSecond=report["host"]["cpuPerSimulatedSecond"],
                accuracyFrom=source, rtfFrom=source)


def same_run(speed, p):
    """The same speed, method and step (steps given as 1e-4 / 28 and as its decimal agree)."""
    return (speed["rpm"], speed["method"]) == (p["rpm"], p["method"]) and math.isclose(speed["step"], p["step"],
                                                                                         rel_tol=1e-9)


def with_timing(p, timings):
    """The point with its RTF, p99 / median and host speed from the first timing report of the same
    speed, method and step (and that report as its RTF's source), else as it was."""
    for path, report in timings:
        for s in report["speeds"]:
            if same_run(s, p):
                return dict(p, rtf=model_rtf(s), p99OverMedian=s["p99OverMedian"],
                            hostCpuPerSimulatedSecond=report["host"]["cpuPerSimulatedSecond"], rtfFrom=path.name)
    return p


def unmatched_timings(points, timings):
    """The timing reports' speeds that give no point its RTF, as 'FILE: METHOD at H us, R rpm'."""
    return [f"{path.name}: {s['method']} at {s['step'] * 1e6:.4g} us, {s['rpm']:g} rpm" for path, report in timings
            for s in report["speeds"] if not any(same_run(s, p) for p in points)]


def label(p):
    return f"{SHORT.get(p['method'], p['method'])} {p['step'] * 1e6:.4g} us"


TOP = 3.0  # [tolerances] the error axis' top: points beyond it are drawn at it
TICKS = (0.1, 0.15, 0.25, 0.35, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0)
MARKERS = {"within scatter": dict(marker="o", fillstyle="full"), "met": dict(marker="o", fillstyle="none"),
           "missed": dict(marker="x", fillstyle="full")}


def panel(ax, rpm, points):
    finite = [p["worst"] for p in points if math.isfinite(p["worst"])]
    top = min(TOP, max([1.5] + [w * 1.15 for w in finite]))
    for k, p in enumerate(sorted(points, key=lambda p: p["rtf"])):
        beyond = not p["worst"] <= top  # (beyond the axis, or not a number: at its top edge, the value named)
        y = top if beyond else p["worst"]
        ax.plot([p["rtf"]], [y], ls="", ms=9, mew=2, color="C0", clip_on=False, **MARKERS[p["verdict"]])
        text = label(p) + (f" ({p['worst']:.3g})" if beyond else "")
        # (labels stepped up by the point's rank in cost, a thin line to their point: neighbours' stay apart)
        ax.annotate(text, (p["rtf"], y), textcoords="offset points", xytext=(8, -14 if beyond else 10 + 16 * (k % 4)),
                    fontsize=8, arrowprops=dict(arrowstyle="-", lw=0.5, color="0.5"))
    ax.axhline(1.0, color="k", lw=1)
    targets = {p["rtfTarget"] for p in points if p["rtfTarget"]}
    for target in targets:
        ax.axvline(target, color="C3", ls="--", lw=1)
    rtfs = [p["rtf"] for p in points] + list(targets)
    low, high = min(rtfs) / 1.5, max(rtfs) * 1.5
    ax.set_xscale("log")
    ax.set_xlim(low, high)
    ax.set_xticks([t for t in TICKS if low <= t <= high], [f"{t:g}" for t in TICKS if low <= t <= high])
    ax.minorticks_off()
    ax.set_ylim(0.0, top)
    ax.set_title(f"{rpm:g} rpm", fontsize=10)
    ax.set_xlabel("RTF: CPU s inside fmi2DoStep per simulated s (dashed: the target)", fontsize=8)
    ax.set_ylabel("largest difference / its tolerance (line: at the tolerance)", fontsize=8)
    ax.grid(True, which="both", alpha=0.25)


def chart(path, points):
    drawn = [p for p in points if p["verdict"] is not None]
    speeds = sorted({p["rpm"] for p in drawn})
    if not speeds:
        raise UserError("no report has an accuracy table (bench-realtime --reference): nothing to draw")
    fig, axes = plt.subplots(1, len(speeds), figsize=(max(9, 6 * len(speeds)), 5.5), squeeze=False)
    for ax, rpm in zip(axes[0], speeds):
        panel(ax, rpm, [p for p in drawn if p["rpm"] == rpm])
    handles = [plt.Line2D([], [], ls="", color="C0", ms=9, mew=2, label=f"every tolerance {v}" if v != "missed"
                          else "a tolerance missed", **m) for v, m in MARKERS.items()]
    fig.legend(handles=handles, loc="lower center", ncol=3, fontsize=8)
    fig.suptitle("The link model's real-time candidates through ChainDrive.fmu: cost against the accuracy table "
                 "(ensembles against ensemble references)\nRT: the real-time method, "
                 "fixed-verlet-implicit-joint-damping; Verlet: fixed-verlet; Newmark: fixed-newmark", fontsize=10)
    fig.tight_layout(rect=(0, 0.06, 1, 0.95))
    fig.savefig(path, dpi=80)
    plt.close(fig)


def table(points):
    lines = ["| speed | method | step | RTF | target | p99 / median | largest difference / tolerance | "
             "tolerances met | within scatter | host speed [CPU s/s] | accuracy from | RTF from |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for p in sorted(points, key=lambda p: (p["rpm"], p["rtf"])):
        worst = ("no reference" if p["worst"] is None else f"{p['worst']:.2f} ({p['worstKey']})"
                 if math.isfinite(p["worst"]) else f"not a number ({p['worstKey']})")
        target = f"{p['rtfTarget']:g}" if p["rtfTarget"] else ""
        lines.append(f"| {p['rpm']:g} rpm | {p['method']} | {p['step'] * 1e6:.4g} us | {p['rtf']:.3g} | {target} | "
                     f"{p['p99OverMedian']:.2f} | {worst} | {p['met']}/{p['quantities']} | "
                     f"{p['withinScatter']}/{p['quantities']} | {p['hostCpuPerSimulatedSecond']:.3g} | "
                     f"{p['accuracyFrom']} | {p['rtfFrom']} |")
    return lines


def run(args):
    points = [with_timing(point(report, speed, path.name), args.timings)
              for path, report in args.loaded for speed in report["speeds"]]
    if unmatched := unmatched_timings(points, args.timings):
        raise UserError(f"--timing: no report gives a point of {'; '.join(unmatched[:3])} (the same speed, method "
                        f"and step)")
    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    chart(out, points)
    rows = table(points)
    print("\n".join(rows))
    runs.write_lines(out.with_suffix(".md"), ["# Work-precision of the real-time candidates", "",
                                              f"`python -m harness realtime-chart {' '.join(args.argv)}`", "",
                                              f"![work-precision]({out.name})", ""] + rows)
    print(f"written: {out}")
    return 0
