"""The Verlet step of a damping setting: the explicit-damping bound, the run-in, the step check
(halving the step until the divergence rate no longer changes) and the start states at the
accepted step."""
import json
import math
import pathlib

import numpy as np
from scipy import stats as scistats

from .analysis import SIGNALS, fmt, signal_divergence
from .twins import continued_states, method_label, run_in, run_twins, verlet

AFTER_SATURATION = 3    # [engine cycles] the ensemble's twins run this long after the step check's saturation
PROBE_PAIRS = 4         # pairs of the step check
STEP_TOLERANCE = 1.25   # halving the step may change the step check's rates by this factor ...
STEP_SIGNIFICANCE = 0.01  # ... or by more, if not significantly (Welch's t-test on the pairs' log rates)
STABILITY_MARGIN = 0.8  # on the explicit-damping step bound (the springs lower the limit too)
MIN_STEP = 2e-7         # [s] the step check halves no further


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
    typical roller seating speed), times STABILITY_MARGIN for the springs acting too."""
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
