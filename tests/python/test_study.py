"""The work-precision and stability study, reduced (--quick): runs end to end and every method
gives a point or a failure that the solver detected and named."""
import json
import math
import subprocess
import sys

import pytest

from harness import paths, study

FAILURE_KINDS = set(study.KIND_CODES) - {"timeout"}


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("study")
    p = subprocess.run([sys.executable, "-m", "harness.study", "--quick", "--jobs", "2", "--out", str(out)],
                       cwd=paths.ROOT, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    return out, json.loads((out / "results.json").read_text())


def test_every_method_gives_a_point_or_a_reported_failure(quick):
    out, r = quick
    (scene,) = r["scenes"]
    for m in study.METHODS:
        pts = [p for p in scene["points"] if p["method"] == m["id"]]
        assert len(pts) == len(m["quick"]), m["id"]
        for p in pts:
            if p["kind"] == "ok":
                e = p["errors"]
                assert p["cpu_per_s"] > 0 and p["repeatsIdentical"]
                for k in ("F_rms_pct", "F_max_N", "phi_rms_rad", "orders_maxabs_dB", "mesh_dB", "short_F_rms_pct"):
                    assert math.isfinite(e[k]), (m["id"], k)
            else:
                # a failure the solver detected and classified (not a crash, not a timeout)
                assert p["kind"] in FAILURE_KINDS, (m["id"], p["kind"], p["failure"])
                assert p["failure"] and p["failureTime"] is not None


def test_compliant_methods_converge_towards_the_reference(quick):
    """Over the short horizon, halving the Verlet step reduces the tensioner-force error, and the
    reference's own change is far below every compliant method's error."""
    _, r = quick
    (scene,) = r["scenes"]
    verlet = sorted([p for p in scene["points"] if p["method"] == "verlet"], key=lambda p: -p["value"])
    assert [p["kind"] for p in verlet] == ["ok", "ok"]
    assert verlet[1]["errors"]["short_F_rms_pct"] < verlet[0]["errors"]["short_F_rms_pct"]
    change = scene["reference"]["change"]["short_F_rms_pct"]
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
    assert "3000 rpm: CPU time at which each method first reaches 1 % RMS error" in text
    assert (out / "wp_3000rpm.png").stat().st_size > 10000
