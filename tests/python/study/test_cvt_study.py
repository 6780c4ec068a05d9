"""The chain CVT's work-precision section (harness/study/cvt.py): its quick variant end to end, and
the comparison with the reference."""
import pytest

from harness.study import cvt


def statistic(mean, ci):
    return {"mean": mean, "ci95": ci, "cycles": 6, "unit": ""}


def point(scale, torque=0.0, energy=0.0):
    return {"method": "m", "setting": 1e-6, "cpuPerRevolution": 0.1,
            "statistics": {k: statistic(100.0 * scale, 1.0) for k in cvt.KEYS},
            "checks": {"torqueBalanceError": torque, "energyBalanceError": energy}}


def test_compare_judges_statistics_and_checks():
    ref = point(1.0)
    near, far, unbalanced = point(1.01), point(1.05), point(1.0, energy=0.02)
    for p in (near, far, unbalanced):
        cvt.compare(p, ref)
    assert near["errors"]["slip"]["percent"] == pytest.approx(1.0)
    assert near["errors"]["slip"]["z"] == pytest.approx(1.0 / 2 ** 0.5)
    assert near["consistent"]
    assert not far["consistent"]             # 5 % off with half-widths of 1 %: |z| = 3.5
    assert not unbalanced["consistent"]      # the energy balance off by 2 % (limit 1 %)


def test_quick_study_gives_points_failures_and_the_section(tmp_path):
    r = cvt.study(tmp_path, quick=True, log=lambda *_: None)
    assert "failure" not in r["reference"]
    by = {(p["method"], p["setting"]): p for p in r["points"]}
    assert "blow-up" in by[("fixed-verlet", 1e-5)]["failure"]  # too long a step: a named failure
    assert by[("fixed-verlet", 1e-6)]["consistent"]             # (the quick reference itself)
    assert by[("arkode-erk", 1e-5)]["cpuPerRevolution"] > 0
    stepping = by[("time-stepping", 5e-6)]               # (from the handover state: Coulomb's friction)
    assert stepping["facets"] == 4 and stepping["lcp"]["lcpSolves"] > 0 and stepping["cpuPerRevolution"] > 0
    rigid = by[("time-stepping-rigid-pins", 5e-6)]             # (the pins closing with Newton impacts)
    assert rigid["lcp"]["impacts"] > 0 and rigid["cpuPerRevolution"] > 0
    cvt.chart(tmp_path / "wp_cvt.png", r)
    text = cvt.section(r)
    assert text.startswith("## The chain CVT") and "energy balance" in text and "failed" in text
    assert "time-stepping (4 facets)" in text and "The friction law" in text
    assert (tmp_path / "wp_cvt.png").stat().st_size > 1000
