"""Picture of a drive at its assembled initial pose (PNG).

    python -m harness picture [--drive FILE] [--out docs/default_drive.png]
"""
import numpy as np

from .. import paths
from ..drive.description import geometry
from . import plt


def drive_picture(path, drive=None, title=None):
    """The drive and the chain at its initial (assembled) pose."""
    g = geometry(drive)
    fig, ax = plt.subplots(figsize=(6.5, 9.0))
    for s in g["sprockets"]:
        o = np.array(s["outline"] + [s["outline"][0]])
        ax.fill(o[:, 0] * 1e3, o[:, 1] * 1e3, color="0.85", lw=0.0)
        ax.plot(o[:, 0] * 1e3, o[:, 1] * 1e3, "k-", lw=0.5)
        c = s["center"]
        ax.plot(c[0] * 1e3, c[1] * 1e3, "k+", ms=6)
        ax.annotate(s["name"], (c[0] * 1e3, c[1] * 1e3), textcoords="offset points", xytext=(4, -12), fontsize=7)
    for gd in g["guides"]:
        for face in gd["faces"]:
            f = np.array(face)
            ax.plot(f[:, 0] * 1e3, f[:, 1] * 1e3, "-", color="tab:blue", lw=3.0, solid_capstyle="round")
        mid = np.array(gd["faces"][0])[len(gd["faces"][0]) // 2]
        ax.annotate(gd["name"], (mid[0] * 1e3, mid[1] * 1e3), textcoords="offset points",
                    xytext=(-75 if mid[0] < 0 else 10, -30 if mid[0] < 0 else 0), fontsize=7, color="tab:blue")
        if gd["pivoting"]:
            pv = np.array(gd["pivot"]) * 1e3
            ax.plot(pv[0], pv[1], "o", color="tab:blue", ms=5)
            face = np.array(gd["faces"][0]) * 1e3
            end = face[np.argmin(np.hypot(face[:, 0] - pv[0], face[:, 1] - pv[1]))]
            ax.plot([pv[0], end[0]], [pv[1], end[1]], "-", color="tab:blue", lw=1.5)  # the arm
            t = g.get("tensioner")
            if t:
                pad = np.array(t["pad"]) * 1e3
                near = face[np.argmin(np.hypot(face[:, 0] - pad[0], face[:, 1] - pad[1]))]
                ax.plot([pad[0], near[0]], [pad[1], near[1]], "-", color="tab:blue", lw=1.5)
    t = g.get("tensioner")
    if t:
        h, p = np.array(t["housing"]) * 1e3, np.array(t["pad"]) * 1e3
        ax.plot([h[0], p[0]], [h[1], p[1]], "-", color="tab:purple", lw=5, solid_capstyle="butt")
        ax.annotate("tensioner", h, textcoords="offset points", xytext=(-30, 10), fontsize=7, color="tab:purple")
    pins = np.array(g["pins"] + [g["pins"][0]]) * 1e3
    ax.plot(pins[:, 0], pins[:, 1], "-", color="tab:red", lw=0.8)
    r = g["rollerRadius"] * 1e3
    for k, (x, y) in enumerate(pins[:-1]):
        ax.add_patch(plt.Circle((x, y), r, fill=False, color="tab:red", lw=0.4))
    ax.plot(pins[0, 0], pins[0, 1], "o", color="k", ms=3)
    for pr, name in zip(g.get("probes", []), ("tight-span probe", "slack-span probe")):
        if pr:
            ax.plot(pr[0] * 1e3, pr[1] * 1e3, "x", color="tab:green", ms=7)
            ax.annotate(name, (pr[0] * 1e3, pr[1] * 1e3), textcoords="offset points", xytext=(6, 4), fontsize=6,
                        color="tab:green")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(title or g["name"], fontsize=9)
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path


def add_arguments(ap):
    ap.add_argument("--drive", help="drive description (default: the embedded default drive)")
    ap.add_argument("--out", default=str(paths.ROOT / "docs" / "default_drive.png"))


def run(args):
    drive_picture(args.out, args.drive)
    print(f"written: {args.out}")
