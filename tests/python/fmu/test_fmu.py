"""ChainDrive.fmu: packaging, model description, the FMI state machine, several instances,
threads, FMU states, errors."""
import json
import re
import shutil
import subprocess
import threading
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from harness import defaults, job, paths
from harness.fmu import export, fmu

W2000 = fmu.rpm_to_rad_s(2000.0)
INPUTS = {"crankshaft.w": W2000, "camshaftIntake.tau": 3.0, "camshaftExhaust.tau": 2.0}
H = 1e-4


def solo_run(name="solo", steps=30, inputs=INPUTS, parameters=None, observe=("tensioner.F", "tensionGuide.phi",
                                                                             "chain.Ftight", "camshaftIntake.w")):
    s = fmu.Slave(name, parameters=parameters)
    s.initialize(inputs=inputs)
    out = []
    for k in range(steps):
        s.step(H, t=k * H)
        out.append([s.get(observe)[n] for n in observe])
    s.close()
    return np.array(out)


def test_validate_fmu_reports_no_problems():
    assert validate_fmu(str(fmu.fmu_path())) == []


@pytest.mark.parametrize("binary", ["ChainDrive.so", "CVTChain.so"])
def test_binary_exports_only_fmi2_and_links_only_libc_libm(binary):
    so = paths.BUILD / binary
    nm = subprocess.run(["nm", "-D", "--defined-only", str(so)], capture_output=True, text=True, check=True).stdout
    names = [line.split()[-1] for line in nm.splitlines() if line.strip()]
    assert names and all(n.startswith("fmi2") for n in names), [n for n in names if not n.startswith("fmi2")]
    assert len(names) == 44  # every FMI 2.0 function, common + co-simulation + model exchange (stubs)
    ldd = subprocess.run(["ldd", str(so)], capture_output=True, text=True, check=True).stdout
    libs = [l.split()[0] for l in ldd.splitlines() if l.strip()]
    allowed = ("linux-vdso.so", "libc.so", "libm.so", "/lib64/ld-linux", "ld-linux")
    assert all(any(l.startswith(a) for a in allowed) for l in libs), libs


def model_description_variables(root):
    xml = {}
    for sv in root.iter("ScalarVariable"):
        typ = [c for c in sv if c.tag in ("Real", "Integer", "Boolean", "String")][0]
        xml[sv.get("name")] = (int(sv.get("valueReference")), typ.tag, sv.get("causality"), typ.get("start", ""))
    return xml


def test_cvt_model_description_and_glue_agree():
    """CVTChain's model description is the single source; its adapter's cvt_variables.h mirrors it."""
    root = ET.parse(paths.ROOT / "modelDescription" / "CVTChain.xml").getroot()
    xml = model_description_variables(root)
    header = (paths.ROOT / "fmu" / "cvt" / "cvt_variables.h").read_text()
    vrs = dict(re.findall(r"\b(k\w+) = (\d+),", header))
    glue = {}
    for name, vr, typ, caus, start in re.findall(
            r'\{"([\w.]+)",\s*(k\w+),\s*Type::(\w+),\s*Causality::(\w+),\s*"([^"]*)"\}', header):
        glue[name] = (int(vrs[vr]), typ, caus.lower(), start)
    assert glue == xml
    guid = re.search(r'kGuid = "([^"]+)"', header).group(1)
    assert guid == root.get("guid")


@pytest.mark.parametrize("description", ["ChainDrive", "CVTChain"])
def test_model_structure_lists_exactly_the_outputs(description):
    """ModelStructure's outputs: exactly the outputs, in order (ChainDrive's generated from its drive)."""
    if description == "ChainDrive":
        root = ET.fromstring(zipfile.ZipFile(fmu.fmu_path()).read("modelDescription.xml"))
    else:
        root = ET.parse(paths.ROOT / "modelDescription" / f"{description}.xml").getroot()
    outputs = [i + 1 for i, sv in enumerate(root.iter("ScalarVariable")) if sv.get("causality") == "output"]
    listed = [int(u.get("index")) for u in root.find("ModelStructure").find("Outputs")]
    assert listed == outputs


def test_wrong_guid_is_rejected():
    with pytest.raises(Exception):
        fmu.Slave("wrong", guid="{00000000-0000-0000-0000-000000000000}")


def test_run_is_finite_and_plausible():
    out = solo_run(steps=40)
    assert np.all(np.isfinite(out))
    F = out[:, 0]
    assert F.min() >= 0.0 and F.max() < 3000.0  # typical: dynamic peaks 1-3 kN at resonance


def test_interleaved_instances_reproduce_their_solo_runs_bit_for_bit():
    solo_a = solo_run("a", inputs=INPUTS)
    other = dict(INPUTS, **{"crankshaft.w": fmu.rpm_to_rad_s(3500.0)})
    solo_b = solo_run("b", inputs=other)
    a, b = fmu.Slave("a2"), fmu.Slave("b2")
    a.initialize(inputs=INPUTS)
    b.initialize(inputs=other)
    ra, rb = [], []
    names = ("tensioner.F", "tensionGuide.phi", "chain.Ftight", "camshaftIntake.w")
    for k in range(len(solo_a)):
        a.step(H, t=k * H)
        b.step(H, t=k * H)
        ra.append([a.get(names)[n] for n in names])
        rb.append([b.get(names)[n] for n in names])
    a.close()
    b.close()
    assert np.array_equal(np.array(ra), solo_a)
    assert np.array_equal(np.array(rb), solo_b)


def test_instances_in_two_threads_reproduce_their_solo_runs_bit_for_bit():
    solo = solo_run("solo")
    results = {}

    def work(key):
        results[key] = solo_run(f"thread{key}")

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for k in range(2):
        assert np.array_equal(results[k], solo)


def test_solver_threads_give_the_outputs_of_one_thread_and_roll_back():
    # 30 communication steps of the default method, every output observed, on 1 and 2 threads;
    # then a state taken and restored on 2 threads replays its steps bit for bit
    names = ("tensioner.F", "tensionGuide.phi", "chain.Ftight", "camshaftIntake.w", "link.Fn", "contacts")
    one = solo_run("one", observe=names)
    two = solo_run("two", observe=names, parameters={"solver.threads": 2})
    assert np.array_equal(one, two)
    s = fmu.Slave("rollback", parameters={"solver.threads": 2})
    s.initialize(inputs=INPUTS)
    s.step(H, t=0.0)
    state = s.slave.getFMUState()
    first = [s.step(H, t=k * H) or s.get(names)["tensioner.F"] for k in range(1, 6)]
    s.slave.setFMUState(state)
    again = [s.step(H, t=k * H) or s.get(names)["tensioner.F"] for k in range(1, 6)]
    assert first == again and first == list(one[1:6, 0])
    s.slave.freeFMUState(state)
    s.close()


@pytest.mark.parametrize("parameters, text", [
    ({"solver.threads": 0}, "solver.threads = 0 is outside 1..16"),
    ({"solver.threads": 2, "fidelity": "span"}, "solver.threads = 2: several threads run the link model"),
    ({"solver.threads": 2, "solver.method": "fixed-newmark"}, "solver.threads = 2: several threads run the link model"),
])
def test_solver_threads_where_they_cannot_run_are_errors(parameters, text):
    s = fmu.Slave("threads", parameters=parameters)
    with pytest.raises(FMICallException):
        s.initialize(inputs=INPUTS)
    assert any(text in m for m in s.errors()), s.errors()
    s.slave.freeInstance()


ROLLBACK_OUTPUTS = ["tensioner.F", "chain.Fslack", "crankshaft.phi", "crankshaft.tauMean"]


@pytest.mark.parametrize("parameters", [{}, {"solver.method": job.REALTIME_METHOD, "solver.step": job.REALTIME_STEP}],
                         ids=["default", "real-time method"])
def test_get_set_state_and_serialization_roll_back_exactly(parameters):
    s = fmu.Slave("state", parameters=parameters)
    s.initialize(inputs=INPUTS)
    for k in range(5):
        s.step(H, t=k * H)
    state = s.slave.getFMUState()
    blob = s.slave.serializeFMUstate(state)
    first = []
    for k in range(5, 15):
        s.step(H, t=k * H)
        first.append(s.get(ROLLBACK_OUTPUTS))
    # roll back in memory
    s.slave.setFMUState(state)
    again = []
    for k in range(5, 15):
        s.step(H, t=k * H)
        again.append(s.get(ROLLBACK_OUTPUTS))
    assert again == first
    # roll back through the serialized bytes
    restored = s.slave.deSerializeFMUstate(blob)
    s.slave.setFMUState(restored)
    third = []
    for k in range(5, 15):
        s.step(H, t=k * H)
        third.append(s.get(ROLLBACK_OUTPUTS))
    assert third == first
    s.slave.freeFMUState(state)
    s.slave.freeFMUState(restored)
    s.close()


@pytest.mark.parametrize("fidelity", ["link", "span"])
def test_step_mean_chain_torque_is_the_angular_impulse_over_the_step(fidelity):
    """Known answer: a camshaft's momentum balance over each communication step, I (w1 - w0) / H =
    its step-mean chain torque - its load (no other torque acts on it), to rounding. I is fitted:
    the sprocket's own in the link model (checked), with the chain lumped on it in the span model.
    The sampled torque misses the balance by what happened between the samples. At the start the
    mean is the torque itself."""
    drive = json.loads((paths.ROOT / "src" / "drives" / "default_drive.json").read_text())
    own_inertia = next(s["inertia"] for s in drive["sprockets"] if s["name"] == "camshaftIntake")
    s = fmu.Slave("mean", parameters={"fidelity": fidelity})
    s.initialize(inputs=INPUTS)
    names = ["camshaftIntake.w", "camshaftIntake.tauChain", "camshaftIntake.tauChainMean", "crankshaft.tau",
             "crankshaft.tauMean"]
    v = s.get(names)
    assert v["crankshaft.tauMean"] == v["crankshaft.tau"]
    assert v["camshaftIntake.tauChainMean"] == v["camshaftIntake.tauChain"]
    rows = []
    for k in range(60):
        w0 = v["camshaftIntake.w"]
        s.step(H, t=k * H)
        v = s.get(names)
        rows.append(((v["camshaftIntake.w"] - w0) / H, v["camshaftIntake.tauChainMean"] - INPUTS["camshaftIntake.tau"],
                     v["camshaftIntake.tauChain"] - INPUTS["camshaftIntake.tau"]))
    s.close()
    accel, mean_torque, sampled_torque = np.array(rows).T
    inertia = np.dot(accel, mean_torque) / np.dot(accel, accel)
    assert np.max(np.abs(mean_torque - inertia * accel)) < 1e-9 * np.max(np.abs(mean_torque))
    assert np.max(np.abs(sampled_torque - inertia * accel)) > 1e-3 * np.max(np.abs(mean_torque))
    if fidelity == "link":
        assert inertia == pytest.approx(own_inertia, rel=1e-9)
    else:
        assert inertia > own_inertia


def test_step_means_are_nan_with_rigid_contacts():
    """Time stepping does not accumulate the impulses: its step means say so (NaN), not 0."""
    s = fmu.Slave("rigid-mean", parameters={"contact.method": "time-stepping"})
    s.initialize(inputs=INPUTS)
    s.step(H, t=0.0)
    got = s.get(["crankshaft.tauMean", "camshaftIntake.tauChainMean", "crankshaft.tau"])
    s.close()
    assert np.isnan(got["crankshaft.tauMean"]) and np.isnan(got["camshaftIntake.tauChainMean"])
    assert np.isfinite(got["crankshaft.tau"])


def test_state_taken_before_the_start_state_restores_the_start():
    # a state taken in initialization mode before any output was read holds no solver state;
    # restoring it must start again from the start state, not step on from where the run got to
    # (found by the FMI call fuzz of the sanitizer stage)
    s = fmu.Slave("early-state")
    s.slave.setupExperiment(startTime=0.0)
    for k, v in INPUTS.items():
        s.set(k, v)
    s.slave.enterInitializationMode()
    state = s.slave.getFMUState()
    observe = ["tensioner.F", "crankshaft.phi", "solver.steps", "solver.time"]
    runs = []
    for restore in (False, True):
        if restore:
            s.slave.setFMUState(state)
        s.slave.exitInitializationMode()
        for k in range(3):
            s.step(H, t=k * H)
        runs.append(s.get(observe))
    assert runs[1] == runs[0] and runs[0]["solver.steps"] == 3 * round(H / defaults.solver("timing").step)
    s.slave.freeFMUState(state)
    s.close()


def test_reset_and_rerun_reproduces_exactly():
    s = fmu.Slave("reset")
    s.initialize(inputs=INPUTS)
    runs = []
    for _ in range(2):
        out = []
        for k in range(10):
            s.step(H, t=k * H)
            out.append(s.get(["tensioner.F", "link.F"]))
        runs.append(out)
        s.slave.reset()
        s.initialize(inputs=INPUTS)
    s.close()
    assert runs[0] == runs[1]


def expect_error(slave, call, *args, text):
    with pytest.raises(FMICallException) as e:
        call(*args)
    assert e.value.status >= 2
    joined = " | ".join(slave.errors())
    assert text in joined, joined


def test_nan_input_is_an_error_and_the_process_survives():
    s = fmu.Slave("nan")
    s.initialize(inputs=INPUTS)
    expect_error(s, s.slave.setReal, [s.vr["crankshaft.w"]], [float("nan")], text="crankshaft.w")
    s.step(H)  # the instance is still usable
    s.close()


@pytest.mark.parametrize("value, text", [(-1.0, "-1 rad/s"), (-1e9, "-1e+9 rad/s"), (1e9, "1e+9 rad/s")])
def test_crankshaft_speed_outside_its_range_is_refused_and_the_run_goes_on(value, text):
    s = fmu.Slave("speed")
    s.initialize(inputs=INPUTS)
    expect_error(s, s.slave.setReal, [s.vr["crankshaft.w"]], [value],
                 text=f"crankshaft.w = {text} is outside [0 rad/s, 3000 rad/s]")
    assert s.get(["crankshaft.w"])["crankshaft.w"] == W2000  # the speed set before stays
    s.step(H)
    assert abs(s.get(["crankshaft.phi"])["crankshaft.phi"] - W2000 * H) < 1e-9
    s.close()


def test_refusal_is_one_line_with_the_fmus_reason():
    s = fmu.Slave("refused")
    with pytest.raises(fmu.Refusal) as e:  # (an FMICallException too, with its status)
        s.initialize(inputs=dict(INPUTS, **{"crankshaft.w": -5.0}))
    assert e.value.status == 3 and e.value.function == "fmi2SetReal"
    assert str(e.value) == ("ChainDrive.fmu: fmi2SetReal: crankshaft.w = -5 rad/s is outside [0 rad/s, 3000 rad/s] "
                            "(the crankshaft turns in the running direction only) (fmi2SetReal returned fmi2Error)")
    s.slave.freeInstance()


def test_negative_step_and_wrong_time_are_errors():
    s = fmu.Slave("step")
    s.initialize(inputs=INPUTS)
    expect_error(s, s.slave.doStep, 0.0, -1e-4, text="communicationStepSize")
    expect_error(s, s.slave.doStep, 0.5, 1e-4, text="currentCommunicationPoint")
    s.close()


def test_wrong_call_order_is_an_error():
    s = fmu.Slave("order")
    expect_error(s, s.slave.doStep, 0.0, 1e-4, text="not allowed in state 'instantiated'")
    expect_error(s, s.slave.exitInitializationMode, text="fmi2ExitInitializationMode")
    s.initialize(inputs=INPUTS)
    expect_error(s, s.slave.setReal, [s.vr["solver.step"]], [1e-6], text="fixed")
    s.close()


def test_missing_or_invalid_drive_file_is_an_error(tmp_path):
    s = fmu.Slave("missing", parameters={"driveFile": str(tmp_path / "nope.json")})
    with pytest.raises(FMICallException):
        s.initialize(inputs=INPUTS)
    assert any("nope.json" in m and "cannot be opened" in m for m in s.errors()), s.errors()
    s.slave.freeInstance()
    bad = tmp_path / "bad.json"
    bad.write_text(open(paths.ROOT / "src" / "drives" / "default_drive.json").read().replace(
        '"numberOfLinks": 120', '"numberOfLinks": 121'))
    s = fmu.Slave("invalid", parameters={"driveFile": str(bad)})
    with pytest.raises(FMICallException):
        s.initialize(inputs=INPUTS)
    assert any("chain.numberOfLinks" in m and "even" in m for m in s.errors()), s.errors()
    s.slave.freeInstance()


def test_bad_parameter_is_an_error():
    s = fmu.Slave("param", parameters={"solver.method": "euler"})
    with pytest.raises(FMICallException):
        s.initialize(inputs=INPUTS)
    assert any("solver.method" in m and "fixed-verlet" in m for m in s.errors()), s.errors()
    s.slave.freeInstance()


@pytest.mark.parametrize("parameters, names", [
    ({"solver.method": "fixed-newmark", "solver.newmarkGamma": 0.3}, ("solver.newmarkGamma", "[0.5, 1]")),
    ({"solver.method": "fixed-newmark", "fidelity": "span"}, ("solver.method", "fixed-newmark", "span")),
])
def test_newmark_parameters_out_of_their_domain_are_errors(parameters, names):
    s = fmu.Slave("newmark", parameters=parameters)
    with pytest.raises(FMICallException):
        s.initialize(inputs=INPUTS)
    assert any(all(n in m for n in names) for m in s.errors()), s.errors()
    s.slave.freeInstance()


def test_fixed_newmark_runs_where_verlet_blows_up():
    # the joints and contacts implicit: 20 us, where fixed-verlet is a blow-up (the test below)
    s = fmu.Slave("newmark20", parameters={"solver.method": "fixed-newmark", "solver.step": 2e-5,
                                           "solver.newmarkGamma": 0.6})
    s.initialize(inputs=INPUTS)
    for _ in range(50):
        s.step(H)
    v = s.get(["tensioner.F", "solver.steps"])
    assert 0.0 < v["tensioner.F"] < 1e3 and v["solver.steps"] == round(50 * H / 2e-5), v
    s.slave.freeInstance()


def test_numerical_failure_is_a_discard_and_the_state_can_be_restored():
    # an explicit step far beyond the stability limit blows up within the first step
    s = fmu.Slave("discard", parameters={"solver.step": 2e-5})
    s.initialize(inputs=INPUTS)
    state = s.slave.getFMUState()
    with pytest.raises(FMICallException) as e:
        s.step(H)
    assert e.value.status == 2  # fmi2Discard
    assert any("blow-up" in m or "non-finite" in m for m in s.errors()), s.errors()
    from fmpy.fmi2 import fmi2LastSuccessfulTime
    assert s.slave.getRealStatus(fmi2LastSuccessfulTime) == 0.0
    s.slave.setFMUState(state)  # roll back; the master could now retry with smaller steps
    assert np.isfinite(s.get(["tensioner.F"])["tensioner.F"])
    s.slave.freeFMUState(state)
    s.close()


def test_tensioner_parameters_take_effect_without_a_new_drive_file():
    base = solo_run("p0", steps=5, observe=("tensioner.F",))
    stiffer = solo_run("p1", steps=5, observe=("tensioner.F",), parameters={"tensioner.preload": 120.0})
    assert stiffer[0, 0] > base[0, 0] + 20.0


def test_runs_with_no_stop_time_and_variable_steps():
    s = fmu.Slave("variable")
    s.initialize(inputs=INPUTS)  # no stop time
    t = 0.0
    for h in (1e-4, 5e-5, 2.5e-4, 1e-5):
        s.step(h, t=t)
        t += h
    # (t need not lie on the solver's grid: the outputs belong to the grid point solver.time reached)
    got = s.get(["crankshaft.phi", "solver.time"])
    assert abs(got["solver.time"] - t) < defaults.solver("timing").step
    assert abs(got["crankshaft.phi"] - W2000 * got["solver.time"]) < 1e-9
    s.close()


def test_contact_method_parameter_selects_time_stepping():
    """Rigid contacts by Moreau-Jean time stepping through the FMU: 1 ms runs with finite,
    plausible outputs and differs from the compliant run (a different contact model)."""
    ts = solo_run("ts", steps=10, parameters={"contact.method": "time-stepping"})
    assert np.all(np.isfinite(ts))
    assert ts[:, 0].min() >= 0.0 and ts[:, 0].max() < 3000.0
    compliant = solo_run("cc", steps=10)
    assert not np.array_equal(ts, compliant)


SPRING_DAMPER_DRIVE = paths.ROOT / "tests" / "data" / "drives" / "default_drive_spring_damper.json"
SPRING_DAMPER_INPUTS = {"crankshaft.w": W2000, "camshaftIntake.tau": 3.0, "camshaftExhaust.tau": 2.0}


def test_event_driven_storm_is_a_discard_with_the_reason():
    """The event-driven method meets a runaway event rate on the drive (a result of the stability
    study; it runs the drive with the spring-damper law, not integrating a hydraulic chamber): the FMU
    reports it as fmi2Discard naming the rate, and the state can be restored."""
    s = fmu.Slave("ed", fmu=export.fmu_for(SPRING_DAMPER_DRIVE), parameters={"contact.method": "event-driven"})
    s.initialize(inputs=SPRING_DAMPER_INPUTS)
    state = s.slave.getFMUState()
    with pytest.raises(FMICallException) as e:
        for k in range(10):
            s.step(H, t=k * H)
    assert e.value.status == 2
    assert any("runaway events" in m and "per s" in m for m in s.errors()), s.errors()
    s.slave.setFMUState(state)
    s.slave.freeFMUState(state)
    s.close()


def test_event_driven_refuses_the_hydraulic_tensioner_by_name():
    """The default drive's hydraulic chamber is not integrated by the event-driven method: the FMU
    refuses the combination when the initialization ends, naming the parameter."""
    s = fmu.Slave("ed-hydraulic", parameters={"contact.method": "event-driven"})
    with pytest.raises(FMICallException):
        s.initialize(inputs=INPUTS)
    assert any("contact.method" in m and "hydraulic" in m for m in s.errors()), s.errors()
    s.slave.freeInstance()


@pytest.mark.parametrize("name,value,text", [("contact.method", "rigid", "contact.method"),
                                             ("chain.jointModel", "pinned", "chain.jointModel")])
def test_invalid_contact_parameters_are_errors(name, value, text):
    s = fmu.Slave("badcontact", parameters={name: value})
    with pytest.raises(FMICallException):
        s.initialize(inputs=INPUTS)
    assert any(text in m and value in m for m in s.errors()), s.errors()
    s.slave.freeInstance()


def test_ideal_joints_with_compliant_contacts_is_an_error():
    s = fmu.Slave("idealcompliant", parameters={"chain.jointModel": "ideal", "contact.method": "compliant"})
    with pytest.raises(FMICallException):
        s.initialize(inputs=INPUTS)
    assert any("ideal" in m for m in s.errors()), s.errors()
    s.slave.freeInstance()
