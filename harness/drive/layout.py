"""The layout aid: a drive from sprocket centres and teeth, a chain designation and guides placed on
the spans (a layout file, schema chaindrive.layout/1: docs/drive_layout.md) made the full drive
description the solver and the FMU read, with what an engineer checks on a sketch: the chain's
length and link count, what closes the chain (the shift of named sprockets, or the tension guide's
angle and the tensioner's stroke) and the same for the neighbouring link counts, each sprocket's
wrap and teeth in mesh, the guide faces on the plates' edge, the tensioner's stroke margin new and
with a worn chain (0.5 % elongation), and a picture, also of a layout that does not close (its
gap marked).

    python -m harness layout FILE [--out DRIVE.json] [--picture PNG] [--overwrite-tracked]
"""
import json
import math
import pathlib

from .. import paths
from ..errors import UserError
from . import description, geometry as geo
from .design import check_out
from .layout_checks import check_drive, wraps
from .layout_drive import (WORN_ELONGATION, Layout, close_by_shift, closure_angle, elongation_taken_up,
                           guide_turn_for_links, shift_for_links)
from .layout_file import read_layout

DEFAULT_STROKE_RANGE = (-0.004, 0.006)  # [m] the hydraulic tensioner's end stops (docs/hydraulic_tensioner.md)


def add_arguments(ap):
    ap.add_argument("layout", help="the layout file (schema chaindrive.layout/1)")
    ap.add_argument("--out", help="the drive file to write (default: results/layout/<layout name>.json)")
    ap.add_argument("--picture", help="the picture to draw (PNG; default: beside --out)")
    ap.add_argument("--info", help="the chaindrive-info executable (default: the build's)")
    ap.add_argument("--overwrite-tracked", action="store_true",
                    help="allow --out to be a file of the repository that git tracks (the test drives)")


def link_count(spec, held):
    """The layout's link count, or the nearest even count to what the path holds."""
    return spec.links if spec.links is not None else 2 * round(held / 2.0)


def stroke_of_turn(layout, turn):
    """The plunger's extension [m] when the tension guide turns by `turn` [rad] from its drawn pose."""
    pivot, pad, _, direction = layout.mounts()
    return geo.dot(geo.sub(geo.rotate_about(pad, pivot, turn), pad), direction)


def stroke_range(spec):
    hydraulic = spec.tensioner.fields.get("hydraulic", {})
    if spec.tensioner.fields.get("model") != "hydraulic":
        return None
    return (hydraulic.get("strokeMin", DEFAULT_STROKE_RANGE[0]), hydraulic.get("strokeMax", DEFAULT_STROKE_RANGE[1]))


def describe_chain(chain):
    estimated = [k for k, v in chain.sources.items() if v.startswith("estimated")]
    return (f"chain {chain.standard}: pitch {chain.pitch * 1e3:g} mm, roller {chain.roller_d * 1e3:g} mm, plate "
            f"{chain.plate_h * 1e3:g} mm, {chain.link_mass * 1e3:g} g and {chain.link_inertia:.4g} kg m^2 per link, "
            f"joint {chain.joint_stiffness:.4g} N/m and {chain.joint_damping:g} N s/m"
            + (f" (estimated: {', '.join(estimated)})" if estimated else ""))


def close(info, spec, n_links):
    """(the closed Layout, the solver's tension-guide angle or None, the solver's message)."""
    if spec.closure["kind"] == "sprocket-shift":
        shift, angle, message = close_by_shift(info, spec, n_links)
        return Layout(spec, shift), angle, message
    layout = Layout(spec)
    angle, message = closure_angle(info, layout.drive(n_links))
    return layout, angle, message


def distance_to_prescribed(layout):
    """The distance [m] from the prescribed sprocket to the first shifted one, and that one's name."""
    name = layout.spec.closure["sprockets"][0]
    return math.hypot(*geo.sub(layout.center(name), layout.center(layout.spec.prescribed["name"]))), name


def neighbour_counts(layout, n_links):
    """What closes the chain with n_links - 2, n_links and n_links + 2 (the Python path): a shift and
    centre distance, or the tension guide's turn and the plunger's stroke."""
    spec, parts = layout.spec, []
    for n in (n_links - 2, n_links, n_links + 2):
        if spec.closure["kind"] == "sprocket-shift":
            shifted = Layout(spec, shift_for_links(spec, n, layout.shift))
            distance, name = distance_to_prescribed(shifted)
            parts.append(f"{n}: shift {shifted.shift * 1e3:+.3f} mm ({spec.prescribed['name']}-{name} "
                         f"{distance * 1e3:.3f} mm)")
            continue
        turn = guide_turn_for_links(layout, n)
        parts.append(f"{n}: " + ("beyond the tension guide's reach (its face, the sprockets)" if turn is None else
                                 f"tension guide {math.degrees(turn):+.3f} deg, stroke "
                                 f"{stroke_of_turn(layout, turn) * 1e3:+.3f} mm"))
    return "link counts (path estimate): " + " | ".join(parts)


def report_closure(layout, angle, n_links):
    spec = layout.spec
    if spec.closure["kind"] == "sprocket-shift":
        distance, name = distance_to_prescribed(layout)
        moved = ", ".join(spec.closure["sprockets"])
        d = spec.closure["direction"]
        print(f"closure: {moved} shifted by {layout.shift * 1e3:+.6f} mm along ({d[0]:.4g}, {d[1]:.4g}): "
              f"{spec.prescribed['name']}-{name} {distance * 1e3:.3f} mm; the solver closes {n_links} links with "
              f"the tension guide at {angle:.3e} rad from its drawn pose")
    else:
        print(f"closure: the tension guide at {math.degrees(angle):+.4f} deg from its drawn pose closes {n_links} links "
              f"(solver), the plunger extended by {stroke_of_turn(layout, angle) * 1e3:+.3f} mm")
    print(neighbour_counts(layout, n_links))


def report_tensioner(layout, angle, n_links):
    """The tension guide and the plunger with the new chain and with a worn one, and their margins
    to the guide's angle range and the plunger's end stops."""
    spec = layout.spec
    low, high = spec.guide(spec.tensioner.guide).angle_range_deg
    estimate = guide_turn_for_links(layout, n_links)
    worn = guide_turn_for_links(layout, n_links, spec.chain.pitch * (1.0 + WORN_ELONGATION))
    print(f"tensioner, new chain: guide {math.degrees(angle):+.4f} deg (path estimate "
          f"{'none' if estimate is None else f'{math.degrees(estimate):+.4f}'} deg), stroke "
          f"{stroke_of_turn(layout, angle) * 1e3:+.3f} mm")
    if worn is None:
        reach, taken = largest_take_up(layout, n_links, low, high)
        print(f"tensioner, worn chain ({WORN_ELONGATION:.1%} longer): NOT taken up: the tension guide takes up at most "
              f"{taken:.2%} elongation, turned {reach:+.1f} deg with the plunger out "
              f"{stroke_of_turn(layout, math.radians(reach)) * 1e3:+.3f} mm (the last 0.5 deg step within its range "
              f"[{low:g}, {high:g}] deg and the plunger's end stop, the chain on its face, clear of the sprockets)")
        return
    worn_deg, stroke = math.degrees(worn), stroke_of_turn(layout, worn)
    margin_deg = high - worn_deg if worn > angle else worn_deg - low
    text = (f"tensioner, worn chain ({WORN_ELONGATION:.1%} longer): guide {worn_deg:+.4f} deg (margin "
            f"{margin_deg:.3f} deg to its range [{low:g}, {high:g}] deg), stroke {stroke * 1e3:+.3f} mm")
    stops = stroke_range(spec)
    if stops:
        text += (f" (margin {(stops[1] - stroke if stroke >= 0.0 else stroke - stops[0]) * 1e3:.3f} mm to the "
                 f"end stops [{stops[0] * 1e3:g}, {stops[1] * 1e3:g}] mm)")
    print(text)


def largest_take_up(layout, n_links, low, high):
    """How far [deg] the tension guide can turn into the chain (within its angle range and the
    plunger's end stop, the chain on its face, its face's circle clear of the sprockets'; steps of
    0.5 deg) and the elongation it takes up there."""
    held = lambda turn: geo.links_held(layout.route_circles(None, math.radians(turn)), layout.chain.pitch)  # noqa
    sign = 1.0 if held(0.1) > held(0.0) else -1.0   # (into the chain: the path grows)
    reach, taken, turn = 0.0, elongation_taken_up(layout, n_links, 0.0), 0.5
    stops = stroke_range(layout.spec)
    while turn <= (high if sign > 0 else -low):
        e = elongation_taken_up(layout, n_links, math.radians(sign * turn))
        if e is None or (stops and stroke_of_turn(layout, math.radians(sign * turn)) > stops[1]):
            break
        reach, taken, turn = sign * turn, e, turn + 0.5
    return reach, taken


def report_guides(layout):
    for name, g in layout.guides().items():
        f = g["spec"].face
        print(f"guide {name}: face R {f['face_r'] * 1e3:g} mm on the span {g['span'][0]}-{g['span'][1]} at {f['at']:g} "
              f"of it, pushing {f['deflect'] * 1e3:g} mm into the taut line, its plates' edge on the face (pin line "
              f"{layout.chain.plate_h / 2 * 1e3:g} mm off it), {math.degrees(g['a1'] - g['a0']):.2f} deg of face")


def output_paths(args, spec):
    stem = pathlib.Path(args.layout).name.split(".")[0]
    args.out = args.out or str(paths.RESULTS / "layout" / f"{stem}.json")
    out = check_out(args)
    return out, pathlib.Path(args.picture) if args.picture else out.with_suffix(".png")


def refuse_open(layout, n_links, held, message, picture):
    """A layout the solver cannot close: the sketch with its gap, and one line saying what to change."""
    from ..plots.layout_sketch import layout_sketch
    spec = layout.spec
    gap = layout_sketch(picture, layout, n_links, f"{spec.name}: does not close with {n_links} links")
    print(neighbour_counts(layout, n_links))
    print(f"sketch with the gap marked: {picture}")
    raise UserError(f"{spec.path}: the chain does not close with {n_links} links (the path at the drawn centres holds "
                    f"{held:.3f}; gap {gap * 1e3:.2f} mm): {message.splitlines()[0] if message else 'no closure'}")


def run(args):
    from ..plots.drive_picture import drive_picture
    spec = read_layout(args.layout)
    out, picture = output_paths(args, spec)
    info = args.info or str(paths.executable("chaindrive-info"))
    held = geo.links_held(Layout(spec).route_circles(), spec.chain.pitch)
    n_links = link_count(spec, held)
    print(f"layout {args.layout}: {spec.name}, {'counter' if spec.sense > 0 else ''}clockwise")
    print(describe_chain(spec.chain))
    print(f"path at the drawn centres: {held * spec.chain.pitch * 1e3:.2f} mm, {held:.3f} links -> {n_links} links "
          f"({'the layout' if spec.links is not None else 'the nearest even count'})")
    layout, angle, message = close(info, spec, n_links)
    picture.parent.mkdir(parents=True, exist_ok=True)
    if angle is None:
        refuse_open(layout, n_links, held, message, picture)
    drive = layout.drive(n_links)
    report_closure(layout, angle, n_links)
    geometry = description.geometry(drive, info)
    teeth = {s["name"]: s["teeth"] for s in spec.sprockets}
    print("wraps: " + ", ".join(f"{k} {w:.1f} deg ({m:.1f} teeth in mesh)" for k, (w, m) in wraps(geometry, teeth).items()))
    report_guides(layout)
    report_tensioner(layout, angle, n_links)
    problems = check_drive(spec.chain, geometry)
    with open(out, "w") as f:
        json.dump(drive, f, indent=2)
        f.write("\n")
    drive_picture(str(picture), str(out), spec.name)
    print(f"written: {out}, {picture}")
    if problems:
        raise UserError(f"{spec.path}: {problems[0]}" + (f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""))
    print("checks: every guide face on the plates' edge outside the loop, arm and tensioner clear, every sprocket "
          "wrapped by more than a pitch")
