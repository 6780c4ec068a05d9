"""The charts of the divergence-rate study: the twin difference over time, the divergence rate per
setting, the per-cycle twin statistics."""
import numpy as np
from matplotlib import ticker

from ...plots import plt
from .analysis import CYCLE_KEYS, SATURATION, SIGNALS, fmt, measured, window_centres

DPI = 110


def save_png(fig, path):
    """Saves at DPI as a 256-colour PNG (charts have few colours; a third of the size)."""
    import io
    from PIL import Image
    buf = io.BytesIO()
    fig.savefig(buf, dpi=DPI)
    plt.close(fig)
    Image.open(buf).convert("RGB").quantize(colors=256).save(path, optimize=True)


def chart_divergence(path, results):
    """Windowed twin difference over time per setting (RMS over the pairs, the band of the pairs),
    the fitted slopes of the pairs, the independent level and its saturation fraction."""
    rows = measured(results)
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
        ax.xaxis.set_major_locator(ticker.MaxNLocator(integer=True))
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
