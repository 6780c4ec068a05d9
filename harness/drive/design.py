"""Designs the default drive (paper Fig. 11, a DOHC four-cylinder timing drive) and writes it where
--out says (default results/design/default_drive.json); a file of the repository (one git tracks,
src/drives/default_drive.json among them) only with --overwrite-tracked.

The layout follows the typical numbers of a passenger-car timing drive (see docs/default_drive.md, "The
default drive"): crankshaft sprocket z=21 with prescribed motion, two camshaft sprockets z=42 (2:1),
an ISO 606 06B-1 simplex roller chain of 120 links, a fixed guide on the tight span and a pivoting
tension guide with a hydraulic tensioner on the slack span. The guides are placed relative to the
straight spans (a given deflection of the chain), and the camshaft height is then adjusted until
the chain closes with exactly 120 links with the tension guide at its drawn (nominal) pose, as
reported by `chaindrive-info`.

    python -m harness design-drive --info build/chaindrive-info [--out FILE] [--overwrite-tracked]
"""
import json
import math
import pathlib
import subprocess
import sys

from .. import paths
from ..errors import UserError
from . import geometry as geo
from .layout_drive import closure_angle

# ---- design values (SI) and their sources -------------------------------------------------
PITCH = 0.009525          # ISO 606 06B-1 (3/8 in)
ROLLER_D = 0.00635        # ISO 606 06B-1 d1
PLATE_H = 0.00826         # ISO 606 06B-1 h2 (max inner plate depth)
N_LINKS = 120             # paper, section 4.2
LINK_MASS = 0.0039        # 0.41 kg/m (06B-1 catalogue mass, typical 0.30-0.45 kg/m) times the pitch
# rollers, pins and bushings (about half the mass) at the pins, plates as p x h rectangles
LINK_INERTIA = LINK_MASS * (PITCH**2 / 8.0 + (PITCH**2 + PLATE_H**2) / 24.0)
Z_CRANK, Z_CAM = 21, 42   # typical: 19-23 / 38-46, 2:1
CAM_SPACING = 0.140       # typical: cam-cam 110-140 mm (the 42-tooth tip circles need > 134 mm)
CAM_INERTIA = 1.0e-3      # camshaft with lobes and sprocket [E]
JOINT_K = 1.2e8           # typical: per-link stiffness 1e8-1.5e8 N/m
JOINT_C = 250.0           # lubricated pin-bushing: 18 % of critical for one link, 1.3 % for a 2 kHz span mode [E]
# tension guide (slack span) and fixed guide (tight span)
TG_FACE_R = 0.35
TG_MARGIN = 0.020          # face beyond the wrapped part at each end
TG_DEFLECT = 0.018        # how far the face pushes into the straight slack span
TG_AT = 0.55              # face centre at this fraction of the span from the crank
TG_INERTIA = 1.0e-3       # PA66 faced steel arm about the pivot [E]
TG_ANGLE_RANGE_DEG = (-6.0, 6.0)  # its closure search range
TG_PIVOT_BEFORE = 0.025   # the pivot beyond the face's lower end, along the span
TG_PIVOT_BEHIND = 0.012   # and behind the face
PAD_AT = 2.0 / 3.0        # the tensioner's pad at this fraction of the arm from the pivot
PAD_BEHIND = 0.010        # behind the face
HOUSING_OUT = 0.030       # the tensioner's housing behind the pad
G_FACE_R = 0.80
G_MARGIN = 0.030
G_DEFLECT = 0.0015
G_AT = 0.50
# tensioner: hydraulic (dynamics/hydraulic_tensioner.h, its defaults: a 12 mm plunger, 20 um
# clearance, oil at 3 bar and 90 C); its plunger spring, typically 10-40 N preload at 2-10 N/mm
TENS_PRELOAD = 25.0
TENS_K = 5000.0
# the spring-damper law the drive had before (its comparison, spring_damper_variant): the preload
# of the spring and the oil at rest (25 N + 2.9 bar on the plunger, 33 N, about 60 N) and damping
# rates for the leak-down (retracting) and the open check valve (extending) [E]
TENS_SD_PRELOAD = 60.0
TENS_SD_C = 3000.0
TENS_SD_C_EXT = 300.0


def pitch_radius(z):
    return geo.pitch_radius(PITCH, z)


common_tangent = geo.common_tangent


def guide_on_span(t1, t2, at, face_r, deflect, outward_sign):
    """Arc face pressing into the straight span t1->t2 from outside the loop (centre only)."""
    ux, uy = t2[0] - t1[0], t2[1] - t1[1]
    L = math.hypot(ux, uy)
    ux, uy = ux / L, uy / L
    # outside of a clockwise loop is on the left of the running direction
    nx, ny = -uy * outward_sign, ux * outward_sign
    mx, my = t1[0] + at * L * ux, t1[1] + at * L * uy
    dist = face_r + PLATE_H / 2.0 - deflect
    return (mx + dist * nx, my + dist * ny), (ux, uy), (nx, ny)


def face_range(prev_c, prev_s, c, face_r, next_c, next_s, margin):
    """Angle range of a guide face covering where the taut chain runs on it, plus a margin [m]
    at both ends (lead-in and lead-out)."""
    rp = math.sqrt((face_r + PLATE_H / 2.0) ** 2 + (PITCH / 2.0) ** 2)
    _, tin = common_tangent(prev_c, prev_s, c, rp)
    tout, _ = common_tangent(c, rp, next_c, next_s)
    a_in = math.atan2(tin[1] - c[1], tin[0] - c[0])
    a_out = math.atan2(tout[1] - c[1], tout[0] - c[0])
    lo, hi = min(a_in, a_out), max(a_in, a_out)
    return lo - margin / face_r, hi + margin / face_r


def tension_guide_mounts(tg_c, tg_u, tg_n, tg_a0, tg_a1):
    """The tension guide's pivot and the tensioner's pad, housing and direction, from the guide's
    face (centre tg_c, angles tg_a0..tg_a1) and its span's direction tg_u and normal tg_n."""
    # tension guide pivot: 25 mm before the lower end of the face, 12 mm behind it
    e0 = (tg_c[0] + TG_FACE_R * math.cos(tg_a0), tg_c[1] + TG_FACE_R * math.sin(tg_a0))
    e1 = (tg_c[0] + TG_FACE_R * math.cos(tg_a1), tg_c[1] + TG_FACE_R * math.sin(tg_a1))
    low, high = (e0, e1) if math.hypot(*e0) < math.hypot(*e1) else (e1, e0)
    pivot = (low[0] - TG_PIVOT_BEFORE * tg_u[0] + TG_PIVOT_BEHIND * tg_n[0],
             low[1] - TG_PIVOT_BEFORE * tg_u[1] + TG_PIVOT_BEHIND * tg_n[1])
    # tensioner pad at two thirds of the face length from the pivot, 10 mm behind the face
    fx, fy = pivot[0] + PAD_AT * (high[0] - pivot[0]), pivot[1] + PAD_AT * (high[1] - pivot[1])
    # project onto the face back: move outward to 10 mm behind the face surface
    dx, dy = fx - tg_c[0], fy - tg_c[1]
    r = math.hypot(dx, dy)
    on_face = (tg_c[0] + TG_FACE_R * dx / r, tg_c[1] + TG_FACE_R * dy / r)
    pad = (on_face[0] + PAD_BEHIND * tg_n[0], on_face[1] + PAD_BEHIND * tg_n[1])
    housing = (pad[0] + HOUSING_OUT * tg_n[0], pad[1] + HOUSING_OUT * tg_n[1])
    return pivot, pad, housing, (-tg_n[0], -tg_n[1])


def build(cam_height):
    rc, rcam = pitch_radius(Z_CRANK), pitch_radius(Z_CAM)
    crank = (0.0, 0.0)
    exh = (-CAM_SPACING / 2.0, cam_height)
    intk = (CAM_SPACING / 2.0, cam_height)
    # clockwise running: signed radii are negative for sprockets
    l1, l2 = common_tangent(crank, -rc, exh, -rcam)   # slack span (left, running upwards)
    r1, r2 = common_tangent(intk, -rcam, crank, -rc)  # tight span (right, running downwards)
    tg_c, tg_u, tg_n = guide_on_span(l1, l2, TG_AT, TG_FACE_R, TG_DEFLECT, +1.0)
    g_c, _, _ = guide_on_span(r1, r2, G_AT, G_FACE_R, G_DEFLECT, +1.0)
    tg_a0, tg_a1 = face_range(crank, -rc, tg_c, TG_FACE_R, exh, -rcam, TG_MARGIN)
    g_a0, g_a1 = face_range(intk, -rcam, g_c, G_FACE_R, crank, -rc, G_MARGIN)
    pivot, pad, housing, direction = tension_guide_mounts(tg_c, tg_u, tg_n, tg_a0, tg_a1)

    r6 = lambda v: round(v, 9)
    deg = lambda a: round(math.degrees(a), 6)
    drive = {
        "schema": "chaindrive.drive/1",
        "name": "DOHC I4 timing drive (paper Fig. 11 layout)",
        "description": "Generated by python -m harness design-drive (harness/drive/design.py); numbers and sources in docs/default_drive.md.",
        "rotation": "clockwise",
        "gravity": [0.0, -9.81],
        "chain": {
            "standard": "ISO 606 06B-1 simplex roller chain",
            "pitch": PITCH, "numberOfLinks": N_LINKS,
            "linkMass": LINK_MASS, "linkInertia": r6(LINK_INERTIA),
            "rollerDiameter": ROLLER_D, "plateHeight": PLATE_H,
            "joint": {"model": "journal-bearing", "stiffness": JOINT_K, "damping": JOINT_C, "clearance": 0.0},
            "route": ["crankshaft", "tensionGuide", "camshaftExhaust", "camshaftIntake", "fixedGuide"],
        },
        "sprockets": [
            {"name": "crankshaft", "center": [0.0, 0.0], "teeth": Z_CRANK,
             "toothProfile": {"standard": "ISO 606", "form": "mean"}, "motion": "prescribed"},
            {"name": "camshaftExhaust", "center": [r6(exh[0]), r6(exh[1])], "teeth": Z_CAM,
             "toothProfile": {"standard": "ISO 606", "form": "mean"}, "motion": "free", "inertia": CAM_INERTIA},
            {"name": "camshaftIntake", "center": [r6(intk[0]), r6(intk[1])], "teeth": Z_CAM,
             "toothProfile": {"standard": "ISO 606", "form": "mean"}, "motion": "free", "inertia": CAM_INERTIA},
        ],
        "guides": [
            {"name": "tensionGuide", "motion": "pivoting", "pivot": [r6(pivot[0]), r6(pivot[1])],
             "inertia": TG_INERTIA, "angleRange_deg": list(TG_ANGLE_RANGE_DEG),
             "profile": [{"type": "arc", "center": [r6(tg_c[0]), r6(tg_c[1])], "radius": TG_FACE_R,
                          "startAngle_deg": deg(tg_a0), "endAngle_deg": deg(tg_a1), "chainSide": "outside"}]},
            {"name": "fixedGuide", "motion": "fixed",
             "profile": [{"type": "arc", "center": [r6(g_c[0]), r6(g_c[1])], "radius": G_FACE_R,
                          "startAngle_deg": deg(g_a0), "endAngle_deg": deg(g_a1), "chainSide": "outside"}]},
        ],
        "tensioner": {"guide": "tensionGuide", "housing": [r6(housing[0]), r6(housing[1])],
                      "direction": [r6(direction[0]), r6(direction[1])], "contactPoint": [r6(pad[0]), r6(pad[1])],
                      "preload": TENS_PRELOAD, "stiffness": TENS_K, "model": "hydraulic"},
        "contact": {
            "frictionRegularization": 0.05,
            "rollerSprocket": {"model": "hunt-crossley", "stiffness": 2.0e8, "exponent": 1.0, "dampingFactor": 0.25,
                               "friction": 0.05, "restitution": 0.5},
            "plateGuide": {"model": "hunt-crossley", "stiffness": 5.0e6, "exponent": 1.0, "dampingFactor": 1.0,
                           "friction": 0.08, "restitution": 0.3},
        },
        "measurement": {"tightSpan": ["camshaftIntake", "fixedGuide"], "slackSpan": ["tensionGuide", "camshaftExhaust"],
                        "monitoredLink": 0},
    }
    return drive


def spring_damper_variant(drive):
    """The drive with the spring-damper tensioner law instead of its hydraulic tensioner (the law the
    default drive had before; for comparisons): a copy of the description dict."""
    variant = json.loads(json.dumps(drive))
    t = variant["tensioner"]
    for key in ("model", "hydraulic"):
        t.pop(key, None)
    t.update({"preload": TENS_SD_PRELOAD, "damping": TENS_SD_C, "dampingExtension": TENS_SD_C_EXT})
    variant["name"] = drive["name"] + ", spring-damper tensioner"
    return variant


def add_arguments(ap):
    ap.add_argument("--info", required=True, help="path of the chaindrive-info executable")
    ap.add_argument("--out", default=str(paths.RESULTS / "design" / "default_drive.json"),
                    help="the drive file to write (default: results/design/default_drive.json)")
    ap.add_argument("--overwrite-tracked", action="store_true",
                    help="allow --out to be a file of the repository that git tracks (src/drives/default_drive.json)")


def tracked(path):
    """Whether git tracks the file in this checkout (False outside one, or without git)."""
    try:
        done = subprocess.run(["git", "-C", str(paths.ROOT), "ls-files", "--error-unmatch", str(path)],
                              capture_output=True, text=True)
    except FileNotFoundError:
        return False
    return done.returncode == 0


def check_out(args):
    """The file to write: never over a tracked one unless asked (a design run is not a decision to
    replace the default drive, whose every committed result follows from it)."""
    out = pathlib.Path(args.out).resolve()
    if tracked(out) and not args.overwrite_tracked:
        raise UserError(f"--out {args.out}: a file of the repository (git tracks it); give --overwrite-tracked "
                        "to replace it, or another --out")
    out.parent.mkdir(parents=True, exist_ok=True)
    return out


def run(args):
    out = check_out(args)
    # scan the camshaft height for closure, then secant until the tension guide closes the chain
    # at its drawn pose
    found = []
    for k in range(121):
        h = 0.300 + 0.0005 * k
        try:
            a, _ = closure_angle(args.info, build(h))
        except ValueError:  # the guide would overlap a sprocket at this height
            continue
        if a is not None:
            found.append((h, a))
    if len(found) < 2:
        sys.exit("design failed: no camshaft height between 300 and 360 mm closes the chain")
    h0, a0 = min(found, key=lambda p: abs(p[1]))
    h1 = h0 + 0.0002
    a1, msg = closure_angle(args.info, build(h1))
    for _ in range(40):
        if a1 is None:
            sys.exit("design failed: " + msg)
        if abs(a1) < 1e-8 or a1 == a0:  # coordinates are written to 1 nm
            break
        h2 = h1 - a1 * (h1 - h0) / (a1 - a0)
        h0, a0 = h1, a1
        h1 = h2
        a1, msg = closure_angle(args.info, build(h1))
    drive = build(h1)
    with open(out, "w") as f:
        json.dump(drive, f, indent=2)
        f.write("\n")
    print(f"camshaft height {h1 * 1e3:.6f} mm, closure angle {math.degrees(a1):.3e} deg -> {args.out}")
