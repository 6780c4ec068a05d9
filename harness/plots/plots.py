"""Plots engineers read: time histories, order spectra, one cycle of a link, cycle statistics."""
import math

import numpy as np

from ..drive.description import geometry
from . import plt


def order_spectrum(t, x, rpm):
    """Single-sided amplitude spectrum over engine order (per crankshaft revolution), Hann window
    with amplitude correction, over the given samples."""
    x = np.asarray(x) - np.mean(x)
    n = len(x)
    dt = t[1] - t[0]
    w = np.hanning(n)
    X = np.fft.rfft(x * w) * 2.0 / np.sum(w)
    f = np.fft.rfftfreq(n, dt)
    return f / (rpm / 60.0), np.abs(X)


def time_histories(path, d, rpm, title, t_end=None, t_counted=None):
    """The outputs over time, up to t_end (default: all); t_counted marks the end of the run-in."""
    if t_end is not None:
        d = {k: v[d["time"] <= t_end] for k, v in d.items()}
    t = d["time"] * 1e3
    fig, ax = plt.subplots(5, 1, figsize=(10, 11), sharex=True)
    if t_counted is not None:
        for a in ax:
            a.axvline(t_counted * 1e3, color="0.3", ls="--", lw=0.8)
        ax[0].annotate(" run-in | counted cycles", (t_counted * 1e3, 1.0), xycoords=("data", "axes fraction"),
                       ha="center", va="bottom", fontsize=7)
    ax[0].plot(t, d["tensioner.F"], lw=0.7)
    ax[0].set_ylabel("tensioner force [N]")
    ax[1].plot(t, d["chain.Ftight"], lw=0.5, label="tight span")
    ax[1].plot(t, d["chain.Fslack"], lw=0.5, label="slack span")
    ax[1].set_ylabel("span force [N]")
    ax[1].legend(fontsize=7, loc="upper right")
    ax[2].plot(t, np.degrees(d["tensionGuide.phi"]), lw=0.7)
    ax[2].set_ylabel("tension guide [deg]")
    for name in ("camshaftIntake", "camshaftExhaust"):
        if name + ".phi" in d:
            dev = np.degrees(d[name + ".phi"] - 0.5 * d["crankshaft.phi"]) * 2.0
            ax[3].plot(t, dev, lw=0.6, label=name)
    ax[3].set_ylabel("cam timing dev. [deg CA]")
    ax[3].legend(fontsize=7, loc="upper right")
    ax[4].plot(t, d["crankshaft.tau"], lw=0.6)
    ax[4].set_ylabel("chain torque on crank [N m]")
    ax[4].set_xlabel("time [ms]")
    for a in ax:
        a.grid(True, lw=0.3)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def periodic_window(time, t0):
    """Samples from t0 to the end without the last one: a run over whole engine cycles sampled at
    a fixed step then spans whole cycles, so that engine orders fall on spectral bins."""
    sel = time >= t0 - 1e-12
    idx = np.flatnonzero(sel)
    if len(idx) > 1:
        sel[idx[-1]] = False
    return sel


def spectra(path, d, rpm, t0, title):
    """Tension-guide motion and tensioner force over engine order (the paper's Figure 13)."""
    sel = periodic_window(d["time"], t0)
    fig, ax = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    for a, key, scale, label in ((ax[0], "tensionGuide.phi", 180.0 / math.pi, "tension guide angle [deg]"),
                                 (ax[1], "tensioner.F", 1.0, "tensioner force [N]")):
        o, amp = order_spectrum(d["time"][sel], d[key][sel] * scale, rpm)
        keep = o <= 40
        a.bar(o[keep], amp[keep], width=0.25, color="tab:blue")
        a.set_ylabel(label)
        a.grid(True, lw=0.3)
        for k in (2, 4, 6, 8):
            a.axvline(k, color="0.7", lw=0.5, ls="--")
    ax[1].set_xlabel("engine order (per crankshaft revolution)")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def path_position(g, x, y):
    """Arc length along the nominal chain path of the points (x, y) (nearest path sample)."""
    p = np.array(g["path"])
    L = g["pathLength"]
    s = np.linspace(0.0, L, len(p))
    d2 = (p[None, :, 0] - np.asarray(x)[:, None]) ** 2 + (p[None, :, 1] - np.asarray(y)[:, None]) ** 2
    return s[np.argmin(d2, axis=1)]


def link_cycle(path, d, rpm, title, t0=0.0, drive=None):
    """One cycle of the monitored link around the drive: its contact forces with sprockets and
    guides and its tensile force over its position along the chain path (the paper's Figure 12)."""
    g = geometry(drive)
    sel = d["time"] >= t0
    t = d["time"][sel]
    pos = path_position(g, d["link.x"][sel], d["link.y"][sel])
    # one revolution: from the first sample to where the position has advanced by the path length
    unwrapped = np.concatenate([[0.0], np.cumsum(np.mod(np.diff(pos) + 0.5 * g["pathLength"], g["pathLength"])
                                                  - 0.5 * g["pathLength"])]) + pos[0]
    one = unwrapped <= unwrapped[0] + g["pathLength"]
    s = unwrapped[one]
    fig, ax = plt.subplots(2, 1, figsize=(11, 6.5), sharex=True)
    for a in ax:
        for seg in g["segments"]:
            lo = seg["start"]
            # shade the segments in the order the link meets them, from its start position
            while lo < s[0] - 1e-9:
                lo += g["pathLength"]
            for start in (lo - g["pathLength"], lo):
                if seg["kind"] == "wrap" and start + seg["length"] > s[0] and start < s[-1]:
                    a.axvspan(start, start + seg["length"], color="0.92" if "Guide" not in seg["element"] else "#dde8f5",
                              lw=0)
    for seg in g["segments"]:
        if seg["kind"] != "wrap":
            continue
        lo = seg["start"]
        while lo < s[0] - 1e-9:
            lo += g["pathLength"]
        for start in (lo - g["pathLength"], lo):
            mid = start + 0.5 * seg["length"]
            if s[0] <= mid <= s[-1]:
                ax[0].annotate(seg["element"], (mid, 1.0), xycoords=("data", "axes fraction"), ha="center",
                               va="bottom", fontsize=7)
    ax[0].plot(s, d["link.FnSprocket"][sel][one], lw=0.6, label="with sprockets")
    ax[0].plot(s, d["link.FnGuide"][sel][one], lw=0.6, label="with guides")
    ax[0].set_ylabel("contact normal force [N]")
    ax[0].legend(fontsize=7, loc="upper right")
    ax[1].plot(s, d["link.F"][sel][one], lw=0.6)
    ax[1].set_ylabel("link tensile force [N]")
    ax[1].set_xlabel(f"position along the chain path [m] (one revolution: {t[one][-1] - t[0]:.4f} s)")
    for a in ax:
        a.grid(True, lw=0.3)
    fig.suptitle(title, fontsize=10, y=0.995)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def dominant_orders(t, x, rpm, count=3):
    """The largest spectral peaks (local maxima, so that the leakage of one order into its
    neighbouring bins is not listed as further orders) between order 0.75 and 40."""
    o, amp = order_spectrum(t, x, rpm)
    padded = np.concatenate(([-np.inf], amp, [-np.inf]))
    peak = (amp >= padded[:-2]) & (amp > padded[2:])
    keep = np.flatnonzero(peak & (o > 0.75) & (o <= 40))
    idx = keep[np.argsort(amp[keep])[::-1][:count]]
    return [(float(o[i]), float(amp[i])) for i in idx]


def cycle_statistics(path, per_cycle, summary, title, keys):
    """Per-cycle values of headline quantities over the counted cycles, with their mean and 95 %
    confidence interval: a run is stationary when the values scatter about a level line."""
    fig, ax = plt.subplots(len(keys), 1, figsize=(10, 2.0 * len(keys) + 1.0), sharex=True)
    for a, key in zip(np.atleast_1d(ax), keys):
        unit, v = per_cycle[key]
        s = summary[key]
        n = np.arange(1, len(v) + 1)
        a.plot(n, v, ".", ms=3, color="tab:blue")
        a.axhline(s["mean"], color="k", lw=0.8)
        a.axhspan(s["mean"] - s["ci95"], s["mean"] + s["ci95"], color="tab:orange", alpha=0.35, lw=0,
                  label="mean +- 95 % confidence half-width")
        a.set_ylabel(f"{key}\n[{unit}]", fontsize=7)
        a.grid(True, lw=0.3)
    np.atleast_1d(ax)[0].legend(fontsize=7, loc="upper right")
    np.atleast_1d(ax)[-1].set_xlabel("counted engine cycle")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
