"""The CVT's main job end to end (harness/cvt/job.py): a short stationary run, its statistics,
checks and plots; the timing drive's options refused."""
import json
import subprocess
import sys

import numpy as np
import pytest

from harness import paths
from harness.cvt import job


def test_short_cvt_job_reports_statistics_checks_and_plots(tmp_path):
    p = subprocess.run([sys.executable, "-m", "harness", "run", "--scene", "cvt", "--revolutions", "2",
                        "--run-in-revolutions", "1", "--solver-step", "1e-6", "--out", str(tmp_path)],
                       capture_output=True, text=True, cwd=paths.ROOT)
    assert p.returncode == 0, p.stderr
    s = json.loads((tmp_path / "cvt_summary.json").read_text())
    stats, checks = s["statistics"], s["checks"]
    assert stats["slip"]["cycles"] == 2
    # the stationary checks: torque balance within 2 %, energy within 1 %
    assert abs(checks["torqueBalanceError"]) < 0.02
    assert abs(checks["energyBalanceError"]) < 0.01
    # the load held: the chain's torque on the driven pulley is the load's, the tight strand tighter
    assert stats["drivenTorque"]["mean"] == pytest.approx(job.DEFAULT_LOAD, rel=0.02)
    assert stats["tightStrandForce"]["mean"] > stats["slackStrandForce"]["mean"]
    for name in ("cvt_figure9.png", "cvt_time_histories.png", "cvt_outputs.csv"):
        assert (tmp_path / name).stat().st_size > 1000, name
    assert "energy balance" in p.stdout and "revolutions" in p.stdout
    # the slip printed in % (the summary keeps the fraction)
    slip = next(line.split() for line in p.stdout.splitlines() if line.split()[:1] == ["slip"])
    assert float(slip[1]) == pytest.approx(100.0 * stats["slip"]["mean"], rel=1e-3) and slip[4] == "%"


def test_revolution_spans_are_whole_revolutions():
    t = np.arange(0.0, 1.05, 0.01)
    spans = job.revolution_spans(t, 0.25, 1)
    assert spans == [(25, 50), (50, 75), (75, 100)]


@pytest.mark.parametrize("option", [["--fidelity", "span"], ["--coupling", "open"], ["--revolutions", "1"]])
def test_options_that_do_not_apply_are_refused(option, tmp_path):
    p = subprocess.run([sys.executable, "-m", "harness", "run", "--scene", "cvt", *option, "--out", str(tmp_path)],
                       capture_output=True, text=True, cwd=paths.ROOT)
    assert p.returncode == 2
    assert option[0] in p.stderr
