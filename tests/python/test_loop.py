"""The closed loop at compiled speed (harness/fmu/loop.py, closed_loop.c) against the Python loop
(fmpy's calls, harness/job.py): each input's value has np.interp's bits wherever it is looked up,
and both loops give the same record, bit for bit, on the default drive and on a drive with a pump
and own-angle tables, for a fixed duration and until a run-in's watch ends; a refused step stops
the compiled loop as it stops the Python loop."""
import math

import numpy as np
import pytest

from harness import job, runin
from harness.drive.description import elements as drive_elements
from harness.fmu import loop
from harness.sweep import cases
from harness.tables import tables

# angles [deg] where a look-up can go wrong: knots, between them, both ends of the period, below
# zero, many periods on, a signed zero, the next doubles around the knots
KNOTS = [0.0, 0.5, 1.0, 359.5, 360.0, 719.5, 720.0]
ANGLES = (KNOTS + [np.nextafter(a, -1e9) for a in KNOTS] + [np.nextafter(a, 1e9) for a in KNOTS]
          + [-0.0, -0.25, -719.75, 1e4 + 0.3, 7.2e6 + 0.1, 123.456789, 1e-300, -1e-300])


def table(kind, column, x, y):
    return tables.Table(kind, x, {column: y})


def irregular(period):
    """Knots not evenly spaced, one of them at the period itself (the same as 0 once wrapped)."""
    x = np.sort(np.concatenate(([0.0, period], np.random.default_rng(1).uniform(0.0, period, 40))))
    return x, np.sin(x * 0.05) * 20.0 + 3.0


@pytest.mark.parametrize("column", ["crankshaft.speed_rpm", "crankshaft.w"])
@pytest.mark.parametrize("factor", [1.0, 1.0 + 1e-3])
def test_speed_term_has_the_python_loops_bits(column, factor):
    x = np.arange(0.0, 720.0, 0.5)
    speed = table("angle", column, x, 3000.0 + 40.0 * np.sin(np.radians(4.0 * x)))
    term = loop.Term.table("speed", 0, speed.x, speed.columns[column], tables.PERIODS["angle"], factor,
                           rpm=column.endswith("_rpm"))
    for a in ANGLES:
        expected = factor * job.speed_at(speed, a)
        assert loop.value_of(term, [a]) == expected, a


@pytest.mark.parametrize("kind, extra", [("sprocket", 37.25), ("angle", 2.0)])
def test_load_terms_have_the_python_loops_bits(kind, extra):
    for x, y in [(np.arange(0.0, tables.PERIODS[kind], 0.5), None), irregular(tables.PERIODS[kind])]:
        y = np.cos(np.radians(3.0 * x)) * 12.0 + 5.0 if y is None else y
        load = tables.Load("camshaftIntake", "test", table(kind, "camshaftIntake.tau", x, y),
                           ratio=extra if kind == "angle" else 1.0, phase_deg=extra if kind == "sprocket" else 0.0)
        term = job.load_term(load, 1)
        for a in ANGLES:
            assert loop.value_of(term, [0.0, a]) == float(load.at(a)), (kind, a)
    constant = job.load_term(tables.Load("pump", "--load", constant=4.5), 1)
    assert loop.value_of(constant, [0.0, 12.0]) == 4.5


def closed(drive=None, tables_dir=None, rpm=6000.0, fidelity="span", compiled=True, duration=0.01, run_in=None,
           factor=1.0 + 1e-3):
    config = job.run_config(rpm=rpm, cycles=2, fidelity=fidelity, drive=drive, tables=tables_dir)
    elements = drive_elements(config.drive)
    inputs = job.table_inputs(job.drive_loads(config, elements), tables.crankshaft_speed(rpm, tables_dir), elements,
                              speed_factor=factor)
    return job.run_closed(config, duration, inputs, progress=False, run_in=run_in, compiled=compiled)


def same_records(a, b):
    assert list(a) == list(b)
    for name in a:
        assert a[name].dtype == b[name].dtype and np.array_equal(a[name], b[name]), name


@pytest.mark.parametrize("drive, tables_dir", [(None, None),
                                               ("tests/drives/diesel_pump.json", "tests/drives/tables/diesel_pump")])
def test_both_loops_give_the_same_record(drive, tables_dir):
    compiled, cpus, loop_cpu = closed(drive, tables_dir)
    python, _, _ = closed(drive, tables_dir, compiled=False)
    same_records(compiled, python)
    assert len(cpus) == len(compiled["time"]) - 1 and 0.0 < math.fsum(cpus) <= loop_cpu


def test_both_loops_end_where_the_run_ins_watch_says():
    watched = [closed(duration=None, run_in=runin.RunIn(1, 1, watches=False), compiled=c)[0] for c in (True, False)]
    same_records(*watched)
    phi = watched[0]["crankshaft.phi"]
    # one run-in cycle and two counted ones: the last row the first at or past three engine cycles
    assert phi[-1] >= 3 * 4.0 * math.pi - 1e-9 > phi[-2]


def test_a_refused_step_stops_both_loops_with_the_fmus_reason():
    # (the link model at 20 us, far above its stable step, blows up in the first step)
    config = job.run_config(rpm=6000.0, cycles=2, fidelity="link", method="fixed-verlet", solver_step=2e-5)
    elements = drive_elements(None)
    inputs = job.table_inputs(job.drive_loads(config, elements), tables.crankshaft_speed(6000.0), elements)
    failures = []
    for compiled in (True, False):
        with pytest.raises(job.RunFailed) as failed:
            job.run_closed(config, 0.01, inputs, progress=False, compiled=compiled)
        failures.append(failed.value)
    assert str(failures[0]) == str(failures[1]) and "blow-up" in str(failures[0]) and "fmi2DoStep" in str(failures[0])
    same_records(failures[0].record, failures[1].record)


def test_both_loops_give_the_same_run_up():
    # (from 1900 rpm to 3100 rpm in 30 ms from t = 5 ms: through the tabulated 2000 and 3000 rpm, and
    # held below the ramp's start and after its end)
    case = cases.Case(rpm=1900.0, fidelity="span", method="fixed-verlet", rpm_end=3100.0, ramp_s=0.03)
    inputs = cases.runup_inputs(case, 0.005, drive_elements(None))
    config = case.config()
    records = [job.run_closed(config, 0.04, inputs, progress=False, compiled=c)[0] for c in (True, False)]
    same_records(*records)
    speed = records[0]["input.crankshaft.w"]
    assert speed[-1] > 3000.0 * math.pi / 30.0 > 2000.0 * math.pi / 30.0 > speed[1]


def test_short_loop_benchmark_compares_both_loops(tmp_path):
    from harness import cli
    out = tmp_path / "loop.md"
    # (a record of one loop that differs from the other's raises: the run returning 0 says they agree)
    assert cli.main(["bench-loop", "--rpm", "3000", "--fidelities", "span", "--cycles", "1", "--repeats", "1",
                     "--out", str(out)]) == 0
    row = next(line for line in out.read_text().splitlines() if line.startswith("| 3000 | span |"))
    assert len(row.split("|")) == 12 and "**" in row


def test_terms_that_say_other_inputs_stop_the_compiled_loop():
    config = job.run_config(rpm=3000.0, cycles=2, fidelity="span")
    elements = drive_elements(None)
    inputs = job.table_inputs(job.drive_loads(config, elements), tables.crankshaft_speed(3000.0), elements)
    inputs.terms["crankshaft.w"].a = 1.0 + 1e-12  # (a perturbed speed the Python look-up does not apply)
    with pytest.raises(RuntimeError, match="input crankshaft.w at step"):
        job.run_closed(config, 0.01, inputs, progress=False)
