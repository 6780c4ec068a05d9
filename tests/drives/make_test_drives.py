"""Generates the four test drives of tests/drives/ (schema chaindrive.drive/1) the way the default
drive was designed (harness/drive/design.py, docs/default_drive.md): the sprockets are laid out,
the guides are placed relative to the straight spans between them (a given deflection of the
taut chain), the tension guide's pivot and the tensioner's pad and housing follow from its face,
and then one coordinate (each drive's camshaft height) is adjusted until the chain closes with the
drive's even number of links with the tension guide at its drawn pose, as `chaindrive-info`
reports (closure angle |phi| of about 1e-8 rad or less: the best on the 0.1 nm grid the coordinates
are written to).

    .venv/bin/python tests/drives/make_test_drives.py --info /path/to/chaindrive-info [--out tests/drives]
        [--only NAME ...] [--pictures DIR]

The drives (names of the JSON files; sprocket and guide names in the drive):

- dohc_8mm.json (A): a DOHC inline-four on an 8 mm chain, turning counterclockwise in the drawing
  (the default drive seen from the back: its layout mirrored). ISO 606 05B-1 simplex roller chain
  (pitch 8.00 mm, roller 5.00 mm, plate height 7.11 mm: LAYOUTS.md section 1), 1.44 g per link
  (0.18 kg/m times the pitch), link inertia as design.py computes it (half the mass at the pins,
  plates as p x h rectangles), joint stiffness the default's 1.2e8 N/m scaled by the pitch squared
  (LAYOUTS.md: "Scale by p^2 for 05B and 06B"), joint damping the default's 250 N s/m. Crank
  `crank` 19 T (prescribed), camshafts `exhaustCam` (right) and `intakeCam` (left) 38 T, 1e-3 kg m^2
  each: the 19/38 pair LAYOUTS.md derives for the Toyota 1ZZ/1AZ-FE 8 mm drives. Cam spacing
  115 mm (the 38-tooth tip circles, 100.7 mm across with the mean ISO 606 form, need more than
  105.7 mm with a roller between them; typical 110-130 mm), camshafts 436.1 mm above the crank
  (crank-to-cam distance 439.9 mm; LAYOUTS.md: I4 420-470 mm), 154 links. Pivoting `tensionerArm` with the hydraulic tensioner on
  the slack span (crank to exhaust camshaft, the right side when turning counterclockwise), fixed
  `tightGuide` on the tight span (intake camshaft to crank). Link inertia 1.839e-8 kg m^2, joint
  stiffness 8.465e7 N/m. Note: with the default's roller-sprocket stiffness (2e8 N/m) on the
  2.7 times lighter link, the real-time method's stable step on this drive (about 3.1 us at
  6000 rpm with a crankshaft vibration) lies below its default 3.571 us (tests/drives/README.md).
- sohc_single_cam.json (B): a single-camshaft (SOHC) drive, the default's 06B-1 chain and link
  data, crank `crankshaft` 21 T (prescribed) at the origin, `camshaft` 42 T (1e-3 kg m^2) straight
  above it at 400.3 mm, 116 links, pivoting `tensionGuide` with the hydraulic tensioner on the
  slack span (left), `fixedGuide` on the tight span (right), clockwise.
- diesel_pump.json (C): a diesel-style DOHC drive with its high-pressure pump in the chain: crank
  `crankshaft` 21 T (prescribed), `camshaftExhaust` (left) and `camshaftIntake` (right) 42 T
  (1e-3 kg m^2, the default's names, so the default torque tables serve them), 140 mm apart as in
  the default, 404.6 mm above the crank (crank-to-cam distance 410.6 mm); `hpPump` 28 T (5e-4 kg m^2: pump shaft, cam and sprocket
  [E]) on the tight side at (135, 210) mm, wrapped from inside the loop (the chain runs around its
  right-hand side, 48 deg: 3-4 rollers seated), 06B-1 chain, 138 links, clockwise. 28/21 teeth run the pump at
  3/4 of crank speed (a 3-plunger CP1-type pump then pumps 2.25 strokes per crank revolution; the
  LAYOUTS.md pumps run at 1/2, 2/3 or 1/1, which would need 42, 32 or 21 teeth; 28 T is the brief's).
  `tensionGuide` with the hydraulic tensioner on the slack span (crank to exhaust camshaft),
  `fixedGuide` on the longer span from the pump down to the crank (228 mm; intake camshaft to pump
  200 mm).
- idler.json (D): a single-camshaft drive with an idler: crank `crankshaft` 21 T (prescribed) at
  the origin, `camshaft` 42 T (1e-3 kg m^2) at x = +40 mm, 452.3 mm high (crank-to-cam distance
  454.0 mm; a tall SOHC block; the offset makes the tight span the longer one), a 19-tooth `idler` (1e-4 kg m^2, free,
  no load: it will later be marked unloaded in the schema) at (120, 235) mm in the middle of the
  long tight span (231 mm above it, 244 mm below), wrapped from inside the loop (39 deg, two
  rollers seated), 06B-1 chain, 130 links, `tensionGuide` with the hydraulic tensioner on the slack span (left), `fixedGuide`
  on the span from the idler down to the crank, clockwise.

Common to all (as the default drive, src/drives/default_drive.json and docs/default_drive.md): ISO
606 mean tooth form; tension guide: PA66 face R 350 mm pushing 18 mm into the straight slack span
at 55 % of its length, 20 mm of face beyond the wrapped part at each end, pivot 25 mm before its
crank-side end and 12 mm behind it, 1e-3 kg m^2, angle range +-6 deg; tensioner pad at two thirds
of the arm, 10 mm behind the face, housing 30 mm further out, plunger pushing the guide towards
the chain, model hydraulic (the device's defaults), plunger spring 25 N at 5 N/mm; fixed guides:
face R 800 mm, 1.5 mm into their span at its middle, 30 mm margins; guide faces at the plates'
edge (face radius plus half the plate height from the taut pin line); contact laws rollerSprocket
and plateGuide and the friction regularisation of the default; measurement: the tight span from
the camshaft the chain leaves last to the next route element (fixed guide, pump or idler), the
slack span from the tension guide to the first camshaft, monitored link 0. The 06B-1 drives use
the default's chain data as written there (link inertia 7.0e-8 kg m^2).

Checks run on every drive (from `chaindrive-info --drive FILE --geometry G.json`): the chain closes
with the tension guide within 1e-7 rad of its drawn pose; every guide face lies outside the chain's
loop at least half a plate height from the pin line and outside every sprocket's tip circle plus
a roller radius; the tension guide's arm and the tensioner's body neither cross the chain nor
enter a sprocket; the tensioner turns the guide towards the chain; every sprocket is wrapped by
at least one pitch. Coordinates are written to 0.1 nm (design.py writes 1 nm; the closure angle
moves about 1.4e-7 rad per nm of camshaft height).
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile

# ---- chains (ISO 606 simplex roller chains; LAYOUTS.md section 1) -------------------------------

JOINT_K_06B = 1.2e8   # the default drive's joint stiffness for 06B-1 [N/m] (typical 1e8-1.5e8)
JOINT_C = 250.0       # the default drive's joint damping [N s/m]


def link_inertia(mass, pitch, plate_h):
    """design.py's link inertia: half the mass at the pins, the plates as p x h rectangles."""
    return mass * (pitch**2 / 8.0 + (pitch**2 + plate_h**2) / 24.0)


class Chain:
    def __init__(self, standard, pitch, roller_d, plate_h, mass, inertia_rounding):
        self.standard, self.pitch, self.roller_d, self.plate_h, self.mass = standard, pitch, roller_d, plate_h, mass
        self.inertia = link_inertia(mass, pitch, plate_h)
        self.inertia_written = inertia_rounding(self.inertia)
        # joint stiffness scaled from the default's 06B-1 value by the pitch squared (LAYOUTS.md)
        self.joint_k = JOINT_K_06B * (pitch / 0.009525) ** 2

    def pitch_radius(self, z):
        return self.pitch / (2.0 * math.sin(math.pi / z))

    def tip_radius(self, z):
        """Tip radius of the ISO 606 mean tooth form (src/description/drive_description.cpp)."""
        d = 2.0 * self.pitch_radius(z)
        da_max = d + 1.25 * self.pitch - self.roller_d
        da_min = d + self.pitch * (1.0 - 1.6 / z) - self.roller_d
        return 0.25 * (da_max + da_min)

    def guide_pin_radius(self, face_r):
        """Pin circle of a convex guide face: chords of one pitch whose plate edges touch it."""
        return math.hypot(face_r + self.plate_h / 2.0, self.pitch / 2.0)


# 06B-1: pitch 9.525 mm, roller 6.35 mm, plate 8.26 mm, 3.9 g per link (0.41 kg/m): the default's,
# its inertia 7.006e-8 kg m^2 written as design.py writes it (to 1e-9: 7.0e-8, the default's value)
CHAIN_06B = Chain("ISO 606 06B-1 simplex roller chain", 0.009525, 0.00635, 0.00826, 0.0039, lambda v: round(v, 9))
# 05B-1: pitch 8.00 mm, roller 5.00 mm, plate 7.11 mm, 1.44 g per link (0.18 kg/m x 8 mm); its
# inertia 1.839e-8 kg m^2 to 4 digits (rounded to 1e-9 as design.py does it would be 2 % low)
CHAIN_05B = Chain("ISO 606 05B-1 simplex roller chain", 0.008, 0.005, 0.00711, 0.00144,
                  lambda v: float(f"{v:.4g}"))

# ---- the parts common to every drive (the default drive's values) -------------------------------

CAM_INERTIA = 1.0e-3
TG = dict(face_r=0.35, deflect=0.018, at=0.55, margin=0.020)  # tension guide on the slack span
FG = dict(face_r=0.80, deflect=0.0015, at=0.50, margin=0.030)  # fixed guide
TG_INERTIA = 1.0e-3
TG_RANGE_DEG = [-6.0, 6.0]
TENS_PRELOAD, TENS_K = 25.0, 5000.0
CONTACT = {
    "frictionRegularization": 0.05,
    "rollerSprocket": {"model": "hunt-crossley", "stiffness": 2.0e8, "exponent": 1.0, "dampingFactor": 0.25,
                       "friction": 0.05, "restitution": 0.5},
    "plateGuide": {"model": "hunt-crossley", "stiffness": 5.0e6, "exponent": 1.0, "dampingFactor": 1.0,
                   "friction": 0.08, "restitution": 0.3},
}
TOOTH = {"standard": "ISO 606", "form": "mean"}

# ---- plane geometry (x right, y up; sense +1 counterclockwise, -1 clockwise) --------------------


def add(a, b, k=1.0):
    return (a[0] + k * b[0], a[1] + k * b[1])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def unit(a):
    n = math.hypot(*a)
    return (a[0] / n, a[1] / n)


def perp(a):
    return (-a[1], a[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def common_tangent(c1, s1, c2, s2):
    """Tangent points of the chain running from circle 1 to circle 2 (signed radii as the solver's
    route circles: sense x pitch radius for a sprocket, -sense x pin radius for a guide): T = c + s m,
    running direction perp(m) (src/assembly/chain_path.cpp, commonTangent)."""
    dx, dy = c2[0] - c1[0], c2[1] - c1[1]
    d = math.hypot(dx, dy)
    c = (s1 - s2) / d
    if abs(c) > 1.0:
        raise ValueError("no common tangent (the circles overlap)")
    m = (math.cos(math.atan2(dy, dx) - math.acos(c)), math.sin(math.atan2(dy, dx) - math.acos(c)))
    return add(c1, m, s1), add(c2, m, s2)


def outward(u, sense):
    """Outward normal of a straight span running along u: left of the running direction for a
    clockwise loop, right of it for a counterclockwise one."""
    p = perp(u)
    return (-sense * p[0], -sense * p[1])


def guide_on_span(t1, t2, g, chain, sense):
    """Centre of an arc face pressing `deflect` into the straight span t1 -> t2 from outside the loop,
    at the fraction `at` of the span from t1; the span's direction and outward normal."""
    L = math.hypot(*sub(t2, t1))
    u = unit(sub(t2, t1))
    n = outward(u, sense)
    mid = add(t1, u, g["at"] * L)
    return add(mid, n, g["face_r"] + chain.plate_h / 2.0 - g["deflect"]), u, n


def face_range(prev, centre, g, nxt, chain, sense, n):
    """Angles [rad] of a guide face covering where the taut chain runs on it (its tangent points to
    the previous and the next route circle, each (centre, signed radius)) plus the margin at both
    ends; continuous around the direction from the face's centre towards the span (-n)."""
    s = -sense * chain.guide_pin_radius(g["face_r"])
    _, tin = common_tangent(prev[0], prev[1], centre, s)
    tout, _ = common_tangent(centre, s, nxt[0], nxt[1])
    ref = math.atan2(-n[1], -n[0])

    def ang(p):
        a = math.atan2(p[1] - centre[1], p[0] - centre[0]) - ref
        return ref + math.atan2(math.sin(a), math.cos(a))

    lo, hi = sorted((ang(tin), ang(tout)))
    return lo - g["margin"] / g["face_r"], hi + g["margin"] / g["face_r"]


def arc_point(c, r, a):
    return (c[0] + r * math.cos(a), c[1] + r * math.sin(a))


def tension_guide_mounts(centre, g, a0, a1, u, n, crank):
    """design.py's tension_guide_mounts for either sense: the pivot 25 mm before the face's end
    nearer the crank (along the span, away from the face) and 12 mm behind the face; the tensioner's
    pad at two thirds of the arm from the pivot, 10 mm behind the face; the housing 30 mm further
    out; the plunger extending towards the chain (-n)."""
    R = g["face_r"]
    e0, e1 = arc_point(centre, R, a0), arc_point(centre, R, a1)
    low, high = (e0, e1) if math.hypot(*sub(e0, crank)) < math.hypot(*sub(e1, crank)) else (e1, e0)
    along = u if dot(u, sub(high, low)) > 0.0 else (-u[0], -u[1])  # from the crank-side end on
    pivot = add(add(low, along, -0.025), n, 0.012)
    f = add(pivot, sub(high, pivot), 2.0 / 3.0)
    d = unit(sub(f, centre))
    on_face = add(centre, d, R)
    pad = add(on_face, n, 0.010)
    housing = add(pad, n, 0.030)
    return pivot, pad, housing, (-n[0], -n[1])


# ---- the chain path and the links it holds (for choosing the link count) -----------------------


def path_segments(circles):
    """The closed path around route circles [(centre, signed radius)]: per element its arc (centre,
    |r|, start angle, signed sweep) and the span after it (from, to) (chain_path.cpp, through)."""
    n = len(circles)
    tang = [common_tangent(circles[i][0], circles[i][1], circles[(i + 1) % n][0], circles[(i + 1) % n][1])
            for i in range(n)]
    segs = []
    for i, (c, s) in enumerate(circles):
        tin, tout = tang[(i - 1) % n][1], tang[i][0]
        a0 = math.atan2(tin[1] - c[1], tin[0] - c[0])
        sweep = math.atan2(tout[1] - c[1], tout[0] - c[0]) - a0
        if s > 0:
            while sweep < 0:
                sweep += 2 * math.pi
        else:
            while sweep > 0:
                sweep -= 2 * math.pi
        segs.append(("arc", c, abs(s), a0, sweep, abs(s * sweep)))
        segs.append(("span", tout, tang[i][1], None, None, math.hypot(*sub(tang[i][1], tout))))
    return segs


def path_point(segs, s):
    L = sum(g[5] for g in segs)
    s %= L
    for g in segs:
        if s <= g[5] or g is segs[-1]:
            if g[0] == "arc":
                return arc_point(g[1], g[2], g[3] + math.copysign(1.0, g[4]) * s / g[2])
            return add(g[1], sub(g[2], g[1]), s / g[5] if g[5] > 0 else 0.0)
        s -= g[5]


def links_held(circles, pitch):
    """How many links of one pitch the path holds (chords walked from the middle of the first wrap,
    as the solver's closure gap: n - gap / p)."""
    segs = path_segments(circles)
    L = sum(g[5] for g in segs)
    s0 = segs[0][5] / 2.0
    p0 = path_point(segs, s0)
    s, k = s0, 0
    while s - s0 < L:
        a, b = s + pitch, s + 1.6 * pitch
        q = path_point(segs, s)
        for _ in range(60):
            m = 0.5 * (a + b)
            if math.hypot(*sub(path_point(segs, m), q)) < pitch:
                a = m
            else:
                b = m
        s = 0.5 * (a + b)
        k += 1
    del p0
    return k - (s - s0 - L) / pitch


# ---- a drive from its layout ---------------------------------------------------------------------


def r9(v):
    """Coordinates to 0.1 nm: the closure angle moves about 1.4e-7 rad per nm of camshaft height,
    so design.py's 1 nm would leave up to about 7e-8 rad."""
    return round(v, 10)


def deg(a):
    return round(math.degrees(a), 6)


class Layout:
    """A drive's layout: chain, sense, sprockets (name, centre, teeth, motion, inertia), the route,
    the guides placed on the spans between their neighbours, the measurement section."""

    def __init__(self, name, title, chain, sense, sprockets, route, tension_guide, fixed_guides, measurement):
        self.name, self.title, self.chain, self.sense = name, title, chain, sense
        self.sprockets = sprockets          # list of dicts: name, center, teeth, motion, inertia
        self.route = route
        self.tension_guide = tension_guide  # its name
        self.fixed_guides = fixed_guides    # their names
        self.measurement = measurement

    def sprocket(self, name):
        return next(s for s in self.sprockets if s["name"] == name)

    def circle(self, name):
        s = self.sprocket(name)
        return (tuple(s["center"]), self.sense * self.chain.pitch_radius(s["teeth"]))

    def crank(self):
        return next(s for s in self.sprockets if s["motion"] == "prescribed")

    def guides(self):
        """Each guide: its face (centre, angle range), its span's direction and outward normal."""
        out = {}
        n = len(self.route)
        for i, gname in enumerate(self.route):
            if gname not in (self.tension_guide, *self.fixed_guides):
                continue
            prev, nxt = self.circle(self.route[i - 1]), self.circle(self.route[(i + 1) % n])
            g = TG if gname == self.tension_guide else FG
            t1, t2 = common_tangent(prev[0], prev[1], nxt[0], nxt[1])
            c, u, nn = guide_on_span(t1, t2, g, self.chain, self.sense)
            a0, a1 = face_range(prev, c, g, nxt, self.chain, self.sense, nn)
            out[gname] = dict(center=c, u=u, n=nn, a0=a0, a1=a1, g=g)
        return out

    def route_circles(self):
        gs = self.guides()
        circles = []
        for name in self.route:
            if name in gs:
                circles.append((gs[name]["center"], -self.sense * self.chain.guide_pin_radius(gs[name]["g"]["face_r"])))
            else:
                circles.append(self.circle(name))
        return circles

    def drive(self, n_links):
        ch = self.chain
        gs = self.guides()
        tg = gs[self.tension_guide]
        pivot, pad, housing, direction = tension_guide_mounts(tg["center"], TG, tg["a0"], tg["a1"], tg["u"], tg["n"],
                                                              tuple(self.crank()["center"]))

        def face(gd):
            a0 = math.atan2(math.sin(gd["a0"]), math.cos(gd["a0"]))  # start in (-180, 180] deg
            return {"type": "arc", "center": [r9(gd["center"][0]), r9(gd["center"][1])], "radius": gd["g"]["face_r"],
                    "startAngle_deg": deg(a0), "endAngle_deg": deg(a0 + gd["a1"] - gd["a0"]), "chainSide": "outside"}

        sprockets = []
        for s in self.sprockets:
            d = {"name": s["name"], "center": [r9(s["center"][0]), r9(s["center"][1])], "teeth": s["teeth"],
                 "toothProfile": dict(TOOTH), "motion": s["motion"]}
            if s["motion"] in ("free", "idler"):
                d["inertia"] = s["inertia"]
            sprockets.append(d)
        guides = [{"name": self.tension_guide, "motion": "pivoting", "pivot": [r9(pivot[0]), r9(pivot[1])],
                   "inertia": TG_INERTIA, "angleRange_deg": list(TG_RANGE_DEG), "profile": [face(tg)]}]
        for fname in self.fixed_guides:
            guides.append({"name": fname, "motion": "fixed", "profile": [face(gs[fname])]})
        return {
            "schema": "chaindrive.drive/1",
            "name": SHORT_NAMES[self.name],
            "description": self.title + ". Generated by tests/drives/make_test_drives.py (its docstring and tests/drives/README.md "
                           "give the layout and the sources of its numbers); designed as the default drive "
                           "(harness/drive/design.py).",
            "rotation": "counterclockwise" if self.sense > 0 else "clockwise",
            "gravity": [0.0, -9.81],
            "chain": {
                "standard": ch.standard,
                "pitch": ch.pitch, "numberOfLinks": n_links,
                "linkMass": ch.mass, "linkInertia": ch.inertia_written,
                "rollerDiameter": ch.roller_d, "plateHeight": ch.plate_h,
                "joint": {"model": "journal-bearing", "stiffness": float(f"{ch.joint_k:.4g}"), "damping": JOINT_C,
                          "clearance": 0.0},
                "route": list(self.route),
            },
            "sprockets": sprockets,
            "guides": guides,
            "tensioner": {"guide": self.tension_guide, "housing": [r9(housing[0]), r9(housing[1])],
                          "direction": [r9(direction[0]), r9(direction[1])], "contactPoint": [r9(pad[0]), r9(pad[1])],
                          "preload": TENS_PRELOAD, "stiffness": TENS_K, "model": "hydraulic"},
            "contact": json.loads(json.dumps(CONTACT)),
            "measurement": dict(self.measurement, monitoredLink=0),
        }


# ---- the four drives: each a function of the coordinate that closes it ---------------------------

# the drives' names: their FMUs' model identifiers (spaces become '_': DOHC_I4_8mm.fmu, ...)
SHORT_NAMES = {"dohc_8mm": "DOHC I4 8mm", "sohc_single_cam": "SOHC single cam", "diesel_pump": "Diesel pump",
               "idler": "Idler drive"}


def dohc_8mm(h):
    """(A) DOHC I4, 05B-1, 19/38/38, counterclockwise: the default mirrored (exhaust right)."""
    spacing = 0.115
    return Layout(
        "dohc_8mm", "DOHC I4 timing drive on an 8 mm chain (05B-1, 19/38 T), counterclockwise", CHAIN_05B, +1.0,
        [dict(name="crank", center=(0.0, 0.0), teeth=19, motion="prescribed"),
         dict(name="exhaustCam", center=(spacing / 2.0, h), teeth=38, motion="free", inertia=CAM_INERTIA),
         dict(name="intakeCam", center=(-spacing / 2.0, h), teeth=38, motion="free", inertia=CAM_INERTIA)],
        ["crank", "tensionerArm", "exhaustCam", "intakeCam", "tightGuide"], "tensionerArm", ["tightGuide"],
        {"tightSpan": ["intakeCam", "tightGuide"], "slackSpan": ["tensionerArm", "exhaustCam"]})


def sohc_single_cam(h):
    """(B) SOHC, 06B-1, 21/42, clockwise, the camshaft straight above the crank."""
    return Layout(
        "sohc_single_cam", "SOHC timing drive (06B-1, 21/42 T), clockwise", CHAIN_06B, -1.0,
        [dict(name="crankshaft", center=(0.0, 0.0), teeth=21, motion="prescribed"),
         dict(name="camshaft", center=(0.0, h), teeth=42, motion="free", inertia=CAM_INERTIA)],
        ["crankshaft", "tensionGuide", "camshaft", "fixedGuide"], "tensionGuide", ["fixedGuide"],
        {"tightSpan": ["camshaft", "fixedGuide"], "slackSpan": ["tensionGuide", "camshaft"]})


PUMP_CENTER = (0.135, 0.210)   # (C): beside the tight span, a little above mid-height


def diesel_pump(h):
    """(C) diesel DOHC with the high-pressure pump on the tight side, 06B-1, 21/42/42/28, clockwise."""
    return Layout(
        "diesel_pump", "Diesel DOHC timing drive with the high-pressure pump in the chain (06B-1, 21/42/42/28 T), "
                       "clockwise", CHAIN_06B, -1.0,
        [dict(name="crankshaft", center=(0.0, 0.0), teeth=21, motion="prescribed"),
         dict(name="camshaftExhaust", center=(-0.070, h), teeth=42, motion="free", inertia=CAM_INERTIA),
         dict(name="camshaftIntake", center=(0.070, h), teeth=42, motion="free", inertia=CAM_INERTIA),
         dict(name="hpPump", center=PUMP_CENTER, teeth=28, motion="free", inertia=5.0e-4)],
        ["crankshaft", "tensionGuide", "camshaftExhaust", "camshaftIntake", "hpPump", "fixedGuide"],
        "tensionGuide", ["fixedGuide"],
        {"tightSpan": ["camshaftIntake", "hpPump"], "slackSpan": ["tensionGuide", "camshaftExhaust"]})


IDLER_CENTER = (0.120, 0.235)  # (D): in the middle of the long tight span, pushing it out
CAM_X_IDLER = 0.040


def idler(h):
    """(D) single camshaft with an idler in the long (tight) span, 06B-1, 21/42/19, clockwise."""
    return Layout(
        "idler", "Single-camshaft timing drive with an idler sprocket (06B-1, 21/42/19 T), clockwise", CHAIN_06B, -1.0,
        [dict(name="crankshaft", center=(0.0, 0.0), teeth=21, motion="prescribed"),
         dict(name="camshaft", center=(CAM_X_IDLER, h), teeth=42, motion="free", inertia=CAM_INERTIA),
         dict(name="idler", center=IDLER_CENTER, teeth=19, motion="idler", inertia=1.0e-4)],
        ["crankshaft", "tensionGuide", "camshaft", "idler", "fixedGuide"], "tensionGuide", ["fixedGuide"],
        {"tightSpan": ["camshaft", "idler"], "slackSpan": ["tensionGuide", "camshaft"]})


# file name -> (layout of the closing coordinate, links, nominal height [m] the scan starts from)
DRIVES = {
    "dohc_8mm": (dohc_8mm, 154, 0.440),
    "sohc_single_cam": (sohc_single_cam, 116, 0.400),
    "diesel_pump": (diesel_pump, 138, 0.400),
    "idler": (idler, 130, 0.455),
}

# ---- chaindrive-info ------------------------------------------------------------------------------


def run_info(info, drive, geometry=None):
    """chaindrive-info on a drive dict: (returncode, stdout, stderr)."""
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(drive, f, indent=1)
        path = f.name
    try:
        cmd = [info, "--drive", path] + (["--geometry", geometry] if geometry else [])
        out = subprocess.run(cmd, capture_output=True, text=True)
    finally:
        os.unlink(path)
    return out.returncode, out.stdout, out.stderr


def closure_angle(info, drive):
    rc, out, err = run_info(info, drive)
    if rc != 0:
        return None, err or out
    m = re.search(r"closure: \S+ = (\S+) rad", out)
    return float(m.group(1)), out


def close(info, make, n_links, h_nominal):
    """The height that closes the chain with the tension guide at its drawn pose: the links the
    path holds (Python) bracket it, chaindrive-info's closure angle refines it by secant steps."""
    pitch = make(h_nominal).chain.pitch
    # the path at the drawn pose holds n_links where links_held(h) = n_links (it grows ~2 dh / p)
    h = h_nominal
    for _ in range(20):
        held = links_held(make(h).route_circles(), pitch)
        dh = (n_links - held) * pitch / 2.0
        h += dh
        if abs(dh) < 1e-7:
            break
    h0, h1 = h - 2e-4, h + 2e-4
    a0, msg0 = closure_angle(info, make(h0).drive(n_links))
    a1, msg1 = closure_angle(info, make(h1).drive(n_links))
    if a0 is None or a1 is None:
        sys.exit(f"design failed near h = {h * 1e3:.3f} mm: {msg0 if a0 is None else msg1}")
    for _ in range(40):
        if abs(a1) < 1e-8 or a1 == a0:  # coordinates are written to 0.1 nm
            break
        h2 = h1 - a1 * (h1 - h0) / (a1 - a0)
        h0, a0 = h1, a1
        h1 = h2
        a1, msg = closure_angle(info, make(h1).drive(n_links))
        if a1 is None:
            sys.exit("design failed: " + msg)
    # the coordinates are written to 0.1 nm, which makes the closure angle jump: the best height on
    # that grid around the secant's
    best = (abs(a1), h1, a1)
    hg = round(h1, 10)
    for k in range(-6, 7):
        a, _ = closure_angle(info, make(hg + k * 1e-10).drive(n_links))
        if a is not None and abs(a) < best[0]:
            best = (abs(a), hg + k * 1e-10, a)
    return best[1], best[2]


# ---- checks on the assembled geometry ----------------------------------------------------------


def seg_dist(p, a, b):
    ab = sub(b, a)
    t = max(0.0, min(1.0, dot(sub(p, a), ab) / max(dot(ab, ab), 1e-30)))
    return math.hypot(*sub(p, add(a, ab, t)))


def segments_cross(p1, p2, q1, q2):
    d1, d2 = cross(sub(p2, p1), sub(q1, p1)), cross(sub(p2, p1), sub(q2, p1))
    d3, d4 = cross(sub(q2, q1), sub(p1, q1)), cross(sub(q2, q1), sub(p2, q1))
    return d1 * d2 < 0 and d3 * d4 < 0


def inside(p, poly):
    c = False
    for i in range(len(poly)):
        a, b = poly[i], poly[(i + 1) % len(poly)]
        if (a[1] > p[1]) != (b[1] > p[1]) and p[0] < a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]):
            c = not c
    return c


def check(layout, drive, geo):
    """The geometric checks of the docstring; returns a list of problems (empty: all good)."""
    problems = []
    ch = layout.chain
    pins = [tuple(p) for p in geo["pins"]]
    chords = [(pins[k], pins[(k + 1) % len(pins)]) for k in range(len(pins))]
    tips = [(tuple(s["center"]), s["tipRadius"]) for s in geo["sprockets"]]

    def min_chain_dist(p):
        return min(seg_dist(p, a, b) for a, b in chords)

    for g in geo["guides"]:
        pts = [tuple(p) for face in g["faces"] for p in face]
        d = min(min_chain_dist(p) for p in pts)
        if d < ch.plate_h / 2.0 - 1e-5:
            problems.append(f"guide {g['name']}: face {d * 1e3:.3f} mm from the pin line, less than half the plate height")
        if any(inside(p, pins) for p in pts):
            problems.append(f"guide {g['name']}: face inside the chain's loop")
        for c, r in tips:
            dd = min(math.hypot(*sub(p, c)) for p in pts)
            if dd < r + ch.roller_d / 2.0:
                problems.append(f"guide {g['name']}: face {dd * 1e3:.2f} mm from a sprocket centre, inside its tip "
                                f"circle plus a roller radius ({(r + ch.roller_d / 2) * 1e3:.2f} mm)")
        wraps = [s for s in geo["segments"] if s["kind"] == "wrap" and s["element"] == g["name"]]
        if not wraps or wraps[0]["length"] <= 0.0:
            problems.append(f"guide {g['name']}: the chain does not run on it")
    # the tension guide's arm and the tensioner's body: outside the loop, crossing no chord
    t = geo["tensioner"]
    tg = next(g for g in geo["guides"] if g["pivoting"])
    face = [tuple(p) for p in tg["faces"][0]]
    pivot = tuple(tg["pivot"])
    arm_end = min(face, key=lambda p: math.hypot(*sub(p, pivot)))
    for what, a, b in (("arm", pivot, arm_end), ("tensioner", tuple(t["housing"]), tuple(t["pad"]))):
        if any(segments_cross(a, b, c, d) for c, d in chords) or inside(a, pins) or inside(b, pins):
            problems.append(f"{what} crosses the chain or lies inside its loop")
        for c, r in tips:
            if seg_dist(c, a, b) < r + ch.roller_d / 2.0:
                problems.append(f"{what} enters a sprocket's tip circle")
    # the tensioner turns the guide so that its face moves towards the chain
    torque = cross(sub(tuple(t["pad"]), pivot), tuple(t["direction"]))
    mid = face[len(face) // 2]
    r = sub(mid, pivot)
    move = (-r[1] * math.copysign(1.0, torque), r[0] * math.copysign(1.0, torque))
    near = min(pins, key=lambda p: math.hypot(*sub(p, mid)))
    if dot(move, sub(near, mid)) <= 0.0:
        problems.append("the tensioner turns the tension guide away from the chain")
    # every sprocket wrapped by more than a pitch
    for s in geo["segments"]:
        if s["kind"] == "wrap" and any(sp["name"] == s["element"] for sp in geo["sprockets"]):
            if s["length"] < ch.pitch:
                problems.append(f"sprocket {s['element']}: wrapped by {s['length'] * 1e3:.2f} mm, less than a pitch")
    return problems


def wrap_angles(geo):
    out = {}
    for s in geo["segments"]:
        if s["kind"] == "wrap":
            sp = next((p for p in geo["sprockets"] if p["name"] == s["element"]), None)
            if sp:
                out[s["element"]] = math.degrees(s["length"] / sp["pitchRadius"])
    return out


def picture(geo, path):
    """The assembled drive from its geometry (sprockets, guides, arm, tensioner, pins, probes)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 9.0))
    for s in geo["sprockets"]:
        o = s["outline"] + [s["outline"][0]]
        ax.fill([p[0] * 1e3 for p in o], [p[1] * 1e3 for p in o], color="0.85", lw=0.0)
        ax.plot([p[0] * 1e3 for p in o], [p[1] * 1e3 for p in o], "k-", lw=0.5)
        ax.annotate(s["name"], (s["center"][0] * 1e3, s["center"][1] * 1e3), fontsize=7)
    for g in geo["guides"]:
        for f in g["faces"]:
            ax.plot([p[0] * 1e3 for p in f], [p[1] * 1e3 for p in f], "-", color="tab:blue", lw=3)
        mid = g["faces"][0][len(g["faces"][0]) // 2]
        ax.annotate(g["name"], (mid[0] * 1e3, mid[1] * 1e3), xytext=(5, 5), textcoords="offset points",
                    fontsize=7, color="tab:blue")
        if g["pivoting"]:
            pv = g["pivot"]
            end = min(g["faces"][0], key=lambda p: math.hypot(p[0] - pv[0], p[1] - pv[1]))
            ax.plot([pv[0] * 1e3, end[0] * 1e3], [pv[1] * 1e3, end[1] * 1e3], "-o", color="tab:blue", lw=1.5, ms=4)
    t = geo.get("tensioner")
    if t:
        h, p, d = t["housing"], t["pad"], t["direction"]
        ax.plot([h[0] * 1e3, p[0] * 1e3], [h[1] * 1e3, p[1] * 1e3], "-", color="tab:purple", lw=5)
        ax.annotate("", xy=(p[0] * 1e3 + 12 * d[0], p[1] * 1e3 + 12 * d[1]), xytext=(p[0] * 1e3, p[1] * 1e3),
                    arrowprops=dict(arrowstyle="->", color="tab:purple"))
    pins = geo["pins"] + [geo["pins"][0]]
    ax.plot([p[0] * 1e3 for p in pins], [p[1] * 1e3 for p in pins], "-", color="tab:red", lw=0.8)
    ax.plot(pins[0][0] * 1e3, pins[0][1] * 1e3, "ko", ms=3)
    for k in (1, 2, 3):  # the running direction: the first links
        ax.plot(pins[k][0] * 1e3, pins[k][1] * 1e3, "o", color="tab:orange", ms=2 + k)
    for pr in geo.get("probes", []):
        if pr:
            ax.plot(pr[0] * 1e3, pr[1] * 1e3, "x", color="tab:green", ms=7)
    ax.set_aspect("equal")
    ax.grid(True, lw=0.3)
    ax.set_title(geo["name"], fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


# ---- main ---------------------------------------------------------------------------------------


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--info", required=True, help="path of the chaindrive-info executable")
    ap.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)), help="output folder (tests/drives)")
    ap.add_argument("--only", nargs="*", choices=sorted(DRIVES), help="generate these drives only")
    ap.add_argument("--pictures", help="also draw each drive into this folder (PNG)")
    args = ap.parse_args(argv)
    failed = False
    for name in args.only or DRIVES:
        make, n_links, h_nominal = DRIVES[name]
        h, a = close(args.info, make, n_links, h_nominal)
        layout = make(h)
        drive = layout.drive(n_links)
        path = os.path.join(args.out, name + ".json")
        with open(path, "w") as f:
            json.dump(drive, f, indent=2)
            f.write("\n")
        fd, geo_path = tempfile.mkstemp(suffix=".json")
        os.close(fd)
        try:
            rc, out, err = run_info(args.info, drive, geo_path)
            with open(geo_path) as f:
                geo = json.load(f) if rc == 0 else None
        finally:
            os.unlink(geo_path)
        sys.stdout.write(out)
        sys.stderr.write(err)
        if rc != 0:
            print(f"{name}: chaindrive-info failed (exit {rc})")
            failed = True
            continue
        problems = check(layout, drive, geo)
        crank = layout.crank()["center"]
        cams = [s for s in layout.sprockets if s["motion"] == "free" and s["teeth"] >= 38]
        dist = math.hypot(cams[0]["center"][0] - crank[0], cams[0]["center"][1] - crank[1])
        wraps = ", ".join(f"{k} {v:.1f} deg" for k, v in wrap_angles(geo).items())
        print(f"{name}: {n_links} links, camshaft height {h * 1e3:.6f} mm, crank-cam distance {dist * 1e3:.1f} mm, "
              f"closure angle {a:.3e} rad; wraps: {wraps} -> {path}")
        for p in problems:
            print(f"{name}: CHECK FAILED: {p}")
        failed = failed or bool(problems) or abs(a) > 1e-7
        if args.pictures:
            os.makedirs(args.pictures, exist_ok=True)
            picture(geo, os.path.join(args.pictures, name + ".png"))
        print()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
