"""Cycle statistics: what engine engineers compare. The link-level dynamics of the drive is
chaotic (twin runs that differ by one rounding separate by about a factor e per 2 ms), so a run's
value at an instant is not reproducible by any other run, but its statistics over engine cycles
are. Every headline quantity is therefore evaluated once per engine cycle (720 deg crank angle,
the period of the valve-train loads) and reported as the mean over the counted cycles with its 95 %
confidence half-width.

Cycles: the engine cycles of the record start where the crankshaft angle passes a multiple of
720 deg (the tables' origin, firing TDC of cylinder 1); the first cycles, the run-in (the start
transient and the creep of the tension guide from the static to the dynamic mean, see
harness/job.py), are discarded. Only whole cycles are counted.

Per cycle: means and peak-to-peak values over the cycle's samples; engine-order amplitudes from
the cycle resampled at RESAMPLE points uniformly in crankshaft angle (order tracking: a cycle is
exactly one period, so order k per crankshaft revolution is DFT bin 2 k, without leakage).

The hydraulic tensioner's chamber pressure (output tensioner.chamberPressure, gauge) is a
headline quantity in bar, its mean, peak-to-peak and minimum (the minimum: how near the chamber
comes to drawing air, its pressure floor), when the record holds a hydraulic chamber: the output
is there and not zero throughout. The FMU reports exactly 0 for the spring-damper law, and a
hydraulic chamber is never at exactly 0 Pa gauge over a whole run (it rests near the supply
pressure minus the check valve's cracking pressure and moves with every load).

Confidence interval: mean +- t_(0.975, n_eff - 1) s / sqrt(n_eff) over the n per-cycle values,
s their sample standard deviation and n_eff = n (1 - r1) / (1 + r1) when the lag-1
autocorrelation r1 of successive cycles is positive (the effective number of independent cycles
of an AR(1) sequence), n otherwise, and at least 2 (one degree of freedom) for two or more cycles:
values that vary slowly from cycle to cycle, as the span model's deterministic modulation over
tens of engine cycles, have r1 near 1, where the AR(1) estimate of n_eff falls towards 1 and its t
quantile grows without bound; two effective cycles give t = 12.7 and an interval of about nine
cycle-to-cycle standard deviations, a wide but finite statement.
"""
import math

import numpy as np

ENGINE_CYCLE = 4.0 * math.pi  # [rad] crankshaft angle of one engine cycle
ORDERS = (2, 4, 6, 8)         # the engine orders of a four-cylinder engine that matter
CHAMBER = "tensioner.chamberPressure"  # [Pa] gauge, the hydraulic tensioner's chamber
BAR = 1e5                     # [Pa]: the chamber pressure's statistics are in bar
RESAMPLE = 1440               # points per cycle for the order analysis (0.5 deg)


def cycle_spans(crank_phi, run_in_cycles):
    """(first sample, last sample + 1, start angle) of the whole engine cycles after the first
    run_in_cycles ones (cycle j spans crankshaft angles [j, j + 1) 720 deg); a cycle's samples run
    from its start up to and including the one at its end."""
    phi = np.asarray(crank_phi)
    spans = []
    j = run_in_cycles
    while (j + 1) * ENGINE_CYCLE <= phi[-1] + 1e-9:
        i0 = int(np.searchsorted(phi, j * ENGINE_CYCLE - 1e-9))
        i1 = int(np.searchsorted(phi, (j + 1) * ENGINE_CYCLE - 1e-9))
        spans.append((i0, min(i1 + 1, len(phi)), j * ENGINE_CYCLE))
        j += 1
    return spans


def order_amplitudes(crank_phi, x, phi0, orders):
    """Amplitudes of the engine orders (per crankshaft revolution) of x over the engine cycle that
    starts at crankshaft angle phi0, from x resampled uniformly in crankshaft angle."""
    grid = phi0 + ENGINE_CYCLE * np.arange(RESAMPLE) / RESAMPLE
    X = np.fft.rfft(np.interp(grid, crank_phi, x)) * 2.0 / RESAMPLE
    return [float(abs(X[int(round(2 * k))])) for k in orders]


def camshaft_timing_deg(d, cam):
    """Timing deviation of a camshaft [deg crank angle]: twice its angle minus the crankshaft's."""
    return np.degrees(2.0 * d[cam + ".phi"] - d["crankshaft.phi"])


def has_chamber(d):
    """Whether the record holds a hydraulic tensioner's chamber pressure: the output is there and
    not zero throughout (the spring-damper law's value; see the module docstring)."""
    return CHAMBER in d and bool(np.any(np.asarray(d[CHAMBER]) != 0.0))


def level_quantities(d):
    """(key, unit, function of one cycle's sample slice -> value) of the headline levels. The keys
    name the output and the statistic; non-SI units carry their suffix."""
    q = [("tensioner.F.mean", "N", lambda s: np.mean(d["tensioner.F"][s])),
         ("tensioner.F.peakToPeak", "N", lambda s: np.ptp(d["tensioner.F"][s])),
         ("chain.Ftight.mean", "N", lambda s: np.mean(d["chain.Ftight"][s])),
         ("chain.Fslack.mean", "N", lambda s: np.mean(d["chain.Fslack"][s])),
         ("tensionGuide.phi.peakToPeak_deg", "deg", lambda s: np.degrees(np.ptp(d["tensionGuide.phi"][s])))]
    for cam in ("camshaftIntake", "camshaftExhaust"):
        if cam + ".phi" in d:
            timing = camshaft_timing_deg(d, cam)
            q.append((f"{cam}.timing.peakToPeak_degCA", "deg", lambda s, x=timing: np.ptp(x[s])))
    if has_chamber(d):
        p = np.asarray(d[CHAMBER]) / BAR
        q += [(CHAMBER + ".mean_bar", "bar", lambda s: np.mean(p[s])),
              (CHAMBER + ".peakToPeak_bar", "bar", lambda s: np.ptp(p[s])),
              (CHAMBER + ".min_bar", "bar", lambda s: np.min(p[s]))]
    return q


# signals whose engine-order amplitudes are headline quantities: (output, unit, scale, key suffix)
ORDER_SIGNALS = (("tensioner.F", "N", 1.0, ""), ("tensionGuide.phi", "deg", 180.0 / math.pi, "_deg"))


def counted_spans(crank_phi, run_in_cycles, cycles=None):
    """cycle_spans() of the counted cycles: the first `cycles` whole cycles after the run-in (all
    when None)."""
    return cycle_spans(crank_phi, run_in_cycles)[:cycles]


def per_cycle(d, run_in_cycles, meshing_order, cycles=None):
    """Per-cycle values of every headline quantity: {key: (unit, array over the counted cycles)},
    the first `cycles` whole cycles after the run-in (all when None); the orders are 2, 4, 6, 8 and
    the crankshaft meshing order."""
    spans = counted_spans(d["crankshaft.phi"], run_in_cycles, cycles)
    cycles = [slice(i0, i1) for i0, i1, _ in spans]
    out = {key: (unit, np.array([float(f(s)) for s in cycles])) for key, unit, f in level_quantities(d)}
    orders = list(ORDERS) + [meshing_order]
    for name, unit, scale, suffix in ORDER_SIGNALS:
        amps = order_amplitudes_per_cycle(d, spans, name, orders, scale)
        for i, k in enumerate(orders):
            out[f"{name}.order{k:g}{suffix}"] = (unit, amps[:, i])
    return out


def order_amplitudes_per_cycle(d, spans, name, orders, scale=1.0):
    """scale times the amplitudes of the engine orders of output `name` in each cycle of spans
    (cycle_spans): an array (cycles, orders)."""
    phi = d["crankshaft.phi"]
    amps = [order_amplitudes(phi[i0:i1], d[name][i0:i1], phi0, orders) for i0, i1, phi0 in spans]
    return scale * np.array(amps).reshape(len(spans), len(orders))


def half_orders(highest):
    """The engine orders one engine cycle resolves (DFT bins of 720 deg: half orders), from 0.5 up
    to and including `highest`."""
    return [0.5 * i for i in range(1, int(math.floor(2.0 * highest + 1e-9)) + 1)]


def order_spectrum(d, spans, name, orders, scale=1.0):
    """(means, 95 % confidence half-widths) over the cycles of spans of the amplitudes of the
    engine orders of output `name` (times scale): the summary's own statistic of its order
    amplitudes (per_cycle, summarize), at any orders; arrays over orders."""
    amps = order_amplitudes_per_cycle(d, spans, name, orders, scale)
    stats = [interval(amps[:, i])[:2] for i in range(len(orders))]
    return np.array([mean for mean, _ in stats]), np.array([half for _, half in stats])


def headline_keys(meshing_order, hydraulic=False):
    """The keys of every headline quantity, in the order of per_cycle(), of a drive whose tensioner
    is hydraulic or not: the keys of a synthetic record of one engine cycle (so that they are
    per_cycle's own, not a copy of them)."""
    phi = np.linspace(0.0, ENGINE_CYCLE, 9)
    record = {name: np.zeros_like(phi) for name in ("tensioner.F", "chain.Ftight", "chain.Fslack", "tensionGuide.phi",
                                                   "camshaftIntake.phi", "camshaftExhaust.phi", CHAMBER)}
    record[CHAMBER] += 1.0 if hydraulic else 0.0
    record["crankshaft.phi"] = phi
    return list(per_cycle(record, 0, meshing_order))


def order_keys(keys):
    """{output: its order-amplitude keys} (ORDER_SIGNALS) among keys."""
    return {name: [k for k in keys if k.startswith(name + ".order")] for name, _, _, _ in ORDER_SIGNALS}


def lag1_autocorrelation(x):
    x = np.asarray(x, float) - np.mean(x)
    den = float(np.dot(x, x))
    return float(np.dot(x[:-1], x[1:]) / den) if len(x) > 2 and den > 0 else 0.0


def interval(values, confidence=0.95):
    """(mean, confidence half-width, effective number of independent cycles) of per-cycle values;
    the half-width is NaN for fewer than two cycles."""
    x = np.asarray(values, float)
    n = len(x)
    if n == 0:
        return math.nan, math.nan, 0.0
    mean = float(np.mean(x))
    if n < 2:
        return mean, math.nan, float(n)
    r1 = lag1_autocorrelation(x)
    n_eff = n * (1.0 - r1) / (1.0 + r1) if r1 > 0 else float(n)
    n_eff = max(n_eff, 2.0)  # see the module docstring: no fewer than two effective cycles
    return mean, student_half_width(x, n_eff, confidence), n_eff


def student_half_width(x, n_eff, confidence=0.95):
    """Student's t half-width of the mean of values x (two or more) worth n_eff independent ones:
    t_(confidence, n_eff - 1) s / sqrt(n_eff), s their sample standard deviation."""
    from scipy import stats as scistats  # (here: scipy.stats takes half a second to import)
    t = float(scistats.t.ppf(0.5 + 0.5 * confidence, n_eff - 1.0))
    return t * float(np.std(x, ddof=1)) / math.sqrt(n_eff)


def summarize(per_cycle_values):
    """{key: {mean, ci95, cycles, unit}} of every headline quantity from its per-cycle values (the
    content of results/summary.json)."""
    out = {}
    for key, (unit, values) in per_cycle_values.items():
        mean, half, _ = interval(values)
        out[key] = {"mean": mean, "ci95": half, "cycles": int(len(values)), "unit": unit}
    return out


def summary(d, run_in_cycles, meshing_order):
    """summarize() of the record d after run_in_cycles engine cycles."""
    return summarize(per_cycle(d, run_in_cycles, meshing_order))


def in_percent(s):
    """A summary entry of a fraction (mean, ci95) in % for printing."""
    return dict(s, mean=100.0 * s["mean"], ci95=100.0 * s["ci95"], unit="%")


def format_line(key, s, periods="cycles"):
    rel = 100.0 * s["ci95"] / abs(s["mean"]) if s["mean"] else math.nan
    return f"  {key:<40} {s['mean']:12.4g} +- {s['ci95']:<10.3g} {s['unit']:<4} ({rel:5.2f} %, {s['cycles']} {periods})"
