"""ChainDrive.fmu in three independent FMI 2 co-simulation importers, driven the same way: the
inputs of communication step k (a dict from inputs_at(k)) are set before the step, the outputs
(names) read after it; each run returns an array (steps x names).

- fmpy: a hand-written master loop on fmpy's FMU2Slave, forming its communication points in one
  of the three ways masters do (TIME_FORMS): t_k = k H; t_(k+1) = t_k + H (accumulated); or the
  step passed as (k+1) H - k H;
- libcosim (the Open Simulation Platform's library, built on FMI Library): time counted in
  integer nanoseconds;
- ecos (a small C++ co-simulation engine): time accumulated, t += H.

The FMU puts every communication point on its own time grid (src/integrators/time_grid.h), so all of them
give the same bits for the same inputs (tests/python/fmu/test_grid.py).
"""
import numpy as np

from . import fmu

TIME_FORMS = ("k*H", "t+=H", "(k+1)H-kH")


def communication_points(form, steps, H, start=0.0):
    """(currentCommunicationPoint, communicationStepSize) of each step, formed as `form` says."""
    points, t = [], start
    for k in range(steps):
        if form == "k*H":
            points.append((start + k * H, H))
        elif form == "t+=H":
            points.append((t, H))
            t += H
        elif form == "(k+1)H-kH":
            points.append((start + k * H, (start + (k + 1) * H) - (start + k * H)))
        else:
            raise ValueError(f"unknown way of forming time '{form}'; known: {', '.join(TIME_FORMS)}")
    return points


def run_fmpy(inputs_at, steps, H, names, parameters=None, form="k*H"):
    s = fmu.Slave("fmpy", parameters=parameters)
    s.initialize(inputs=inputs_at(0))
    out = []
    try:
        for k, (t, h) in enumerate(communication_points(form, steps, H)):
            for name, value in inputs_at(k).items():
                s.set(name, value)
            s.slave.doStep(currentCommunicationPoint=t, communicationStepSize=h)
            values = s.get(names)
            out.append([values[n] for n in names])
    finally:
        s.close()
    return np.array(out)


def run_libcosim(inputs_at, steps, H, names, parameters=None):
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.ERROR)
    md, _ = fmu.unpacked()
    variables = {v.name: v for v in md.modelVariables}
    ex = CosimExecution.from_step_size(int(round(H * 1e9)))
    idx = ex.add_local_slave(CosimLocalSlave(fmu_path=str(fmu.fmu_path()), instance_name="chaindrive"))
    for name, value in (parameters or {}).items():
        v = variables[name]
        {"Real": ex.real_initial_value, "Integer": ex.integer_initial_value, "Boolean": ex.boolean_initial_value,
         "String": ex.string_initial_value}[v.type](idx, v.valueReference, value)
    for name, value in inputs_at(0).items():
        ex.real_initial_value(idx, variables[name].valueReference, value)
    observer = CosimObserver.create_last_value()
    ex.add_observer(observer)
    manipulator = CosimManipulator.create_override()
    ex.add_manipulator(manipulator)
    out = []
    for k in range(steps):
        u = inputs_at(k)
        manipulator.slave_real_values(idx, [variables[n].valueReference for n in u], list(u.values()))
        if not ex.step():
            raise RuntimeError(f"libcosim: step {k} failed")
        out.append(observer.last_real_values(idx, [variables[n].valueReference for n in names]))
    return np.array(out)


def run_ecos(inputs_at, steps, H, names, parameters=None):
    from ecospy import EcosSimulation, EcosSimulationStructure

    structure = EcosSimulationStructure()
    structure.add_model("chaindrive", str(fmu.fmu_path()))
    structure.add_parameter_set("parameters", {f"chaindrive::{k}": v for k, v in (parameters or {}).items()})
    sim = EcosSimulation(structure=structure, step_size=H)
    out = []
    try:
        for name, value in inputs_at(0).items():
            sim.set_real(f"chaindrive::{name}", float(value))
        sim.init(0.0, "parameters")
        for k in range(steps):
            for name, value in inputs_at(k).items():
                sim.set_real(f"chaindrive::{name}", float(value))
            sim.step(1)
            out.append([sim.get_real(f"chaindrive::{n}") for n in names])
        sim.terminate()
    finally:
        sim.free()
    return np.array(out)


IMPORTERS = {"fmpy": run_fmpy, "libcosim": run_libcosim, "ecos": run_ecos}
