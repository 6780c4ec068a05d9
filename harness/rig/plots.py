"""The tensioner's force-displacement loops, as the suppliers' rig reports them."""
from ..plots import plt

COLOURS = {20.0: "tab:blue", 100.0: "tab:orange", 200.0: "tab:red"}


def loops(path, loops, amplitudes, frequencies):
    """One panel per amplitude: force over the plunger's displacement (positive: extending) for
    each frequency, the last period of each run; the arrow of time marked at the top of the loop."""
    fig, axes = plt.subplots(1, len(amplitudes), figsize=(11, 4.6))
    for ax, a in zip(axes, amplitudes):
        for f in frequencies:
            d = loops[(f, a)]
            x, force = d["stroke"] * 1e3, d["force"]
            ax.plot(x, force, color=COLOURS.get(f), lw=1.4, label=f"{f:g} Hz, peak {force.max():.0f} N")
            i = int(force.argmax())
            j = min(i + max(len(x) // 40, 1), len(x) - 1)
            ax.annotate("", xy=(x[j], force[j]), xytext=(x[i], force[i]),
                        arrowprops=dict(arrowstyle="->", color=COLOURS.get(f)))
        ax.set_title(f"amplitude {a * 1e3:g} mm")
        ax.set_xlabel("plunger displacement [mm] (> 0: extending)")
        ax.set_ylabel("force on the plunger [N]")
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right", fontsize=8)
    fig.suptitle("Hydraulic tensioner on the rig: x(t) = a sin(2 pi f t), default device, 90 C oil, 3 bar supply "
                 "(last of max(0.25 s, 10) periods)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
