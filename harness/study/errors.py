"""Errors of a method: its cycle statistics against the reference ensemble (in % or dB, in units of
the reference's scatter, z against the combined interval) and its trajectory over the short
horizon."""
import math

import numpy as np
from scipy import stats as scistats

from .. import cycle_stats
from .methods import OUTPUT_STEP, SHORT_HORIZON, VERDICT_KEYS


def is_order(key):
    return ".order" in key


def statistics(d, first_cycle, cycles, mesh):
    """{key: (unit, per-cycle values)} of the first `cycles` whole engine cycles from cycle index
    first_cycle on (crankshaft angle, harness/cycle_stats.py)."""
    return cycle_stats.per_cycle(d, first_cycle, mesh, cycles)


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


def z_score(mean, half, ref_mean, ref_half):
    """The difference of two means over their combined 95 % half-width: |z| <= 1 when the
    difference lies within the scatter of both (NaN without intervals)."""
    combined = math.hypot(half, ref_half)
    return (mean - ref_mean) / combined if combined > 0 else math.nan


def compare(stats, ref):
    """Per headline quantity: the method's cycle mean and half-width, and its error against the
    reference (% or dB; in units of the reference's scatter; z against the combined interval)."""
    out = {}
    for key, (unit, v) in stats.items():
        r = ref[key]
        mean, half, _ = cycle_stats.interval(v)
        out[key] = dict(mean=mean, ci95=half, cycles=int(len(v)), unit=unit,
                        error=relative_error(key, mean, r["mean"]), errorUnit="dB" if is_order(key) else "%",
                        # an interval reaching down to zero amplitude is drawn down to -20 dB of the mean
                        errorLow=relative_error(key, mean - half, r["mean"], floor=0.1 * mean),
                        errorHigh=relative_error(key, mean + half, r["mean"]),
                        scatter=(mean - r["mean"]) / r["sd"] if r["sd"] > 0 else math.nan,
                        z=z_score(mean, half, r["mean"], r["ci95"]))
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
