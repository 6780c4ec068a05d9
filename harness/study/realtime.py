"""Real time: CPU and wall time per fmi2DoStep of ChainDrive.fmu through fmpy's FMU2Slave at fixed
communication steps (dostep_timings; the study's realtime() and the benchmark use it)."""
import time

import numpy as np

from .. import job
from ..tables import tables

INPUT_DT = 1e-5  # [s] sample interval of the table inputs


def dostep_timings(params, h, n, ts):
    """n fmi2DoStep calls of h seconds on a fresh instance with FMU parameters params, inputs
    from the time series ts (tables.time_series, at INPUT_DT) before each step. Returns {step,
    steps, failure} and, when steps were taken, the CPU time per step (median, p99, max; the
    first step excluded: it carries the start), the wall time (wall_median, wall_p99, wall_max),
    the deadline misses (wall time above h) and the ratio of the median CPU time to h."""
    from ..fmu import fmu
    s = fmu.Slave("rt", parameters=params)
    inputs = [k for k in ts if k not in ("time", "crank_angle_deg")]  # (the default drive's: tables.time_series)
    s.initialize(inputs={k: float(ts[k][0]) for k in inputs})
    cpu, wall, failure = [], [], None
    try:
        for k in range(n):
            i = min(int(round(k * h / INPUT_DT)), len(ts["time"]) - 1)
            for name in inputs:
                s.set(name, float(ts[name][i]))
            c0 = time.thread_time_ns()  # (this thread's: the FMU computes in it, numpy's BLAS threads do not)
            w0 = time.perf_counter_ns()
            s.slave.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
            cpu.append((time.thread_time_ns() - c0) * 1e-9)
            wall.append((time.perf_counter_ns() - w0) * 1e-9)
    except Exception as e:  # fmi2Discard / fmi2Error: report
        failure = f"{e}: {' | '.join(s.errors())[-300:]}"
    finally:
        s.close()
    r = dict(step=h, steps=len(cpu), failure=failure)
    if cpu:
        c = np.array(cpu[1:] if len(cpu) > 2 else cpu)
        w = np.array(wall[1:] if len(wall) > 2 else wall)
        r.update(median=float(np.median(c)), p99=float(np.percentile(c, 99)), max=float(c.max()),
                 wall_median=float(np.median(w)), wall_p99=float(np.percentile(w, 99)), wall_max=float(w.max()),
                 misses=int(np.sum(w > h)), ratio=float(np.median(c)) / h)
    return r


def realtime(study):
    quick = study.quick
    rpm = 3000.0
    cases = [("compliant / real-time method", {"solver.method": job.REALTIME_METHOD, "solver.step": job.REALTIME_STEP},
              1.0),
             ("compliant / fixed-verlet", {"solver.method": "fixed-verlet", "solver.step": 2.5e-6}, 1.0),
             ("compliant / arkode-erk-fixed", {"solver.method": "arkode-erk-fixed", "solver.step": 2e-6}, 1.0),
             ("time-stepping (rigid contacts)", {"contact.method": "time-stepping", "solver.step": 2.5e-6}, 0.1)]
    t_total = 0.01 if quick else 0.2
    ts = tables.time_series(rpm, t_total + 0.01, INPUT_DT)
    out = []
    study.log(f"\n## real time: CPU time per fmi2DoStep, {rpm:g} rpm, table inputs")
    for label, params, share in cases:
        for h in (1e-4, 1e-3):
            r = dict(label=label) | dostep_timings(params, h, max(5, int(round(share * t_total / h))), ts)
            out.append(r)
            if "median" in r:
                study.log(f"  {label:<34} step {h * 1e3:g} ms: {r['steps']} steps, CPU per doStep median "
                          f"{r['median'] * 1e3:.3f} ms, p99 {r['p99'] * 1e3:.3f} ms, max {r['max'] * 1e3:.3f} ms "
                          f"({r['ratio']:.2f} x the step); wall max {r['wall_max'] * 1e3:.3f} ms, "
                          f"{r['misses']} deadline misses" + (f"; FAILED: {r['failure']}" if r["failure"] else ""))
            else:
                study.log(f"  {label:<34} step {h * 1e3:g} ms: FAILED: {r['failure']}")
    return out
