"""The CVT's plots: the paper's Figure 9 (the forces on one pin and its link's tensile force over
one chain revolution) and the time histories of speeds, slip and forces."""
import math

import numpy as np

from ..plots import plt
from ..plots.plots import RUN_IN_SHADE

PULLEY_SHADES = {0: ("driving pulley", "#dbe9f6"), 1: ("driven pulley", "#fde3c8")}


def _shade_pulleys(ax, x, pulley):
    """Shades where the pin is pressed by a pulley's sheaves."""
    for k, (label, colour) in PULLEY_SHADES.items():
        on = pulley == k
        ax.fill_between(x, 0, 1, where=on, color=colour, transform=ax.get_xaxis_transform(), label=label, lw=0)


def figure9(path, d, span, title):
    """The monitored pin over one chain revolution (samples span = (a, b)): the sheaves' normal
    force, the radial and circumferential friction, and the link's tensile force."""
    a, b = span
    t = d["time"][a:b]
    x = (t - t[0]) / (t[-1] - t[0])
    pulley = d["pinPulley"][a:b]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    _shade_pulleys(top, x, pulley)
    top.plot(x, d["pinNormalForce"][a:b], label="normal force (wedge, radial)", color="C0")
    top.plot(x, d["pinRadialFriction"][a:b], label="radial friction", color="C2")
    top.plot(x, d["pinCircumferentialFriction"][a:b], label="circumferential friction", color="C3")
    top.set_ylabel("force on the pin [N]")
    top.legend(loc="upper right", fontsize=8, ncol=2)
    top.set_title("Forces on a rocker pin and in its link over one chain revolution\n" + title, fontsize=10)
    _shade_pulleys(bottom, x, pulley)
    bottom.plot(x, d["linkTension"][a:b] / 1e3, color="k", label="tensile force of the link")
    bottom.set_ylabel("link tensile force [kN]")
    bottom.set_xlabel("fraction of a chain revolution")
    bottom.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


ENVELOPE_WINDOWS = 16  # envelope windows per chain revolution in the time histories


def envelope(x, window):
    """(minimum, mean, maximum) of x over consecutive windows of `window` samples (a last partial
    window dropped): arrays over the windows."""
    count = len(x) // window
    w = np.asarray(x[:count * window], float).reshape(count, window)
    return w.min(axis=1), w.mean(axis=1), w.max(axis=1)


def _envelope_plot(ax, t, x, window, label=None, colour=None):
    """x as its envelope over windows: the band from minimum to maximum and the mean as a line."""
    low, mean, high = envelope(x, window)
    centre = envelope(t, window)[1]
    line, = ax.plot(centre, mean, lw=1.0, color=colour, label=None if label is None else f"{label}: mean")
    ax.fill_between(centre, low, high, color=line.get_color(), alpha=0.25, lw=0,
                    label=None if label is None else f"{label}: minimum to maximum")


def time_histories(path, d, spans, title):
    """Speeds [rpm], slip [%], strand forces and clamping forces over the whole run as envelopes
    (minimum to maximum and mean over windows of 1/ENVELOPE_WINDOWS chain revolution: the pins'
    passage makes the raw signals solid bands); the run-in, before the counted revolutions
    (spans), shaded."""
    t = d["time"] * 1e3
    window = max(1, (spans[0][1] - spans[0][0]) // ENVELOPE_WINDOWS)
    rpm_per_rad_s = 60.0 / (2.0 * math.pi)
    panels = (("speed [rpm]", (("driving pulley", rpm_per_rad_s * d["drivingSpeed"]),
                               ("driven pulley", rpm_per_rad_s * d["drivenSpeed"]))),
              ("slip [%]", ((None, 100.0 * d["slip"]),)),
              ("strand force [N]", (("tight strand", d["tightStrandForce"]), ("slack strand", d["slackStrandForce"]))),
              ("clamping force [kN]", (("driving pulley", d["clampingForceDriving"] / 1e3),
                                       ("driven pulley", d["clampingForceDriven"] / 1e3))))
    fig, axes = plt.subplots(len(panels), 1, figsize=(9, 10.5), sharex=True)
    for ax, (unit, curves) in zip(axes, panels):
        for k, (label, x) in enumerate(curves):
            _envelope_plot(ax, t, x, window, label, colour=f"C{k if len(curves) > 1 else 3}")
        ax.set_ylabel(unit)
        ax.axvspan(t[0], t[spans[0][0]], color=RUN_IN_SHADE, lw=0, zorder=0)
        ax.grid(True, lw=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="best", fontsize=7, ncol=2)
    axes[3].set_xlabel("time [ms]")
    axes[0].set_title(f"CVT time histories: mean and minimum to maximum over 1/{ENVELOPE_WINDOWS} chain revolution "
                      f"(run-in shaded)\n{title}", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
