"""The sketch of a layout the solver could not close (harness/drive/layout.py): the sprockets' pitch
and tip circles, the guide faces, the tension guide's arm and the tensioner at the drawn pose, the
chain's pins walked along the taut path for the drive's link count, and the gap between the last
pin and the first marked, so that one sees what to move."""
import math

import numpy as np

from ..drive import geometry as geo
from . import plt


def draw_circles(ax, layout):
    for s in layout.spec.sprockets:
        c = np.array(layout.center(s["name"])) * 1e3
        ch = layout.chain
        for r, style in ((geo.pitch_radius(ch.pitch, s["teeth"]), "--"),
                         (geo.tip_radius(ch.pitch, ch.roller_d, s["teeth"]), "-")):
            ax.add_patch(plt.Circle(c, r * 1e3, fill=False, ls=style, color="k", lw=0.6))
        ax.annotate(s["name"], c, textcoords="offset points", xytext=(4, -12), fontsize=7)


def draw_guides(ax, layout):
    guides = layout.guides()
    for name, g in guides.items():
        a = np.linspace(g["a0"], g["a1"], 40)
        r = g["spec"].face["face_r"]
        ax.plot((g["center"][0] + r * np.cos(a)) * 1e3, (g["center"][1] + r * np.sin(a)) * 1e3, "-",
                color="tab:blue", lw=3)
        ax.annotate(name, (g["center"][0] * 1e3 + r * 1e3 * math.cos(a[20]), g["center"][1] * 1e3
                           + r * 1e3 * math.sin(a[20])), textcoords="offset points", xytext=(6, 0), fontsize=7,
                    color="tab:blue")
    pivot, pad, housing, _ = layout.mounts(guides)
    ax.plot(pivot[0] * 1e3, pivot[1] * 1e3, "o", color="tab:blue", ms=5)
    ax.plot([housing[0] * 1e3, pad[0] * 1e3], [housing[1] * 1e3, pad[1] * 1e3], "-", color="tab:purple", lw=5)


def layout_sketch(path, layout, n_links, title):
    """Draws the layout with n_links walked along its taut path and the gap marked; returns the gap
    [m] (the last pin to the first: 0 when the path holds exactly n_links)."""
    fig, ax = plt.subplots(figsize=(6.5, 9.0))
    draw_circles(ax, layout)
    draw_guides(ax, layout)
    pins = np.array(geo.pins_walked(layout.route_circles(), layout.chain.pitch, n_links)) * 1e3
    ax.plot(pins[:, 0], pins[:, 1], "-", color="tab:red", lw=0.8)
    ax.plot(pins[0, 0], pins[0, 1], "ko", ms=4)
    gap = math.hypot(*(pins[-1] - pins[0])) / 1e3
    ax.plot([pins[0, 0], pins[-1, 0]], [pins[0, 1], pins[-1, 1]], "-", color="magenta", lw=3)
    ax.annotate(f"gap {gap * 1e3:.2f} mm: {n_links} links", pins[-1], textcoords="offset points", xytext=(8, 8),
                fontsize=8, color="magenta", weight="bold")
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(title, fontsize=9)
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return gap
