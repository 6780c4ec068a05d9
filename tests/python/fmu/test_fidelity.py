"""The parameter `fidelity` of ChainDrive.fmu: the link-by-link model (link, the default) or the
span model (span) of the same drive, in one FMU. Bad names are initialization errors naming the
parameter, the value and the allowed values; the span fidelity runs, rolls back bit for bit and
its states are refused by link-fidelity instances (and the other way round)."""
import struct

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

from harness.fmu import fmu

W3000 = fmu.rpm_to_rad_s(3000.0)
INPUTS = {"crankshaft.w": W3000, "camshaftIntake.tau": 6.0, "camshaftExhaust.tau": 4.0}
H = 1e-4
SPAN = {"fidelity": "span"}


def output_bits(s):
    """Every output of the instance, Reals as their 64 bits, Integers as they are."""
    values = s.get()
    return tuple(struct.unpack("<Q", struct.pack("<d", values[n]))[0] if s.type[n] == "Real" else values[n]
                 for n in s.outputs)


def run_on(s, first, last):
    """Communication steps first..last-1 of H; the outputs (as bits) after each."""
    rows = []
    for k in range(first, last):
        s.step(H, t=k * H)
        rows.append(output_bits(s))
    return rows


def test_fidelity_is_a_structural_string_parameter_with_default_link():
    s = fmu.Slave("default")
    fidelity = [v for v in s.md.modelVariables if v.name == "fidelity"][0]
    assert (fidelity.valueReference, fidelity.type, fidelity.causality, fidelity.variability, fidelity.initial) == \
        (108, "String", "parameter", "fixed", "exact")
    assert fidelity.start == "link"
    assert "link" in fidelity.description and "span" in fidelity.description
    s.slave.setupExperiment(startTime=0.0)
    s.slave.enterInitializationMode()
    assert s.slave.getString([108]) == [b"link"]
    s.slave.exitInitializationMode()
    with pytest.raises(FMICallException) as e:  # fixed: not after the initialization
        s.slave.setString([108], ["span"])
    assert e.value.status == 3
    assert any("fidelity" in m and "fixed" in m for m in s.errors()), s.errors()
    s.close()


def test_every_output_states_what_the_span_fidelity_gives():
    s = fmu.Slave("descriptions")
    outputs = [v for v in s.md.modelVariables if v.causality == "output"]
    undocumented = [v.name for v in outputs if "span fidelity" not in (v.description or "")
                    and "both fidelities" not in (v.description or "")]
    assert undocumented == []
    s.slave.freeInstance()


@pytest.mark.parametrize("value", ["beam", "Span", ""])
def test_unknown_fidelity_is_an_initialization_error_naming_parameter_value_and_allowed_values(value):
    s = fmu.Slave("badfidelity")
    s.slave.setupExperiment(startTime=0.0)
    s.set("fidelity", value)  # accepted by the setter; checked when the initialization ends
    s.slave.enterInitializationMode()
    with pytest.raises(FMICallException) as e:
        s.slave.exitInitializationMode()
    assert e.value.status == 3  # fmi2Error
    assert any(m.startswith("fidelity:") and f"'{value}'" in m and "allowed: link, span" in m
               for m in s.errors()), s.errors()
    s.slave.freeInstance()


@pytest.mark.parametrize("name,value", [("contact.method", "time-stepping"), ("chain.jointModel", "ideal")])
def test_span_fidelity_with_rigid_contacts_or_ideal_joints_is_an_error(name, value):
    s = fmu.Slave("spanrigid", parameters=dict(SPAN, **{name: value}))
    with pytest.raises(FMICallException) as e:
        s.initialize(inputs=INPUTS)
    assert e.value.status == 3
    assert any(name in m and value in m and "'span'" in m for m in s.errors()), s.errors()
    s.slave.freeInstance()


def test_span_fidelity_runs_with_finite_outputs_and_no_contact_forces():
    s = fmu.Slave("span", parameters=SPAN)
    s.initialize(inputs=INPUTS)
    assert s.slave.getString([108]) == [b"span"]
    start = s.get(["link.x", "link.y"])
    for k in range(50):
        s.step(H, t=k * H)
        out = s.get()
        assert all(np.isfinite(v) for v in out.values()), out
        assert out["link.Fn"] == 0.0 and out["link.FnSprocket"] == 0.0 and out["link.FnGuide"] == 0.0
        assert out["contacts"] == 0
        assert out["tensioner.F"] > 0.0
        assert out["chain.Ftight"] > 0.0 and out["chain.maxJointDeformation"] > 0.0
    assert out["solver.time"] == pytest.approx(50 * H, rel=0.0, abs=1e-15)
    assert out["crankshaft.phi"] == pytest.approx(W3000 * 50 * H, rel=1e-12)
    # the monitored link moved with the chain (some 6 m/s at 3000 rpm: about 30 mm in 5 ms)
    assert out["link.F"] > 0.0
    assert np.hypot(out["link.x"] - start["link.x"], out["link.y"] - start["link.y"]) > 0.01
    s.close()


def test_span_fidelity_state_rolls_back_bit_for_bit_in_memory_and_serialized():
    s = fmu.Slave("spanstate", parameters=SPAN)
    s.initialize(inputs=INPUTS)
    run_on(s, 0, 10)
    state = s.slave.getFMUState()
    blob = s.slave.serializeFMUstate(state)
    first = run_on(s, 10, 30)
    s.slave.setFMUState(state)
    assert run_on(s, 10, 30) == first
    restored = s.slave.deSerializeFMUstate(blob)
    s.slave.setFMUState(restored)
    assert run_on(s, 10, 30) == first
    s.slave.freeFMUState(state)
    s.slave.freeFMUState(restored)
    s.close()
    # the span model's state is small: the serialized state of a link instance is far larger
    link = fmu.Slave("linkstate")
    link.initialize(inputs=INPUTS)
    link_state = link.slave.getFMUState()
    assert len(link.slave.serializeFMUstate(link_state)) > 10 * len(blob)
    link.slave.freeFMUState(link_state)
    link.close()


def test_states_of_the_other_fidelity_are_refused_and_the_instance_runs_on():
    span = fmu.Slave("spansrc", parameters=SPAN)
    span.initialize(inputs=INPUTS)
    run_on(span, 0, 3)
    span_state = span.slave.getFMUState()
    span_blob = span.slave.serializeFMUstate(span_state)
    link = fmu.Slave("linkdst")
    link.initialize(inputs=INPUTS)
    run_on(link, 0, 3)
    link_state = link.slave.getFMUState()
    link_blob = link.slave.serializeFMUstate(link_state)
    reference = run_on(link, 3, 5)
    link.slave.setFMUState(link_state)
    # a span state into the link instance: in memory and through its bytes
    deserialized = link.slave.deSerializeFMUstate(span_blob)
    for state in (span_state, deserialized):
        link.messages.clear()
        with pytest.raises(FMICallException) as e:
            link.slave.setFMUState(state)
        assert e.value.status == 3
        assert any("components" in m and "fidelity" in m for m in link.errors()), link.errors()
    # the refused restores changed nothing
    assert run_on(link, 3, 5) == reference
    # and a link state into the span instance
    linked = span.slave.deSerializeFMUstate(link_blob)
    span.messages.clear()
    with pytest.raises(FMICallException) as e:
        span.slave.setFMUState(linked)
    assert e.value.status == 3
    assert any("components" in m for m in span.errors()), span.errors()
    assert all(np.isfinite(v) for v in span.get().values())
    run_on(span, 3, 4)
    for owner, state in ((span, span_state), (span, linked), (link, link_state), (link, deserialized)):
        owner.slave.freeFMUState(state)
    span.close()
    link.close()
