"""The work-precision and stability study, reduced (--quick): runs end to end and every method
gives a point or a failure that the solver detected and named."""
import json
import math
import subprocess
import sys

import numpy as np
import pytest

from harness import paths
from harness.study import errors, ladder, methods, report

FAILURE_KINDS = set(methods.KIND_CODES) - {"timeout"}


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("study")
    p = subprocess.run([sys.executable, "-m", "harness", "study", "--quick", "--jobs", "2", "--out", str(out)],
                       cwd=paths.ROOT, capture_output=True, text=True, timeout=2400)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    return out, json.loads((out / "results.json").read_text())


def test_every_method_gives_a_point_or_a_reported_failure(quick):
    out, r = quick
    (scene,) = r["scenes"]
    for m in methods.METHODS:
        pts = [p for p in scene["points"] if p["method"] == m["id"]]
        assert len(pts) == len(m["quick"]), m["id"]
        for p in pts:
            if p["kind"] == "ok":
                e = p["errors"]
                assert p["cpu_per_s"] > 0 and p["repeatsIdentical"]
                for k in methods.VERDICT_KEYS:
                    assert math.isfinite(e[k]["error"]) and math.isfinite(e[k]["z"]), (m["id"], k)
                    assert e[k]["cycles"] == 2, (m["id"], k)
                assert math.isfinite(e["short_F_rms_pct"]) and isinstance(p["consistent"], bool)
            else:
                # a failure the solver detected and classified (not a crash, not a timeout)
                assert p["kind"] in FAILURE_KINDS, (m["id"], p["kind"], p["failure"])
                assert p["failure"] and p["failureTime"] is not None


def test_reference_ensemble_has_intervals_and_is_checked(quick):
    _, r = quick
    (scene,) = r["scenes"]
    ref = scene["reference"]
    F = ref["statistics"]["tensioner.F.mean"]
    assert F["cycles"] == 3 and F["ci95"] > 0 and F["sd"] > 0 and 20.0 < F["mean"] < 500.0
    assert isinstance(ref["check"]["consistent"], bool)
    assert set(ref["check"]["errors"]) == set(ref["statistics"])


def test_errors_are_differences_of_cycle_statistics():
    """The error measure on a constructed case: a method whose cycles equal the reference's shifted
    by one reference scatter is off by that shift, in % and in units of the scatter."""
    rng = np.random.default_rng(1)
    ref_values = 100.0 + rng.normal(0.0, 4.0, 60)
    ref = errors.reference_statistics({"tensioner.F.mean": ("N", ref_values), "tensioner.F.order2": ("N", ref_values)})
    sd = ref["tensioner.F.mean"]["sd"]
    e = errors.compare({"tensioner.F.mean": ("N", ref_values[:20] + sd), "tensioner.F.order2": ("N", ref_values[:20])},
                      ref)
    shift = e["tensioner.F.mean"]
    mean20 = float(np.mean(ref_values[:20]))
    assert shift["error"] == pytest.approx(100.0 * (mean20 + sd - ref["tensioner.F.mean"]["mean"])
                                           / ref["tensioner.F.mean"]["mean"])
    assert shift["scatter"] == pytest.approx((mean20 + sd - ref["tensioner.F.mean"]["mean"]) / sd)
    assert shift["errorUnit"] == "%" and e["tensioner.F.order2"]["errorUnit"] == "dB"
    assert abs(e["tensioner.F.order2"]["z"]) < 1.0  # a subset of the same cycles: consistent
    assert abs(shift["z"]) > 1.0                    # shifted by a whole cycle scatter: not consistent


def test_compliant_methods_converge_towards_the_reference(quick):
    """Over the short horizon, halving the Verlet step reduces the tensioner-force error, and the
    reference's own change is far below every compliant method's error."""
    _, r = quick
    (scene,) = r["scenes"]
    verlet = sorted([p for p in scene["points"] if p["method"] == "verlet"], key=lambda p: -p["value"])
    assert [p["kind"] for p in verlet] == ["ok", "ok"]
    assert verlet[1]["errors"]["short_F_rms_pct"] < verlet[0]["errors"]["short_F_rms_pct"]
    change = scene["reference"]["short"]["change"]["short_F_rms_pct"]
    compliant = [p for p in scene["points"] if p["kind"] == "ok" and p["method"] in ("verlet", "erk", "bdf-klu")]
    assert compliant and all(change < p["errors"]["short_F_rms_pct"] for p in compliant)


def test_stability_map_detects_and_names_failures(quick):
    _, r = quick
    runs = r["stability"]["runs"]
    assert runs
    for x in runs:
        assert x["kind"] == "ok" or x["kind"] in FAILURE_KINDS or x["kind"] == "timeout", x
    # an explicit step far beyond the stability limit is a detected blow-up, not garbage
    big = [x for x in runs if x["method"] == "verlet" and x["axis"] == "step [us]" and x["x"] == 8e-6]
    assert big and big[0]["kind"] == "blow-up", big


def test_real_time_timings_and_report(quick):
    out, r = quick
    assert {x["step"] for x in r["realtime"]} == {1e-4, 1e-3}
    for x in r["realtime"]:
        assert x.get("median", 0) > 0 or x["failure"], x
    text = (out / "report.md").read_text()
    assert "As accurate as the physics allows" in text and "Reference ensemble" in text
    assert (out / "wp_6000rpm.png").stat().st_size > 10000


def test_report_shows_the_span_model_when_the_results_hold_it(quick, tmp_path):
    """A comparison of python -m harness fidelity in the results: the report gets the fidelity
    ladder's section and the work-precision chart the span model's point."""
    _, r = quick
    (scene,) = r["scenes"]
    link = scene["reference"]["statistics"]
    span = {k: dict(v, mean=1.02 * v["mean"]) for k, v in link.items()}
    rows = ladder.compare(link, span, [ladder.Tolerance("tensioner.F.mean", 3.0, "%")])
    comparison = dict(rpm=scene["rpm"], rows=rows, spanMeetsAll=True, recommendation="span",
                      tolerances=["tensioner.F.mean=3%"], command="python -m harness fidelity --rpm 6000",
                      link=dict(cycles=3, cpuPerSimulatedSecond=9.0), span=dict(cycles=3, cpuPerSimulatedSecond=0.1))
    assert ladder.span_point(comparison)["error"] == pytest.approx(2.0)
    report.write(tmp_path, dict(r, fidelity=[comparison]))
    text = (tmp_path / "report.md").read_text()
    assert "## Fidelity ladder: span model against link model" in text and "| tensioner.F.mean |" in text
    assert (tmp_path / "wp_6000rpm.png").stat().st_size > 10000
