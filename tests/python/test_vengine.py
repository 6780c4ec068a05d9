"""The V-engine coupling (harness/vengine.py): the balances on a record with known answers, the
coupling's sign conventions and held inputs on a brief coupled run, the same bits when libcosim
or ecos steps the three FMUs, and the communication steps it refuses."""
import math

import numpy as np
import pytest

from harness import vengine
from harness_cli import harness, one_error_line


def synthetic_record(n=2001, h=1e-4):
    """Three FMUs' record with known answers: each primary shaft turns at 200 rad/s plus a ripple,
    its bank's shaft at the held samples of that speed (a left-point sum), a load of 5 N m plus a
    ripple; chain torque on the primary's shaft 5.1 N m; energies balanced."""
    t = np.arange(n) * h
    rec = {"time": t, "primary.crankshaft.phi": 250.0 * t}
    for bank, (shaft, _) in vengine.BANKS.items():
        w = 200.0 + 10.0 * np.sin(2.0 * math.pi * 300.0 * t)
        phi_p = 200.0 * t - 10.0 / (2.0 * math.pi * 300.0) * (np.cos(2.0 * math.pi * 300.0 * t) - 1.0)
        rec[f"primary.{shaft}.phi"], rec[f"primary.{shaft}.w"] = phi_p + 0.01, w
        rec[f"{bank}.shaft.phi"] = np.concatenate([[0.0], np.cumsum(w[:-1] * h)])
        rec[f"primary.input.{shaft}.tau"] = 5.0 + np.sin(2.0 * math.pi * 300.0 * t)
        rec[f"primary.{shaft}.tauChain"] = np.full(n, 5.1)
    for name in ("primary", *vengine.BANKS):
        rec[f"{name}.energy.input"] = 2.0 * t
        rec[f"{name}.energy.dissipated"] = 2.0 * t
        rec[f"{name}.energy.kinetic"] = np.zeros(n)
        rec[f"{name}.energy.elastic"] = np.zeros(n)
    return rec


def test_the_balances_measure_known_answers():
    """Chain torque 5.1 N m against a mean load of 5 N m: +2 %; the work the held speed gives the
    bank against the primary's: their difference is the load times the drift's increments, the sum
    computed here directly; the drift from the start's offset (0.01 rad on the primary) within the
    held-speed error h * 10 rad/s; energy balances 0."""
    rec = synthetic_record()
    b = vengine.balances(rec, 0, len(rec["time"]))
    for shaft, _ in vengine.BANKS.values():
        x = b[shaft]
        assert x["torqueError"] == pytest.approx(5.1 / np.mean(rec[f"primary.input.{shaft}.tau"][1:]) - 1.0, rel=1e-12)
        load = rec[f"primary.input.{shaft}.tau"][1:]
        work_p = np.sum(load * np.diff(rec[f"primary.{shaft}.phi"]))
        work_b = np.sum(load * np.diff(rec[f"{bank_of(shaft)}.shaft.phi"]))
        assert x["workError"] == pytest.approx(work_b / work_p - 1.0, rel=1e-12)
        assert 0.0 < x["driftMax_deg"] < math.degrees(10.0 * 1e-4) * 2.0
    for name in ("primary", *vengine.BANKS):
        assert b[f"{name}.energyBalance"] == pytest.approx(0.0, abs=1e-12)


def bank_of(shaft):
    return next(b for b, (s, _) in vengine.BANKS.items() if s == shaft)


def test_a_brief_coupled_run_keeps_the_coupling_and_its_conventions():
    """Three FMUs, 2 engine cycles at 0.1 ms: each bank's shaft turns by exactly its held speed
    input times the step; the primary's shaft load is minus the bank's chain torque on its shaft,
    positive (the bank loads the shaft); the bank's camshafts turn at half the crankshaft's speed;
    the drift stays below 0.1 deg of the shaft and the work error below 5 %."""
    tables = vengine.engine_tables(3000.0)
    h = 1e-4
    rec, cpu = vengine.run_coupled(3000.0, 1, 1, h, tables)
    assert cpu > 0.0
    for bank, (shaft, _) in vengine.BANKS.items():
        turn = np.diff(rec[f"{bank}.shaft.phi"])[1:]
        assert np.max(np.abs(turn - rec[f"{bank}.input.shaft.w"][2:] * h)) < 1e-12
        load = rec[f"primary.input.{shaft}.tau"][1:]
        assert np.mean(load) > 0.0
        # the load held over a step: minus the bank's step-mean torque over the step before carried on
        # half a step (2 m_k - m_k-1)
        mean = rec[f"{bank}.shaft.tauMean"]
        assert np.array_equal(rec[f"primary.input.{shaft}.tau"][3:], -(2.0 * mean[2:-1] - mean[1:-2]))
        cam = rec[f"{bank}.intakeCam.phi"][-1] / rec["primary.crankshaft.phi"][-1]
        assert cam == pytest.approx(0.5, rel=0.01)
    b = vengine.balances(rec, 0, len(rec["time"]))
    for shaft, _ in vengine.BANKS.values():
        assert b[shaft]["driftMax_deg"] < 0.1 and abs(b[shaft]["workError"]) < 0.05, b[shaft]


def test_speed_first_with_the_step_mean_torque_is_refused():
    line = one_error_line(*harness("v-engine", "--coupling", "speed-first")[::2])
    assert "--torque extrapolated with --coupling speed-first" in line and "allowed: --torque sampled" in line, line


def test_a_communication_step_that_splits_a_solver_step_is_refused():
    line = one_error_line(*harness("v-engine", "--steps", "3e-5")[::2])
    assert "--steps 3e-05" in line and "bank drive" in line and "1e-4/32" in line, line


@pytest.mark.parametrize("importer", ["libcosim", "ecos"])
def test_another_importer_steps_the_coupled_v6_to_the_same_bits(importer):
    """The same coupling with libcosim (manipulator and observer around its fixed-step algorithm) or
    ecos (inputs set before, outputs read after each step) stepping the three FMUs gives fmpy's bits
    for every output the coupling reads and each tensioner force, over two engine cycles at 0.1 ms."""
    tables = vengine.engine_tables(3000.0)
    fmpy_record, _ = vengine.run_coupled(3000.0, 1, 1, 1e-4, tables)
    names = {name: ["tensioner.F"] for name in vengine.FMUS}
    run = {"libcosim": vengine.run_libcosim, "ecos": vengine.run_ecos}[importer]
    other = run(len(fmpy_record["time"]) - 1, 1e-4, tables, names)
    assert set(other) >= {f"{n}.tensioner.F" for n in vengine.FMUS}
    for key, values in other.items():
        assert np.array_equal(values, fmpy_record[key][1:]), key


def test_the_cycle_statistics_measure_known_answers():
    """Per engine cycle of the crankshaft's angle: each tensioner force's mean (100 N plus a ripple of
    order 3), each shaft load's mean (5 N m), each bank's camshaft timing peak-to-peak: the camshaft
    0.002 rad ahead and behind its half of the crankshaft's angle at order 1 gives 2 x 2 x 0.002 rad
    of crank angle, 0.229 deg."""
    n = 4 * 720 + 1
    crank = np.linspace(0.0, 4 * 4.0 * math.pi, n)
    rec = {"primary.crankshaft.phi": crank, "primary.tensioner.F": 100.0 + 10.0 * np.sin(3.0 * crank),
           "primary.chain.Ftight": np.full(n, 900.0)}
    for bank, (shaft, _) in vengine.BANKS.items():
        rec[f"{bank}.tensioner.F"] = 100.0 + 10.0 * np.sin(3.0 * crank)
        rec[f"primary.input.{shaft}.tau"] = 5.0 + np.sin(crank)
        rec[f"{bank}.intakeCam.phi"] = crank / vengine.CAM_RATIO + 0.002 * np.sin(crank)
    from harness import cycle_stats
    spans = cycle_stats.counted_spans(crank, 1, None)
    stats = vengine.per_cycle(rec, spans)
    assert len(spans) == 3
    for bank, (shaft, _) in vengine.BANKS.items():
        assert np.allclose(stats[f"{bank}.tensioner.F.mean"][1], 100.0, atol=1e-9)
        assert np.allclose(stats[f"{shaft}.load.mean"][1], 5.0, atol=1e-9)
        assert np.allclose(stats[f"{bank}.intakeCam.timing.peakToPeak_degCA"][1], math.degrees(4 * 0.002), rtol=1e-4)


def test_a_study_point_warns_of_what_it_missed():
    """An energy balance beyond the limit and a tensioner that had not settled are warning lines."""
    result = {"balances": {"primary.energyBalance": -0.07, "left.energyBalance": 0.01, "right.energyBalance": 0.0},
              "settled": {"primary": {"runInCycles": 40, "tensionerSettled": False},
                          "left": {"runInCycles": 9, "tensionerSettled": True},
                          "right": {"runInCycles": 9, "tensionerSettled": True}}}
    lines = vengine.warnings_of(result)
    assert len(lines) == 2 and lines[0].startswith("primary: energy balance -7.00 %"), lines
    assert "primary: the tensioner had not settled after 40 cycles" in lines
    assert vengine.warnings_of({"failed": "x"}) == []
