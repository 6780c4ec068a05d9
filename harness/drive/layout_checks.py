"""The checks a layout aid makes on the drive it wrote, from the solver's assembled geometry
(chaindrive-info --geometry): every guide face outside the chain's loop on the plates' edge and
clear of the sprockets, the tension guide's arm and the tensioner's body clear of the chain and
the sprockets, the tensioner turning its guide towards the chain, every sprocket wrapped by more
than a pitch; and what the sketch reports of each sprocket's wrap.
"""
import math

from . import geometry as geo


def check_guides(chain, geometry, chords, tips):
    problems = []
    for g in geometry["guides"]:
        pts = [tuple(p) for face in g["faces"] for p in face]
        d = min(min(geo.seg_dist(p, a, b) for a, b in chords) for p in pts)
        if d < chain.plate_h / 2.0 - 1e-5:
            problems.append(f"guide {g['name']}: face {d * 1e3:.3f} mm from the pin line, less than half the plate height")
        if any(geo.inside(p, [c[0] for c in chords]) for p in pts):
            problems.append(f"guide {g['name']}: face inside the chain's loop")
        for c, r in tips:
            dd = min(math.hypot(*geo.sub(p, c)) for p in pts)
            if dd < r + chain.roller_d / 2.0:
                problems.append(f"guide {g['name']}: face {dd * 1e3:.2f} mm from a sprocket centre, inside its tip "
                                f"circle plus a roller radius ({(r + chain.roller_d / 2) * 1e3:.2f} mm)")
        wraps = [s for s in geometry["segments"] if s["kind"] == "wrap" and s["element"] == g["name"]]
        if not wraps or wraps[0]["length"] <= 0.0:
            problems.append(f"guide {g['name']}: the chain does not run on it")
    return problems


def check_tensioner(chain, geometry, chords, tips):
    problems, t = [], geometry.get("tensioner")
    if not t:
        return problems
    pins = [c[0] for c in chords]
    tg = next(g for g in geometry["guides"] if g["pivoting"])
    face, pivot = [tuple(p) for p in tg["faces"][0]], tuple(tg["pivot"])
    arm_end = min(face, key=lambda p: math.hypot(*geo.sub(p, pivot)))
    for what, a, b in (("arm", pivot, arm_end), ("tensioner", tuple(t["housing"]), tuple(t["pad"]))):
        if any(geo.segments_cross(a, b, c, d) for c, d in chords) or geo.inside(a, pins) or geo.inside(b, pins):
            problems.append(f"{what} crosses the chain or lies inside its loop")
        for c, r in tips:
            if geo.seg_dist(c, a, b) < r + chain.roller_d / 2.0:
                problems.append(f"{what} enters a sprocket's tip circle")
    torque = geo.cross(geo.sub(tuple(t["pad"]), pivot), tuple(t["direction"]))
    mid = face[len(face) // 2]
    r = geo.sub(mid, pivot)
    move = (-r[1] * math.copysign(1.0, torque), r[0] * math.copysign(1.0, torque))
    near = min(pins, key=lambda p: math.hypot(*geo.sub(p, mid)))
    if geo.dot(move, geo.sub(near, mid)) <= 0.0:
        problems.append("the tensioner turns the tension guide away from the chain")
    return problems


def check_drive(chain, geometry):
    """The problems of an assembled drive (empty: every check passed)."""
    pins = [tuple(p) for p in geometry["pins"]]
    chords = [(pins[k], pins[(k + 1) % len(pins)]) for k in range(len(pins))]
    tips = [(tuple(s["center"]), s["tipRadius"]) for s in geometry["sprockets"]]
    problems = check_guides(chain, geometry, chords, tips) + check_tensioner(chain, geometry, chords, tips)
    for s in geometry["segments"]:
        if s["kind"] == "wrap" and any(sp["name"] == s["element"] for sp in geometry["sprockets"]):
            if s["length"] < chain.pitch:
                problems.append(f"sprocket {s['element']}: wrapped by {s['length'] * 1e3:.2f} mm, less than a pitch")
    return problems


def wraps(geometry, teeth):
    """Each sprocket's wrap angle [deg] and teeth in mesh on the assembled chain (teeth: by name)."""
    out = {}
    for s in geometry["segments"]:
        sp = next((p for p in geometry["sprockets"] if p["name"] == s["element"]), None)
        if s["kind"] == "wrap" and sp:
            angle = s["length"] / sp["pitchRadius"]
            out[s["element"]] = (math.degrees(angle), angle / (2.0 * math.pi) * teeth[s["element"]])
    return out
