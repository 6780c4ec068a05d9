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
RPM_PER_RAD_S = 30.0 / math.pi


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


def timing_deg(d, elements, name):
    """Timing deviation of free sprocket `name` [deg crank angle]: its angle times its ratio to the
    crankshaft (drive.description.Elements.ratio) minus the crankshaft's angle."""
    return np.degrees(elements.ratio(name) * d[name + ".phi"] - d[elements.crank + ".phi"])


def is_camshaft(elements, name):
    """A camshaft of a four-stroke engine: a free sprocket turning at half the crankshaft speed."""
    return abs(elements.ratio(name) - 2.0) < 1e-9


def has_chamber(d):
    """Whether the record holds a hydraulic tensioner's chamber pressure: the output is there and
    not zero throughout (the spring-damper law's value; see the module docstring)."""
    return CHAMBER in d and bool(np.any(np.asarray(d[CHAMBER]) != 0.0))


def level_quantities(d, elements):
    """(key, unit, function of one cycle's sample slice -> value) of the headline levels of a drive
    (drive.description.Elements) whose outputs the record d holds. The keys name the output and the
    statistic; non-SI units carry their suffix."""
    q = []
    if "tensioner.F" in d:
        q += [("tensioner.F.mean", "N", lambda s: np.mean(d["tensioner.F"][s])),
              ("tensioner.F.peakToPeak", "N", lambda s: np.ptp(d["tensioner.F"][s]))]
    for probe in ("chain.Ftight", "chain.Fslack"):
        if probe in d:
            q.append((probe + ".mean", "N", lambda s, x=d[probe]: np.mean(x[s])))
    if elements.tension_guide:
        phi = d[elements.tension_guide + ".phi"]
        q.append((elements.tension_guide + ".phi.peakToPeak_deg", "deg", lambda s: np.degrees(np.ptp(phi[s]))))
    for sprocket in elements.free:
        if is_camshaft(elements, sprocket.name):
            timing = timing_deg(d, elements, sprocket.name)
            q.append((f"{sprocket.name}.timing.peakToPeak_degCA", "deg", lambda s, x=timing: np.ptp(x[s])))
        else:  # a pump, a balancer, an idler: its speed fluctuation
            w = np.asarray(d[sprocket.name + ".w"]) * RPM_PER_RAD_S
            q.append((f"{sprocket.name}.w.peakToPeak_rpm", "rpm", lambda s, x=w: np.ptp(x[s])))
    if has_chamber(d):
        p = np.asarray(d[CHAMBER]) / BAR
        q += [(CHAMBER + ".mean_bar", "bar", lambda s: np.mean(p[s])),
              (CHAMBER + ".peakToPeak_bar", "bar", lambda s: np.ptp(p[s])),
              (CHAMBER + ".min_bar", "bar", lambda s: np.min(p[s]))]
    return q


def order_signals(elements):
    """The signals whose engine-order amplitudes are headline quantities: (output, unit, scale, key
    suffix): the tensioner force and the tension guide's angle."""
    if not elements.tension_guide:
        return ()
    return (("tensioner.F", "N", 1.0, ""), (elements.tension_guide + ".phi", "deg", 180.0 / math.pi, "_deg"))


def counted_spans(crank_phi, run_in_cycles, cycles=None):
    """cycle_spans() of the counted cycles: the first `cycles` whole cycles after the run-in (all
    when None)."""
    return cycle_spans(crank_phi, run_in_cycles)[:cycles]


def per_cycle(d, run_in_cycles, elements, cycles=None):
    """Per-cycle values of every headline quantity of the drive (drive.description.Elements):
    {key: (unit, array over the counted cycles)}, the first `cycles` whole cycles after the run-in
    (all when None); the orders are 2, 4, 6, 8 and the crankshaft meshing order."""
    crank = d[elements.crank + ".phi"]
    spans = counted_spans(crank, run_in_cycles, cycles)
    cycles = [slice(i0, i1) for i0, i1, _ in spans]
    out = {key: (unit, np.array([float(f(s)) for s in cycles])) for key, unit, f in level_quantities(d, elements)}
    orders = list(ORDERS) + [elements.meshing_order]
    for name, unit, scale, suffix in order_signals(elements):
        amps = order_amplitudes_per_cycle(d, spans, name, orders, scale, elements.crank)
        for i, k in enumerate(orders):
            out[f"{name}.order{k:g}{suffix}"] = (unit, amps[:, i])
    return out


def order_amplitudes_per_cycle(d, spans, name, orders, scale=1.0, crank="crankshaft"):
    """scale times the amplitudes of the engine orders of output `name` in each cycle of spans
    (cycle_spans) over the angle of the prescribed sprocket `crank`: an array (cycles, orders)."""
    phi = d[crank + ".phi"]
    amps = [order_amplitudes(phi[i0:i1], d[name][i0:i1], phi0, orders) for i0, i1, phi0 in spans]
    return scale * np.array(amps).reshape(len(spans), len(orders))


def half_orders(highest):
    """The engine orders one engine cycle resolves (DFT bins of 720 deg: half orders), from 0.5 up
    to and including `highest`."""
    return [0.5 * i for i in range(1, int(math.floor(2.0 * highest + 1e-9)) + 1)]


def order_spectrum(d, spans, name, orders, scale=1.0, crank="crankshaft"):
    """(means, 95 % confidence half-widths) over the cycles of spans of the amplitudes of the
    engine orders of output `name` (times scale): the summary's own statistic of its order
    amplitudes (per_cycle, summarize), at any orders; arrays over orders."""
    amps = order_amplitudes_per_cycle(d, spans, name, orders, scale, crank)
    stats = [interval(amps[:, i])[:2] for i in range(len(orders))]
    return np.array([mean for mean, _ in stats]), np.array([half for _, half in stats])


def headline_keys(elements):
    """The keys of every headline quantity of a drive (drive.description.Elements), in the order of
    per_cycle(): the keys of a synthetic record of one engine cycle with the drive's outputs (so that
    they are per_cycle's own, not a copy of them)."""
    phi = np.linspace(0.0, ENGINE_CYCLE, 9)
    names = ["tensioner.F"] if elements.tension_guide else []
    names += [p for p, measured in (("chain.Ftight", elements.tight_span), ("chain.Fslack", elements.slack_span))
              if measured]
    names += [elements.tension_guide + ".phi"] if elements.tension_guide else []
    names += [f"{s.name}.{q}" for s in elements.free for q in ("phi", "w")] + [CHAMBER]
    record = {name: np.zeros_like(phi) for name in names}
    record[CHAMBER] += 1.0 if elements.hydraulic else 0.0
    record[elements.crank + ".phi"] = phi
    return list(per_cycle(record, 0, elements))


def order_keys(keys):
    """{output: its order-amplitude keys} among keys (a key <output>.order<k>[suffix])."""
    grouped = {}
    for k in keys:
        if ".order" in k:
            grouped.setdefault(k.rsplit(".order", 1)[0], []).append(k)
    return grouped


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


def summary(d, run_in_cycles, elements):
    """summarize() of the record d of a drive (drive.description.Elements) after run_in_cycles engine
    cycles."""
    return summarize(per_cycle(d, run_in_cycles, elements))


def in_percent(s):
    """A summary entry of a fraction (mean, ci95) in % for printing."""
    return dict(s, mean=100.0 * s["mean"], ci95=100.0 * s["ci95"], unit="%")


def format_line(key, s, periods="cycles"):
    rel = 100.0 * s["ci95"] / abs(s["mean"]) if s["mean"] else math.nan
    return f"  {key:<40} {s['mean']:12.4g} +- {s['ci95']:<10.3g} {s['unit']:<4} ({rel:5.2f} %, {s['cycles']} {periods})"
