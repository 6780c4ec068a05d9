"""The divergence-rate study, reduced (--quick): runs end to end, finds a positive divergence rate
on the default drive, and reports a run that blows up as a failure, not as a number."""
import json
import math
import subprocess
import sys

import pytest

from harness import paths
from harness.study.chaos import analysis, twins


def run_chaos(out, *options):
    p = subprocess.run([sys.executable, "-m", "harness", "chaos", "--quick", "--jobs", "2", "--out", str(out),
                        *options], cwd=paths.ROOT, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    return json.loads((out / "results.json").read_text())


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("chaos")
    return out, run_chaos(out)


def test_default_drive_diverges_at_a_positive_rate(quick):
    out, r = quick
    (default,) = r["settings"]
    assert default["id"] == "default" and default["status"] == "ok"
    for name, *_ in analysis.SIGNALS:
        sig = default["signals"][name]
        rate = sig["rate_per_ms"]
        # twins that differ by 1e-12 separate within milliseconds, not seconds
        assert rate["median"] is not None and 0.05 < rate["min"] <= rate["median"] <= rate["max"] < 20.0, name
        assert math.isfinite(sig["efold_ms"]) and sig["independentLevel"] > 0.0
    saturation = default["signals"]["tensioner.F"]["saturation_ms"]["median"]
    assert saturation is not None and saturation < 1e3 * r["cycle"] * default["twinCycles"]
    assert (out / "report.md").exists() and (out / "lambda.png").exists() and (out / "divergence.png").exists()


def test_per_cycle_twin_statistics_are_reported(quick):
    _, r = quick
    c = r["settings"][0]["cycles"]
    assert c["pairs"] == 3 and c["cycles"] == twins.QUICK_CYCLES
    for key in analysis.CYCLE_KEYS:
        k = c["keys"][key]
        assert len(k["ratio"]) == twins.QUICK_CYCLES and all(x >= 0.0 for x in k["ratio"]) and 0.0 <= k["bound"] < 1.0


def test_a_blow_up_is_a_failure_not_a_number(tmp_path):
    # ten times the joint damping is unstable in explicit Verlet at 2.5 us
    r = run_chaos(tmp_path, "--settings", "joint10", "--verlet-steps", "2.5e-6")
    (s,) = r["settings"]
    assert s["status"] == "failed" and "signals" not in s
    assert [t["kind"] for t in s["runIn"]] == ["blow-up"] and s["runIn"][0]["failureTime"] > 0.0
    report = (tmp_path / "report.md").read_text()
    assert "FAILED" in report and "blow-up" in report
