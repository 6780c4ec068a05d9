"""The stability map: each method at its default setting over engine speed, over its step or
tolerance, and over joint and contact stiffness, from the pre-loaded state."""
import concurrent.futures as cf
import json

from ..tables import tables
from .methods import METHODS, OUTPUT_STEP, default_drive_json, run_solver, setting_label


def scaled_drive(path, joint=1.0, contact=1.0):
    d = default_drive_json()
    d["chain"]["joint"]["stiffness"] *= joint
    for law in ("rollerSprocket", "plateGuide"):
        d["contact"][law]["stiffness"] *= contact
    path.write_text(json.dumps(d, indent=1))
    return path


def stability(study):
    quick = study.quick
    sd = study.runs_dir / "stability"
    sd.mkdir(parents=True, exist_ok=True)
    t_run, speeds, factors, methods = plan(quick)
    inputs = {}
    for rpm in sorted(set(speeds + [3000])):
        inputs[rpm] = tables.write_inputs_csv(sd / f"inputs_{rpm}.csv", rpm, t_run + 0.01, dt=1e-5)
    drives = {}
    for f in factors:
        drives[("joint", f)] = scaled_drive(sd / f"drive_joint_{f:g}.json", joint=f)
        drives[("contact", f)] = scaled_drive(sd / f"drive_contact_{f:g}.json", contact=f)
    jobs = [job for m in methods for job in method_jobs(m, speeds, factors, drives, quick)]
    study.log(f"\n## stability map: {len(jobs)} runs of {t_run * 1e3:g} ms from the pre-loaded state")

    def one(job):
        return stability_run(study, sd, inputs, t_run, job)

    out = []
    with cf.ThreadPoolExecutor(max_workers=study.args.jobs) as ex:
        for r in ex.map(one, jobs):
            out.append(r)
            study.log(stability_line(r))
    return dict(duration=t_run, runs=out)


def plan(quick):
    """(run length [s], engine speeds, stiffness factors, methods) of the map."""
    if quick:
        return 5e-3, [1000, 6000], [1.0, 64.0], [METHODS[0], next(m for m in METHODS if m["id"] == "ts")]
    return 0.02, [1000, 2000, 3000, 4000, 5000, 6000], [0.25, 1.0, 4.0, 16.0, 64.0], METHODS


def method_jobs(m, speeds, factors, drives, quick):
    """The runs of one method: (axis, x, method, setting, rpm, drive file or None)."""
    jobs = []
    for rpm in speeds:
        jobs.append(("speed [rpm]", rpm, m, m["default"], rpm, None))
    values = [m["stability"][0], m["stability"][-1]] if quick else m["stability"]
    for v in values:
        jobs.append((("step [us]" if m["option"] == "step" else "rtol"), v, m, v, 3000, None))
    for f in factors:
        jobs.append(("joint stiffness factor", f, m, m["default"], 3000, drives[("joint", f)]))
        jobs.append(("contact stiffness factor", f, m, m["default"], 3000, drives[("contact", f)]))
    return jobs


def stability_run(study, sd, inputs, t_run, job):
    """One run of the map: ok, or the failure the solver detected, or the wall-time budget."""
    axis, x, m, v, rpm, drive = job
    tag = f"{m['id']}_{axis.split()[0]}_{x:g}"
    ostep = max(OUTPUT_STEP, v) if m["option"] == "step" else OUTPUT_STEP  # no CSV: any output step
    s = run_solver(sd, tag, m, v, rpm, inputs[rpm], t_run, study.timeout, drive=drive, write_csv=False,
                   output_step=ostep)
    return dict(axis=axis, x=x, method=m["id"], label=m["label"], setting=setting_label(m, v), kind=s["kind"],
                failure=s.get("failure"), failureTime=s.get("failureTime"), simulated=s.get("simulated", 0.0),
                cpu_per_s=(s["cpuSeconds"] / s["simulated"]) if s.get("simulated") else None)


def stability_line(r):
    msg = (f"{r['cpu_per_s']:.1f} CPU s/s" if r["kind"] == "ok" else
           f"FAILED {r['kind']} at t = {r['failureTime'] or 0:.6f} s: {r['failure']}")
    return f"  {r['label']:<34} {r['axis']:<26} {r['x']:<8g} {r['setting']:<16} {msg}"
