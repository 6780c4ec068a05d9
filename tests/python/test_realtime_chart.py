"""The work-precision chart of the real-time candidates (harness/bench/realtime_chart.py): each
report's speed a point, its error the largest difference over its tolerance, its verdict from the
accuracy table; reports it cannot read are named."""
import json

import pytest

from harness import cli
from harness.bench import realtime_chart

KEYS = ("tensioner.F.mean", "tensionGuide.phi.peakToPeak_deg", "tensioner.F.order6")
TOLERANCE = {"tensioner.F.mean": 2.0, "tensionGuide.phi.peakToPeak_deg": 10.0, "tensioner.F.order6": 3.0}


def row(key, difference, z):
    return dict(key=key, difference=difference, tolerance=TOLERANCE[key], meets=abs(difference) <= TOLERANCE[key],
                withinScatter=abs(z) <= 1.0, z=z)


def report(rpm, method, step, rtf, differences, zs):
    speed = dict(rpm=rpm, method=method, step=step, cycles=480, rtf=rtf, rtfRuns=[rtf], rtfTarget=None,
                 model=dict(median=1e-4, p99=1.2e-4, max=2e-4), p99OverMedian=1.2,
                 accuracy=[row(k, d, z) for k, d, z in zip(KEYS, differences, zs)])
    return dict(machine="test", command="test", replicas=4, host=dict(cpuPerSimulatedSecond=1.0, cpuPerLinkStep=2e-8),
                speeds=[speed])


def point_of(r):
    return realtime_chart.point(r, r["speeds"][0], "report.json")


def test_a_point_is_its_largest_difference_over_its_tolerance_and_its_verdict():
    # guide p-p 6 % of 10 % (0.6) is the largest share; every difference met, one not within scatter
    met = point_of(report(3000.0, "fixed-verlet", 2.5e-6, 1.0, [1.0, -6.0, 0.3], [0.5, -1.4, 0.2]))
    assert met["worst"] == pytest.approx(0.6) and met["worstKey"] == "tensionGuide.phi.peakToPeak_deg"
    assert met["verdict"] == "met" and met["withinScatter"] == 2 and met["met"] == 3
    # order 6 at +4.2 dB misses its 3 dB: the largest share 1.4, the verdict missed
    missed = point_of(report(3000.0, "fixed-newmark", 7e-6, 1.9, [-2.8, 1.0, 4.2], [-1.8, 0.1, 5.0]))
    assert missed["worst"] == pytest.approx(1.4) and missed["verdict"] == "missed"
    inside = point_of(report(3000.0, "fixed-verlet", 2.5e-6, 1.0, [0.1, 1.0, 0.1], [0.1, 0.2, 0.3]))
    assert inside["verdict"] == "within scatter"


def test_the_chart_and_its_table_are_written(tmp_path):
    paths = []
    for k, (method, step, rtf, differences, zs) in enumerate([
            ("fixed-verlet-implicit-joint-damping", 3.57e-6, 0.83, [0.0, -1.4, 0.3], [0.0, -0.2, 0.2]),
            ("fixed-newmark", 7.14e-6, 1.86, [-2.8, -1.2, 4.5], [-1.8, -0.3, 5.0])]):
        paths.append(tmp_path / f"r{k}.json")
        paths[-1].write_text(json.dumps(report(6000.0, method, step, rtf, differences, zs)))
    out = tmp_path / "wp.png"
    assert cli.main(["realtime-chart", *map(str, paths), "--out", str(out)]) == 0
    assert out.stat().st_size > 0
    table = out.with_suffix(".md").read_text()
    assert "| 6000 rpm | fixed-verlet-implicit-joint-damping | 3.57 us | 0.83 | 0.35 | 1.20 | 0.14 (" in table
    assert "| 6000 rpm | fixed-newmark | 7.14 us | 1.86 | 0.35 | 1.20 | 1.50 (tensioner.F.order6) | 1/3 | 1/3 |" in table


def test_a_timing_report_gives_the_rtf_of_its_speed_method_and_step(tmp_path, capsys):
    # the ensemble ran beside another job (RTF 1.0); the quiet timing run gives 0.83, for that step only
    ensemble = tmp_path / "ensemble.json"
    ensemble.write_text(json.dumps(report(3000.0, "fixed-verlet", 2.5e-6, 1.0, [0.1, 1.0, 0.1], [0.1, 0.2, 0.3])))
    timing = report(3000.0, "fixed-verlet", 2.5000000000000002e-06, 0.83, [], [])  # (the same step, rounded)
    timing["host"]["cpuPerSimulatedSecond"] = 0.9
    (tmp_path / "timing.json").write_text(json.dumps(timing))
    out = tmp_path / "wp.png"
    assert cli.main(["realtime-chart", str(ensemble), "--timing", str(tmp_path / "timing.json"), "--out", str(out)]) == 0
    row = next(r for r in out.with_suffix(".md").read_text().splitlines() if r.startswith("| 3000 rpm"))
    assert "| 2.5 us | 0.83 | 0.25 |" in row and row.endswith("| 0.9 | ensemble.json | timing.json |")
    # a timing of a step no report has is named, not dropped
    timing["speeds"].append(dict(timing["speeds"][0], step=3e-6, rtf=0.5))
    (tmp_path / "timing.json").write_text(json.dumps(timing))
    with pytest.raises(SystemExit):
        cli.main(["realtime-chart", str(ensemble), "--timing", str(tmp_path / "timing.json"), "--out", str(out)])
    assert "timing.json: fixed-verlet at 3 us, 3000 rpm" in capsys.readouterr().err


def test_a_difference_that_is_not_a_number_is_missed_and_drawn_at_the_top(tmp_path):
    nan = point_of(report(6000.0, "fixed-verlet", 2.5e-6, 1.0, [float("nan"), 1.0, 0.1], [float("nan"), 0.1, 0.1]))
    assert nan["verdict"] == "missed" and nan["worst"] == float("inf") and nan["worstKey"] == "tensioner.F.mean"
    out = tmp_path / "wp.png"
    path = tmp_path / "nan.json"
    path.write_text(json.dumps(report(6000.0, "fixed-verlet", 2.5e-6, 1.0, [float("nan"), 1.0, 0.1], [0.0, 0.1, 0.1])))
    assert cli.main(["realtime-chart", str(path), "--out", str(out)]) == 0
    assert "| not a number (tensioner.F.mean) | 2/3 |" in out.with_suffix(".md").read_text()


def test_reports_without_an_accuracy_table_draw_nothing_and_say_so(tmp_path, capsys):
    path = tmp_path / "timing.json"
    path.write_text(json.dumps(report(6000.0, "fixed-verlet", 2.5e-6, 1.0, [], [])))
    with pytest.raises(SystemExit):
        cli.main(["realtime-chart", str(path), "--out", str(tmp_path / "wp.png")])
    assert "no report has an accuracy table" in capsys.readouterr().err


def test_a_file_that_is_not_a_report_is_named(tmp_path, capsys):
    summary = tmp_path / "summary.json"
    summary.write_text(json.dumps({"tensioner.F.mean": {"mean": 1.0}}))
    with pytest.raises(SystemExit) as e:
        cli.main(["realtime-chart", str(summary), "--out", str(tmp_path / "wp.png")])
    assert e.value.code == 2 and "summary.json: not a report of bench-realtime" in capsys.readouterr().err
    with pytest.raises(SystemExit) as e:
        cli.main(["realtime-chart", str(tmp_path / "missing.json")])
    assert e.value.code == 2 and "missing.json: not a readable JSON report" in capsys.readouterr().err
    incomplete = report(6000.0, "fixed-verlet", 2.5e-6, 1.0, [], [])
    del incomplete["speeds"][0]["p99OverMedian"]
    summary.write_text(json.dumps(incomplete))
    with pytest.raises(SystemExit):
        cli.main(["realtime-chart", str(summary)])
    assert "no speeds[0].p99OverMedian" in capsys.readouterr().err
