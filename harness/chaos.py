"""Divergence rate and the chaos floor, measured with twin runs that differ by one rounding.

    python -m harness.chaos [--quick] [--out DIR] [--report FILE] [--jobs N] [--rpm 3000]
                            [--settings default,both4,...] [--pairs N] [--cycles N] [--max-cycles N]
                            [--verlet-steps 2.5e-6,...] [--keep-runs] [--report-only RESULTS_JSON]

Scene: the default drive at --rpm (3000), open loop with the measured-torque tables
(harness/tables.py: crankshaft speed fluctuation and camshaft torques over crank angle, as the
--inputs time series of chaindrive-run).

Damping settings (--settings, all by default): the default drive; joint damping
(chain.joint.damping) and contact damping (contact.rollerSprocket.dampingFactor and
contact.plateGuide.dampingFactor) both raised 4x and 10x; each of them alone 4x and 10x (which
damping matters); and a method check on the default damping from the same start states
(adaptive arkode-erk at rtol 1e-8 instead of fixed-step Verlet).

Per setting:
1. Run-in from the pre-loaded state, the run-in of harness/main.py (whole engine cycles, at least
   2 and at least 0.15 s: 4 cycles at 3000 rpm), with fixed-verlet at the first step of
   --verlet-steps (2.5, 2, 1.25, 1, 0.625, 0.5, 0.4, 0.25 us) below the explicit-damping bound
   (step_bound: h c / m < 2 for a link with its joint dampers and with a contact damper at an
   impact peak, times 0.8) that completes it; the steps that failed are reported with the
   failure the solver detected (blow-up, ...). Explicit --verlet-steps are tried as given.
2. Step check: the damping forces are explicit in Verlet. Too much joint damping for the step
   blows up; too much contact damping does not: the contact force, clamped at zero, chatters,
   and the run goes on with wrong dynamics and a wrong divergence rate (contact damping 10x at
   2.5 us diverges at several times the rate it has at 1 us or 0.5 us). So the rate lambda of
   the tensioner force is measured on PROBE_PAIRS (4) pairs at the run-in's step and at half of
   it, and the step is halved until the pairs' log rates at the two steps no longer differ
   significantly (Welch's t-test at the 1 % level: the rate of a pair changes with any change
   of step, as every trajectory does) or differ by less than a factor STEP_TOLERANCE (1.25),
   down to MIN_STEP (0.2 us). Every step checked is reported.
3. Start states S_0 ... S_(N-1): the run-in's final state (again at the accepted step if the
   check went below the run-in's step), then the run continued one engine cycle at a time, so
   that pair k starts at a cycle boundary k cycles after S_0 (the ensemble samples different
   states on the same engine phase).
4. Twin pairs k = 0 .. N-1 (--pairs, 12): twin A runs from S_k, twin B from S_k with one state
   component multiplied by 1 + 1e-12 (a different component per pair: x or y of links spread
   along the chain, or a rotor angle), outputs every 20 us. Their length: the latest
   saturation time (b) of any pair and signal in the accepted step check plus AFTER_SATURATION
   (3) engine cycles, at least --cycles (5), at most --max-cycles (15). A twin that fails is a
   reported failure, not a number; the other pairs still count.

Measures, per setting and per signal (tensioner force, tension-guide angle), on the difference
B - A as RMS over 1 ms windows, time counted from the perturbation:
(a) divergence rate lambda [1/ms]: least-squares slope of ln(windowed difference) between its
    first crossing of FIT_LOW (1e-6) and of FIT_HIGH (1e-2) times the independent level (below),
    and at least 100 times its first window (the output's print floor, or the adaptive method's
    own error level); median and range over the pairs, and the e-folding time 1/lambda.
(b) saturation time: the first window in which the difference reaches half the independent
    level: the RMS difference of two unrelated runs with the same inputs, measured between twin
    A runs that start at least two engine cycles apart (the same engine phase, unrelated
    states). In ms and in engine cycles; median and range over the pairs.
(c) cycle independence: the per-cycle statistics of harness/cycle_stats.per_cycle (tensioner
    force mean, peak-to-peak and order 2, tight-span force mean, tension-guide angle
    peak-to-peak) of twin A and twin B, cycle by cycle (cycle 0 starts at the perturbation).
    r_j = median over the pairs of |x_B - x_A| in cycle j, divided by the median |x - x'| over
    all pairs of distinct engine cycles of the twin A runs (the difference of unrelated
    cycles): about 1 once the twins are independent. Medians, not RMS: the per-cycle values
    have heavy tails (a peak-to-peak is set by the largest impact of its cycle). The bound is
    the 2.5 % quantile of the same ratio for N random pairs of those unrelated cycles (4000
    draws): independent twins fall below it with 2.5 % probability. A statistic counts as
    independent from the first cycle j whose r_j reaches its bound (the report also counts
    later cycles below it), the twins' cycle statistics from the largest such j over the
    statistics; the report adds the rank correlation of x_A and x_B over the pairs.

--quick: the default setting only, a 1-cycle run-in, no step check, 3 pairs of 2 cycles: a
smoke test (about 15 s on 2 cores; run by tests/python/test_chaos.py).

Outputs in DIR (default results/chaos): results.json, divergence.png (windowed twin difference
over time per setting with the fitted slopes), cycles.png (per-cycle twin statistics),
lambda.png (divergence rate per setting with its spread), and the report (markdown; default
DIR/report.md); run files under DIR/runs (removed unless --keep-runs). At most 2 runs at a time
(--jobs 1 or 2: the machine's cores are shared).
"""
import argparse
import concurrent.futures as cf
import datetime
import json
import math
import pathlib
import shutil
import sys
import time

import numpy as np
from scipy import stats as scistats

from . import cycle_stats, paths, plots, runs, study, tables
from .main import run_in_cycles

OUTPUT_STEP = 2e-5      # [s] output interval of every twin (50 kHz)
WINDOW = 1e-3           # [s] RMS window of the twin difference
PERTURBATION = 1e-12    # relative change of one state component
FIT_LOW = 1e-6          # fit window of the exponential phase, as fractions of the independent level
FIT_HIGH = 1e-2
FLOOR_MARGIN = 100.0    # and the fit starts at least this factor above the first window
SATURATION = 0.5        # saturated: windowed difference >= this fraction of the independent level
AFTER_SATURATION = 3    # [engine cycles] the ensemble's twins run this long after the step check's saturation
PROBE_PAIRS = 4         # pairs of the step check
STEP_TOLERANCE = 1.25   # halving the step may change the step check's rates by this factor ...
STEP_SIGNIFICANCE = 0.01  # ... or by more, if not significantly (Welch's t-test on the pairs' log rates)
STABILITY_MARGIN = 0.8  # on the explicit-damping step bound (the springs lower the limit too)
MIN_STEP = 2e-7         # [s] the step check halves no further
MAX_JOBS = 2            # never more runs at a time (shared machine)
VERLET_STEPS = (2.5e-6, 2e-6, 1.25e-6, 1e-6, 6.25e-7, 5e-7, 4e-7, 2.5e-7)  # all divide the output step

# (output, label, unit at the edge, scale from SI)
SIGNALS = (("tensioner.F", "tensioner force", "N", 1.0),
           ("tensionGuide.phi", "tension-guide angle", "deg", 180.0 / math.pi))
CYCLE_KEYS = ("tensioner.F.mean", "tensioner.F.peakToPeak", "tensioner.F.order2", "chain.Ftight.mean",
              "tensionGuide.phi.peakToPeak_deg")

SETTINGS = [
    dict(id="default", label="default damping", joint=1.0, contact=1.0),
    dict(id="both4", label="joint + contact damping x4", joint=4.0, contact=4.0),
    dict(id="both10", label="joint + contact damping x10", joint=10.0, contact=10.0),
    dict(id="joint4", label="joint damping x4", joint=4.0, contact=1.0),
    dict(id="joint10", label="joint damping x10", joint=10.0, contact=1.0),
    dict(id="contact4", label="contact damping x4", joint=1.0, contact=4.0),
    dict(id="contact10", label="contact damping x10", joint=1.0, contact=10.0),
    # method check: the default drive from the default setting's start states, adaptive ERK
    dict(id="erk", label="default, arkode-erk rtol 1e-8", joint=1.0, contact=1.0, states_from="default",
         pairs=6, cycles=2, method=dict(contact="compliant", integrator="arkode-erk", option="rtol", value=1e-8)),
]


# ---------------------------------------------------------------------------------------------
# drives, states, perturbations

def damped_drive(path, joint, contact):
    """The default drive with joint damping and both contact damping factors scaled."""
    d = study.default_drive_json()
    d["chain"]["joint"]["damping"] *= joint
    for law in ("rollerSprocket", "plateGuide"):
        d["contact"][law]["dampingFactor"] *= contact
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(d, indent=1))
    return path


def rotor_angle_states(drive):
    """{rotor name: index of its angle in the state vector}: the layout of src/assembly/assembly.cpp (6 per
    link, then per rotor its angle and, if free, its rate; sprockets first, then pivoting guides)."""
    idx = 6 * drive["chain"]["numberOfLinks"]
    out = {}
    for s in drive["sprockets"]:
        out[s["name"]] = idx
        idx += 1 if s.get("motion") == "prescribed" else 2
    for g in drive["guides"]:
        if g.get("motion") == "pivoting":
            out[g["name"]] = idx
            idx += 2
    return out


def perturbation_plan(drive, pairs):
    """(label, state index) per pair: link x or y spread along the chain, every third a rotor angle;
    pair k's component does not depend on the number of pairs (the step check's pairs are the
    ensemble's first ones)."""
    links = drive["chain"]["numberOfLinks"]
    rotors = list(rotor_angle_states(drive).items())
    plan = []
    for k in range(pairs):
        if k % 3 == 2:
            name, idx = rotors[(k // 3) % len(rotors)]
            plan.append((f"{name} angle", idx))
        else:
            link = (17 * k) % links
            coord = "xy"[k % 2]
            plan.append((f"link {link} {coord}", 6 * link + "xy".index(coord)))
    return plan


def perturbed_state(src, dst, index, relative):
    """Copies a state file with state component `index` multiplied by (1 + relative)."""
    s = json.loads(pathlib.Path(src).read_text())
    v = float.fromhex(s["y"][index])
    w = v * (1.0 + relative)
    if w == v:
        raise ValueError(f"state {index} = {v!r}: a relative change of {relative:g} does not change it")
    s["y"][index] = w.hex()
    pathlib.Path(dst).write_text(json.dumps(s, indent=1))
    return dst


# ---------------------------------------------------------------------------------------------
# runs

class Context:
    """What every run of the study shares: options, the inputs, the engine cycle, the log."""

    def __init__(self, args, settings):
        self.args = args
        self.quick = args.quick
        self.out = pathlib.Path(args.out)
        self.runs_dir = self.out / "runs"
        self.rpm = float(args.rpm)
        # an engine cycle as a whole number of output steps, so that the start states and the
        # twins' samples share one time grid
        self.cycle = round(120.0 / self.rpm / OUTPUT_STEP) * OUTPUT_STEP
        self.run_in_cycles = 1 if self.quick else run_in_cycles(self.rpm)
        self.timeout = 120.0 if self.quick else args.timeout
        self.verlet_steps = args.verlet_steps
        self.max_cycles = 2 if self.quick else args.max_cycles
        self.mesh = study.meshing_order(study.default_drive_json())
        self.log_lines = []
        self.states = {}  # setting id -> (start-state files, method that made them)
        longest = max(self.pairs(s) - 1 + max(self.cycles(s), self.max_cycles) for s in settings)
        self.runs_dir.mkdir(parents=True, exist_ok=True)
        self.inputs = tables.write_inputs_csv(self.runs_dir / "inputs.csv", self.rpm,
                                              (self.run_in_cycles + longest + 1) * self.cycle, dt=OUTPUT_STEP)

    def log(self, line):
        print(line, flush=True)
        self.log_lines.append(line)

    def pairs(self, s):
        return 3 if self.quick else self.args.pairs or s.get("pairs", 12)

    def cycles(self, s):
        """Shortest twin [engine cycles]: the step check's twins, and the least of the ensemble's."""
        return 2 if self.quick else self.args.cycles or s.get("cycles", 5)

    def solve(self, sd, tag, method, duration, **kw):
        """One chaindrive-run (study.run_solver) with the study's inputs; adaptive methods get no
        step-size floor (their steps at contact onsets go below the default 1e-10 s at tight
        tolerances)."""
        extra = ("--min-step", "1e-15") if method["option"] == "rtol" else ()
        return study.run_solver(sd, tag, method, method["value"], self.rpm, self.inputs, duration, self.timeout,
                                extra=extra, output_step=OUTPUT_STEP, **kw)


def verlet(step):
    return dict(contact="compliant", integrator="fixed-verlet", option="step", value=step)


def method_label(m):
    return f"{m['integrator']} {m['value'] * 1e6:g} us" if m["option"] == "step" else \
        f"{m['integrator']} rtol {m['value']:g}"


def failure_of(r):
    return dict(kind=r["kind"], failure=r.get("failure"), failureTime=r.get("failureTime"))


def run_in(ctx, drive, sd, steps):
    """The run-in from the pre-loaded state with the first Verlet step of `steps` that completes
    it: (S_0, its method, every step tried with its outcome)."""
    sd.mkdir(parents=True, exist_ok=True)
    state = sd / "S0.json"
    tried = []
    for step in steps:
        state.unlink(missing_ok=True)
        m = verlet(step)
        r = ctx.solve(sd, f"runin_{step:g}", m, ctx.run_in_cycles * ctx.cycle, drive=drive, save_state=state,
                      write_csv=False)
        tried.append(dict(step=step, cpuSeconds=r.get("cpuSeconds"), **failure_of(r)))
        ctx.log(f"  run-in {ctx.run_in_cycles} cycles, {method_label(m)}: " +
                ("ok" if r["kind"] == "ok" else f"FAILED ({r['kind']}) at t = {r.get('failureTime') or 0:.6f} s: "
                                                 f"{r.get('failure')}"))
        if r["kind"] == "ok":
            return state, m, tried
    return None, None, tried


def continued_states(ctx, m, drive, sd, files, count):
    """S_0 .. S_(count-1): `files` continued one engine cycle at a time; (states, None) or
    (None, the failure)."""
    files = list(files)
    while len(files) < count:
        k = len(files)
        r = ctx.solve(sd, f"segment_{k}", m, ctx.cycle, initial_state=files[-1], drive=drive,
                      save_state=sd / f"S{k}.json", write_csv=False)
        if r["kind"] != "ok":
            ctx.log(f"  start state {k}: FAILED ({r['kind']}): {r.get('failure')}")
            return None, dict(step=m["value"], stage=f"start state {k}", **failure_of(r))
        files.append(sd / f"S{k}.json")
    return files, None


def twin(ctx, sd, tag, m, drive, state, duration):
    """One twin: its outputs (the columns the analysis needs) or its failure."""
    r = ctx.solve(sd, tag, m, duration, initial_state=state, drive=drive)
    out = dict(cpuSeconds=r.get("cpuSeconds"), simulated=r.get("simulated"), **failure_of(r))
    if r["kind"] == "ok":
        d = runs.read_csv(r["csv"])
        out["data"] = {c: d[c] for c in KEEP_COLUMNS}
        if not ctx.args.keep_runs:
            pathlib.Path(r["csv"]).unlink()
    return out


KEEP_COLUMNS = ("time", "crankshaft.phi", "camshaftIntake.phi", "camshaftExhaust.phi", "tensioner.F",
                "tensionGuide.phi", "chain.Ftight", "chain.Fslack")


def run_twins(ctx, m, drive, states, sd, cycles, quiet=False):
    """Every pair: twin A from S_k, twin B from S_k with one component perturbed, `cycles` engine
    cycles long."""
    sd.mkdir(parents=True, exist_ok=True)
    plan = perturbation_plan(json.loads(pathlib.Path(drive).read_text()), len(states))
    duration = cycles * ctx.cycle + 1e-3  # 1 ms more: the crankshaft lags the mean speed a little
    jobs = []
    for k, (state, (label, index)) in enumerate(zip(states, plan)):
        pert = perturbed_state(state, sd / f"S{k}_perturbed.json", index, PERTURBATION)
        jobs.append((k, label, index, state, pert))
    with cf.ThreadPoolExecutor(max_workers=ctx.args.jobs) as ex:
        futures = [(job, ex.submit(twin, ctx, sd, f"A{job[0]}", m, drive, job[3], duration),
                    ex.submit(twin, ctx, sd, f"B{job[0]}", m, drive, job[4], duration)) for job in jobs]
        pairs = []
        for (k, label, index, _, _), fa, fb in futures:
            a, b = fa.result(), fb.result()
            p = dict(start=k, perturbation=label, stateIndex=index, A=a, B=b)
            p["kind"] = "ok" if a["kind"] == b["kind"] == "ok" else (a if a["kind"] != "ok" else b)["kind"]
            pairs.append(p)
            if p["kind"] != "ok" or not quiet:
                ctx.log(f"  pair {k:2d} ({label}): " + ("ok" if p["kind"] == "ok" else
                        f"FAILED ({p['kind']}): {(a if a['kind'] != 'ok' else b).get('failure')}"))
    return pairs


def probe(ctx, s, step, drive, states, sd):
    """The step check at one Verlet step: PROBE_PAIRS pairs of ctx.cycles(s) cycles; the
    divergence rate of the tensioner force and the saturation times of both signals."""
    m = verlet(step)
    pairs = run_twins(ctx, m, drive, states[:PROBE_PAIRS], sd / f"probe_{step:g}", ctx.cycles(s), quiet=True)
    ok = [p for p in pairs if p["kind"] == "ok"]
    out = dict(step=step, pairs=len(ok), failures=[p["kind"] for p in pairs if p["kind"] != "ok"], rate_per_ms=None,
               saturation_ms={})
    if len(ok) >= 2:
        for name, *_ in SIGNALS:
            sig = signal_divergence(ok, name, ctx.cycle)
            out["saturation_ms"][name] = sig["saturation_ms"]["max"] if sig["saturation_ms"]["n"] == len(ok) else None
            if name == SIGNALS[0][0]:
                out["rate_per_ms"] = sig["rate_per_ms"]["median"]
                out["rates_per_ms"] = [q["fit"].get("rate", 0.0) * 1e-3 if q["fit"]["status"] == "ok" else None
                                       for q in sig["pairs"]]
    ctx.log(f"  step check {method_label(m)}: lambda F {fmt(out['rate_per_ms'])} 1/ms over {len(ok)} pairs"
            + (f", failed: {out['failures']}" if out["failures"] else ""))
    return out


def rates_agree(a, b):
    """Two step checks agree unless their pairs' log rates differ significantly (Welch's t-test at
    STEP_SIGNIFICANCE: the rate of a pair changes with any change of step, as every trajectory
    does, so only a shift beyond that scatter counts) and by more than a factor STEP_TOLERANCE.
    No rate at either step (no divergence measurable) agrees only with no rate at the other."""
    la = np.log([x for x in a.get("rates_per_ms", []) if x and x > 0])
    lb = np.log([x for x in b.get("rates_per_ms", []) if x and x > 0])
    if len(la) < 2 or len(lb) < 2:
        return len(la) == len(lb) == 0 and not a["failures"] and not b["failures"]
    diff = abs(float(la.mean() - lb.mean()))
    p = float(scistats.ttest_ind(la, lb, equal_var=False).pvalue)
    b["logRateDifference"], b["pValue"] = diff, p
    return p > STEP_SIGNIFICANCE or diff <= math.log(STEP_TOLERANCE)


def step_bound(drive_path, rpm):
    """Largest Verlet step [s] at which the explicit damping forces are stable, h c / m < 2 for a
    link (mass m) with the damping coefficient c of: its two joints with neighbours in antiphase
    (c = 4 c_joint), a roller or plate contact at its impact peak (Hunt-Crossley: c = 1.5 alpha
    F_N, with F_N = v sqrt(k m), the peak force of an impact at speed v = omega_crank p, the
    roller seating speed of DOMAIN.md), times STABILITY_MARGIN for the springs acting too."""
    d = json.loads(pathlib.Path(drive_path).read_text())
    ch = d["chain"]
    m = ch["linkMass"]
    speed = 2.0 * math.pi * rpm / 60.0 * ch["pitch"]
    out = dict(joint=STABILITY_MARGIN * 2.0 * m / (4.0 * ch["joint"]["damping"]), impactSpeed=speed)
    for law in ("rollerSprocket", "plateGuide"):
        c = d["contact"][law]
        peak = speed * math.sqrt(c["stiffness"] * m)
        out[law] = STABILITY_MARGIN * 2.0 * m / (1.5 * c["dampingFactor"] * peak)
    out["bound"] = min(out["joint"], out["rollerSprocket"], out["plateGuide"])
    return out


def choose_step(ctx, s, drive, sd):
    """The Verlet step of a setting: the first of --verlet-steps below the explicit-damping bound
    that completes the run-in (too much joint damping for the step blows up), then halved until
    halving no longer changes the divergence rate (rates_agree; too much contact damping for the
    step makes the clamped contact force chatter instead of blowing up). Returns dict(step (None
    if none works), tried, checks, converged, bound, states: the start states made at the
    run-in's step)."""
    bound = step_bound(drive, ctx.rpm)
    steps = ctx.verlet_steps
    if not ctx.args.explicit_steps:
        steps = [h for h in steps if h <= bound["bound"]] or [min(steps)]
    ctx.log(f"  explicit-damping step bound {bound['bound'] * 1e6:.3g} us (joints {bound['joint'] * 1e6:.3g}, rollers "
            f"{bound['rollerSprocket'] * 1e6:.3g}, plates {bound['plateGuide'] * 1e6:.3g} us)")
    s0, m0, tried = run_in(ctx, drive, sd / "probe", steps)
    out = dict(step=m0["value"] if m0 else None, tried=tried, checks=[], converged=None, states=[s0] if s0 else [],
               bound=bound)
    if s0 is None or ctx.quick:
        return out
    states, failure = continued_states(ctx, m0, drive, sd / "probe", [s0], PROBE_PAIRS)
    if states is None:
        return dict(out, step=None, tried=tried + [failure])
    out["states"] = states
    step = m0["value"]
    checks = out["checks"]
    checks.append(probe(ctx, s, step, drive, states, sd))
    while True:
        checks.append(probe(ctx, s, step / 2.0, drive, states, sd))
        if rates_agree(checks[-2], checks[-1]):
            return dict(out, step=step, converged=True)
        step /= 2.0
        if step / 2.0 < MIN_STEP:
            return dict(out, step=step, converged=False)


def twin_cycles(ctx, s, check):
    """Ensemble twin length [engine cycles]: the latest saturation time of any pair and signal in
    the accepted step check, plus AFTER_SATURATION cycles; at least ctx.cycles(s), at most
    ctx.max_cycles (also when a pair of the check did not saturate)."""
    if ctx.quick or s.get("states_from"):
        return ctx.cycles(s)
    times = list((check or {}).get("saturation_ms", {}).values())
    if not times or None in times:
        return max(ctx.cycles(s), ctx.max_cycles)
    need = math.ceil(max(times) * 1e-3 / ctx.cycle - 1e-9) + AFTER_SATURATION
    return int(min(max(need, ctx.cycles(s)), max(ctx.max_cycles, ctx.cycles(s))))


def start_states(ctx, s, drive, sd, choice):
    """S_0 .. S_(N-1) at the chosen step (those of the step check continued, or the run-in again
    if the step check went below the run-in's step) and the method that made them; (None, None,
    failure) if a run fails."""
    m = verlet(choice["step"])
    if choice["tried"][-1]["step"] == choice["step"]:
        files, failure = continued_states(ctx, m, drive, sd / "probe", choice["states"], ctx.pairs(s))
    else:
        s0, m, tried = run_in(ctx, drive, sd, (choice["step"],))
        if s0 is None:
            return None, None, tried[0]
        files, failure = continued_states(ctx, m, drive, sd, [s0], ctx.pairs(s))
    if files is None:
        return None, None, failure
    ctx.states[s["id"]] = (files, m)
    return files, m, None


# ---------------------------------------------------------------------------------------------
# analysis

def windowed_rms(x, n):
    """RMS of x over consecutive windows of n samples (a last partial window is dropped)."""
    m = len(x) // n
    return np.sqrt(np.mean(np.square(x[:m * n]).reshape(m, n), axis=1))


def window_centres(count):
    return (np.arange(count) + 0.5) * WINDOW


def independent_level(pairs, name):
    """RMS difference of two unrelated runs with the same inputs: twin A runs that start at least
    two engine cycles apart (one, if the ensemble is that small), compared at equal times since
    their start, i.e. at the same engine phase."""
    gap = 2 if max(p["start"] for p in pairs) - min(p["start"] for p in pairs) >= 2 else 1
    msq = []
    for p in pairs:
        for q in pairs:
            if q["start"] - p["start"] >= gap:
                a, b = p["A"]["data"][name], q["A"]["data"][name]
                n = min(len(a), len(b))
                msq.append(np.mean(np.square(a[:n] - b[:n])))
    return float(np.sqrt(np.mean(msq)))


def fit_divergence(w, level):
    """Exponential phase of the windowed twin difference w: the least-squares slope of ln w
    [1/s] between the first crossings of the low and high levels (see the module doc)."""
    t = window_centres(len(w))
    lo, hi = max(FIT_LOW * level, FLOOR_MARGIN * w[0]), FIT_HIGH * level
    above_lo = np.nonzero(w >= lo)[0]
    if lo >= hi or not len(above_lo):
        return dict(status="no-growth" if lo < hi else "floor-too-high", low=lo, high=hi)
    i_lo = int(above_lo[0])
    above_hi = np.nonzero(w[i_lo:] >= hi)[0]
    status = "ok" if len(above_hi) else "not-saturated"
    i_hi = i_lo + int(above_hi[0]) if len(above_hi) else len(w) - 1
    sel = np.arange(i_lo, i_hi + 1)
    sel = sel[w[sel] > 0]
    if len(sel) < 3:
        return dict(status="too-few-windows", low=lo, high=hi, tLow=float(t[i_lo]), tHigh=float(t[i_hi]))
    slope, intercept = np.polyfit(t[sel], np.log(w[sel]), 1)
    resid = np.log(w[sel]) - (slope * t[sel] + intercept)
    r2 = 1.0 - float(np.sum(resid ** 2)) / max(float(np.sum((np.log(w[sel]) - np.log(w[sel]).mean()) ** 2)), 1e-300)
    return dict(status=status, rate=float(slope), intercept=float(intercept), tLow=float(t[i_lo]),
                tHigh=float(t[i_hi]), r2=r2, low=lo, high=hi)


def saturation_time(w, level):
    """Centre of the first window whose twin difference reaches SATURATION x the independent level."""
    hit = np.nonzero(w >= SATURATION * level)[0]
    return float(window_centres(len(w))[hit[0]]) if len(hit) else None


def spread(values):
    v = [x for x in values if x is not None]
    if not v:
        return dict(median=None, min=None, max=None, n=0)
    return dict(median=float(np.median(v)), min=float(np.min(v)), max=float(np.max(v)), n=len(v))


def rounded(x, digits=3):
    return [float(f"{v:.{digits}g}") for v in x]


def signal_divergence(pairs, name, cycle):
    """Measures (a) and (b) of one signal over the ensemble of pairs."""
    n = int(round(WINDOW / OUTPUT_STEP))
    level = independent_level(pairs, name)
    per_pair, curves = [], []
    for p in pairs:
        a, b = p["A"]["data"][name], p["B"]["data"][name]
        m = min(len(a), len(b))
        w = windowed_rms(b[:m] - a[:m], n)
        fit = fit_divergence(w, level)
        t_sat = saturation_time(w, level)
        per_pair.append(dict(start=p["start"], perturbation=p["perturbation"], fit=fit, saturation=t_sat))
        curves.append(w)
    m = min(len(w) for w in curves)
    W = np.array([w[:m] for w in curves])
    rates = [q["fit"].get("rate") if q["fit"]["status"] == "ok" else None for q in per_pair]
    sat = spread([q["saturation"] for q in per_pair])
    rate_spread = spread(rates)
    median = rate_spread["median"]
    return dict(independentLevel=level, pairs=per_pair,
                rate_per_ms={k: (v * 1e-3 if isinstance(v, float) else v) for k, v in rate_spread.items()},
                efold_ms=(1.0 / (median * 1e-3)) if median and median > 0 else None,
                saturation_ms={k: (v * 1e3 if isinstance(v, float) else v) for k, v in sat.items()},
                saturation_cycles={k: (v / cycle if isinstance(v, float) else v) for k, v in sat.items()},
                curve=dict(window=WINDOW, rms=rounded(np.sqrt(np.mean(W ** 2, axis=0))), min=rounded(W.min(axis=0)),
                           max=rounded(W.max(axis=0))))


def cycle_values(d, mesh):
    """Per-cycle statistics of one twin, from the cycle that starts at its first sample."""
    first = int(round(d["crankshaft.phi"][0] / cycle_stats.ENGINE_CYCLE))
    pc = cycle_stats.per_cycle(d, first, mesh)
    return {key: pc[key][1] for key in CYCLE_KEYS}


def unrelated_difference(values):
    """Median |x - x'| over all pairs of distinct engine cycles: the difference of unrelated cycles."""
    i, j = np.triu_indices(len(values), 1)
    return float(np.median(np.abs(values[i] - values[j])))


def independence_bound(values, pairs, probability=0.025, draws=4000):
    """The `probability` quantile of the median |x - x'| over `pairs` random pairs of distinct
    cycles (drawn from `values`), relative to unrelated_difference: independent twins fall below
    it only with that probability. Distribution-free: the per-cycle values have heavy tails (a
    peak-to-peak is set by the largest impact of the cycle). Seeded: the report is reproducible."""
    rng = np.random.default_rng(1)
    i = rng.integers(0, len(values), (draws, pairs))
    j = (i + rng.integers(1, len(values), (draws, pairs))) % len(values)
    medians = np.median(np.abs(values[i] - values[j]), axis=1)
    return float(np.quantile(medians, probability)) / unrelated_difference(values)


def distinct_cycles(pairs, XA):
    """The per-cycle values of the distinct engine cycles of the twin A runs (A_k continues S_k,
    so A_k's cycle j is engine cycle k + j of one trajectory), in engine-cycle order."""
    base = {}
    for p, row in zip(pairs, XA):
        for j, x in enumerate(row):
            base.setdefault(p["start"] + j, float(x))
    return np.array([base[i] for i in sorted(base)])


def cycle_independence(pairs, mesh):
    """Measure (c): per-cycle twin statistics, cycle by cycle: r_j = median over the pairs of
    |x_B - x_A| in cycle j over the median difference of unrelated cycles, its bound, and the
    rank correlation of x_A and x_B over the pairs."""
    va = [cycle_values(p["A"]["data"], mesh) for p in pairs]
    vb = [cycle_values(p["B"]["data"], mesh) for p in pairs]
    cycles = min(len(v[CYCLE_KEYS[0]]) for v in va + vb)
    out = dict(pairs=len(pairs), cycles=cycles, keys={})
    for key in CYCLE_KEYS:
        XA = np.array([v[key][:cycles] for v in va])
        XB = np.array([v[key][:cycles] for v in vb])
        between = distinct_cycles(pairs, XA)
        ratio = np.median(np.abs(XB - XA), axis=0) / unrelated_difference(between)
        bound = independence_bound(between, len(pairs))
        corr = [float(scistats.spearmanr(XA[:, j], XB[:, j])[0]) if len(pairs) >= 3 else None for j in range(cycles)]
        reached = [j for j in range(cycles) if ratio[j] >= bound]
        first = reached[0] if reached else None
        out["keys"][key] = dict(ratio=[float(r) for r in ratio], bound=bound, correlation=corr,
                                betweenCycles=float(np.std(between, ddof=1)), distinctCycles=len(between),
                                lag1=cycle_stats.lag1_autocorrelation(between), firstIndependent=first,
                                laterBelowBound=0 if first is None else int(np.sum(ratio[first:] < bound)),
                                A=[rounded(r, 5) for r in XA], B=[rounded(r, 5) for r in XB],
                                distinct=rounded(between, 5))
    firsts = [k["firstIndependent"] for k in out["keys"].values()]
    out["firstIndependent"] = None if None in firsts else max(firsts)
    return out


def analyse(ctx, pairs):
    ok = [p for p in pairs if p["kind"] == "ok"]
    res = dict(signals={name: signal_divergence(ok, name, ctx.cycle) for name, *_ in SIGNALS},
               cycles=cycle_independence(ok, ctx.mesh))
    return res


def setting_states(ctx, s, drive, sd, res):
    """The start states of a setting, the method that made them and the step choice; on failure
    (None, None, None) with res marked failed."""
    if s.get("states_from"):
        if s["states_from"] not in ctx.states:
            res.update(status="failed", failure=f"needs the start states of '{s['states_from']}', not run")
            return None, None, None
        states, state_method = ctx.states[s["states_from"]]
        ctx.log(f"  start states of '{s['states_from']}' ({method_label(state_method)})")
        return states[:ctx.pairs(s)], state_method, dict(checks=[], converged=None)
    choice = choose_step(ctx, s, drive, sd)
    res["runIn"] = choice["tried"]
    if choice["step"] is None:
        res.update(status="failed", failure="no Verlet step of --verlet-steps completes the run-in"
                   if all(t["kind"] != "ok" for t in choice["tried"]) else "a start state failed")
        return None, None, None
    states, state_method, failure = start_states(ctx, s, drive, sd, choice)
    if states is None:
        res.update(status="failed", failure="a start state failed", runIn=res["runIn"] + [failure])
        return None, None, None
    return states, state_method, choice


def run_setting(ctx, s):
    """One damping setting: run-in, start states, twins, measures; failures are reported as such."""
    sd = ctx.runs_dir / s["id"]
    drive = damped_drive(sd / "drive.json", s["joint"], s["contact"])
    d = json.loads(drive.read_text())
    res = dict(id=s["id"], label=s["label"], jointFactor=s["joint"], contactFactor=s["contact"],
               jointDamping=d["chain"]["joint"]["damping"],
               rollerAlpha=d["contact"]["rollerSprocket"]["dampingFactor"],
               guideAlpha=d["contact"]["plateGuide"]["dampingFactor"], runIn=[])
    ctx.log(f"\n## {s['label']} ({s['id']}): joint damping {res['jointDamping']:g} N s/m, contact damping factors "
            f"{res['rollerAlpha']:g} / {res['guideAlpha']:g} s/m")
    states, state_method, choice = setting_states(ctx, s, drive, sd, res)
    if states is None:
        return res
    res["stepChecks"] = choice["checks"]
    res["stepConverged"] = choice["converged"]
    res["stepBound"] = choice.get("bound")
    m = s.get("method") or state_method
    res["method"] = dict(m, label=method_label(m))
    res["statesMethod"] = method_label(state_method)
    accepted = next((c for c in choice["checks"] if c["step"] == m.get("value")), None)
    res["twinCycles"] = twin_cycles(ctx, s, accepted)
    ctx.log(f"  ensemble: {len(states)} pairs of {res['twinCycles']} engine cycles, {method_label(m)}")
    pairs = run_twins(ctx, m, drive, states, sd, res["twinCycles"])
    res["pairFailures"] = [dict(start=p["start"], perturbation=p["perturbation"],
                                **failure_of(p["A"] if p["A"]["kind"] != "ok" else p["B"]))
                           for p in pairs if p["kind"] != "ok"]
    done = [p for p in pairs if p["kind"] == "ok"]
    cpu = [p[t]["cpuSeconds"] for p in done for t in "AB"]
    sim = [p[t]["simulated"] for p in done for t in "AB"]
    res["cpuPerSimulatedSecond"] = float(np.sum(cpu) / np.sum(sim)) if done else None
    if len(done) < 2:
        res["status"] = "failed"
        res["failure"] = f"{len(pairs) - len(done)} of {len(pairs)} pairs failed"
        return res
    res.update(analyse(ctx, done))
    res["status"] = "ok" if len(done) == len(pairs) else "partial"
    ctx.log(setting_line(res))
    return res


def setting_line(r):
    if r["status"] == "failed":
        return f"  {r['label']}: FAILED: {r.get('failure')}"
    F, P = r["signals"]["tensioner.F"], r["signals"]["tensionGuide.phi"]
    j = r["cycles"]["firstIndependent"]
    return (f"  {r['label']} [{r['method']['label']}]: lambda F {fmt_spread(F['rate_per_ms'])} 1/ms "
            f"(e-folding {fmt(F['efold_ms'])} ms), angle {fmt_spread(P['rate_per_ms'])} 1/ms; saturated after "
            f"{fmt(F['saturation_ms']['median'])} ms ({fmt(F['saturation_cycles']['median'])} cycles), angle "
            f"{fmt(P['saturation_ms']['median'])} ms; cycle statistics independent from cycle "
            f"{j if j is not None else 'none of those run'} ({r['twinCycles']} cycles run)")


def fmt(x, digits=3):
    return "-" if x is None else f"{x:.{digits}g}"


def fmt_spread(s, digits=3):
    if s.get("median") is None:
        return "-"
    return f"{s['median']:.{digits}g} [{s['min']:.{digits}g}, {s['max']:.{digits}g}]"


# ---------------------------------------------------------------------------------------------
# charts

DPI = 110


def save_png(fig, path):
    """Saves at DPI as a 256-colour PNG (charts have few colours; a third of the size)."""
    import io
    from PIL import Image
    buf = io.BytesIO()
    fig.savefig(buf, dpi=DPI)
    plots.plt.close(fig)
    Image.open(buf).convert("RGB").quantize(colors=256).save(path, optimize=True)


def measured(results):
    return [r for r in results["settings"] if r["status"] != "failed"]


def chart_divergence(path, results):
    """Windowed twin difference over time per setting (RMS over the pairs, the band of the pairs),
    the fitted slopes of the pairs, the independent level and its saturation fraction."""
    rows = measured(results)
    plt = plots.plt
    fig, axes = plt.subplots(len(rows), len(SIGNALS), figsize=(11.0, 1.9 * len(rows) + 0.6), squeeze=False,
                             sharex=True)
    for ax_row, r in zip(axes, rows):
        for ax, (name, label, unit, scale) in zip(ax_row, SIGNALS):
            sig = r["signals"][name]
            c = sig["curve"]
            t = window_centres(len(c["rms"])) * 1e3
            lo, hi = np.maximum(np.array(c["min"]), 1e-300), np.array(c["max"])
            ax.fill_between(t, lo * scale, hi * scale, color="0.85", lw=0, label="range over the pairs")
            ax.semilogy(t, np.array(c["rms"]) * scale, "k-", lw=1.0, label="RMS over the pairs")
            for q in sig["pairs"]:
                f = q["fit"]
                if f["status"] == "ok":
                    tt = np.array([f["tLow"], f["tHigh"]])
                    ax.semilogy(tt * 1e3, np.exp(f["intercept"] + f["rate"] * tt) * scale, "-", color="tab:red",
                                lw=0.8, alpha=0.7)
            ax.axhline(sig["independentLevel"] * scale, color="tab:blue", ls="--", lw=0.8,
                       label="independent runs")
            ax.axhline(SATURATION * sig["independentLevel"] * scale, color="tab:blue", ls=":", lw=0.8)
            ax.set_ylim(max(lo.min() * scale, 1e-12 * sig["independentLevel"] * scale),
                        3.0 * max(hi.max(), sig["independentLevel"]) * scale)
            ax.set_title(f"{r['label']} ({r['method']['label']}): {label}, lambda "
                         f"{fmt(sig['rate_per_ms']['median'])} 1/ms", fontsize=7.5)
            ax.set_ylabel(f"|B - A| RMS 1 ms [{unit}]", fontsize=7)
            ax.tick_params(labelsize=7)
            ax.grid(True, which="major", lw=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("time since the perturbation [ms]", fontsize=8)
    axes[0][0].legend(fontsize=6, loc="lower right")
    fig.suptitle(f"Twin runs that differ by 1e-12 in one state component ({results['rpm']:g} rpm); red: fitted "
                 f"exponential phase of each pair", fontsize=9)
    fig.tight_layout()
    save_png(fig, path)


def chart_lambda(path, results):
    """Divergence rate per setting, median and range over the pairs, both signals."""
    plt = plots.plt
    rs = results["settings"]
    fig, ax = plt.subplots(figsize=(9.0, 3.8))
    x = np.arange(len(rs))
    width = 0.38
    for i, (name, label, *_ ) in enumerate(SIGNALS):
        for xi, r in zip(x, rs):
            pos = xi + (i - 0.5) * width
            if r["status"] == "failed" or r["signals"][name]["rate_per_ms"]["median"] is None:
                ax.text(pos, 0.02, "FAILED" if r["status"] == "failed" else "no fit", rotation=90, fontsize=7,
                        color="tab:red", ha="center", va="bottom")
                continue
            s = r["signals"][name]["rate_per_ms"]
            ax.bar(pos, s["median"], width, color=("tab:gray", "tab:olive")[i], label=label if xi == 0 else None)
            ax.errorbar(pos, s["median"], yerr=[[s["median"] - s["min"]], [s["max"] - s["median"]]], color="k",
                        capsize=3, lw=0.8)
            ax.text(pos, s["max"] * 1.02, f"{1.0 / s['median']:.2g} ms", ha="center", va="bottom", fontsize=6)
    ax.set_xticks(x)
    ax.set_xticklabels([r["label"] for r in rs], rotation=20, ha="right", fontsize=7)
    ax.set_ylabel("divergence rate lambda [1/ms]")
    ax.set_title("Divergence rate of twin runs: median and range over the pairs (labels: e-folding time)", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(True, axis="y", lw=0.3)
    fig.tight_layout()
    save_png(fig, path)


def chart_cycles(path, results):
    """Per-cycle twin statistics: the ratio of the twin difference to that of independent cycles,
    cycle by cycle after the perturbation, per setting; and twin A against twin B of the default."""
    plt = plots.plt
    rows = measured(results)
    fig, axes = plt.subplots(2, 3, figsize=(11.0, 6.4))
    for ax, key in zip(axes.flat, CYCLE_KEYS):
        for r in rows:
            c = r["cycles"]["keys"][key]
            line, = ax.plot(np.arange(len(c["ratio"])), c["ratio"], "o-", ms=3, lw=0.9, label=r["label"])
            ax.axhline(c["bound"], color=line.get_color(), ls="--", lw=0.5)
        ax.axhline(1.0, color="k", lw=0.6)
        ax.set_title(key, fontsize=8)
        ax.set_ylim(bottom=0.0)
        ax.xaxis.set_major_locator(plots.matplotlib.ticker.MaxNLocator(integer=True))
        ax.set_xlabel("engine cycle after the perturbation", fontsize=7)
        ax.set_ylabel("median |B - A| / unrelated cycles", fontsize=7)
        ax.tick_params(labelsize=7)
        ax.grid(True, lw=0.3)
    axes.flat[0].legend(fontsize=5.5)
    ax = axes.flat[5]
    c = rows[0]["cycles"]["keys"][CYCLE_KEYS[0]]
    A, B = np.array(c["A"]), np.array(c["B"])
    for j in range(A.shape[1]):
        ax.plot(A[:, j], B[:, j], "o", ms=3.5, label=f"cycle {j}")
    lim = [min(A.min(), B.min()), max(A.max(), B.max())]
    ax.plot(lim, lim, "k-", lw=0.5)
    ax.set_xlabel(f"twin A: {CYCLE_KEYS[0]} [N]", fontsize=7)
    ax.set_ylabel(f"twin B: {CYCLE_KEYS[0]} [N]", fontsize=7)
    ax.set_title(f"{rows[0]['label']}: twin B against twin A, per cycle", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.legend(fontsize=6)
    fig.suptitle(f"Per-cycle statistics of twin pairs ({results['rpm']:g} rpm); dashed: the 2.5 % bound of "
                 "independent twins per setting, solid: their expected value", fontsize=9)
    fig.tight_layout()
    save_png(fig, path)


# ---------------------------------------------------------------------------------------------
# the damping values in the measures of the literature

def hunt_crossley_restitution(alpha, speed):
    """Coefficient of restitution of one impact under the project's law F = k d (1 + 1.5 alpha d'),
    clamped at zero, at approach speed `speed` [m/s]. With exponent 1 it depends on alpha v only:
    in units of v/omega and 1/omega the penetration obeys u'' = -u max(0, 1 + 1.5 alpha v u')."""
    from scipy.integrate import solve_ivp
    a = 1.5 * alpha * speed

    def rhs(_, y):
        return [y[1], -y[0] * max(0.0, 1.0 + a * y[1])]

    def separated(_, y):
        return y[0]
    separated.terminal, separated.direction = True, -1.0
    sol = solve_ivp(rhs, (0.0, 100.0), [0.0, 1.0], events=separated, rtol=1e-10, atol=1e-12, max_step=0.01)
    return float(-sol.y_events[0][0][1])


def strand_lengths(geometry):
    """Lengths of the chain between two sprocket wraps (free spans and guide wraps together): the
    strands that vibrate longitudinally between the sprockets."""
    sprockets = {s["name"] for s in geometry["sprockets"]}
    segs = geometry["segments"]
    first = next(i for i, s in enumerate(segs) if s["kind"] == "wrap" and s["element"] in sprockets)
    strands, current = [], dict(start=segs[first]["element"], length=0.0)
    for s in segs[first + 1:] + segs[:first + 1]:
        if s["kind"] == "wrap" and s["element"] in sprockets:
            strands.append(dict(current, end=s["element"]))
            current = dict(start=s["element"], length=0.0)
        else:
            current["length"] += s["length"]
    return strands


ROLLER_SPEEDS = (1.0, 2.0, 3.0, 5.0)   # [m/s] roller seating impacts: about omega p (DOMAIN.md)
GUIDE_SPEEDS = (0.1, 0.3, 1.0, 3.0)    # [m/s] normal speeds of link plates meeting a guide


def damping_measures(factors=(1.0, 4.0, 10.0)):
    """The project's damping values (and the raised ones) as damping ratios and restitution
    coefficients, the measures in which the literature states them."""
    d = study.default_drive_json()
    ch = d["chain"]
    m, k, c, p = ch["linkMass"], ch["joint"]["stiffness"], ch["joint"]["damping"], ch["pitch"]
    strand = max(strand_lengths(plots.geometry()), key=lambda s: s["length"])
    wave = p * math.sqrt(k / m)                  # [m/s] longitudinal wave speed of the chain
    f1 = wave / (2.0 * strand["length"])         # [Hz] first longitudinal mode, strand fixed at both ends
    out = dict(linkMass=m, jointStiffness=k, jointDamping=c, pitch=p, rollerDiameter=ch["rollerDiameter"],
               strandLength=strand["length"],
               strandFrequency=f1, waveSpeed=wave, factors=list(factors), rows=[])
    for f in factors:
        cf_ = c * f
        roller = d["contact"]["rollerSprocket"]["dampingFactor"] * f
        guide = d["contact"]["plateGuide"]["dampingFactor"] * f
        out["rows"].append(dict(
            factor=f, jointDamping=cf_,
            zetaOneJoint=cf_ / (2.0 * math.sqrt(k * m)),      # one link against one joint
            zetaHighest=2.0 * cf_ / (2.0 * math.sqrt(k * m)),  # neighbours in antiphase: 4k, 4c
            zetaStrand=math.pi * f1 * cf_ / k,                # stiffness-proportional: zeta = omega c / (2 k)
            rollerAlpha=roller, rollerRestitution=[hunt_crossley_restitution(roller, v) for v in ROLLER_SPEEDS],
            guideAlpha=guide, guideRestitution=[hunt_crossley_restitution(guide, v) for v in GUIDE_SPEEDS]))
    return out


# ---------------------------------------------------------------------------------------------
# report

def by_id(results, key):
    return next((r for r in results["settings"] if r["id"] == key and r["status"] != "failed"), None)


def rate(r, name="tensioner.F"):
    return r["signals"][name]["rate_per_ms"]["median"] if r else None


def results_table(results):
    lines = ["| setting | integrator | lambda tensioner force [1/ms] | e-folding [ms] | lambda guide angle [1/ms] | "
             "e-folding [ms] | force saturated after [ms] (cycles) | angle saturated after [ms] (cycles) | cycle "
             "statistics independent from cycle |", "|---|---|---|---|---|---|---|---|---|"]
    for r in results["settings"]:
        if r["status"] == "failed":
            tried = "; ".join(f"{t['step'] * 1e6:g} us: {t['kind']}" for t in r["runIn"])
            lines.append(f"| {r['label']} | FAILED: {r.get('failure')} ({tried}) | - | - | - | - | - | - | - |")
            continue
        F, P = r["signals"]["tensioner.F"], r["signals"]["tensionGuide.phi"]
        j = r["cycles"]["firstIndependent"]
        lines.append(
            f"| {r['label']} | {r['method']['label']} | {fmt_spread(F['rate_per_ms'])} | {fmt(F['efold_ms'])} | "
            f"{fmt_spread(P['rate_per_ms'])} | {fmt(P['efold_ms'])} | {saturation_cell(F)} | {saturation_cell(P)} | "
            f"{independence_cell(r)} |")
    return lines


def independence_cell(r):
    j = r["cycles"]["firstIndependent"]
    if j is not None:
        return str(j)
    return f"not within the {r['twinCycles']} cycles run" + (" (lambda check only)" if r["id"] == "erk" else "")


def saturation_cell(sig):
    s = sig["saturation_ms"]
    if s["median"] is None:
        return "not within the run"
    missing = len(sig["pairs"]) - s["n"]
    return (f"{fmt(s['median'])} [{fmt(s['min'])}, {fmt(s['max'])}] ({fmt(sig['saturation_cycles']['median'], 2)})"
            + (f", {missing} pairs not within the run" if missing else ""))


def steps_table(results):
    lines = ["| setting | Verlet steps tried for the run-in | step check: median lambda of the tensioner force "
             f"[1/ms] over {PROBE_PAIRS} pairs (p: Welch's t-test against the step before) | twins | twin length [cycles] | CPU s per simulated s | pairs (failed) |",
             "|---|---|---|---|---|---|---|"]
    for r in results["settings"]:
        tried = ", ".join(f"{t['step'] * 1e6:g} us {'ok' if t['kind'] == 'ok' else t['kind']}" for t in r["runIn"])
        n_fail = len(r.get("pairFailures", []))
        twins = r["method"]["label"] if "method" in r else "-"
        pairs = "-" if "cycles" not in r else f"{r['cycles']['pairs'] + n_fail} ({n_fail})"
        lines.append(f"| {r['label']} | {tried or 'start states of the default setting'} | {step_check_cell(r)} | "
                     f"{twins} | {r.get('twinCycles', '-')} | {fmt(r.get('cpuPerSimulatedSecond'))} | {pairs} |")
        for f in r.get("pairFailures", []):
            lines.append(f"| | pair {f['start']} ({f['perturbation']}): {f['kind']} at {fmt(f['failureTime'], 6)} s: "
                         f"{f['failure']} | | | | | |")
    return lines


def step_check_cell(r):
    checks = r.get("stepChecks") or []
    if not checks:
        return "-"
    cell = ", ".join(f"{c['step'] * 1e6:g} us: {fmt(c['rate_per_ms'])}"
                     + (f" (p {c['pValue']:.2g})" if c.get("pValue") is not None else "") for c in checks)
    verdict = {True: "converged", False: "NOT converged down to the smallest step", None: ""}[r.get("stepConverged")]
    return f"{cell} ({verdict})"


def cycles_table(results):
    keys = CYCLE_KEYS
    lines = ["| setting | statistic | r_j for cycles 0, 1, 2, ... | bound | rank correlation A-B over the pairs | "
             "s.d. between cycles | lag-1 autocorr. (cycles) | independent from cycle |",
             "|---|---|---|---|---|---|---|---|"]
    for r in measured(results):
        for key in keys:
            c = r["cycles"]["keys"][key]
            corr = ", ".join(fmt(x, 2) for x in c["correlation"])
            lines.append(f"| {r['label']} | {key} | {', '.join(f'{x:.2f}' for x in c['ratio'])} | {c['bound']:.2f} | "
                         f"{corr} | {c['betweenCycles']:.3g} | {c['lag1']:.2f} ({c['distinctCycles']}) | "
                         f"{first_cell(c)} |")
    return lines


def first_cell(c):
    if c["firstIndependent"] is None:
        return "not within the run"
    return f"{c['firstIndependent']} ({c['laterBelowBound']} later cycles below the bound)"


def ratio_to_default(results, key):
    d, r = by_id(results, "default"), by_id(results, key)
    return rate(r) / rate(d) if r and d and rate(r) and rate(d) else None


def verdict_lines(results):
    """The verdict, argued from the measured rates; settings missing or failed are said so."""
    d = by_id(results, "default")
    if not d or rate(d) is None:
        return ["The default setting has no measured divergence rate: no verdict."]
    lam = rate(d)
    F = d["signals"]["tensioner.F"]
    out = [f"- Default damping: the tensioner force of twin runs diverges at lambda = {lam:.2g} 1/ms, a factor e "
           f"every {1 / lam:.2g} ms (pairs: {fmt_spread(F['rate_per_ms'], 2)} 1/ms); 1e-12 grows to the level of "
           f"unrelated runs in {fmt(F['saturation_ms']['median'], 2)} ms, and a difference of one rounding (1e-16) "
           f"would take about {math.log(1e4) / lam:.0f} ms more."]
    erk = by_id(results, "erk")
    if erk and rate(erk):
        out.append(f"- The rate is the model's, not the integrator's: adaptive arkode-erk (rtol 1e-8) from the same "
                   f"start states gives {fmt_spread(erk['signals']['tensioner.F']['rate_per_ms'], 2)} 1/ms; the step "
                   "checks of every setting (table above) agree too.")
    for key, name in (("both4", "4x"), ("both10", "10x")):
        r = by_id(results, key)
        if r is None:
            out.append(f"- Joint and contact damping {name}: not measured (failed or not run).")
        elif rate(r) is None:
            out.append(f"- Joint and contact damping {name}: no exponential divergence found within "
                       f"{r['twinCycles']} engine cycles.")
        else:
            rf = r["signals"]["tensioner.F"]
            out.append(f"- Joint and contact damping {name}: lambda = {rate(r):.2g} 1/ms ({rate(r) / lam:.2f} of the "
                       f"default, e-folding {1 / rate(r):.2g} ms); the twins still reach the level of unrelated runs "
                       f"after {fmt(rf['saturation_ms']['median'], 2)} ms ({fmt(rf['saturation_cycles']['median'], 2)} "
                       f"engine cycles), and their cycle statistics are independent from cycle "
                       f"{fmt(r['cycles']['firstIndependent'])} on.")
    parts = [f"{by_id(results, k)['label']}: {ratio_to_default(results, k):.2f}" for k in
             ("joint4", "joint10", "contact4", "contact10") if ratio_to_default(results, k)]
    if parts:
        out.append("- Each damping alone, lambda relative to the default: " + "; ".join(parts) + ".")
    return out + verdict_conclusion(results)


def verdict_conclusion(results):
    """The judgement: which damping sets the rate, and whether any removes the divergence."""
    joint = [ratio_to_default(results, k) for k in ("joint4", "joint10")]
    contact = [ratio_to_default(results, k) for k in ("contact4", "contact10", "both4", "both10")]
    b10 = by_id(results, "both10")
    out = [""]
    if all(joint) and all(0.7 <= x <= 1.4 for x in joint):
        out.append("Joint damping does not set the rate: ten times the default joint damping, which overdamps every "
                   "link mode, leaves lambda within the spread of the default.")
    if any(contact) and min(x for x in contact if x) < 0.5:
        r4, r10 = ratio_to_default(results, "both4"), ratio_to_default(results, "both10")
        trend = ("it falls little more from 4x to 10x" if r4 and r10 and r10 / r4 > 0.5 else
                 "it keeps falling from 4x to 10x")
        out.append("Contact damping does: it makes the roller and plate impacts less elastic, and lambda falls with "
                   f"it; {trend}.")
    if b10 and rate(b10):
        out.append("No damping tried removes the divergence: with both raised tenfold, far beyond what the "
                   "literature supports for oil-wetted steel impacts (below), twin runs still separate "
                   "exponentially and their cycle statistics decorrelate within a few engine cycles. The chaos is "
                   "a property of the physics, the unilateral contacts with their impacts (rollers seating in "
                   "tooth gaps at the polygon frequency, link plates meeting the guides), not of too little "
                   "damping; damping sets its rate. Realistic damping, the defaults or less for the impacts, keeps "
                   "the rate at about the default's: pointwise agreement of two runs is lost within about one "
                   "engine cycle, and what a run predicts is its statistics over cycles.")
    elif b10:
        out.append("With both raised tenfold no divergence is measurable: at that damping the chaos is removed.")
    return out


def write_report(results, report_path, chart_dir):
    rel = pathlib.Path(chart_dir).resolve().relative_to(pathlib.Path(report_path).resolve().parent) \
        if pathlib.Path(chart_dir).resolve().is_relative_to(pathlib.Path(report_path).resolve().parent) \
        else pathlib.Path(chart_dir).resolve()
    L = [f"# Divergence rate and the chaos floor, measured ({results['rpm']:g} rpm)", "",
         f"`{results['command']}` on {results['machine']}; {results['started']}, "
         f"{results['wall_seconds'] / 60:.1f} min wall time{' (quick smoke variant)' if results['quick'] else ''}.",
         "Method, criteria and options: the docstring of `harness/chaos.py`. Results: "
         f"[`results.json`]({rel / 'results.json'}).", ""]
    L += ["## Results", ""] + results_table(results) + [""]
    L += [f"![twin difference]({rel / 'divergence.png'})", "", f"![divergence rate]({rel / 'lambda.png'})", ""]
    L += ["Integrators, steps and failures:", ""] + steps_table(results) + [""]
    L += ["### Per-cycle statistics of the twins", "",
          "r_j = median over the pairs of |x_B - x_A| in engine cycle j after the perturbation, divided by the median "
          "|x - x'| over all pairs of distinct engine cycles of the twin A runs (unrelated cycles): about 1 for "
          "independent twins, below the bound (the 2.5 % quantile of the same ratio for as many random pairs of "
          "unrelated cycles, 4000 draws) by chance in 2.5 % of the cycles. Medians, because the per-cycle values "
          "have heavy tails. Correlation: Spearman's rank correlation of x_A and x_B over the pairs.", ""]
    L += cycles_table(results) + [""]
    L += [f"![per-cycle statistics]({rel / 'cycles.png'})", ""]
    L += ["## Verdict: physics, not too little damping", ""] + verdict_lines(results) + [""]
    L += damping_section(results["damping"])
    runs.write_lines(report_path, L)


def damping_section(dm):
    rows = dm["rows"]
    head = "| measure | " + " | ".join(f"{r['factor']:g}x" for r in rows) + " |"
    L = ["## The damping values against the literature", "",
         f"Chain joint: k = {dm['jointStiffness']:.3g} N/m, link mass {dm['linkMass'] * 1e3:g} g, longest strand "
         f"between two sprockets {dm['strandLength'] * 1e3:.0f} mm (first longitudinal mode fixed-fixed "
         f"{dm['strandFrequency']:.0f} Hz, wave speed {dm['waveSpeed']:.0f} m/s). Joint damping is "
         "stiffness-proportional, so its damping ratio grows with frequency: zeta = pi f c / k.", "",
         head, "|---|" + "---|" * len(rows),
         "| joint damping c [N s/m] | " + " | ".join(f"{r['jointDamping']:g}" for r in rows) + " |",
         "| zeta, one link on one joint | " + " | ".join(f"{100 * r['zetaOneJoint']:.1f} %" for r in rows) + " |",
         "| zeta, highest link mode (neighbours in antiphase) | " + " | ".join(
             f"{100 * r['zetaHighest']:.0f} %" for r in rows) + " |",
         f"| zeta, first longitudinal strand mode ({dm['strandFrequency']:.0f} Hz) | " + " | ".join(
             f"{100 * r['zetaStrand']:.1f} %" for r in rows) + " |",
         "| roller-sprocket alpha [s/m] | " + " | ".join(f"{r['rollerAlpha']:g}" for r in rows) + " |"]
    for i, v in enumerate(ROLLER_SPEEDS):
        L.append(f"| roller-sprocket restitution e at {v:g} m/s | " + " | ".join(
            f"{r['rollerRestitution'][i]:.2f}" for r in rows) + " |")
    L.append("| plate-guide alpha [s/m] | " + " | ".join(f"{r['guideAlpha']:g}" for r in rows) + " |")
    for i, v in enumerate(GUIDE_SPEEDS):
        L.append(f"| plate-guide restitution e at {v:g} m/s | " + " | ".join(
            f"{r['guideRestitution'][i]:.2f}" for r in rows) + " |")
    L += ["", "Restitution: one impact integrated under the project's law F = k d (1 + 1.5 alpha d') clamped at zero "
          "(`hunt_crossley_restitution`); with exponent 1 it depends on alpha v only, and e ~ 1 - alpha v only "
          "while alpha v << 1.", ""]
    return L + literature_lines(dm)


STEEL_DENSITY = 7800.0            # [kg/m^3]
OIL_VISCOSITY = (0.0085, 0.05)    # [Pa s] engine oil SAE 5W-30 hot (100 C) and warm (40 C) [E]


def roller_stokes_numbers(d_roller):
    """Impact Stokes numbers St = rho d v / (9 mu) (a sphere's, the definition of Joseph et al.)
    of a steel roller at the roller seating speeds, in hot and in warm engine oil."""
    return {mu: [STEEL_DENSITY * d_roller * v / (9.0 * mu) for v in ROLLER_SPEEDS] for mu in OIL_VISCOSITY}


def literature_lines(dm):
    """What the stored public literature gives on chain damping, and where the defaults sit."""
    st = roller_stokes_numbers(dm["rollerDiameter"])
    rows = {r["factor"]: r for r in dm["rows"]}
    lo, hi = min(min(v) for v in st.values()), max(max(v) for v in st.values())
    d, x4, x10 = rows[1.0], rows.get(4.0), rows.get(10.0)
    return [
        "### Published figures", "",
        "Found with the project's search of stored public pages, which for most papers holds only the first page "
        "(abstract and introduction): parameter tables deeper in the papers could not be read, and no number is "
        "quoted here that was not read.", "",
        "| topic | source | what it gives |", "|---|---|---|",
        "| chain dynamics | G. Hippmann, M. Arnold, M. Schittenhelm, \"Efficient simulation of bush and roller chain "
        "drives\", Multibody Dynamics 2005, ECCOMAS Thematic Conference, Madrid, 21-24 June 2005 | the dynamics of "
        "valve-train chain drives \"is dominated by the effects of high velocities and transient driving torques "
        "as well as by polygonal action and rotatory impacts\"; no damping figure on the readable page. |",
        "| chain joints | A. Becker, D. Meffert, B. Sauer, \"Friction and wear investigations on single chain joints\", "
        "Forschung im Ingenieurwesen 83 (2019) 53-63, doi:10.1007/s10010-019-00297-x | timing-chain joints run in "
        "mixed and boundary friction; admissible wear elongation 0.5 %. No damping figure. |",
        "| chain joints | S. L. Pedersen, J. M. Hansen, J. A. C. Ambrosio, \"A roller chain drive model including "
        "contact with guide-bars\", Multibody System Dynamics 12 (2004) 285-301 | links as spring-damper "
        "assemblies, roller-guide contact as a continuous force (the model used here); the values are beyond the "
        "readable first page. |",
        "| chain joints | MSC Adams Machinery, \"Create Chain - Roller\" (https://adams.thisaray.com/adams_machinery/"
        "dialogboxes/chain_geo_rol.html) | \"the stiffness and damping of the bushing connecting two links\" are "
        "user inputs; no value. |",
        "| roller impacts | FunctionBay RecurDyn Chain, \"Contact Characteristic Page\" (https://functionbay.com/"
        "documentation/onlinehelp/Documents/contactcharacteristicpage.htm) | f_n = k d^m1 + c (d'/abs(d')) "
        "abs(d')^m2 d^m3, \"k and c ... determined by an experimental method\"; no value. |",
        "| roller impacts | S. L. Pedersen, \"Model of contact between rollers and sprockets in chain-drive "
        "systems\", Archive of Applied Mechanics 74 (2005) 489-508 | roller-sprocket contact as a continuous "
        "contact force; values beyond the readable first page. |",
        "| roller impacts | M. S. Kim, G. E. Johnson, \"A general multi-body dynamic model to predict the behavior "
        "of roller chain drives at moderate and high speeds\", University of Michigan, Deep Blue (year not on the "
        "readable page; http://deepblue.lib.umich.edu/bitstream/handle/2027.42/6004/bac0133.0001.001.txt) | engagement as \"a series of elastic collisions "
        "and rebounds\"; no value on the readable page. |",
        "| oil-wetted impacts | G. G. Joseph, R. Zenit, M. L. Hunt, A. M. Rosenwinkel, \"Particle-wall collisions "
        "in a viscous fluid\", Journal of Fluid Mechanics 433 (2001) 329-346 | no rebound below an impact Stokes "
        "number of about 10; above about 500 the restitution approaches its dry value (spheres of 3-12 mm). |",
        "| oil-wetted impacts | T. Mueller, K. Huang, \"Influence of the liquid film thickness on the coefficient of "
        "restitution for wet particles\" (arXiv:1601.07032, 2016); F. Gollwitzer, I. Rehberg, C. A. Kruelle, "
        "K. Huang, \"Coefficient of restitution for wet particles\" (arXiv:1202.1750, 2012) | the wet restitution "
        "falls linearly with 1/St; the film thickness relative to the particle size matters. |",
        "| PA66 guides | - | no figure for the damping or restitution of steel plates on polyamide guides was found. |",
        "",
        "### Where the defaults sit", "",
        f"- Roller seating impacts: the default alpha = {d['rollerAlpha']:g} s/m gives e = "
        + " / ".join(f"{e:.2f}" for e in d["rollerRestitution"]) + " at " + " / ".join(f"{v:g}" for v in ROLLER_SPEEDS)
        + " m/s. A steel roller of d = 6.35 mm in engine oil of 8.5 to 50 mPa s [E] meets the tooth at an impact "
        f"Stokes number St = rho d v / (9 mu) of {lo:.0f} to {hi:.0f}: far above the no-rebound limit of about 10 "
        "and partly above the dry limit of about 500 of Joseph et al. (a sphere's figures; a roller held by chain "
        "tension is an analogy, not a measurement). The oil film alone therefore does not make seating impacts "
        "plastic: their restitution lies between the wet and the dry value, so the default is on the dissipative "
        "side of plausible, 4x contact damping (e = " + " / ".join(f"{e:.2f}" for e in x4["rollerRestitution"])
        + ") asks for more dissipation than the oil film gives by this analogy, and 10x (e = "
        + " / ".join(f"{e:.2f}" for e in x10["rollerRestitution"]) + ") for impacts close to the no-rebound "
        "limit, which the analogy places near St = 10, far below the rollers' Stokes numbers. The drive's "
        "restitution for the rigid contact methods (rollerSprocket 0.5, plateGuide 0.3) matches the compliant "
        "law's values at 3-5 m/s and 1-3 m/s.",
        f"- Joint damping: {d['jointDamping']:g} N s/m is {100 * d['zetaOneJoint']:.0f} % of critical for one link on "
        f"one joint and {100 * d['zetaStrand']:.1f} % for the first longitudinal strand mode "
        f"({dm['strandFrequency']:.0f} Hz); being stiffness-proportional, it damps lower modes less (zeta = pi f c / "
        f"k: {100 * math.pi * 500.0 * d['jointDamping'] / dm['jointStiffness']:.2f} % at 500 Hz). No published "
        "figure was found to set it against; the joints run in mixed and boundary friction (Becker et al.), whose "
        "dissipation a viscous damper represents only on average. 4x and 10x give "
        f"{100 * x4['zetaStrand']:.0f} % and {100 * x10['zetaStrand']:.0f} % on the strand mode and overdamp the "
        f"link modes ({100 * x4['zetaOneJoint']:.0f} % and {100 * x10['zetaOneJoint']:.0f} % of critical on one "
        "joint); they also cost a 2x and 5x smaller explicit step.",
        f"- Plate-guide contacts: alpha = {d['guideAlpha']:g} s/m gives e = "
        + " / ".join(f"{e:.2f}" for e in d["guideRestitution"]) + " at " + " / ".join(f"{v:g}" for v in GUIDE_SPEEDS)
        + " m/s; with no published figure for steel on PA66 found, it stays an engineering estimate [E].",
        "",
    ]


# ---------------------------------------------------------------------------------------------
# main

def write_outputs(results, out, report):
    out.mkdir(parents=True, exist_ok=True)
    (out / "results.json").write_text(json.dumps(results, indent=1))
    if measured(results):
        chart_divergence(out / "divergence.png", results)
        chart_cycles(out / "cycles.png", results)
    chart_lambda(out / "lambda.png", results)
    write_report(results, report, out)


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="the smoke variant (default setting, 3 short pairs)")
    ap.add_argument("--out", default=None, help="output directory (default results/chaos or results/chaos-quick)")
    ap.add_argument("--report", default=None, help="report file (default OUT/report.md)")
    ap.add_argument("--jobs", type=int, default=1, help=f"runs at a time, at most {MAX_JOBS}")
    ap.add_argument("--rpm", type=float, default=3000.0, help="mean engine speed [rpm]")
    ap.add_argument("--settings", default=None,
                    help="damping settings, comma separated, of: " + ", ".join(s["id"] for s in SETTINGS))
    ap.add_argument("--pairs", type=int, default=None, help="twin pairs per setting (default 12; method checks 6)")
    ap.add_argument("--cycles", type=int, default=None,
                    help="engine cycles of the step check's twins and the least of the ensemble's (default 5; "
                         "the method check 2)")
    ap.add_argument("--max-cycles", type=int, default=15,
                    help=f"longest twin of the ensemble [engine cycles]: saturation + {AFTER_SATURATION} cycles, up "
                         "to this")
    ap.add_argument("--verlet-steps", default=None,
                    help="Verlet steps to try for the run-in [s], comma separated, largest first")
    ap.add_argument("--timeout", type=float, default=3600.0, help="wall-time budget of one run [s]")
    ap.add_argument("--keep-runs", action="store_true", help="keep the run files (states, CSV) under OUT/runs")
    ap.add_argument("--report-only", metavar="RESULTS_JSON", help="only rewrite the charts and the report")
    args = ap.parse_args(argv)
    if not 1 <= args.jobs <= MAX_JOBS:
        ap.error(f"--jobs {args.jobs}: between 1 and {MAX_JOBS} (the machine's cores are shared)")
    known = {s["id"]: s for s in SETTINGS}
    ids = args.settings.split(",") if args.settings else (["default"] if args.quick else list(known))
    unknown = [i for i in ids if i not in known]
    if unknown:
        ap.error(f"unknown settings {unknown}; known: {list(known)}")
    args.selected = [known[i] for i in ids]
    args.explicit_steps = bool(args.verlet_steps)
    args.verlet_steps = tuple(float(x) for x in args.verlet_steps.split(",")) if args.verlet_steps else VERLET_STEPS
    if args.out is None:
        args.out = str(paths.RESULTS / ("chaos-quick" if args.quick else "chaos"))
    return args


def main(argv=None):
    args = parse_args(argv)
    out = pathlib.Path(args.out)
    report = pathlib.Path(args.report) if args.report else out / "report.md"
    if args.report_only:
        results = json.loads(pathlib.Path(args.report_only).read_text())
        results["damping"] = damping_measures()
        write_outputs(results, out, report)
        return 0
    shutil.rmtree(out / "runs", ignore_errors=True)
    started = datetime.datetime.now()
    w0 = time.monotonic()
    ctx = Context(args, args.selected)
    ctx.log(f"chaos study{' (quick)' if args.quick else ''}: {runs.machine()}")
    ctx.log(f"{args.rpm:g} rpm, engine cycle {ctx.cycle * 1e3:g} ms, run-in {ctx.run_in_cycles} cycles, output step "
            f"{OUTPUT_STEP * 1e6:g} us, perturbation {PERTURBATION:g} relative, runs at a time {args.jobs}")
    settings = [run_setting(ctx, s) for s in args.selected]
    command = " ".join(["python -m harness.chaos"] + (list(argv) if argv is not None else sys.argv[1:]))
    results = dict(machine=runs.machine(), command=command, started=started.isoformat(timespec="seconds"),
                   wall_seconds=time.monotonic() - w0, quick=args.quick, rpm=args.rpm, cycle=ctx.cycle,
                   runInCycles=ctx.run_in_cycles, outputStep=OUTPUT_STEP, window=WINDOW, perturbation=PERTURBATION,
                   fitLow=FIT_LOW, fitHigh=FIT_HIGH, saturation=SATURATION, settings=settings,
                   damping=damping_measures(), log=ctx.log_lines)
    write_outputs(results, out, report)
    if not args.keep_runs:
        shutil.rmtree(out / "runs", ignore_errors=True)
    print(f"\nwritten: {out / 'results.json'}, {report} ({results['wall_seconds'] / 60:.1f} min)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
