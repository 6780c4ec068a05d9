"""A layout (layout_file.LayoutSpec) made a drive description: the guides placed on their spans,
the tension guide's pivot and the tensioner from its face, and the chain closed with its link
count, by a shift of named sprockets (the solver's closure angle brought to zero by secant steps
through chaindrive-info) or by the tension guide itself.
"""
import json
import math
import os
import re
import subprocess
import tempfile

from ..errors import UserError
from . import geometry as geo

WORN_ELONGATION = 0.005   # a timing chain's allowed wear elongation (about 0.5 %)


def r10(v):
    """Coordinates to 0.1 nm: the closure angle moves about 1.4e-7 rad per nm of a camshaft's
    height, so 1 nm would leave up to about 7e-8 rad."""
    return round(v, 10)


def deg(a):
    return round(math.degrees(a), 6)


class Layout:
    """A layout with its closing sprockets shifted by `shift` [m] along the closure's direction."""

    def __init__(self, spec, shift=0.0):
        self.spec, self.shift, self.sense = spec, shift, spec.sense
        self.chain = spec.chain

    def center(self, name):
        s = self.spec.sprocket(name)
        closure = self.spec.closure
        if closure["kind"] == "sprocket-shift" and name in closure["sprockets"]:
            return geo.add(s["center"], closure["direction"], self.shift)
        return s["center"]

    def circle(self, name, pitch=None):
        """The route circle of a sprocket (centre, signed pitch radius); `pitch` for a worn chain."""
        return (self.center(name), self.sense * geo.pitch_radius(pitch or self.chain.pitch,
                                                                 self.spec.sprocket(name)["teeth"]))

    def guides(self):
        """Each guide's face on its span: centre, angle range, the span's direction and outward normal."""
        out, route = {}, self.spec.route
        for i, name in enumerate(route):
            g = self.spec.guide(name)
            if g is None:
                continue
            span = (route[i - 1], route[(i + 1) % len(route)])
            prev, nxt = self.circle(span[0]), self.circle(span[1])
            try:
                t1, t2 = geo.common_tangent(prev[0], prev[1], nxt[0], nxt[1])
                c, u, n = geo.guide_on_span(t1, t2, g.face, self.chain.plate_h, self.sense)
                pin_r = geo.guide_pin_radius(g.face["face_r"], self.chain.plate_h, self.chain.pitch)
                a0, a1 = geo.face_range(prev, c, g.face, nxt, pin_r, self.sense, n)
            except ValueError:
                raise UserError(f"{self.spec.path}: guides: '{name}' (face radius {g.face['face_r'] * 1e3:g} mm pushing "
                                f"{g.face['deflect'] * 1e3:g} mm into the span {span[0]}-{span[1]}): its face's circle "
                                f"meets a sprocket's, so the chain cannot run from one to the other; give it a smaller "
                                f"push_mm or radius_mm, or move the sprockets apart") from None
            out[name] = dict(center=c, u=u, n=n, a0=a0, a1=a1, spec=g, span=span)
        return out

    def mounts(self, guides=None):
        """The tension guide's pivot and the tensioner's pad, housing and plunger direction: the pivot
        `before` beyond the face's end nearer the pivot's sprocket (along the span, away from the face)
        and `behind` the face; the pad at `padAt` of the arm from the pivot, `padBehind` the face; the
        housing further out; the plunger extending towards the chain."""
        t = self.spec.tensioner
        g = (guides or self.guides())[t.guide]
        spec, r = g["spec"], g["spec"].face["face_r"]
        near = self.center(spec.pivot_near or self.spec.prescribed["name"])
        e0, e1 = geo.arc_point(g["center"], r, g["a0"]), geo.arc_point(g["center"], r, g["a1"])
        dist = lambda p: math.hypot(*geo.sub(p, near))  # noqa: E731
        low, high = (e0, e1) if dist(e0) < dist(e1) else (e1, e0)
        along = g["u"] if geo.dot(g["u"], geo.sub(high, low)) > 0.0 else (-g["u"][0], -g["u"][1])
        pivot = geo.add(geo.add(low, along, -spec.pivot_before), g["n"], spec.pivot_behind)
        f = geo.add(pivot, geo.sub(high, pivot), t.pad_at)
        on_face = geo.add(g["center"], geo.unit(geo.sub(f, g["center"])), r)
        pad = geo.add(on_face, g["n"], t.pad_behind)
        housing = geo.add(pad, g["n"], t.housing_out)
        return pivot, pad, housing, (-g["n"][0], -g["n"][1])

    def route_circles(self, pitch=None, guide_turn=0.0):
        """The route's circles for the chain's path; `pitch` for a worn chain, `guide_turn` [rad]
        turns the tension guide about its pivot."""
        p = pitch or self.chain.pitch
        guides = self.guides()
        pivot = self.mounts(guides)[0] if guide_turn else None
        circles = []
        for name in self.spec.route:
            if name not in guides:
                circles.append(self.circle(name, p))
                continue
            g = guides[name]
            c = geo.rotate_about(g["center"], pivot, guide_turn) if pivot and name == self.spec.tensioner.guide else g["center"]
            circles.append((c, -self.sense * geo.guide_pin_radius(g["spec"].face["face_r"], self.chain.plate_h, p)))
        if pivot:
            self.check_on_face(circles, guides[self.spec.tensioner.guide], guide_turn)
        return circles

    def check_on_face(self, circles, guide, turn):
        """ValueError when the chain's tangent points on the turned tension guide leave its face (the
        path would run over the face's end, which the circle of the face does not see)."""
        i = self.spec.route.index(self.spec.tensioner.guide)
        prev, c, nxt = circles[i - 1], circles[i], circles[(i + 1) % len(circles)]
        _, t_in = geo.common_tangent(prev[0], prev[1], c[0], c[1])
        t_out, _ = geo.common_tangent(c[0], c[1], nxt[0], nxt[1])
        mid = 0.5 * (guide["a0"] + guide["a1"])
        for t in (t_in, t_out):
            a = math.atan2(t[1] - c[0][1], t[0] - c[0][0]) - turn - mid
            if abs(math.atan2(math.sin(a), math.cos(a))) > 0.5 * (guide["a1"] - guide["a0"]):
                raise ValueError(f"the chain leaves the face of {self.spec.tensioner.guide}")

    def drive(self, n_links):
        """The drive description (schema chaindrive.drive/1) with n_links links."""
        spec, ch, guides = self.spec, self.chain, self.guides()
        xy = lambda p: [r10(p[0]), r10(p[1])]  # noqa: E731

        def face(g):
            a0 = math.atan2(math.sin(g["a0"]), math.cos(g["a0"]))  # start in (-180, 180] deg
            return {"type": "arc", "center": xy(g["center"]), "radius": g["spec"].face["face_r"],
                    "startAngle_deg": deg(a0), "endAngle_deg": deg(a0 + g["a1"] - g["a0"]), "chainSide": "outside"}

        sprockets = []
        for s in spec.sprockets:
            d = {"name": s["name"], "center": xy(self.center(s["name"])), "teeth": s["teeth"],
                 "toothProfile": {"standard": "ISO 606", "form": s["form"]}, "motion": s["motion"]}
            if s["motion"] != "prescribed":
                d["inertia"] = s["inertia"]
            sprockets.append(d)
        drive_guides = []
        for g in spec.guides:
            d = {"name": g.name, "motion": "pivoting" if g.pivoting else "fixed"}
            if g.pivoting:
                d.update({"pivot": xy(self.mounts(guides)[0]), "inertia": g.inertia,
                          "angleRange_deg": list(g.angle_range_deg)})
            drive_guides.append(dict(d, profile=[face(guides[g.name])]))
        drive = {
            "schema": "chaindrive.drive/1", "name": spec.name, "description": spec.description,
            "rotation": "counterclockwise" if self.sense > 0 else "clockwise", "gravity": list(spec.gravity),
            "chain": {"standard": ch.standard, "pitch": ch.pitch, "numberOfLinks": n_links, "linkMass": ch.link_mass,
                      "linkInertia": ch.link_inertia, "rollerDiameter": ch.roller_d, "plateHeight": ch.plate_h,
                      "joint": {"model": "journal-bearing", "stiffness": ch.joint_stiffness, "damping": ch.joint_damping,
                                "clearance": 0.0},
                      "route": list(spec.route)},
            "sprockets": sprockets, "guides": drive_guides}
        _, pad, housing, direction = self.mounts(guides)
        drive["tensioner"] = {"guide": spec.tensioner.guide, "housing": xy(housing), "direction": xy(direction),
                              "contactPoint": xy(pad), **spec.tensioner.fields}
        drive["contact"] = json.loads(json.dumps(spec.contact))
        drive["measurement"] = dict(spec.measurement, monitoredLink=spec.measurement.get("monitoredLink", 0))
        return drive


# ---- the solver's closure (chaindrive-info) ------------------------------------------------------

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
    """The tension guide's angle [rad] that closes the drive's chain (chaindrive-info), or None and
    the tool's message."""
    rc, out, err = run_info(info, drive)
    if rc != 0:
        return None, (err or out).strip()
    m = re.search(r"closure: \S+ = (\S+) rad", out)
    return float(m.group(1)), out


def shift_for_links(spec, n_links, start=0.0):
    """The shift [m] at which the taut path at the drawn pose holds n_links (the Python path: it
    grows about 2 shift / pitch)."""
    shift = start
    for _ in range(20):
        held = geo.links_held(Layout(spec, shift).route_circles(), spec.chain.pitch)
        step = (n_links - held) * spec.chain.pitch / 2.0
        shift += step
        if abs(step) < 1e-7:
            break
    return shift


def close_by_shift(info, spec, n_links):
    """The shift that closes the chain with n_links and the tension guide at its drawn pose: the
    Python path brackets it, chaindrive-info's closure angle refines it by secant steps, then the
    best on the 0.1 nm grid the coordinates are written to. Returns (shift, angle, message): angle
    None when the solver cannot close it near the path's shift."""
    s = shift_for_links(spec, n_links)
    s0, s1 = s - 2e-4, s + 2e-4
    a0, msg0 = closure_angle(info, Layout(spec, s0).drive(n_links))
    a1, msg1 = closure_angle(info, Layout(spec, s1).drive(n_links))
    if a0 is None or a1 is None:
        return s, None, msg0 if a0 is None else msg1
    for _ in range(40):
        if abs(a1) < 1e-8 or a1 == a0:
            break
        s0, a0, s1 = s1, a1, s1 - a1 * (s1 - s0) / (a1 - a0)
        a1, msg = closure_angle(info, Layout(spec, s1).drive(n_links))
        if a1 is None:
            return s1, None, msg
    best = (abs(a1), s1, a1)
    grid = round(s1, 10)
    for k in range(-6, 7):
        a, _ = closure_angle(info, Layout(spec, grid + k * 1e-10).drive(n_links))
        if a is not None and abs(a) < best[0]:
            best = (abs(a), grid + k * 1e-10, a)
    return best[1], best[2], ""


def guide_turn_for_links(layout, n_links, pitch=None, limit=0.5):
    """The tension guide's turn [rad] about its pivot at which the taut path holds n_links of
    `pitch` (the Python path): steps of 0.02 rad towards more links until the count is passed, then
    bisection; None where it is not found within `limit` rad (or the guide would cut a sprocket)."""
    p = pitch or layout.chain.pitch

    def excess(turn):
        try:
            return geo.links_held(layout.route_circles(p, turn), p) - n_links
        except ValueError:  # (the turned guide overlaps its neighbour, or the chain leaves its face)
            return None

    e0 = excess(0.0)
    if e0 == 0.0:
        return 0.0
    grows = excess(1e-3) > e0   # turning counterclockwise lengthens the path
    step = 0.02 if grows == (e0 < 0.0) else -0.02
    a, b = 0.0, None
    while abs(a + step) <= limit:
        e = excess(a + step)
        if e is None:
            return None
        if (e > 0.0) != (e0 > 0.0):
            b = a + step
            break
        a += step
    if b is None:
        return None
    for _ in range(45):
        m = 0.5 * (a + b)
        e = excess(m)
        if e is None:
            return None
        if (e > 0.0) == (e0 > 0.0):
            a = m
        else:
            b = m
    return 0.5 * (a + b)


def elongation_taken_up(layout, n_links, turn):
    """The largest chain elongation (a fraction) the taut path takes up with the tension guide turned
    by `turn` [rad] (bisection over 0-5 %; None if the guide cannot turn that far)."""
    def excess(e):
        p = layout.chain.pitch * (1.0 + e)
        return geo.links_held(layout.route_circles(p, turn), p) - n_links
    try:
        if excess(0.0) < 0.0:
            return 0.0
        a, b = 0.0, 0.05
        for _ in range(24):
            m = 0.5 * (a + b)
            a, b = (m, b) if excess(m) > 0.0 else (a, m)
        return a
    except ValueError:
        return None
