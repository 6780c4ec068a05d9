"""The fidelity ladder: the span model's cycle statistics against the link model's (the
reference), quantity by quantity within a tolerance, the recommendation of the cheapest fidelity
that meets them all, and the accuracy table of the study report. Pure functions on summaries
({key: {mean, ci95, cycles, unit}}, harness/cycle_stats.py); python -m harness fidelity
(harness/study/fidelity.py) runs the models.

Tolerances:
  KEY=X%      a level of the summary (tensioner.F.mean=3%): meets when |span - link| / |link| <= X %
  KEY=XdB     one order amplitude (tensioner.F.order2=3dB): meets when |20 log10(span / link)| <= X dB
  orders=XdB  every order amplitude whose link value is at least ORDER_SHARE of the largest order
              amplitude of the same signal: the smaller ones are too weak for a ratio in dB to mean
              anything (a tenth of the largest is already -20 dB below it)
An explicit KEY takes precedence over orders=. Beside the tolerance, each difference is set against
the scatter of both runs: z = (span - link) / sqrt(ci_span^2 + ci_link^2), within the scatter when
|z| <= 1 (the combined 95 % interval).
"""
import collections
import math

from .. import cycle_stats
from .errors import is_order, relative_error, z_score

ORDERS = "orders"
ORDER_SHARE = 0.1
FORMS = ("KEY=X% (a level of the summary, e.g. tensioner.F.mean=3%), KEY=XdB (one order amplitude, e.g. "
         "tensioner.F.order2=3dB) or orders=XdB (every order amplitude of at least 10 % of its signal's largest)")
# the acceptance set of the span model: span forces within 3 %, motion peak-to-peak within 10 %, orders 3 dB
DEFAULT_TOLERANCES = ("tensioner.F.mean=3%", "chain.Ftight.mean=3%", "chain.Fslack.mean=3%",
                      "tensionGuide.phi.peakToPeak_deg=10%", "camshaftIntake.timing.peakToPeak_degCA=10%",
                      "camshaftExhaust.timing.peakToPeak_degCA=10%", "orders=3dB")
# and a hydraulic tensioner's mean chamber pressure as its force (the minimum and peak-to-peak,
# near zero or set by single impacts, are no level to hold to a relative tolerance)
HYDRAULIC_TOLERANCES = (f"{cycle_stats.CHAMBER}.mean_bar=3%",)


def default_tolerances(hydraulic, keys=None):
    """The acceptance set of a drive whose tensioner is hydraulic or not: with `keys` (its summary's,
    cycle_stats.headline_keys), the default's set named after the drive's own elements (its span
    forces, its tension guide's and every loaded sprocket's peak-to-peak); without, the default
    drive's."""
    if keys is None:
        return DEFAULT_TOLERANCES + (HYDRAULIC_TOLERANCES if hydraulic else ())
    levels = [f"{k}=3%" for k in keys if k in ("tensioner.F.mean", "chain.Ftight.mean", "chain.Fslack.mean")]
    motion = [f"{k}=10%" for k in keys if k.endswith((".phi.peakToPeak_deg", ".timing.peakToPeak_degCA"))]
    return tuple(levels + motion + [f"{ORDERS}=3dB"]) + (HYDRAULIC_TOLERANCES if hydraulic else ())

Tolerance = collections.namedtuple("Tolerance", "key limit unit")  # limit in unit: "%" or "dB"


def parse_tolerance(text, keys):
    """The Tolerance of KEY=X%, KEY=XdB or orders=XdB; keys: the summary's keys. Raises
    ValueError saying what is wrong."""
    key, sep, value = (part.strip() for part in text.partition("="))
    if not sep or not key or not value:
        raise ValueError("not of the form KEY=VALUE")
    unit = "dB" if value.endswith("dB") else "%" if value.endswith("%") else None
    if unit is None:
        raise ValueError(f"'{value}' has no unit: % or dB")
    try:
        limit = float(value[:-len(unit)])
    except ValueError:
        raise ValueError(f"'{value[:-len(unit)]}' is not a number") from None
    if not (math.isfinite(limit) and limit > 0.0):
        raise ValueError(f"{value}: a tolerance must be positive")
    if key != ORDERS and key not in keys:
        raise ValueError(f"'{key}' is not a quantity of the summary ({', '.join(keys)})")
    wants_dB = key == ORDERS or is_order(key)
    if wants_dB != (unit == "dB"):
        raise ValueError(f"'{key}' takes a tolerance in {'dB' if wants_dB else '%'}")
    return Tolerance(key, limit, unit)


def selected_orders(link):
    """The order-amplitude keys of the link summary whose amplitude is at least ORDER_SHARE of the
    largest order amplitude of the same signal."""
    selected = []
    for keys in cycle_stats.order_keys(link).values():
        largest = max((link[k]["mean"] for k in keys), default=0.0)
        selected += [k for k in keys if largest > 0.0 and link[k]["mean"] >= ORDER_SHARE * largest]
    return selected


def per_quantity(tolerances, link):
    """{summary key: Tolerance} of the tolerances, in the order of the link summary: orders=
    expanded by selected_orders(), explicit keys taking precedence."""
    chosen = {}
    for t in tolerances:
        if t.key == ORDERS:
            chosen.update({k: t._replace(key=k) for k in selected_orders(link)})
    chosen.update({t.key: t for t in tolerances if t.key != ORDERS})
    return {k: chosen[k] for k in link if k in chosen}


def compare_quantity(key, link, span, tolerance):
    """One quantity: both values with their intervals, the difference (% or dB, as
    relative_error), whether it meets the tolerance and whether it lies within the combined
    interval of both runs."""
    difference = relative_error(key, span["mean"], link["mean"])
    z = z_score(span["mean"], span["ci95"], link["mean"], link["ci95"])
    return dict(key=key, unit=link["unit"],
                link={k: link[k] for k in ("mean", "ci95", "cycles")},
                span={k: span[k] for k in ("mean", "ci95", "cycles")},
                difference=difference, differenceUnit=tolerance.unit, tolerance=tolerance.limit,
                meets=bool(abs(difference) <= tolerance.limit),  # NaN (no link level) does not meet
                combined=math.hypot(span["ci95"], link["ci95"]), z=z, withinScatter=bool(abs(z) <= 1.0))


def compare(link, span, tolerances):
    """The rows of compare_quantity() of every quantity with a tolerance (Tolerance objects as
    parsed; orders= resolved against the link summary)."""
    return [compare_quantity(key, link[key], span[key], t) for key, t in per_quantity(tolerances, link).items()]


def recommend(candidates):
    """The cheapest candidate that meets all its tolerances: candidates are dicts with fidelity,
    cost (CPU s per simulated s, None when unknown: ranked after the known ones, in the order
    given) and meetsAll. Returns its fidelity, None if none meets them."""
    meeting = [(c["cost"] if c["cost"] is not None else math.inf, i, c["fidelity"])
               for i, c in enumerate(candidates) if c["meetsAll"]]
    return min(meeting)[2] if meeting else None


def span_point(comparison):
    """The span model as a point of the work-precision chart of the tensioner-force mean: its CPU
    s per simulated s, its difference from the link model [%] and the combined interval as the
    error bar (None without that row or cost)."""
    row = next((r for r in comparison["rows"] if r["key"] == "tensioner.F.mean"), None)
    cost = comparison["span"]["cpuPerSimulatedSecond"]
    if row is None or cost is None:
        return None
    half = 100.0 * row["combined"] / abs(row["link"]["mean"])
    return dict(cpu_per_s=cost, error=row["difference"], errorLow=row["difference"] - half,
                errorHigh=row["difference"] + half)


def value_cell(v, unit):
    return f"{v['mean']:.4g} +- {v['ci95']:.2g} {unit}"


def verdict_cell(row):
    scatter = "within scatter" if row["withinScatter"] else f"z {row['z']:+.1f}"
    return f"{'met' if row['meets'] else '**missed**'} ({scatter})"


def accuracy_table(comparisons):
    """Markdown: rows per quantity, per speed the link and span means +- their 95 % half-widths,
    the difference, the tolerance and met/missed (with whether the difference lies within the
    combined interval); comparisons as written by python -m harness fidelity (fidelity.json)."""
    head = "| quantity |" + "".join(f" {c['rpm']:g} rpm: link | span | difference | tolerance | span |"
                                    for c in comparisons)
    lines = [head, "|---|" + "---|---|---|---|---|" * len(comparisons)]
    keys = list(dict.fromkeys(r["key"] for c in comparisons for r in c["rows"]))
    for key in keys:
        cells = []
        for c in comparisons:
            r = next((r for r in c["rows"] if r["key"] == key), None)
            cells += (["-"] * 5 if r is None else
                      [value_cell(r["link"], r["unit"]), value_cell(r["span"], r["unit"]),
                       f"{r['difference']:+.2f} {r['differenceUnit']}", f"{r['tolerance']:g} {r['differenceUnit']}",
                       verdict_cell(r)])
        lines.append(f"| {key} | " + " | ".join(cells) + " |")
    return lines


def cost_table(comparisons):
    """Markdown: per speed the cycles and CPU s per simulated s of both fidelities, their ratio and
    the recommendation."""
    lines = ["| speed | link: cycles | link: CPU s per simulated s | span: cycles | span: CPU s per simulated s | "
             "link / span | span meets all | recommendation |", "|---|---|---|---|---|---|---|---|"]
    for c in comparisons:
        link, span = c["link"]["cpuPerSimulatedSecond"], c["span"]["cpuPerSimulatedSecond"]
        ratio = f"{link / span:.0f}" if link and span else "-"
        lines.append(f"| {c['rpm']:g} rpm | {c['link']['cycles']} | {number(link)} | {c['span']['cycles']} | "
                     f"{number(span)} | {ratio} | {'yes' if c['spanMeetsAll'] else 'no'} | {c['recommendation']} |")
    return lines


def number(x):
    return "-" if x is None else f"{x:.3g}"


def report_lines(comparisons):
    """The report section "Fidelity ladder: span model against link model"."""
    tolerances = list(dict.fromkeys(t for c in comparisons for t in c["tolerances"]))
    return (["## Fidelity ladder: span model against link model", "",
             "The span model (rotors and longitudinal spans) against the link-by-link model, both through "
             "ChainDrive.fmu in closed loop with the torque tables (`python -m harness fidelity`): cycle means "
             "+- their 95 % half-widths, the difference of the span model from the link model (% for levels, dB "
             "for order amplitudes), the tolerance and whether the span model meets it; *within scatter* when "
             "the difference lies within the combined 95 % interval of both runs. Tolerances: "
             + ", ".join(f"`{t}`" for t in tolerances) + f" (orders: those of at least {100 * ORDER_SHARE:g} % of "
             "the largest order amplitude of their signal in the link run; `-`: not among them at that speed). "
             "Cost: CPU seconds inside fmi2DoStep per simulated second.", "",
             "Runs: " + "; ".join(f"`{c['command']}`" for c in comparisons) + ".", ""]
            + accuracy_table(comparisons) + [""] + cost_table(comparisons) + [""])
