"""The CVT's plots: the paper's Figure 9 (the forces on one pin and its link's tensile force over
one chain revolution) and the time histories of speeds, slip and forces."""
from ..plots import plt

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


def time_histories(path, d, counted_from, title):
    """Speeds, slip, strand forces and clamping forces over the whole run; the counted part after
    the dashed line."""
    t = d["time"] * 1e3
    fig, axes = plt.subplots(4, 1, figsize=(9, 10), sharex=True)
    axes[0].plot(t, d["drivingSpeed"], label="driving pulley")
    axes[0].plot(t, d["drivenSpeed"], label="driven pulley")
    axes[0].set_ylabel("speed [rad/s]")
    axes[1].plot(t, 100.0 * d["slip"], color="C3")
    axes[1].set_ylabel("slip [%]")
    axes[2].plot(t, d["tightStrandForce"], label="tight strand")
    axes[2].plot(t, d["slackStrandForce"], label="slack strand")
    axes[2].set_ylabel("strand force [N]")
    axes[3].plot(t, d["clampingForceDriving"] / 1e3, label="driving pulley")
    axes[3].plot(t, d["clampingForceDriven"] / 1e3, label="driven pulley")
    axes[3].set_ylabel("clamping force [kN]")
    axes[3].set_xlabel("time [ms]")
    for ax in axes:
        ax.axvline(t[counted_from], color="grey", ls="--", lw=0.8)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="upper right", fontsize=8)
    axes[0].set_title("CVT time histories (the counted revolutions after the dashed line)\n" + title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
