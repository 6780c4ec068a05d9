"""One global time grid in ChainDrive.fmu (src/integrators/time_grid.h): the same inputs give the same bits
whatever way a master forms its communication points and whichever importer runs the FMU; points
off the grid are integrated to the grid point before them, with the remainder carried."""
import numpy as np
import pytest

from harness.fmu import fmu, importers

H = 1e-4
W3000 = fmu.rpm_to_rad_s(3000.0)
OBSERVED = ["tensioner.F", "tensionGuide.phi", "chain.Ftight", "chain.Fslack", "camshaftIntake.phi",
            "crankshaft.tau", "link.F", "solver.time"]


def inputs_at(k, dt=H):
    """Time-varying inputs of step k: the order-2 content of an engine, so the drive is excited."""
    t = k * dt
    return {"crankshaft.w": W3000 * (1.0 + 0.01 * np.sin(2 * W3000 * t)),
            "camshaftIntake.tau": 3.0 + 10.0 * np.sin(2 * W3000 * t),
            "camshaftExhaust.tau": 2.0 + 8.0 * np.sin(2 * W3000 * t + 1.0)}


# the fixed-step methods over 30 ms (300 communication steps), time stepping (some 1000 CPU s per
# simulated s) and two adaptive ones over 10 ms (100 steps, of which 83 communication points and
# 98 step sizes differ between the ways of forming time)
METHODS = [
    pytest.param({"solver.method": "fixed-verlet", "solver.step": 2.5e-6}, 300, id="fixed-verlet"),
    pytest.param({"solver.method": "arkode-erk-fixed", "solver.step": 2e-6}, 300, id="arkode-erk-fixed"),
    pytest.param({"contact.method": "time-stepping", "solver.step": 2.5e-6}, 100, id="time-stepping"),
    pytest.param({"fidelity": "span", "solver.step": 2.5e-6}, 300, id="span-fixed-verlet"),
    pytest.param({"solver.method": "arkode-erk", "solver.tolerance": 1e-5}, 100, id="arkode-erk"),
    pytest.param({"solver.method": "cvode-bdf-klu", "solver.tolerance": 1e-5}, 100, id="cvode-bdf-klu"),
]


def test_the_three_ways_of_forming_time_give_different_doubles():
    """The premise of the tests below: the three ways really pass different numbers."""
    pts = {f: importers.communication_points(f, 300, H) for f in importers.TIME_FORMS}
    cps = {f: np.array([p[0] for p in v]) for f, v in pts.items()}
    steps = {f: np.array([p[1] for p in v]) for f, v in pts.items()}
    assert np.count_nonzero(cps["k*H"] != cps["t+=H"]) > 100
    assert np.count_nonzero(steps["(k+1)H-kH"] != H) > 100


@pytest.mark.parametrize("parameters,steps", METHODS)
def test_every_way_of_forming_time_and_every_importer_gives_the_same_bits(parameters, steps):
    reference = importers.run_fmpy(inputs_at, steps, H, OBSERVED, parameters, form="k*H")
    assert np.all(np.isfinite(reference))
    # the solver reached every communication point (they are on the grid)
    assert np.allclose(reference[:, -1], H * np.arange(1, steps + 1), rtol=0.0, atol=1e-15)
    runs = {f"fmpy {form}": importers.run_fmpy(inputs_at, steps, H, OBSERVED, parameters, form=form)
            for form in importers.TIME_FORMS[1:]}
    runs["libcosim"] = importers.run_libcosim(inputs_at, steps, H, OBSERVED, parameters)
    runs["ecos"] = importers.run_ecos(inputs_at, steps, H, OBSERVED, parameters)
    for name, out in runs.items():
        differ = np.flatnonzero(np.any(out != reference, axis=1))
        assert differ.size == 0, f"{name}: first difference at step {differ[0]}: {out[differ[0]]} vs {reference[differ[0]]}"


def solver_times(step, points, parameters):
    """solver.time after each (cp, h) of `points`, one fresh instance."""
    s = fmu.Slave("grid", parameters=dict(parameters, **{"solver.step": step}))
    s.initialize(inputs=inputs_at(0))
    out = []
    for cp, h in points:
        s.slave.doStep(currentCommunicationPoint=cp, communicationStepSize=h)
        out.append(s.get(["solver.time"])["solver.time"])
    s.close()
    return np.array(out)


def test_points_off_the_grid_go_to_the_grid_point_before_them_and_the_remainder_is_carried():
    """A step of H/3 with a 2.5 us grid (13 1/3 steps): the solver stops at 13, 26, then 40 steps
    (back on the grid at 1e-4 s): never past the master's time, never a step or more behind."""
    h = 2.5e-6
    points = [(k * H / 3.0, H / 3.0) for k in range(6)]
    times = solver_times(h, points, {"solver.method": "fixed-verlet"})
    grid_steps = np.round(times / h).astype(int)
    assert list(grid_steps) == [13, 26, 40, 53, 66, 80]
    master = np.array([cp + dt for cp, dt in points])
    assert np.all(times <= master + 1e-15) and np.all(master - times < h)
    # adaptive methods follow the same rule on their 1 us quantum (33 1/3 us -> 33, 66, 100 us)
    times = solver_times(h, points[:3], {"solver.method": "arkode-erk"})
    assert list(np.round(times / 1e-6).astype(int)) == [33, 66, 100]


def test_a_rounded_step_of_one_sixtieth_of_a_second_is_snapped_not_drifted():
    """Masters pass 1/60 s as 0.016666666666666677; with a grid that divides 1/60 s (6000 steps)
    every way of forming time lands on the same grid points, with the same bits."""
    rounded = 0.016666666666666677
    assert rounded != 1.0 / 60.0
    step = (1.0 / 60.0) / 6000.0
    results = []
    for form in importers.TIME_FORMS:
        points = importers.communication_points(form, 3, rounded)
        s = fmu.Slave("sixtieth", parameters={"solver.step": step})
        s.initialize(inputs=inputs_at(0))
        rows = []
        for cp, h in points:
            s.slave.doStep(currentCommunicationPoint=cp, communicationStepSize=h)
            rows.append([s.get(OBSERVED)[n] for n in OBSERVED])
        s.close()
        results.append(np.array(rows))
    assert np.array_equal(np.round(results[0][:, -1] / step), [6000.0, 12000.0, 18000.0])
    for r in results[1:]:
        assert np.array_equal(r, results[0])


def test_state_of_another_time_grid_is_refused():
    a = fmu.Slave("a", parameters={"solver.step": 2.5e-6})
    a.initialize(inputs=inputs_at(0))
    a.step(H, t=0.0)
    blob = a.slave.serializeFMUstate(a.slave.getFMUState())
    a.close()
    b = fmu.Slave("b", parameters={"solver.step": 2e-6})
    b.initialize(inputs=inputs_at(0))
    state = b.slave.deSerializeFMUstate(blob)
    with pytest.raises(Exception):
        b.slave.setFMUState(state)
    assert any("time grid" in m for m in b.errors()), b.errors()
    b.slave.freeInstance()
