"""Speed against accuracy: work-precision charts on cycle statistics and a stability map of every
method.

    python -m harness.study [--quick] [--out DIR] [--jobs N] [--scenes 1000,3000,6000]

Scenes: the default drive at 1000, 3000 and 6000 rpm, open loop with the measured-torque tables
(harness/tables.py: crankshaft speed fluctuation and camshaft torques over crank angle).

Why statistics: the link-level dynamics of the drive is chaotic (impacts of rollers on teeth and
of link plates on guides): two runs that differ by one rounding grow apart exponentially
(docs/study/chaos.md), so after a few milliseconds any two solutions, the reference's among them,
differ at the level of the signal itself. What a method can get right, and what engineers compare,
are the statistics over engine cycles: means, peak-to-peak values and engine-order amplitudes, each
known only to within the scatter of the cycles (harness/cycle_stats.py).

1. Start transient: from the pre-loaded state, fixed-verlet at 1 us over the main job's run-in
   (whole engine cycles, at least 2 and at least 0.15 s); its final state is saved at t0 and every
   run below starts from it (chaindrive-run --initial-state). Every run then settles for one engine
   cycle (in which the rigid-contact models find their own equilibrium: with ideal joints the chain
   cannot stretch) and is measured over the next N whole engine cycles (N: about 0.8 s of engine
   time, CYCLES_TIME, or --cycles-time; a quarter of that for the costly rigid-contact methods).
2. Reference ensemble: arkode-erk at rtol 1e-8 over three times as many cycles; for each headline
   quantity the mean over its cycles with the 95 % confidence half-width, and the cycle-to-cycle
   standard deviation (the reference's own scatter). Its convergence is checked by a second, very
   different accurate method (fixed-verlet at 0.25 us) over the same cycles: their statistics must
   agree within their intervals.
3. Every method (contact method x integrator) over a geometric sweep of its step or tolerance:
   CPU seconds per simulated second (median of up to 3 runs; repeated runs are also checked to be
   bit-identical) and, per headline quantity, its error: the difference of its cycle mean from
   the reference's, in % (levels) or dB (order amplitudes) and in units of the reference's
   cycle-to-cycle scatter, with z = difference / sqrt(ci_method^2 + ci_reference^2). A statistic
   is consistent with the reference when |z| <= 1 (within the 95 % interval of the difference); a
   method is as accurate as the physics allows when all its headline statistics are consistent,
   jointly at 95 % (Bonferroni: each |z| <= the (1 - 0.05/K) quantile over 1.96 for K statistics).
   A run that fails is a failure marker with the kind the solver reports.
4. Convergence order: the short-horizon trajectory error over the first 2 ms after t0 (before the
   chaotic growth), against arkode-erk at rtol 1e-11, checked at 1e-12.
5. Stability map: each method at its default setting over engine speed, over its step or
   tolerance, and over joint and contact stiffness (factors on the default drive), from the
   pre-loaded state over 20 ms: ok, or the failure detected by the solver (blow-up, non-finite
   state, tunnelling, LCP ray termination or numerical failure, Newton failure, step-size
   collapse, runaway events) or the wall-time budget.
6. Real time: CPU time per fmi2DoStep of ChainDrive.fmu through fmpy's FMU2Slave at fixed
   communication steps of 100 us and 1 ms, for the fixed-step methods (median, 99th percentile,
   maximum).

Every run writes outputs every 60 us (OUTPUT_STEP): a whole number of steps of every fixed step
of the sweeps, so that all runs share their output times on the time grid (src/run/time_grid.h).

--quick: 6000 rpm (the shortest cycle), a 2-cycle run-in, 2 measured cycles, a reference at rtol 1e-6 over 3 cycles, one or two points per method, a reduced
stability map and short real-time timings: a smoke test of the whole chain (each method gives a
point or a reported failure) for CI.

Outputs in DIR (default results/study): report.md, results.json, work-precision charts
wp_<rpm>rpm.png, stability_<axis>.png, and the CSV of every run under runs/ (not for the
repository). The report is written by harness/study_report.py.
"""
import argparse
import concurrent.futures as cf
import datetime
import json
import math
import pathlib
import shutil
import subprocess
import sys
import time

import numpy as np
from scipy import stats as scistats

from . import cycle_stats, paths, runs, tables
from .drive import drive_json, meshing_order
from .main import run_in_cycles

SHORT_HORIZON = 2e-3     # [s] window of the short-horizon (trajectory) errors
OUTPUT_STEP = 6e-5       # [s] output interval of every run: whole steps of every fixed step below
THRESHOLD_RMS = 1.0      # [%] the "1 % RMS error" of the tensioner force over the short horizon
CYCLES_TIME = 0.8        # [s] engine time measured per point (whole cycles, at least MIN_CYCLES)
MIN_CYCLES = 6
CHAOS_RESULTS = paths.ROOT / "docs" / "study" / "chaos" / "results.json"  # divergence rates, for the report
REFERENCE_FACTOR = 3     # the reference ensemble: this many times the cycles of a point
RIGID_SHARE = 0.25       # rigid-contact methods (100-3000 CPU s/s): this share of the cycles
SETTLE_CYCLES = 1        # engine cycles of every run before its measured ones
# headline statistics of the verdict "as accurate as the physics allows" (levels, then orders)
VERDICT_KEYS = ["tensioner.F.mean", "tensioner.F.peakToPeak", "chain.Ftight.mean", "chain.Fslack.mean",
                "tensionGuide.phi.peakToPeak_deg", "tensioner.F.order2", "tensioner.F.order4", "tensioner.F.order6",
                "tensioner.F.order8"]

# Methods: contact method x integrator (x joint model), each with a sweep of one setting.
METHODS = [
    dict(id="verlet", label="compliant / fixed-verlet", contact="compliant", integrator="fixed-verlet",
         option="step", full=[4e-6, 3e-6, 2.5e-6, 2e-6, 1e-6, 5e-7], quick=[2e-6, 1e-6], default=2.5e-6,
         stability=[1e-6, 2e-6, 3e-6, 4e-6, 6e-6, 8e-6], fixed=True),
    dict(id="erk-fixed", label="compliant / arkode-erk-fixed", contact="compliant", integrator="arkode-erk-fixed",
         option="step", full=[4e-6, 2e-6, 1e-6], quick=[2e-6], default=2e-6,
         stability=[1e-6, 2e-6, 4e-6, 6e-6, 8e-6, 1.2e-5], fixed=True),
    dict(id="erk", label="compliant / arkode-erk", contact="compliant", integrator="arkode-erk",
         option="rtol", full=[1e-3, 1e-4, 1e-5, 1e-6, 1e-7], quick=[1e-4], default=1e-5,
         stability=[1e-2, 1e-3, 1e-5, 1e-7]),
    dict(id="bdf-klu", label="compliant / cvode-bdf-klu", contact="compliant", integrator="cvode-bdf-klu",
         option="rtol", full=[1e-3, 1e-4, 1e-5, 1e-6], quick=[1e-4], default=1e-5,
         stability=[1e-2, 1e-3, 1e-5, 1e-7]),
    dict(id="bdf-band", label="compliant / cvode-bdf-band", contact="compliant", integrator="cvode-bdf-band",
         option="rtol", full=[1e-3, 1e-5], quick=[1e-4], default=1e-5,
         stability=[1e-2, 1e-3, 1e-5, 1e-7]),
    dict(id="ts", label="time-stepping (rigid contacts)", contact="time-stepping", integrator="fixed-verlet",
         option="step", full=[3e-6, 2.5e-6, 1e-6], quick=[2.5e-6], default=2.5e-6,
         stability=[1e-6, 2e-6, 3e-6, 4e-6, 6e-6], fixed=True),
    dict(id="ts-ideal", label="time-stepping, ideal joints", contact="time-stepping", joints="ideal",
         integrator="fixed-verlet", option="step", full=[2e-5, 1e-5, 5e-6], quick=[2e-5], default=2e-5,
         stability=[5e-6, 1e-5, 2e-5, 4e-5, 8e-5], fixed=True),
    dict(id="ed", label="event-driven (rigid contacts)", contact="event-driven", integrator="arkode-erk",
         option="rtol", full=[1e-3, 1e-5, 1e-7], quick=[1e-5], default=1e-5, stability=[1e-3, 1e-5, 1e-7]),
    dict(id="ed-ideal", label="event-driven, ideal joints", contact="event-driven", joints="ideal",
         integrator="arkode-erk", option="rtol", full=[1e-4, 1e-6], quick=[1e-5], default=1e-5,
         stability=[1e-3, 1e-5, 1e-7]),
]
REFERENCE = dict(id="reference", label="reference: compliant / arkode-erk", contact="compliant",
                 integrator="arkode-erk", option="rtol")
REFERENCE_CHECK = dict(id="reference-check", label="reference check: compliant / fixed-verlet", contact="compliant",
                       integrator="fixed-verlet", option="step")

KIND_CODES = {"blow-up": "BU", "non-finite": "NF", "tunnelling": "TU", "lcp-ray-termination": "RAY",
              "lcp-numerical-failure": "LCP", "lcp-iteration-limit": "LIT", "newton-failure": "NEW",
              "step-size-collapse": "STEP", "runaway-events": "EVT", "timeout": "TIME", "other": "ERR"}


def default_drive_json():
    return drive_json()


def setting_label(m, v):
    return f"h = {v * 1e6:g} us" if m["option"] == "step" else f"rtol = {v:g}"


def is_rigid(m):
    return m["contact"] != "compliant"


# ---------------------------------------------------------------------------------------------
# runs

def run_solver(out_dir, tag, m, value, rpm, inputs_csv, duration, timeout, initial_state=None, drive=None,
               save_state=None, write_csv=True, extra=(), output_step=OUTPUT_STEP):
    """One chaindrive-run; returns the parsed summary (with 'kind' = ok / failure kind / timeout).
    The fixed-step schemes never step past an output time, so their step must not exceed the
    output step: a run whose effective step differs from the one asked for is an error."""
    out_dir.mkdir(parents=True, exist_ok=True)
    csv = out_dir / f"{tag}.csv"
    summary = out_dir / f"{tag}.json"
    cmd = [paths.executable("chaindrive-run"), "--rpm", repr(float(rpm)), "--inputs", str(inputs_csv),
           "--duration", repr(duration), "--output-step", repr(output_step), "--contact-method", m["contact"],
           "--integrator", m["integrator"], f"--{m['option']}", repr(value), "--summary", str(summary), "--quiet"]
    if m.get("joints"):
        cmd += ["--joint-model", m["joints"]]
    if write_csv:
        cmd += ["--out", str(csv)]
    if initial_state:
        cmd += ["--initial-state", str(initial_state)]
    if drive:
        cmd += ["--drive", str(drive)]
    if save_state:
        cmd += ["--save-state", str(save_state)]
    cmd += list(extra)
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return dict(kind="timeout", failure=f"exceeded the wall-time budget of {timeout:g} s", cpuSeconds=timeout,
                    simulated=0.0, requested=duration, csv=None)
    wall = time.monotonic() - t0
    if p.returncode not in (0, 3) or not summary.exists():
        raise RuntimeError(f"chaindrive-run failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr.strip()}")
    s = json.loads(summary.read_text())
    if write_csv and abs(s.get("outputStep", output_step) - output_step) > 1e-9 * output_step:
        raise RuntimeError(f"{tag}: the output step {output_step:g} s is not a whole number of steps of "
                           f"{value:g} s (the runner wrote outputs every {s['outputStep']:g} s)")
    s["kind"] = "ok" if s["status"] == "ok" else s.get("failureKind", "other")
    s["csv"] = str(csv) if (write_csv and s["status"] == "ok") else None
    s["wall"] = wall
    return s


# ---------------------------------------------------------------------------------------------
# errors: cycle statistics against the reference ensemble, trajectory over the short horizon

def is_order(key):
    return ".order" in key


def statistics(d, first_cycle, cycles, mesh):
    """{key: (unit, per-cycle values)} of the first `cycles` whole engine cycles from cycle index
    first_cycle on (crankshaft angle, harness/cycle_stats.py)."""
    return {k: (u, v[:cycles]) for k, (u, v) in cycle_stats.per_cycle(d, first_cycle, mesh).items()}


def reference_statistics(stats):
    """{key: {mean, ci95, cycles, sd, unit}} of the reference ensemble; sd is its cycle-to-cycle
    standard deviation (its own scatter)."""
    out = {}
    for key, (unit, v) in stats.items():
        mean, half, _ = cycle_stats.interval(v)
        out[key] = dict(mean=mean, ci95=half, cycles=int(len(v)), sd=float(np.std(v, ddof=1)), unit=unit)
    return out


def relative_error(key, value, ref, floor=1e-30):
    """value against ref: in dB for order amplitudes (value at least floor), in % otherwise."""
    if is_order(key):
        return 20.0 * math.log10(max(value, floor, 1e-30) / max(ref, 1e-30))
    return 100.0 * (value - ref) / abs(ref) if ref else math.nan


def compare(stats, ref):
    """Per headline quantity: the method's cycle mean and half-width, and its error against the
    reference (% or dB; in units of the reference's scatter; z against the combined interval)."""
    out = {}
    for key, (unit, v) in stats.items():
        r = ref[key]
        mean, half, _ = cycle_stats.interval(v)
        combined = math.hypot(half, r["ci95"])
        out[key] = dict(mean=mean, ci95=half, cycles=int(len(v)), unit=unit,
                        error=relative_error(key, mean, r["mean"]), errorUnit="dB" if is_order(key) else "%",
                        # an interval reaching down to zero amplitude is drawn down to -20 dB of the mean
                        errorLow=relative_error(key, mean - half, r["mean"], floor=0.1 * mean),
                        errorHigh=relative_error(key, mean + half, r["mean"]),
                        scatter=(mean - r["mean"]) / r["sd"] if r["sd"] > 0 else math.nan,
                        z=(mean - r["mean"]) / combined if combined > 0 else math.nan)
    return out


def joint_limit(k):
    """|z| limit for K statistics to be jointly consistent at 95 % (Bonferroni), in units of the
    1.96 of a single 95 % interval."""
    return float(scistats.norm.ppf(1.0 - 0.025 / k) / scistats.norm.ppf(0.975))


def as_accurate_as_physics(errors):
    """All headline statistics of VERDICT_KEYS consistent with the reference, jointly at 95 %."""
    zs = [errors[k]["z"] for k in VERDICT_KEYS if k in errors]
    return bool(zs) and all(math.isfinite(z) and abs(z) <= joint_limit(len(zs)) for z in zs)


def rms(x):
    return float(np.sqrt(np.mean(np.square(x))))


def short_errors(d, ref, t0):
    """Trajectory errors over the first SHORT_HORIZON after t0, against the short reference (the
    same output times on the grid)."""
    n = min(len(d["time"]), len(ref["time"]))
    tt = ref["time"][:n]
    w = (tt > t0 + 0.5 * OUTPUT_STEP) & (tt <= t0 + SHORT_HORIZON + 0.5 * OUTPUT_STEP)
    eF = d["tensioner.F"][:n][w] - ref["tensioner.F"][:n][w]
    eP = d["tensionGuide.phi"][:n][w] - ref["tensionGuide.phi"][:n][w]
    return dict(short_F_rms_pct=100.0 * rms(eF) / rms(ref["tensioner.F"][:n][w]), short_F_max_N=float(np.max(np.abs(eF))),
                short_phi_rms_rad=rms(eP))


# ---------------------------------------------------------------------------------------------
# one scene: transient, references, sweeps

class Study:
    def __init__(self, args):
        self.args = args
        self.quick = args.quick
        self.out = pathlib.Path(args.out)
        self.runs_dir = self.out / "runs"
        self.mesh = meshing_order(default_drive_json())
        self.log_lines = []
        self.timeout = 120.0 if self.quick else args.timeout

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
            f"{'consistent' if p['consistent'] else 'NOT consistent'}  2 ms: F {e['short_F_rms_pct']:.3g} %")


# ---------------------------------------------------------------------------------------------
# stability map

def scaled_drive(path, joint=1.0, contact=1.0):
    d = default_drive_json()
    d["chain"]["joint"]["stiffness"] *= joint
    for law in ("rollerSprocket", "plateGuide"):
        d["contact"][law]["stiffness"] *= contact
    path.write_text(json.dumps(d, indent=1))
    return path


def stability(study):
    args = study.args
    quick = study.quick
    sd = study.runs_dir / "stability"
    sd.mkdir(parents=True, exist_ok=True)
    t_run = 5e-3 if quick else 0.02
    speeds = [1000, 6000] if quick else [1000, 2000, 3000, 4000, 5000, 6000]
    factors = [1.0, 64.0] if quick else [0.25, 1.0, 4.0, 16.0, 64.0]
    methods = [METHODS[0], next(m for m in METHODS if m["id"] == "ts")] if quick else METHODS
    inputs = {}
    for rpm in sorted(set(speeds + [3000])):
        inputs[rpm] = tables.write_inputs_csv(sd / f"inputs_{rpm}.csv", rpm, t_run + 0.01, dt=1e-5)
    drives = {}
    for f in factors:
        drives[("joint", f)] = scaled_drive(sd / f"drive_joint_{f:g}.json", joint=f)
        drives[("contact", f)] = scaled_drive(sd / f"drive_contact_{f:g}.json", contact=f)
    jobs = []
    for m in methods:
        for rpm in speeds:
            jobs.append(("speed [rpm]", rpm, m, m["default"], rpm, None))
        values = [m["stability"][0], m["stability"][-1]] if quick else m["stability"]
        for v in values:
            jobs.append((("step [us]" if m["option"] == "step" else "rtol"), v, m, v, 3000, None))
        for f in factors:
            jobs.append(("joint stiffness factor", f, m, m["default"], 3000, drives[("joint", f)]))
            jobs.append(("contact stiffness factor", f, m, m["default"], 3000, drives[("contact", f)]))
    study.log(f"\n## stability map: {len(jobs)} runs of {t_run * 1e3:g} ms from the pre-loaded state")

    def one(job):
        axis, x, m, v, rpm, drive = job
        tag = f"{m['id']}_{axis.split()[0]}_{x:g}"
        ostep = max(OUTPUT_STEP, v) if m["option"] == "step" else OUTPUT_STEP  # no CSV: any output step
        s = run_solver(sd, tag, m, v, rpm, inputs[rpm], t_run, study.timeout, drive=drive, write_csv=False,
                       output_step=ostep)
        return dict(axis=axis, x=x, method=m["id"], label=m["label"], setting=setting_label(m, v), kind=s["kind"],
                    failure=s.get("failure"), failureTime=s.get("failureTime"), simulated=s.get("simulated", 0.0),
                    cpu_per_s=(s["cpuSeconds"] / s["simulated"]) if s.get("simulated") else None)

    out = []
    with cf.ThreadPoolExecutor(max_workers=args.jobs) as ex:
        for r in ex.map(one, jobs):
            out.append(r)
            msg = (f"{r['cpu_per_s']:.1f} CPU s/s" if r["kind"] == "ok" else
                   f"FAILED {r['kind']} at t = {r['failureTime'] or 0:.6f} s: {r['failure']}")
            study.log(f"  {r['label']:<34} {r['axis']:<26} {r['x']:<8g} {r['setting']:<16} {msg}")
    return dict(duration=t_run, runs=out)


# ---------------------------------------------------------------------------------------------
# real time: CPU time per doStep through FMU2Slave

def realtime(study):
    from . import fmu
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


# ---------------------------------------------------------------------------------------------
# the command

def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="the reduced variant (CI)")
    ap.add_argument("--out", default=None, help="output directory (default results/study or results/study-quick)")
    ap.add_argument("--scenes", default=None, help="engine speeds [rpm], comma separated (default 1000,3000,6000)")
    ap.add_argument("--jobs", type=int, default=1, help="runs in parallel (timings are cleaner with 1)")
    ap.add_argument("--cycles-time", type=float, default=CYCLES_TIME,
                    help=f"engine time measured per point [s] (whole cycles, at least {MIN_CYCLES}; "
                         f"default {CYCLES_TIME})")
    ap.add_argument("--repeats", type=int, default=3, help="runs per point for the median CPU time")
    ap.add_argument("--repeat-below", type=float, default=20.0,
                    help="repeat a point only if one run takes less than this many CPU seconds")
    ap.add_argument("--timeout", type=float, default=3600.0, help="wall-time budget of one measured run [s]")
    ap.add_argument("--keep-csv", action="store_true", help="keep the output CSV of every point")
    ap.add_argument("--skip", default="", help="parts to skip: comma separated of wp, stability, realtime")
    ap.add_argument("--resume", action="store_true",
                    help="reuse the scenes already finished in --out (scene_<rpm>rpm.json)")
    ap.add_argument("--chaos", default=str(CHAOS_RESULTS),
                    help="results of python -m harness.chaos for the report's last section (default %(default)s)")
    ap.add_argument("--report-only", metavar="RESULTS_JSON",
                    help="only rewrite the report and charts into --out from the results of an earlier run")
    args = ap.parse_args(argv)
    if args.out is None:
        args.out = (str(pathlib.Path(args.report_only).parent) if args.report_only else
                    str(paths.RESULTS / ("study-quick" if args.quick else "study")))
    return args


def chaos_results(args):
    """The divergence-rate study's results for the report (None if it has not been run)."""
    path = pathlib.Path(args.chaos)
    return json.loads(path.read_text()) if path.exists() else None


def rewrite_report(args):
    from . import study_report
    r = json.loads(pathlib.Path(args.report_only).read_text())
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if pathlib.Path(args.report_only).resolve() != (out / "results.json").resolve():
        (out / "results.json").write_text(json.dumps(r, indent=1))
    study_report.write(out, r, chaos_results(args))
    print(f"written: {out / 'report.md'}")
    return 0


def main(argv=None):
    from . import study_report
    args = parse_args(argv)
    if args.report_only:
        return rewrite_report(args)
    scenes_rpm = [6000.0] if args.quick else [1000.0, 3000.0, 6000.0]
    if args.scenes:
        scenes_rpm = [float(x) for x in args.scenes.split(",")]
    skip = set(filter(None, args.skip.split(",")))
    study = Study(args)
    out = pathlib.Path(args.out)
    if not args.resume:
        shutil.rmtree(out / "runs", ignore_errors=True)
        for f in out.glob("scene_*rpm.json"):
            f.unlink()
    out.mkdir(parents=True, exist_ok=True)
    started = datetime.datetime.now()
    w0 = time.monotonic()
    study.log(f"study{' (quick)' if args.quick else ''}: {runs.machine()}")
    scenes = [study.scene(rpm) for rpm in scenes_rpm] if "wp" not in skip else []
    stab = stability(study) if "stability" not in skip else dict(duration=0.0, runs=[])
    rt = realtime(study) if "realtime" not in skip else []
    wall = time.monotonic() - w0
    command = " ".join(["python -m harness.study"] + (argv if argv is not None else sys.argv[1:]))
    results = dict(machine=runs.machine(), started=started.isoformat(timespec="seconds"), wall_seconds=wall,
                   quick=args.quick, command=command, scenes=scenes, stability=stab, realtime=rt, log=study.log_lines,
                   settings=dict(repeats=args.repeats, repeat_below=args.repeat_below, jobs=args.jobs,
                                 timeout=args.timeout))
    (out / "results.json").write_text(json.dumps(results, indent=1))
    study_report.write(out, results, chaos_results(args))
    if not args.keep_csv and not args.quick:
        shutil.rmtree(out / "runs", ignore_errors=True)
    print(f"\nwritten: {out / 'report.md'} ({wall / 60:.1f} min)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
