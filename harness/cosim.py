"""ChainDrive.fmu in libcosim (the Open Simulation Platform's co-simulation library, built on FMI
Library): a second, independent importer. Its time is counted in nanoseconds; the FMU receives
the communication point t_k = k dt_ns / 1e9 and the step t_(k+1) - t_k, both as doubles."""
import numpy as np

from . import fmu


def run(inputs_at, steps, step_ns, names, parameters=None):
    """Runs `steps` communication steps; inputs_at(k) gives the inputs (dict) for step k. Returns
    an array (steps x names) of the outputs after each step."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.ERROR)
    md, _ = fmu.unpacked()
    vr = {v.name: v.valueReference for v in md.modelVariables}
    ex = CosimExecution.from_step_size(step_ns)
    slave = CosimLocalSlave(fmu_path=str(fmu.fmu_path()), instance_name="chaindrive")
    idx = ex.add_local_slave(slave)
    for name, value in (parameters or {}).items():
        var = next(v for v in md.modelVariables if v.name == name)
        {"Real": ex.real_initial_value, "Integer": ex.integer_initial_value, "Boolean": ex.boolean_initial_value,
         "String": ex.string_initial_value}[var.type](idx, vr[name], value)
    for name, value in inputs_at(0).items():
        ex.real_initial_value(idx, vr[name], value)
    observer = CosimObserver.create_last_value()
    ex.add_observer(observer)
    manipulator = CosimManipulator.create_override()
    ex.add_manipulator(manipulator)
    out = []
    for k in range(steps):
        u = inputs_at(k)
        manipulator.slave_real_values(idx, [vr[n] for n in u], list(u.values()))
        ex.step()
        out.append(observer.last_real_values(idx, [vr[n] for n in names]))
    return np.array(out)


def run_fmpy_like_libcosim(inputs_at, steps, step_ns, names, parameters=None):
    """The same master loop with fmpy, on libcosim's time points."""
    s = fmu.Slave("fmpy", parameters=parameters)
    s.initialize(inputs=inputs_at(0))
    out = []
    for k in range(steps):
        t0, t1 = (k * step_ns) / 1e9, ((k + 1) * step_ns) / 1e9
        for name, value in inputs_at(k).items():
            s.set(name, value)
        s.slave.doStep(currentCommunicationPoint=t0, communicationStepSize=t1 - t0)
        out.append([s.get(names)[n] for n in names])
    s.close()
    return np.array(out)
