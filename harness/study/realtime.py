"""Real time: CPU time per fmi2DoStep of ChainDrive.fmu through fmpy's FMU2Slave at fixed
communication steps."""
import time

import numpy as np

from ..tables import tables


def realtime(study):
    from ..fmu import fmu
    quick = study.quick
    rpm = 3000.0
    cases = [("compliant / fixed-verlet", {"solver.method": "fixed-verlet", "solver.step": 2.5e-6}, 1.0),
             ("compliant / arkode-erk-fixed", {"solver.method": "arkode-erk-fixed", "solver.step": 2e-6}, 1.0),
             ("time-stepping (rigid contacts)", {"contact.method": "time-stepping", "solver.step": 2.5e-6}, 0.1)]
    t_total = 0.01 if quick else 0.2
    ts = tables.time_series(rpm, t_total + 0.01, 1e-5)
    out = []
    study.log(f"\n## real time: CPU time per fmi2DoStep, {rpm:g} rpm, table inputs")
    for label, params, share in cases:
        for h in (1e-4, 1e-3):
            n = max(5, int(round(share * t_total / h)))
            s = fmu.Slave("rt", parameters=params)
            s.initialize(inputs={k: float(ts[k][0]) for k in fmu.INPUTS})
            times, failure = [], None
            cpu_wall = []
            try:
                for k in range(n):
                    i = min(int(round(k * h / 1e-5)), len(ts["time"]) - 1)
                    for name in fmu.INPUTS:
                        s.set(name, float(ts[name][i]))
                    c0 = time.process_time_ns()
                    w0 = time.perf_counter_ns()
                    s.slave.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
                    times.append((time.process_time_ns() - c0) * 1e-9)
                    cpu_wall.append((time.perf_counter_ns() - w0) * 1e-9)
            except Exception as e:  # fmi2Discard / fmi2Error: report
                failure = f"{e}: {' | '.join(s.errors())[-300:]}"
            finally:
                s.close()
            warm = times[1:] if len(times) > 2 else times
            r = dict(label=label, step=h, steps=len(times), failure=failure)
            if warm:
                a = np.array(warm)
                w = np.array(cpu_wall[1:] if len(cpu_wall) > 2 else cpu_wall)
                r.update(median=float(np.median(a)), p99=float(np.percentile(a, 99)), max=float(a.max()),
                         wall_median=float(np.median(w)), wall_max=float(w.max()),
                         misses=int(np.sum(w > h)), ratio=float(np.median(a)) / h)
            out.append(r)
            if warm:
                study.log(f"  {label:<34} step {h * 1e3:g} ms: {r['steps']} steps, CPU per doStep median "
                          f"{r['median'] * 1e3:.3f} ms, p99 {r['p99'] * 1e3:.3f} ms, max {r['max'] * 1e3:.3f} ms "
                          f"({r['ratio']:.2f} x the step); wall max {r['wall_max'] * 1e3:.3f} ms, "
                          f"{r['misses']} deadline misses" + (f"; FAILED: {failure}" if failure else ""))
            else:
                study.log(f"  {label:<34} step {h * 1e3:g} ms: FAILED: {failure}")
    return out
