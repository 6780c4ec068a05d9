"""Plane geometry of a drive's layout, as the solver's chain path sees it (x right, y up, metres;
a sense of +1 is counterclockwise, -1 clockwise): the route's circles and their common tangents,
the taut path around them, the links it holds, guide faces placed on a span, and the small
vector helpers they are written with. The layout aid (layout.py) and the default drive's design
(design.py) build on it; the solver's own closure (src/assembly/chain_path.cpp) decides in the end.
"""
import math


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


def rotate_about(p, centre, angle):
    """p turned by `angle` [rad, counterclockwise] about centre."""
    c, s = math.cos(angle), math.sin(angle)
    d = sub(p, centre)
    return (centre[0] + c * d[0] - s * d[1], centre[1] + s * d[0] + c * d[1])


def arc_point(c, r, a):
    return (c[0] + r * math.cos(a), c[1] + r * math.sin(a))


# ---- the chain's circles -------------------------------------------------------------------------

def pitch_radius(pitch, teeth):
    return pitch / (2.0 * math.sin(math.pi / teeth))


def tip_radius(pitch, roller_d, teeth):
    """Tip radius of the ISO 606 mean tooth form (src/description/drive_description.cpp)."""
    d = 2.0 * pitch_radius(pitch, teeth)
    da_max = d + 1.25 * pitch - roller_d
    da_min = d + pitch * (1.0 - 1.6 / teeth) - roller_d
    return 0.25 * (da_max + da_min)


def guide_pin_radius(face_r, plate_h, pitch):
    """Pin circle of a convex guide face: chords of one pitch whose plate edges touch it (the
    solver's guidePinRadius)."""
    return math.hypot(face_r + plate_h / 2.0, pitch / 2.0)


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


# ---- guides on a span ----------------------------------------------------------------------------

def guide_on_span(t1, t2, g, plate_h, sense):
    """Centre of an arc face (radius g["face_r"]) pressing g["deflect"] into the straight span
    t1 -> t2 from outside the loop, at the fraction g["at"] of the span from t1: its plates' edges
    on the face, so the pin line runs half a plate height off it. Returns the centre, the span's
    direction and its outward normal."""
    length = math.hypot(*sub(t2, t1))
    u = unit(sub(t2, t1))
    n = outward(u, sense)
    mid = add(t1, u, g["at"] * length)
    return add(mid, n, g["face_r"] + plate_h / 2.0 - g["deflect"]), u, n


def face_range(prev, centre, g, nxt, pin_radius, sense, n):
    """Angles [rad] of a guide face covering where the taut chain runs on it (its tangent points to
    the previous and the next route circle, each (centre, signed radius)) plus g["margin"] at both
    ends; continuous around the direction from the face's centre towards the span (-n)."""
    s = -sense * pin_radius
    _, tin = common_tangent(prev[0], prev[1], centre, s)
    tout, _ = common_tangent(centre, s, nxt[0], nxt[1])
    ref = math.atan2(-n[1], -n[0])

    def ang(p):
        a = math.atan2(p[1] - centre[1], p[0] - centre[0]) - ref
        return ref + math.atan2(math.sin(a), math.cos(a))

    lo, hi = sorted((ang(tin), ang(tout)))
    return lo - g["margin"] / g["face_r"], hi + g["margin"] / g["face_r"]


# ---- the taut path and the links it holds --------------------------------------------------------

def path_segments(circles):
    """The closed path around route circles [(centre, signed radius)]: per element its arc (centre,
    |r|, start angle, signed sweep, length) and the span after it (from, to, length)
    (chain_path.cpp, through)."""
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


def path_length(segs):
    return sum(g[5] for g in segs)


def path_point(segs, s):
    s %= path_length(segs)
    for g in segs:
        if s <= g[5] or g is segs[-1]:
            if g[0] == "arc":
                return arc_point(g[1], g[2], g[3] + math.copysign(1.0, g[4]) * s / g[2])
            return add(g[1], sub(g[2], g[1]), s / g[5] if g[5] > 0 else 0.0)
        s -= g[5]


def next_pin(segs, s, pitch):
    """Arc length of the next pin one pitch (a chord) beyond the pin at arc length s."""
    a, b = s + pitch, s + 1.6 * pitch
    q = path_point(segs, s)
    for _ in range(60):
        m = 0.5 * (a + b)
        if math.hypot(*sub(path_point(segs, m), q)) < pitch:
            a = m
        else:
            b = m
    return 0.5 * (a + b)


def links_held(circles, pitch):
    """How many links of one pitch the path holds: chords walked from the middle of the first wrap,
    the last part the chord from the last whole link's pin back to the first pin over the pitch
    (continuous in the layout: an arc length there would jump by the arc's excess over its chord
    whenever a pin passes the start)."""
    segs = path_segments(circles)
    length = path_length(segs)
    s0 = segs[0][5] / 2.0
    first = path_point(segs, s0)
    s, k = s0, 0
    while True:
        after = next_pin(segs, s, pitch)
        if after - s0 >= length:
            return k + math.hypot(*sub(first, path_point(segs, s))) / pitch
        s, k = after, k + 1


def pins_walked(circles, pitch, count):
    """The pins of `count` links walked along the path from the middle of the first wrap (count + 1
    points: the last meets the first when the chain closes)."""
    segs = path_segments(circles)
    s = segs[0][5] / 2.0
    pins = [path_point(segs, s)]
    for _ in range(count):
        s = next_pin(segs, s, pitch)
        pins.append(path_point(segs, s))
    return pins


# ---- checks on an assembled chain ----------------------------------------------------------------

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
