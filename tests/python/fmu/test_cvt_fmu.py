"""CVTChain.fmu: the chain CVT for transmission and vehicle simulation through fmpy: validation,
a loaded run, the start ratio and clamping force, the ratio input shifting the chain, bit-identical
instances, FMU states, errors."""
import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from harness.fmu import fmu

PATH = fmu.fmu_path("CVTChain")
W = fmu.rpm_to_rad_s(2000.0)
H = 1e-4
OBSERVE = ("drivenPulley.w", "slip", "chain.Ftight", "chain.Fslack", "drivenPulley.Fclamp", "drivenPulley.tau", "link.F")


def cvt(name="cvt", parameters=None, load=60.0):
    s = fmu.Slave(name, fmu=PATH, parameters=parameters)
    s.initialize(inputs={"drivingPulley.w": W, "drivenPulley.tauLoad": load})
    return s


def run(s, steps, start=0):
    out = []
    for k in range(start, start + steps):
        s.step(H, t=k * H)
        out.append([s.get(OBSERVE)[n] for n in OBSERVE])
    return np.array(out)


def test_validate_fmu_reports_no_problems():
    assert validate_fmu(str(PATH)) == []


def test_loaded_run_transmits_the_torque_with_a_little_slip():
    s = cvt(load=60.0)
    out = run(s, 300)  # 30 ms: half a chain revolution
    got = s.get(["solver.steps", "contacts"])
    s.close()
    assert np.all(np.isfinite(out))
    late = out[150:]
    assert np.all(late[:, 2] > late[:, 3])  # tight strand tighter than the slack one
    slip = late[:, 1].mean()
    assert 0.0 < slip < 0.02
    assert late[:, 0].mean() == pytest.approx(W * (1.0 - slip), rel=1e-3)  # ratio 1: driven = driving (1 - slip)
    assert late[:, 5].mean() == pytest.approx(60.0, rel=0.05)  # the chain holds the load
    assert got["solver.steps"] == 300 * 200  # 0.5 us steps
    assert 25 <= got["contacts"] <= 40       # the pins of the two wraps


def test_start_ratio_and_clamping_force():
    s = cvt(parameters={"ratio": 2.0, "clampingForce": 30000.0}, load=0.0)
    out = run(s, 100)
    s.close()
    assert out[-1, 0] == pytest.approx(W / 2.0, rel=5e-3)  # no load: the geometric ratio
    assert out[-20:, 4].mean() == pytest.approx(30000.0, rel=0.1)  # the clamping force it was assembled with


def test_ratio_input_shifts_the_chain_and_its_range_is_checked():
    s = cvt("shift", load=30.0)
    for k in range(800):  # 1.0 -> 1.3 over 50 ms, then 30 ms held
        s.step(H, inputs={"ratio": 1.0 + 0.3 * min(1.0, k / 500.0)}, t=k * H)
    w_driven = s.get(["drivenPulley.w"])["drivenPulley.w"]
    assert W / w_driven == pytest.approx(1.3, rel=0.01)
    with pytest.raises(FMICallException):
        s.set("ratio", 2.5)  # beyond the default CVT's ratio range [0.5, 2]
    assert any("ratio = 2.5" in m and "ratioRange" in m for m in s.errors()), s.messages
    s.close()


def test_two_instances_interleaved_reproduce_their_solo_runs_bit_for_bit():
    solo = run(cvt("solo"), 60)
    a, b = cvt("a"), cvt("b", load=120.0)
    ra, rb = [], []
    for k in range(60):
        a.step(H, t=k * H)
        b.step(H, t=k * H)
        ra.append([a.get(OBSERVE)[n] for n in OBSERVE])
        rb.append([b.get(OBSERVE)[n] for n in OBSERVE])
    a.close()
    b.close()
    assert np.array_equal(np.array(ra), solo)
    assert not np.array_equal(np.array(rb), solo)


def test_rollback_and_serialized_state_repeat_the_steps_bit_for_bit():
    s = cvt("rollback")
    run(s, 20)
    state = s.slave.getFMUstate()
    serialized = s.slave.serializeFMUstate(state)
    first = run(s, 30, start=20)
    s.slave.setFMUstate(state)
    again = run(s, 30, start=20)
    s.slave.setFMUstate(s.slave.deSerializeFMUstate(serialized))
    third = run(s, 30, start=20)
    s.slave.freeFMUstate(state)
    s.close()
    assert np.array_equal(first, again) and np.array_equal(first, third)


@pytest.mark.parametrize("name, value, field", [("solver.method", "cvode-bdf-klu", "solver.method"),
                                                ("ratio", 9.0, "ratio"),
                                                ("cvtFile", "/nonexistent/cvt.json", "/nonexistent/cvt.json")])
def test_bad_parameters_are_errors_naming_them(name, value, field):
    s = fmu.Slave("bad", fmu=PATH, parameters={name: value})
    with pytest.raises(FMICallException):
        s.initialize()
    assert any(field in m for m in s.errors()), s.messages
    s.slave.freeInstance()


def test_too_long_a_step_is_a_named_discard_not_a_crash():
    s = cvt("long", parameters={"solver.step": 1e-5})
    with pytest.raises(FMICallException):
        run(s, 5)
    assert any("blow-up" in m for m in s.errors()), s.messages
    s.slave.freeInstance()
