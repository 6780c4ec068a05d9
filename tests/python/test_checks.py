"""A run's own checks: a missed limit is a warning line and an entry of the run's JSON, and with
--strict the exit status 1; a fidelity outside the accuracy it was checked for says so."""
import json
import subprocess
import sys

import numpy as np

from harness import checks, paths
from harness.cvt import job as cvt_job


def test_the_energy_balance_of_a_record():
    # 10 J in, 8 J dissipated, kinetic energy up by 1 J, elastic by 0.5 J: 0.5 J unaccounted, 6.25 %
    record = {"energy.input": np.array([0.0, 10.0]), "energy.dissipated": np.array([2.0, 10.0]),
              "energy.kinetic": np.array([1.0, 2.0]), "energy.elastic": np.array([0.0, 0.5])}
    error = checks.energy_balance_error(record, 0, 1)
    assert error == 0.5 / 8.0
    assert checks.energy_warnings(error) and "+6.25 %" in checks.energy_warnings(error)[0]
    assert checks.energy_warnings(0.01) == []


def test_the_cvt_balances_warn_beyond_their_limits():
    within = {"torqueBalanceError": 0.019, "energyBalanceError": -0.009}
    assert cvt_job.check_warnings(within) == []
    beyond = {"torqueBalanceError": -0.0928, "energyBalanceError": float("nan")}
    lines = cvt_job.check_warnings(beyond)
    assert len(lines) == 2 and "-9.28 %" in lines[0] and "limit 2 %" in lines[0]  # (NaN is not within)


def test_the_span_fidelity_notes_its_checked_accuracy():
    assert checks.fidelity_notes("link", None) == []
    note, = checks.fidelity_notes("span", None)
    ladder = [json.loads(f.read_text()) for f in checks.FIDELITY_CHECKS.glob("fidelity-*.json")]
    assert len(ladder) == 3
    rows = [row for speed in ladder for row in speed["rows"]]
    missed = sum(not row["meets"] for row in rows)
    assert f"missed {missed} of {len(rows)} tolerances" in note
    assert "default drive only" in checks.fidelity_notes("span", "my_drive.json")[0]


def test_a_cvt_run_that_misses_its_checks_says_so_and_fails_with_strict(tmp_path):
    """The CVT at a 2 us step (four times the default): its balances miss their limits."""
    command = [sys.executable, "-m", "harness", "run", "--scene", "cvt", "--revolutions", "2",
               "--run-in-revolutions", "2", "--load-torque", "80", "--solver-step", "2e-6", "--out", str(tmp_path)]
    loose = subprocess.run(command, capture_output=True, text=True, cwd=paths.ROOT)
    assert loose.returncode == 0, loose.stderr
    assert "warning: energy balance" in loose.stdout
    assert json.loads((tmp_path / "cvt_summary.json").read_text())["warnings"]
    strict = subprocess.run(command + ["--strict"], capture_output=True, text=True, cwd=paths.ROOT)
    assert strict.returncode == checks.EXIT_STRICT
