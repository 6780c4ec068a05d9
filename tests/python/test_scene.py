"""Scenes through ChainDrive.fmu with the measured-torque tables (synthesized, harness/tables/data):
the main job (harness/job.py)."""
import json
import subprocess
import sys

import numpy as np
import pytest

from harness import job as scene
from harness import cycle_stats, paths
from harness.drive.description import elements
from harness.plots import plots
from harness.tables import tables

RPM = 2000.0


@pytest.fixture(scope="module")
def closed_loop_2000():
    config = scene.run_config(rpm=RPM, solver_step=2.5e-6)
    cycle = 120.0 / RPM
    d, _, _ = scene.run_closed(config, 3 * cycle, scene.table_inputs(scene.drive_loads(config, elements()),
                                                                tables.crankshaft_speed(RPM), elements()))
    return d, d["time"] >= cycle  # the first engine cycle is the start transient


def test_outputs_finite_and_tensioner_force_plausible(closed_loop_2000):
    d, sel = closed_loop_2000
    for k, v in d.items():
        if not k.startswith("input."):
            assert np.all(np.isfinite(v)), k
    F = d["tensioner.F"][sel]
    # typical: quasi-static tensioner force 100-400 N, dynamic peaks 1-3 kN at resonance; the
    # default hydraulic tensioner at rest pushes about 60 N (its spring's 25 N and the oil's 2.9 bar
    # on the plunger), so a mean of 30-400 N and peaks below 3 kN
    assert 30.0 < F.mean() < 400.0
    assert F.min() >= 0.0 and F.max() < 3000.0
    # the camshafts follow the crankshaft at half its speed
    w = d["camshaftIntake.w"][sel].mean()
    assert w == pytest.approx(0.5 * RPM * 2 * np.pi / 60, rel=0.01)


def test_tensioner_force_spectrum_sits_at_the_engine_orders_of_the_tables(closed_loop_2000):
    d, sel = closed_loop_2000
    o, a = plots.order_spectrum(d["time"][sel], d["tensioner.F"][sel], RPM)
    keep = (o > 0.75) & (o < 40)
    o, a = o[keep], a[keep]
    peaks = [i for i in range(1, len(a) - 1) if a[i] >= a[i - 1] and a[i] >= a[i + 1]]
    top = sorted(peaks, key=lambda i: a[i], reverse=True)
    print("largest tensioner-force peaks (order, N):", [(round(o[i], 2), round(a[i], 1)) for i in top[:5]])
    # the camshaft-torque tables of a four-cylinder engine have engine order 2 and its multiples,
    # order 2 by far the largest; the crankshaft-speed table adds even orders, strongest near the
    # crankshaft's torsional resonance (400 Hz: order 12 at 2000 rpm)
    torque = tables.camshaft_torque(RPM).columns["camshaftIntake.tau"]
    spectrum = np.abs(np.fft.rfft(torque - torque.mean()))
    assert np.argmax(spectrum) == 4  # bin 4 over 720 deg = order 2
    # the largest component sits at an even engine order of the tables (tolerance: the window's
    # resolution, 0.25 order): with the hydraulic tensioner's stiff oil column the force follows the
    # crankshaft-speed table's order 12 (400 Hz) more than the camshafts' order 2; what follows
    # is the drive's own response
    assert abs(o[top[0]] - 2.0 * round(o[top[0]] / 2.0)) <= 0.26


def test_main_job_open_loop_quick(tmp_path):
    p = subprocess.run([sys.executable, "-m", "harness", "run", "--coupling", "open", "--cycles", "3", "--run-in", "1",
                        "--out", str(tmp_path)], capture_output=True, text=True, cwd=paths.ROOT)
    assert p.returncode == 0, p.stderr + p.stdout
    assert "tensioner.F.mean" in p.stdout and "real-time factor" in p.stdout
    for name in ("outputs.csv", "summary.json", "drive.png", "time_histories.png", "cycle_statistics.png", "spectra.png",
                 "link_cycle.png"):
        assert (tmp_path / name).stat().st_size > 1000, name
    summary = json.loads((tmp_path / "summary.json").read_text())
    expected = {"tensioner.F.mean", "tensioner.F.peakToPeak", "chain.Ftight.mean", "chain.Fslack.mean",
                "tensionGuide.phi.peakToPeak_deg", "camshaftIntake.timing.peakToPeak_degCA",
                "camshaftExhaust.timing.peakToPeak_degCA"}
    expected |= {f"tensioner.F.order{k}" for k in (2, 4, 6, 8, 21)}
    expected |= {f"tensionGuide.phi.order{k}_deg" for k in (2, 4, 6, 8, 21)}
    # the default drive's tensioner is hydraulic: its chamber pressure's statistics too
    expected |= {f"tensioner.chamberPressure.{s}_bar" for s in ("mean", "peakToPeak", "min")}
    assert set(summary) == expected
    for key, s in summary.items():
        assert set(s) == {"mean", "ci95", "cycles", "unit"}, key
        assert s["cycles"] == 3 and np.isfinite(s["mean"]) and s["ci95"] > 0.0, (key, s)
    # the tight span carries the camshaft torques: its mean force exceeds the slack span's
    assert summary["chain.Ftight.mean"]["mean"] > summary["chain.Fslack.mean"]["mean"]
    # its own check: the energy balance over the counted cycles, within its limit at the default step
    run = json.loads((tmp_path / "run.json").read_text())
    assert abs(run["checks"]["energyBalanceError"]) < run["checks"]["energyBalanceLimit"]
    assert run["warnings"] == [] and run["notes"] == [] and "checks: energy balance" in p.stdout


def test_main_job_span_fidelity_quick(tmp_path):
    """The main job with the span model (FMU parameter fidelity): the same summary and plots,
    the fidelity named in the header line, its own solver step, a fraction of the link model's cost."""
    p = subprocess.run([sys.executable, "-m", "harness", "run", "--fidelity", "span", "--rpm", "6000", "--cycles", "3",
                        "--run-in", "2", "--out", str(tmp_path)], capture_output=True, text=True, cwd=paths.ROOT)
    assert p.returncode == 0, p.stderr + p.stdout
    assert p.stdout.startswith("ChainDrive.fmu, span fidelity:") and "fixed-verlet at 33.3333 us" in p.stdout
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert list(summary) == cycle_stats.headline_keys(elements())
    assert all(s["cycles"] == 3 and np.isfinite(s["mean"]) for s in summary.values())
    run = json.loads((tmp_path / "run.json").read_text())
    assert run["fidelity"] == "span" and run["solverStep_s"] == 1e-4 / 3
    assert len(run["notes"]) == 1 and "note: span fidelity: outside the accuracy it was checked for" in p.stdout
    # the link model costs about 9 CPU s per simulated s inside fmi2DoStep; the span model a few hundredths
    assert 0.0 < run["doStepCpuPerSimulatedSecond"] < 2.0
    for name in ("outputs.csv", "time_histories.png", "cycle_statistics.png", "spectra.png", "link_cycle.png"):
        assert (tmp_path / name).stat().st_size > 1000, name
