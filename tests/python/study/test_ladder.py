"""The fidelity ladder's logic (harness/study/ladder.py) on synthetic summaries: tolerances parsed
and refused, quantities within and outside their tolerance, the orders chosen by the 10 % rule,
differences in dB, and the recommendation of the cheapest fidelity that meets all."""
import dataclasses
import math

import pytest

from harness import cycle_stats, paths
from harness.drive import description
from harness.drive.description import elements
from harness.study import ladder

KEYS = cycle_stats.headline_keys(dataclasses.replace(elements(), hydraulic=False))


def summary(**means):
    """A summary of every headline quantity: mean 1 +- 0.01 unless given (key with _ for .)."""
    out = {k: dict(mean=1.0, ci95=0.01, cycles=30, unit="N") for k in KEYS}
    for name, value in means.items():
        mean, ci95 = value if isinstance(value, tuple) else (value, 0.01)
        out[name.replace("__", ".")] = dict(mean=mean, ci95=ci95, cycles=30, unit="N")
    return out


@pytest.mark.parametrize("text, expected", [
    ("tensioner.F.mean=2%", ("tensioner.F.mean", 2.0, "%")),
    ("chain.Fslack.mean = 0.5 %", ("chain.Fslack.mean", 0.5, "%")),
    ("camshaftIntake.timing.peakToPeak_degCA=10%", ("camshaftIntake.timing.peakToPeak_degCA", 10.0, "%")),
    ("tensioner.F.order2=3dB", ("tensioner.F.order2", 3.0, "dB")),
    ("tensionGuide.phi.order21_deg=1.5dB", ("tensionGuide.phi.order21_deg", 1.5, "dB")),
    ("orders=3dB", ("orders", 3.0, "dB")),
])
def test_valid_tolerances(text, expected):
    assert tuple(ladder.parse_tolerance(text, KEYS)) == expected


@pytest.mark.parametrize("text, says", [
    ("tensioner.F.mean", "KEY=VALUE"),
    ("=3%", "KEY=VALUE"),
    ("tensioner.F.mean=", "KEY=VALUE"),
    ("tensioner.F.mean=3", "no unit"),
    ("tensioner.F.mean=3N", "no unit"),
    ("tensioner.F.mean=abc%", "not a number"),
    ("tensioner.F.mean=-1%", "positive"),
    ("tensioner.F.mean=0%", "positive"),
    ("tensioner.F.mean=nan%", "positive"),
    ("tensioner.F.means=3%", "not a quantity of the summary"),
    ("tensioner.F.mean=3dB", "in %"),
    ("orders=3%", "in dB"),
    ("tensioner.F.order2=3%", "in dB"),
])
def test_invalid_tolerances_say_what_is_wrong(text, says):
    with pytest.raises(ValueError, match=says):
        ladder.parse_tolerance(text, KEYS)


def test_orders_are_those_of_at_least_a_tenth_of_their_signals_largest():
    link = summary(tensioner__F__order2=10.0, tensioner__F__order4=1.0, tensioner__F__order6=0.99,
                   tensioner__F__order8=4.0, tensioner__F__order21=0.5,
                   tensionGuide__phi__order2_deg=0.03, tensionGuide__phi__order4_deg=0.2,
                   tensionGuide__phi__order6_deg=0.019, tensionGuide__phi__order8_deg=0.0,
                   tensionGuide__phi__order21_deg=0.05)
    # each signal against its own largest: 10 N for the force, 0.2 deg for the guide angle
    assert ladder.selected_orders(link) == ["tensioner.F.order2", "tensioner.F.order4", "tensioner.F.order8",
                                            "tensionGuide.phi.order2_deg", "tensionGuide.phi.order4_deg",
                                            "tensionGuide.phi.order21_deg"]
    tolerances = [ladder.parse_tolerance(t, KEYS) for t in ("orders=3dB", "tensioner.F.order6=6dB",
                                                             "tensioner.F.order2=1dB", "tensioner.F.mean=2%")]
    chosen = ladder.per_quantity(tolerances, link)
    # explicit keys win over orders=, in the summary's order
    assert list(chosen) == ["tensioner.F.mean", "tensioner.F.order2", "tensioner.F.order4", "tensioner.F.order6",
                            "tensioner.F.order8", "tensionGuide.phi.order2_deg", "tensionGuide.phi.order4_deg",
                            "tensionGuide.phi.order21_deg"]
    assert chosen["tensioner.F.order2"].limit == 1.0 and chosen["tensioner.F.order6"].limit == 6.0
    assert chosen["tensioner.F.order4"] == ladder.Tolerance("tensioner.F.order4", 3.0, "dB")


def test_a_level_within_and_outside_its_tolerance():
    t = ladder.Tolerance("tensioner.F.mean", 3.0, "%")
    within = ladder.compare_quantity("tensioner.F.mean", dict(mean=100.0, ci95=1.0, cycles=24, unit="N"),
                                     dict(mean=102.0, ci95=0.5, cycles=200, unit="N"), t)
    assert within["difference"] == pytest.approx(2.0) and within["differenceUnit"] == "%"
    assert within["meets"] and within["tolerance"] == 3.0
    # 2 N against a combined half-width of sqrt(1 + 0.25) N: beyond the scatter of both runs
    assert within["z"] == pytest.approx(2.0 / math.sqrt(1.25)) and not within["withinScatter"]
    outside = ladder.compare_quantity("tensioner.F.mean", dict(mean=100.0, ci95=5.0, cycles=24, unit="N"),
                                      dict(mean=96.5, ci95=0.5, cycles=200, unit="N"), t)
    assert outside["difference"] == pytest.approx(-3.5) and not outside["meets"]
    assert outside["withinScatter"]  # a wide link interval: the difference is within the reference's scatter


def test_order_differences_are_in_dB():
    t = ladder.Tolerance("tensioner.F.order2", 3.0, "dB")
    link = dict(mean=10.0, ci95=0.2, cycles=24, unit="N")
    def span_at(mean):
        return ladder.compare_quantity(t.key, link, dict(mean=mean, ci95=0.1, cycles=200, unit="N"), t)

    louder, softer, half = span_at(10.0 * 10 ** (3.1 / 20)), span_at(10.0 * 10 ** (-2.9 / 20)), span_at(5.0)
    assert louder["difference"] == pytest.approx(3.1) and not louder["meets"]
    assert softer["difference"] == pytest.approx(-2.9) and softer["meets"]
    assert half["difference"] == pytest.approx(-6.0206, abs=1e-4) and half["differenceUnit"] == "dB"


def test_compare_takes_the_quantities_with_a_tolerance():
    link = summary(tensioner__F__mean=(100.0, 1.0), chain__Ftight__mean=(300.0, 3.0), tensioner__F__order2=10.0)
    span = summary(tensioner__F__mean=(101.0, 0.3), chain__Ftight__mean=(330.0, 1.0), tensioner__F__order2=9.0)
    tolerances = [ladder.parse_tolerance(t, KEYS) for t in ("tensioner.F.mean=3%", "chain.Ftight.mean=3%")]
    rows = ladder.compare(link, span, tolerances)
    assert [(r["key"], r["meets"]) for r in rows] == [("tensioner.F.mean", True), ("chain.Ftight.mean", False)]


def test_the_recommendation_is_the_cheapest_that_meets_all():
    link = dict(fidelity="link", cost=9.0, meetsAll=True)
    assert ladder.recommend([link, dict(fidelity="span", cost=0.01, meetsAll=True)]) == "span"
    assert ladder.recommend([link, dict(fidelity="span", cost=0.01, meetsAll=False)]) == "link"
    # a cheaper rung that misses, a costlier one that meets: the one that meets
    assert ladder.recommend([link, dict(fidelity="span", cost=0.01, meetsAll=False),
                             dict(fidelity="mid", cost=0.5, meetsAll=True)]) == "mid"
    # the link model's cost unknown (a summary without run.json): a measured rung that meets is cheaper
    assert ladder.recommend([dict(fidelity="link", cost=None, meetsAll=True),
                             dict(fidelity="span", cost=0.01, meetsAll=True)]) == "span"
    assert ladder.recommend([dict(fidelity="span", cost=0.01, meetsAll=False)]) is None


def comparison(rpm, span_mean):
    link, span = summary(tensioner__F__mean=(100.0, 1.0)), summary(tensioner__F__mean=(span_mean, 0.5))
    rows = ladder.compare(link, span, [ladder.Tolerance("tensioner.F.mean", 3.0, "%")])
    return dict(rpm=rpm, rows=rows, spanMeetsAll=all(r["meets"] for r in rows), recommendation="span",
                tolerances=["tensioner.F.mean=3%"], command=f"python -m harness fidelity --rpm {rpm:g}",
                link=dict(cycles=24, cpuPerSimulatedSecond=9.0), span=dict(cycles=200, cpuPerSimulatedSecond=0.01))


def test_accuracy_table_and_span_point():
    lines = ladder.report_lines([comparison(1000.0, 102.0), comparison(3000.0, 95.0)])
    assert lines[0] == "## Fidelity ladder: span model against link model"
    assert "`tensioner.F.mean=3%`" in lines[2] and "`python -m harness fidelity --rpm 3000`" in lines[4]
    row = next(x for x in lines if x.startswith("| tensioner.F.mean"))
    assert row.count("|") == 1 + 2 * 5 + 1
    assert "+2.00 %" in row and "met (z +1.8)" in row and "-5.00 %" in row and "**missed**" in row
    assert any(x.startswith("| 1000 rpm | 24 | 9 | 200 | 0.01 | 900 |") for x in lines)
    p = ladder.span_point(comparison(1000.0, 102.0))
    assert p["cpu_per_s"] == 0.01 and p["error"] == pytest.approx(2.0)
    assert p["errorHigh"] - p["error"] == pytest.approx(100.0 * math.hypot(1.0, 0.5) / 100.0)


def test_the_default_set_names_the_drives_own_elements():
    """A drive whose sprockets and guide have other names than the default drive's gets the same
    acceptance set in its own names (a single-camshaft drive: one timing), the default drive its
    own set unchanged."""
    default = description.elements(description.drive_json(None))
    assert ladder.default_tolerances(True, cycle_stats.headline_keys(default)) == ladder.default_tolerances(True)
    single = description.elements(description.drive_json(paths.ROOT / "tests/drives/sohc_single_cam.json"))
    keys = cycle_stats.headline_keys(single)
    specs = ladder.default_tolerances(True, keys)
    assert "camshaft.timing.peakToPeak_degCA=10%" in specs
    assert not any("camshaftIntake" in s for s in specs)
    for spec in specs:  # each one a tolerance of that drive's summary
        ladder.parse_tolerance(spec, keys)
    assert ladder.default_tolerances(False, keys)[-1] == "orders=3dB"
