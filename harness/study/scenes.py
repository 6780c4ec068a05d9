"""One scene of the study: the start transient, the reference ensemble and its checks, and every
method's sweep of points, each measured against the reference."""
import concurrent.futures as cf
import json
import math
import pathlib

import numpy as np

from .. import runs
from ..drive.description import elements
from ..job import run_in_cycles
from ..tables import tables
from .errors import as_accurate_as_physics, compare, reference_statistics, short_errors, statistics
from .methods import (METHODS, MIN_CYCLES, REFERENCE, REFERENCE_CHECK, REFERENCE_FACTOR, RIGID_SHARE, SETTLE_CYCLES,
                      SHORT_HORIZON, HORIZON_LABEL, default_drive_json, is_rigid, run_solver, setting_label)


class Study:
    def __init__(self, args):
        self.args = args
        self.quick = args.quick
        self.out = pathlib.Path(args.out)
        self.runs_dir = self.out / "runs"
        self.mesh = elements(default_drive_json())  # (the default drive's elements: the cycle statistics')
        self.log_lines = []
        # (--quick: a guard against a hang, not a measure: under ./run.sh test two pytest workers and a
        # compile share 2 cores, and time stepping's run took more than 120 s there)
        self.timeout = 600.0 if self.quick else args.timeout

    def log(self, s):
        print(s, flush=True)
        self.log_lines.append(s)

    def plan(self, rpm):
        """Engine cycles of the scene: run-in (before t0), measured per point (compliant and
        rigid), of the reference ensemble."""
        cycle = 120.0 / rpm
        if self.quick:
            return dict(cycle=cycle, run_in=2, cycles=2, rigid=2, reference=3)
        n = max(MIN_CYCLES, int(round(self.args.cycles_time / cycle)))
        return dict(cycle=cycle, run_in=run_in_cycles(rpm), cycles=n, rigid=max(2, int(round(RIGID_SHARE * n))),
                    reference=REFERENCE_FACTOR * n)

    def measured_run(self, sd, tag, m, value, rpm, plan, cycles, state, extra=()):
        """A run from t0 over SETTLE_CYCLES + cycles engine cycles (plus a tenth for the speed
        fluctuation); returns (summary, data or None)."""
        duration = (SETTLE_CYCLES + cycles + 0.1) * plan["cycle"]
        budget = self.timeout * max(1.0, cycles / plan["cycles"])
        s = run_solver(sd, tag, m, value, rpm, plan["inputs"], duration, budget, initial_state=state, extra=extra)
        return s, (runs.read_csv(s["csv"]) if s["kind"] == "ok" else None)

    def point(self, sd, m, value, rpm, plan, state, ref, short_ref, t0):
        tag = f"{m['id']}_{value:g}"
        cycles = plan["rigid"] if is_rigid(m) else plan["cycles"]
        s, d = self.measured_run(sd, tag, m, value, rpm, plan, cycles, state)
        cpus, identical = self.repeat_timings(sd, tag, m, value, rpm, plan, cycles, state, s)
        p = dict(method=m["id"], label=m["label"], option=m["option"], value=value, kind=s["kind"],
                 failure=s.get("failure"), failureTime=s.get("failureTime"), simulated=s.get("simulated", 0.0),
                 cpu_runs=cpus, cpu=float(np.median(cpus)), repeatsIdentical=identical)
        p["cpu_per_s"] = p["cpu"] / (s["simulated"] if s["kind"] == "ok" else s["requested"])
        for k in ("steps", "rhsEvaluations", "events", "lcpSolves", "lcpSizeMean", "lcpSizeMax", "pivots",
                  "regularizedLcps"):
            if k in s:
                p[k] = s[k]
        if d is not None:
            p["errors"] = compare(statistics(d, plan["run_in"] + SETTLE_CYCLES, cycles, self.mesh), ref)
            p["errors"].update(short_errors(d, short_ref, t0))
            p["consistent"] = as_accurate_as_physics(p["errors"])
            if not self.args.keep_csv and not self.quick:
                pathlib.Path(s["csv"]).unlink()
        return p

    def repeat_timings(self, sd, tag, m, value, rpm, plan, cycles, state, first):
        """CPU times of repeated runs (median), only while a run is cheap; repeats must be
        bit-identical to the first run."""
        cpus, identical = [first["cpuSeconds"]], True
        repeats = 1 if self.quick else self.args.repeats
        for k in range(1, repeats):
            if first["kind"] != "ok" or first["cpuSeconds"] > self.args.repeat_below:
                break
            r, _ = self.measured_run(sd, f"{tag}_r{k}", m, value, rpm, plan, cycles, state)
            if r["kind"] != "ok":
                return cpus, False
            cpus.append(r["cpuSeconds"])
            identical = identical and pathlib.Path(r["csv"]).read_bytes() == pathlib.Path(first["csv"]).read_bytes()
            pathlib.Path(r["csv"]).unlink()
        return cpus, identical

    def scene(self, rpm):
        done = self.out / f"scene_{rpm:g}rpm.json"
        if self.args.resume and done.exists():
            self.log(f"\n## scene {rpm:g} rpm: results of an earlier run ({done.name})")
            sc = json.loads(done.read_text())
            for p in sc["points"]:
                self.log(point_line(p))
            return sc
        sc = self.run_scene(rpm)
        done.write_text(json.dumps(sc, indent=1))
        return sc

    def transient(self, sd, rpm, plan):
        """The start transient from the pre-loaded state over the run-in; returns (state file, t0)."""
        state = sd / "state.json"
        verlet = METHODS[0]
        tr = run_solver(sd, "transient", verlet, 1e-6 if not self.quick else 2e-6, rpm, plan["inputs"],
                        plan["run_in"] * plan["cycle"], 10 * self.timeout, save_state=state, write_csv=False)
        if tr["kind"] != "ok":
            raise RuntimeError(f"the start transient failed: {tr.get('failure')}")
        return state, json.loads(state.read_text())["time_s"], tr["cpuSeconds"]

    def references(self, sd, rpm, plan, state, t0):
        """The reference ensemble and its check (cycle statistics), and the short-horizon reference
        and its check (trajectories)."""
        rtol, h_check = (1e-6, 5e-7) if self.quick else (1e-8, 2.5e-7)
        s_ref, d_ref = self.measured_run(sd, "reference", REFERENCE, rtol, rpm, plan, plan["reference"], state)
        s_chk, d_chk = self.measured_run(sd, "reference_check", REFERENCE_CHECK, h_check, rpm, plan,
                                         plan["reference"], state)
        short_rtol = (1e-8, 1e-9) if self.quick else (1e-11, 1e-12)
        # at these tolerances the steps at contact onsets (kinks of the force laws) go below the
        # default step-size floor of 1e-10 s
        tight = ["--min-step", "1e-15"]
        shorts = [run_solver(sd, f"short_{r:g}", REFERENCE, r, rpm, plan["inputs"], SHORT_HORIZON,
                             20 * self.timeout, initial_state=state, extra=tight) for r in short_rtol]
        failed = [s for s in (s_ref, s_chk, *shorts) if s["kind"] != "ok"]
        if failed:
            raise RuntimeError(f"a reference run failed: {failed[0].get('failure')}")
        first = plan["run_in"] + SETTLE_CYCLES
        ref = reference_statistics(statistics(d_ref, first, plan["reference"], self.mesh))
        check = compare(statistics(d_chk, first, plan["reference"], self.mesh), ref)
        d_short = [runs.read_csv(s["csv"]) for s in shorts]
        reference = dict(method="arkode-erk", rtol=rtol, cpu_per_s=s_ref["cpuPerSimulatedSecond"], statistics=ref,
                         check=dict(method="fixed-verlet", step=h_check, cpu_per_s=s_chk["cpuPerSimulatedSecond"],
                                    errors=check, consistent=as_accurate_as_physics(check)),
                         short=dict(rtol=short_rtol[0], check_rtol=short_rtol[1],
                                    change=short_errors(d_short[1], d_short[0], t0)))
        return reference, d_short[0]

    def run_scene(self, rpm):
        plan = self.plan(rpm)
        sd = self.runs_dir / f"{rpm:g}rpm"
        sd.mkdir(parents=True, exist_ok=True)
        total = (plan["run_in"] + SETTLE_CYCLES + plan["reference"] + 0.5) * plan["cycle"]
        plan["inputs"] = tables.write_inputs_csv(sd / "inputs.csv", rpm, total, dt=1e-5)
        self.log(f"\n## scene {rpm:g} rpm: run-in {plan['run_in']} cycles, then every run {SETTLE_CYCLES} cycle "
                 f"settling + {plan['cycles']} measured cycles ({plan['rigid']} for rigid contacts; reference "
                 f"{plan['reference']})")
        state, t0, cpu_tr = self.transient(sd, rpm, plan)
        reference, short_ref = self.references(sd, rpm, plan, state, t0)
        self.log(reference_line(reference))
        scene = dict(rpm=rpm, plan={k: v for k, v in plan.items() if k != "inputs"}, t0=t0, transientCpu=cpu_tr,
                     reference=reference, points=[])
        jobs = [(m, v) for m in METHODS for v in (m["quick"] if self.quick else m["full"])]
        with cf.ThreadPoolExecutor(max_workers=self.args.jobs) as ex:
            futs = [ex.submit(self.point, sd, m, v, rpm, plan, state, reference["statistics"], short_ref, t0)
                    for m, v in jobs]
            for f in futs:
                p = f.result()
                scene["points"].append(p)
                self.log(point_line(p))
        return scene


def reference_line(reference):
    F = reference["statistics"]["tensioner.F.mean"]
    chk = reference["check"]
    worst = max(chk["errors"].items(), key=lambda kv: abs(kv[1]["z"]) if math.isfinite(kv[1]["z"]) else 0.0)
    return (f"reference arkode-erk rtol {reference['rtol']:g} ({reference['cpu_per_s']:.0f} CPU s/s): tensioner force "
            f"mean {F['mean']:.2f} +- {F['ci95']:.2f} N over {F['cycles']} cycles (cycle scatter {F['sd']:.2f} N); "
            f"check fixed-verlet {chk['step'] * 1e6:g} us: {'consistent' if chk['consistent'] else 'NOT consistent'} "
            f"(largest |z| {abs(worst[1]['z']):.2f} at {worst[0]}); short horizon change "
            f"{reference['short']['change']['short_F_rms_pct']:.2g} %")


def point_line(p):
    head = f"  {p['label']:<34} {setting_label(p, p['value']):<16}"
    if p["kind"] != "ok":
        return head + f" FAILED ({p['kind']}) at t = {p.get('failureTime') or 0:.6f} s: {p['failure']}"
    e = p["errors"]
    F, pp, o2 = e["tensioner.F.mean"], e["tensioner.F.peakToPeak"], e["tensioner.F.order2"]
    return (head + f" {p['cpu_per_s']:9.2f} CPU s/s  F mean {F['error']:+6.2f} % (z {F['z']:+5.2f})  F p2p "
            f"{pp['error']:+6.2f} % (z {pp['z']:+5.2f})  order 2 {o2['error']:+5.2f} dB (z {o2['z']:+5.2f})  "
            f"{'consistent' if p['consistent'] else 'NOT consistent'}  {HORIZON_LABEL}: F {e['short_F_rms_pct']:.3g} %")
