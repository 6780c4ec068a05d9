"""The measures of the divergence-rate study on the twin pairs: (a) the divergence rate, (b) the
saturation time, (c) the independence of the twins' cycle statistics (see chaos.py)."""
import math

import numpy as np
from scipy import stats as scistats

from ... import cycle_stats
from .twins import OUTPUT_STEP

WINDOW = 1e-3           # [s] RMS window of the twin difference
FIT_LOW = 1e-6          # fit window of the exponential phase, as fractions of the independent level
FIT_HIGH = 1e-2
FLOOR_MARGIN = 100.0    # and the fit starts at least this factor above the first window
SATURATION = 0.5        # saturated: windowed difference >= this fraction of the independent level

# (output, label, unit at the edge, scale from SI)
SIGNALS = (("tensioner.F", "tensioner force", "N", 1.0),
           ("tensionGuide.phi", "tension-guide angle", "deg", 180.0 / math.pi))
CYCLE_KEYS = ("tensioner.F.mean", "tensioner.F.peakToPeak", "tensioner.F.order2", "chain.Ftight.mean",
              "tensionGuide.phi.peakToPeak_deg")


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
        out["keys"][key] = statistic_independence(pairs, XA, XB, cycles)
    firsts = [k["firstIndependent"] for k in out["keys"].values()]
    out["firstIndependent"] = None if None in firsts else max(firsts)
    return out


def statistic_independence(pairs, XA, XB, cycles):
    """Measure (c) of one statistic, its per-cycle values XA and XB of the twins (pairs x cycles)."""
    between = distinct_cycles(pairs, XA)
    ratio = np.median(np.abs(XB - XA), axis=0) / unrelated_difference(between)
    bound = independence_bound(between, len(pairs))
    corr = [float(scistats.spearmanr(XA[:, j], XB[:, j])[0]) if len(pairs) >= 3 else None for j in range(cycles)]
    reached = [j for j in range(cycles) if ratio[j] >= bound]
    first = reached[0] if reached else None
    return dict(ratio=[float(r) for r in ratio], bound=bound, correlation=corr,
                betweenCycles=float(np.std(between, ddof=1)), distinctCycles=len(between),
                lag1=cycle_stats.lag1_autocorrelation(between), firstIndependent=first,
                laterBelowBound=0 if first is None else int(np.sum(ratio[first:] < bound)),
                A=[rounded(r, 5) for r in XA], B=[rounded(r, 5) for r in XB],
                distinct=rounded(between, 5))


def analyse(ctx, pairs):
    ok = [p for p in pairs if p["kind"] == "ok"]
    res = dict(signals={name: signal_divergence(ok, name, ctx.cycle) for name, *_ in SIGNALS},
               cycles=cycle_independence(ok, ctx.mesh))
    return res


def measured(results):
    return [r for r in results["settings"] if r["status"] != "failed"]


def fmt(x, digits=3):
    return "-" if x is None else f"{x:.{digits}g}"


def fmt_spread(s, digits=3):
    if s.get("median") is None:
        return "-"
    return f"{s['median']:.{digits}g} [{s['min']:.{digits}g}, {s['max']:.{digits}g}]"
