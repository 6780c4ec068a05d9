"""Sweeps on Dask (harness/sweep/): a LocalCluster of 2 single-threaded workers gives every case
the statistics of running it here, bit for bit; a resumed sweep computes nothing it has; a bad
case is reported while the others finish; a worker killed during a sweep loses no case; the
command writes the dataset and the plots. Span fidelity and few cycles: seconds per case."""
import dataclasses
import os
import signal
import subprocess
import sys
import threading
import time

import pytest

from harness.sweep.cases import Case, run_case
from harness.sweep.execute import dask_client, run_cases

BASE = Case(rpm=0.0, fidelity="span", cycles=2)
SPEEDS = (2000.0, 3000.0, 4000.0, 5000.0)


@pytest.fixture(scope="module")
def client():
    with dask_client(workers=2) as c:
        yield c


@pytest.fixture(scope="module")
def four_cases():
    cases = [dataclasses.replace(BASE, rpm=r) for r in SPEEDS]
    return cases, [run_case(c) for c in cases]


def test_two_workers_give_the_statistics_of_one_by_one(client, four_cases, tmp_path):
    cases, here = four_cases
    results, computed = run_cases(cases, tmp_path, client=client, progress=False)
    assert computed == 4
    assert all(r["status"] == "ok" for r in results), [r.get("error") for r in results]
    for r, h in zip(results, here):
        assert r["rows"] == h["rows"]          # every statistic, exactly
        assert r["spectra"] == h["spectra"]
    assert len({r["rows"][0]["tensioner.F.mean"] for r in results}) == 4  # four different speeds


def test_a_resumed_sweep_computes_only_what_is_missing(client, four_cases, tmp_path):
    cases, here = four_cases
    run_cases(cases, tmp_path, client=client, progress=False)
    again, computed = run_cases(cases, tmp_path, client=client, progress=False)
    assert computed == 0
    assert [r["rows"] for r in again] == [h["rows"] for h in here]
    next(tmp_path.glob("*.json")).unlink()  # a sweep stopped before its last case
    _, computed = run_cases(cases, tmp_path, client=client, progress=False)
    assert computed == 1
    # another setting is another case
    _, computed = run_cases([dataclasses.replace(cases[0], cycles=3)], tmp_path, client=client, progress=False)
    assert computed == 1


def test_bad_cases_are_reported_and_the_others_finish(client, tmp_path):
    cases = [dataclasses.replace(BASE, rpm=3000.0), dataclasses.replace(BASE, rpm=3000.0, method="no-such-method"),
             dataclasses.replace(BASE, rpm=9000.0), dataclasses.replace(BASE, rpm=3000.0, solver_step=-1.0)]
    results, _ = run_cases(cases, tmp_path, client=client, progress=False)
    assert [r["status"] for r in results] == ["ok", "failed", "failed", "failed"]
    assert "solver.method: 'no-such-method' is unknown" in results[1]["error"]
    assert "9000 rpm is outside the tabulated range 1000-6000 rpm" in results[2]["error"]
    assert "solver.step = -1 s is outside [1e-9 s, 0.001 s]" in results[3]["error"]
    assert len(list(tmp_path.glob("*.json"))) == 1  # failures are not cached: they run again next time


def test_a_worker_killed_during_a_sweep_loses_no_case(client, tmp_path):
    cases = [dataclasses.replace(BASE, rpm=r, cycles=12) for r in SPEEDS]
    out = {}
    sweep = threading.Thread(target=lambda: out.update(r=run_cases(cases, tmp_path, client=client, progress=False)))
    sweep.start()
    deadline = time.time() + 60
    while not any(client.processing().values()):  # wait until a worker runs a case
        assert time.time() < deadline, "no case started"
        time.sleep(0.05)
    busy = next(w for w, tasks in client.processing().items() if tasks)
    os.kill(client.run(os.getpid, workers=[busy])[busy], signal.SIGKILL)
    sweep.join(timeout=300)
    results, computed = out["r"]
    assert computed == 4
    assert all(r["status"] == "ok" for r in results), [r.get("error") for r in results]
    assert [r["rows"] for r in results] == [run_case(c)["rows"] for c in cases]


def test_the_command_writes_the_dataset_and_the_plots_and_a_run_up(tmp_path):
    xr = pytest.importorskip("xarray")
    cmd = [sys.executable, "-m", "harness.sweep", "--rpm", "2000,3000", "--runup", "2000:3000", "--ramp-time", "0.4",
           "--fidelity", "span", "--cycles", "2", "--workers", "2", "--no-progress", "--out", str(tmp_path)]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout + p.stderr
    sweep = xr.open_dataset(tmp_path / "sweep.nc", engine="h5netcdf")
    assert list(sweep["rpm"].values) == [2000.0, 3000.0]
    assert sweep["tensioner.F.mean"].attrs["units"] == "N"
    assert sweep["tensionGuide.phi.orderAmplitude"].dims == ("point", "order")
    assert sweep.attrs["fidelity"] == "span" and "sprockets" in sweep.attrs["drive_json"]
    runup = xr.open_dataset(tmp_path / "runup.nc", engine="h5netcdf")
    rpm = runup["rpm"].values
    assert len(rpm) >= 5 and rpm[0] < 2200.0 and rpm[-1] > 2700.0 and all(rpm[1:] > rpm[:-1])  # a cycle per point
    for study in ("sweep", "runup"):
        for png in ("campbell_tensioner_F.png", "campbell_tensionGuide_phi.png", "order_cuts.png",
                    "forces_over_speed.png"):
            assert (tmp_path / study / png).stat().st_size > 10000, (study, png)


@pytest.mark.parametrize("argv, message", [
    (["--rpm", "3000:1000:500"], "TO >= FROM"),
    (["--rpm", "fast"], "'fast': expected FROM:TO:STEP"),
    (["--runup", "1000"], "--runup 1000: expected FROM:TO"),
    (["--cycles", "1"], "--cycles 1: at least 2"),
    (["--workers", "0"], "--workers 0: must be >= 1"),
])
def test_bad_options_are_named(argv, message):
    p = subprocess.run([sys.executable, "-m", "harness.sweep"] + argv, capture_output=True, text=True, timeout=60)
    assert p.returncode == 2 and message in p.stderr, p.stderr


def test_run_up_inputs_follow_the_tables_speed_dependence_and_hold_beyond_them():
    import math
    from harness import job
    from harness.sweep.cases import runup_inputs
    from harness.tables import tables
    from harness.drive.description import elements
    case, drive = Case(rpm=800.0, rpm_end=6500.0, ramp_s=1.0), elements()
    inputs = runup_inputs(case, 0.2, drive)
    at = {r: job.table_inputs(job.drive_loads(job.run_config(rpm=r), drive), tables.crankshaft_speed(r), drive)
          for r in (1000.0, 2000.0, 3000.0, 6000.0)}

    def rad_s(rpm):
        return rpm * 2.0 * math.pi / 60.0
    for angle in (0.0, 123.0, 400.0):
        crank = {"crankshaft": angle, "camshaftIntake": 0.5 * angle, "camshaftExhaust": 0.5 * angle}
        held = inputs(0.1, crank)           # run-in at 800 rpm: the 1000 rpm table's shape
        ref = at[1000.0](0.1, crank)
        assert held["camshaftIntake.tau"] == ref["camshaftIntake.tau"]
        assert held["crankshaft.w"] == pytest.approx(ref["crankshaft.w"] * 800.0 / 1000.0, rel=1e-12)
        mid = inputs(0.2 + 1700.0 / 5700.0, crank)  # 2500 rpm: halfway between two tables
        lo, hi = at[2000.0](0.0, crank), at[3000.0](0.0, crank)
        assert mid["camshaftExhaust.tau"] == pytest.approx(0.5 * (lo["camshaftExhaust.tau"] + hi["camshaftExhaust.tau"]))
        assert mid["crankshaft.w"] == pytest.approx(rad_s(2500.0) * 0.5 * (lo["crankshaft.w"] / rad_s(2000.0)
                                                                          + hi["crankshaft.w"] / rad_s(3000.0)))
        top = inputs(5.0, crank)             # after the ramp: 6500 rpm, the 6000 rpm table's shape
        assert top["camshaftIntake.tau"] == at[6000.0](0.0, crank)["camshaftIntake.tau"]
        assert top["crankshaft.w"] == pytest.approx(at[6000.0](0.0, crank)["crankshaft.w"] * 6500.0 / 6000.0)
