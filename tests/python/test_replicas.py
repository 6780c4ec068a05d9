"""Replicas (harness/replicas.py): the ensemble's statistics from the replicas' summaries, each
replica's perturbed input, the option's checks and a short ensemble through ChainDrive.fmu."""
import json
import math
import pathlib

import pytest
from scipy import stats

from harness import job, replicas
from harness.drive.description import elements
from harness.tables import tables
from harness.bench import realtime
from harness_cli import harness, one_error_line


def stat(mean, ci95, cycles=100, unit="deg"):
    return dict(mean=mean, ci95=ci95, cycles=cycles, unit=unit)


def test_replicas_that_disagree_widen_the_interval_to_their_spread():
    # four runs each claiming +- 0.01 whose means spread by 0.02: the spread sets the interval
    means = [0.31, 0.33, 0.34, 0.36]
    s = replicas.combine_quantity([stat(m, 0.01) for m in means])
    sd = math.sqrt(sum((m - 0.335) ** 2 for m in means) / 3)
    assert s["mean"] == pytest.approx(0.335)
    assert s["ci95"] == pytest.approx(stats.t.ppf(0.975, 3) * sd / 2.0)
    assert s["withinRuns"] == pytest.approx(0.01 / 2.0) and s["ci95"] > 5 * s["withinRuns"]
    assert s["spreadRatio"] == pytest.approx(sd / (0.01 / 1.96))  # the replicas' scatter over their own
    assert s["replicas"] == 4 and s["cycles"] == 400 and s["unit"] == "deg" and s["replicaMeans"] == means


def test_replicas_that_happen_to_agree_keep_their_own_intervals():
    s = replicas.combine_quantity([stat(1.0, 0.2), stat(1.0 + 1e-6, 0.2)])
    assert s["ci95"] == pytest.approx(math.sqrt(2 * 0.2 ** 2) / 2) and s["betweenRuns"] < s["ci95"]
    assert s["spreadRatio"] < 1e-4


def test_one_replica_is_the_run_itself():
    s = replicas.combine_quantity([stat(2.0, 0.3)])
    assert s["mean"] == 2.0 and s["ci95"] == pytest.approx(0.3) and math.isnan(s["betweenRuns"])


def test_the_ensemble_has_the_quantities_every_replica_has():
    a = {"x": stat(1.0, 0.1), "y": stat(2.0, 0.1)}
    b = {"x": stat(1.2, 0.1)}
    assert list(replicas.combine([a, b])) == ["x"]


def test_replica_k_perturbs_the_crankshaft_speed_by_k_parts_in_a_billion(tmp_path):
    config = job.run_config(rpm=3000.0, out=tmp_path, replicas=3)
    r2 = replicas.replica_config(config, 2)
    assert r2.speed_perturbation == pytest.approx(2e-9) and r2.replicas == 1 and r2.out == tmp_path / "replica2"
    assert replicas.replica_config(config, 0).speed_perturbation == 0.0
    loads, speed, drive = job.drive_loads(config, elements()), tables.crankshaft_speed(3000.0), elements()
    angles = {"crankshaft": 90.0, "camshaftIntake": 15.0, "camshaftExhaust": 20.0}
    plain = job.table_inputs(loads, speed, drive)(0.0, angles)
    perturbed = job.table_inputs(loads, speed, drive, speed_factor=1.0 + 2e-9)(0.0, angles)
    assert perturbed["crankshaft.w"] == plain["crankshaft.w"] * (1.0 + 2e-9) != plain["crankshaft.w"]
    assert {k: v for k, v in perturbed.items() if k != "crankshaft.w"} == \
        {k: v for k, v in plain.items() if k != "crankshaft.w"}


def test_an_ensemble_of_fewer_than_one_run_is_refused(tmp_path):
    line = one_error_line(*harness("run", "--replicas", "0", "--out", str(tmp_path))[::2])
    assert "--replicas 0: at least 1 run" in line, line


def test_the_cvt_scene_refuses_replicas(tmp_path):
    line = one_error_line(*harness("run", "--scene", "cvt", "--replicas", "2", "--out", str(tmp_path))[::2])
    assert "--replicas 2: does not apply to the CVT scene" in line, line


def test_an_ensembles_accuracy_row_names_its_replicas():
    one, four = stat(1.0, 0.1, 480), replicas.combine_quantity([stat(1.0, 0.1, 480)] * 4)
    assert realtime.cycles_cell(one) == "480 cycles" and realtime.cycles_cell(four) == "4 x 480 cycles"


def test_a_short_ensemble_writes_its_replicas_and_their_statistics(tmp_path):
    status, out, err = harness("run", "--rpm", "3000", "--cycles", "2", "--run-in", "1", "--replicas", "2",
                               "--out", str(tmp_path))
    assert status == 0, err
    ensemble = json.loads((tmp_path / "summary.json").read_text())
    runs = [json.loads((tmp_path / f"replica{k}" / "summary.json").read_text()) for k in range(2)]
    F = ensemble["tensioner.F.mean"]
    assert F["replicaMeans"] == [r["tensioner.F.mean"]["mean"] for r in runs]
    assert F["replicaMeans"][0] != F["replicaMeans"][1]  # the perturbation reaches the FMU and grows
    assert F["mean"] == pytest.approx(sum(F["replicaMeans"]) / 2) and F["cycles"] == 4
    assert json.loads((tmp_path / "run.json").read_text())["replicas"] == 2
    assert "ensemble of 2 replicas" in out and pathlib.Path(tmp_path / "replica1" / "outputs.csv").exists()
