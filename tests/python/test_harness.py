"""The harness end to end on the solver alone: inputs, a short run, the plots, the summary."""
import json
import math
import subprocess
import sys

import numpy as np
import pytest

from harness import paths, runs
from harness.plots import drive_picture, plots
from harness.tables import tables
from harness_cli import harness, one_error_line


def test_short_run_writes_finite_outputs(tmp_path):
    inputs = tables.write_inputs_csv(tmp_path / "in.csv", 3000.0, 0.004)
    code, text, s = runs.run(tmp_path / "out.csv", rpm=3000.0, duration=0.004, inputs_csv=inputs,
                             integrator="fixed-verlet", step=3e-6, output_step=1e-4)
    assert code == 0, text
    d = runs.read_csv(tmp_path / "out.csv")
    assert len(d["time"]) == 41
    for k, v in d.items():
        assert np.all(np.isfinite(v)), k
    # tensioner force physically plausible: positive, below 2 kN (typical: dynamic peaks 1-3 kN at resonance)
    assert 0.0 <= d["tensioner.F"].min() and d["tensioner.F"].max() < 2000.0
    assert s["cpu_per_sim_s"] > 0 and s["steps"] > 1000


def test_invalid_drive_reports_the_field(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"chain": {"pitch": -1}}')
    p = subprocess.run([paths.executable("chaindrive-run"), "--drive", str(bad), "--duration", "0.001"],
                       capture_output=True, text=True)
    assert p.returncode == 2
    # one line: the tool, the field, its value and range
    assert p.stderr.count("\n") == 1 and p.stderr.startswith("chaindrive-run: error: "), p.stderr
    assert "chain.pitch: -1 is out of range" in p.stderr


def test_failure_is_reported_not_hidden(tmp_path):
    code, text, s = runs.run(tmp_path / "out.csv", rpm=3000.0, duration=0.002, integrator="fixed-verlet",
                             step=1e-5, output_step=1e-4)
    assert code == 3
    assert "blow-up" in s["failure"] or "non-finite" in s["failure"]


def test_output_step_is_rounded_to_whole_grid_steps(tmp_path):
    # the fixed-step schemes take whole steps of exactly the step on the grid t0 + k h: an output
    # step that is not a whole number of steps is rounded to one, and the runner says so
    # (stderr) and writes the steps it used (summary); 20 us of 4 us steps with outputs asked
    # every 6 us: outputs every 8 us (2 steps), the last at 16 us
    summary, out = tmp_path / "s.json", tmp_path / "o.csv"
    p = subprocess.run([paths.executable("chaindrive-run"), "--integrator", "fixed-verlet", "--step", "4e-6",
                        "--output-step", "6e-6", "--duration", "2e-5", "--summary", str(summary), "--out", str(out),
                        "--quiet"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert "not a whole number of grid steps" in p.stderr
    s = json.loads(summary.read_text())
    assert s["step"] == 4e-6 and s["outputStep"] == pytest.approx(8e-6, rel=1e-12) and s["steps"] == 4
    assert np.allclose(runs.read_csv(out)["time"], [0.0, 8e-6, 16e-6], rtol=0, atol=1e-15)


def test_drive_picture(tmp_path):
    p = drive_picture.drive_picture(tmp_path / "drive.png")
    assert p.stat().st_size > 20000


def test_the_picture_of_a_drive_that_does_not_close_is_one_error_line(tmp_path):
    """The idler drive with ten links too few: the closure's own line, no traceback."""
    drive = json.loads((paths.ROOT / "tests" / "drives" / "idler.json").read_text())
    drive["chain"]["numberOfLinks"] = 120
    (tmp_path / "short.json").write_text(json.dumps(drive))
    line = one_error_line(*harness("picture", "--drive", str(tmp_path / "short.json"), "--out", str(tmp_path / "p.png"))[::2])
    assert "chain.numberOfLinks: 120 links cannot close around the layout" in line
    assert line.endswith("the path holds between 129.95 and 130.07 links; 130 links close it"), line




def test_dominant_orders_are_peaks_not_leakage_bins():
    # 3000 rpm, six revolutions: bins 1/6 order apart; an order between two bins leaks into both,
    # and both neighbours must not be listed as separate orders ahead of the next real one
    rpm = 3000.0
    t = np.arange(0.0, 0.12, 1e-5)
    w = 2.0 * math.pi * rpm / 60.0
    x = 5.0 * np.sin(8.08 * w * t) + 3.0 * np.sin(2.0 * w * t) + 1.0 * np.sin(13.0 * w * t)
    found = plots.dominant_orders(t, x, rpm, count=3)
    orders = [o for o, _ in found]
    assert abs(orders[0] - 8.08) < 0.1, found
    assert abs(orders[1] - 2.0) < 1e-6 and abs(orders[2] - 13.0) < 1e-6, found


def test_runs_forwards_the_tools_notes(tmp_path, capfd):
    """chaindrive-run's notes on stderr reach the caller's stderr (an output step rounded to whole
    grid steps: 1e-5 s on the span model's 33.3 us grid), and the CSV's own time column has the
    step it wrote."""
    runs.run(tmp_path / "out.csv", duration=1e-3, output_step=1e-5, fidelity="span")
    assert "outputs every 3.33333e-05 s" in capfd.readouterr().err
    t = runs.read_csv(tmp_path / "out.csv")["time"]
    assert np.diff(t) == pytest.approx(1e-4 / 3, rel=1e-9)
