"""The layout file (schema `chaindrive.layout/1`, docs/drive_layout.md): a drive as an engineer
sketches it: sprocket centres and teeth, the chain by its ISO 606 designation, the route, the
guides placed on the spans, the tensioner relative to its guide's face, and what closes the
chain. Read into a LayoutSpec in SI units; every mistake is a UserError naming the file, the field,
the value and what is allowed. Lengths are given in metres (`center`) or millimetres
(`center_mm`), angles in degrees (`_deg`).
"""
import dataclasses
import json
import math

from ..errors import UserError
from . import design
from .chains import CHAINS, ChainData, JOINT_DAMPING
from .description import drive_json

SCHEMA = "chaindrive.layout/1"

# the default drive's guides and tensioner (design.py, docs/default_drive.md): what a layout leaves out
TENSION_GUIDE_DEFAULTS = dict(face_r=design.TG_FACE_R, deflect=design.TG_DEFLECT, at=design.TG_AT,
                              margin=design.TG_MARGIN)
FIXED_GUIDE_DEFAULTS = dict(face_r=design.G_FACE_R, deflect=design.G_DEFLECT, at=design.G_AT, margin=design.G_MARGIN)
PIVOT_BEFORE, PIVOT_BEHIND = design.TG_PIVOT_BEFORE, design.TG_PIVOT_BEHIND   # [m]
PAD_AT, PAD_BEHIND, HOUSING_OUT = design.PAD_AT, design.PAD_BEHIND, design.HOUSING_OUT
TENSION_GUIDE_INERTIA, ANGLE_RANGE_DEG = design.TG_INERTIA, design.TG_ANGLE_RANGE_DEG
TENSIONER_DEFAULTS = {"preload": design.TENS_PRELOAD, "stiffness": design.TENS_K, "model": "hydraulic"}
OWN_CHAIN_FIELDS = ("pitch", "rollerDiameter", "plateHeight", "linkMass", "linkInertia")
# the fields given as lengths (metres, or millimetres with the suffix _mm)
LENGTHS = {"pitch", "rollerDiameter", "plateHeight", "center", "radius", "push", "margin", "before", "behind",
           "padBehind", "housing"}
TOP_FIELDS = ("schema", "name", "description", "rotation", "gravity", "chain", "sprockets", "route", "guides",
              "tensioner", "contact", "closure", "measurement")
GUIDE_FIELDS = ("name", "motion", "radius", "push", "at", "margin")
PIVOTING_FIELDS = GUIDE_FIELDS + ("inertia", "angleRange_deg", "pivot")
# the drive schema's tensioner fields a layout passes on (the drive's reader checks them)
TENSIONER_FIELDS = ("guide", "padAt", "padBehind", "housing", "model", "preload", "stiffness", "damping",
                    "dampingExtension", "hydraulic")


@dataclasses.dataclass(frozen=True)
class GuideSpec:
    name: str
    pivoting: bool
    face: dict                  # face_r, deflect, at, margin [m, m, fraction, m]
    inertia: float = 0.0
    angle_range_deg: tuple = ANGLE_RANGE_DEG
    pivot_near: str = ""        # the pivot lies at the face's end nearer this sprocket's centre
    pivot_before: float = PIVOT_BEFORE
    pivot_behind: float = PIVOT_BEHIND


@dataclasses.dataclass(frozen=True)
class TensionerSpec:
    guide: str
    pad_at: float               # the pad at this fraction of the arm from the pivot to the far end
    pad_behind: float           # [m] behind the face
    housing_out: float          # [m] the housing behind the pad
    fields: dict                # the drive schema's tensioner fields besides its geometry


@dataclasses.dataclass(frozen=True)
class LayoutSpec:
    path: str
    name: str
    description: str
    sense: float                # +1 counterclockwise, -1 clockwise
    chain: ChainData
    links: int | None           # None: the nearest even count to the path
    sprockets: tuple            # dicts: name, center, teeth, motion, inertia, form
    route: tuple
    guides: tuple               # GuideSpec in the file's order
    tensioner: TensionerSpec
    contact: dict
    closure: dict               # {"kind": "tensioner"} or {"kind": "sprocket-shift", "sprockets", "direction"}
    measurement: dict | None
    gravity: list

    def sprocket(self, name):
        return next(s for s in self.sprockets if s["name"] == name)

    def guide(self, name):
        return next((g for g in self.guides if g.name == name), None)

    @property
    def prescribed(self):
        return next(s for s in self.sprockets if s["motion"] == "prescribed")


class Reader:
    """Field access with errors naming the file and the field."""

    def __init__(self, path):
        self.path = path

    def fail(self, field, problem):
        raise UserError(f"{self.path}: {field}: {problem}")

    def number(self, obj, key, where, default=None, positive=False, low=None, high=None):
        value = obj.get(key, default)
        if value is None:
            self.fail(f"{where}{key}", "missing (a number)")
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            self.fail(f"{where}{key}", f"{json.dumps(value)} is not a finite number")
        if positive and value <= 0.0:
            self.fail(f"{where}{key}", f"{value} must be positive")
        if (low is not None and value < low) or (high is not None and value > high):
            self.fail(f"{where}{key}", f"{value} lies outside [{low}, {high}]")
        return float(value)

    def known(self, obj, where, allowed):
        """A misspelled or misplaced field is an error, not a default silently taken: every key of obj
        is one of `allowed` (lengths also with the suffix _mm)."""
        if not isinstance(obj, dict):
            self.fail(where.rstrip(".") or "(file)", f"{json.dumps(obj)} is not an object")
        names = set(allowed) | {a + "_mm" for a in allowed if a in LENGTHS}
        for key in obj:
            if key not in names:
                self.fail(f"{where}{key}", f"not a field here; the fields: {', '.join(sorted(names))}")

    def once(self, obj, key, where):
        if key in obj and key + "_mm" in obj:
            self.fail(f"{where}{key}", f"given twice ({key} and {key}_mm): give one")

    def length(self, obj, key, where, default=None, positive=False):
        """A length given as `key` [m] or `key_mm` [mm], in metres."""
        self.once(obj, key, where)
        if key + "_mm" in obj:
            return self.number(obj, key + "_mm", where, positive=positive) / 1000.0
        return self.number(obj, key, where, default=default, positive=positive)

    def point(self, obj, key, where):
        """A point [x, y] given as `key` [m] or `key_mm` [mm], in metres."""
        self.once(obj, key, where)
        mm = key + "_mm" in obj
        value = obj.get(key + "_mm" if mm else key)
        field = f"{where}{key}{'_mm' if mm else ''}"
        if not (isinstance(value, list) and len(value) == 2):
            self.fail(field, f"{json.dumps(value)} is not a point [x, y]")
        xy = [self.number({"v": v}, "v", field + "[]") for v in value]
        return (xy[0] / 1000.0, xy[1] / 1000.0) if mm else (xy[0], xy[1])

    def choice(self, obj, key, where, allowed, default=None):
        value = obj.get(key, default)
        if value not in allowed:
            self.fail(f"{where}{key}", f"{json.dumps(value)} is not one of {', '.join(allowed)}")
        return value


def read_chain(rd, obj):
    """The chain by designation (with optional overrides) or by its own dimensions."""
    if not isinstance(obj, dict):
        rd.fail("chain", "missing (an object with designation, or pitch, rollerDiameter, plateHeight, linkMass, "
                         "linkInertia)")
    designation = obj.get("designation")
    if designation is not None and designation not in CHAINS:
        rd.fail("chain.designation", f"{json.dumps(designation)} is not one of {', '.join(CHAINS)} "
                                     "(or give the chain's own pitch, rollerDiameter, plateHeight, linkMass, linkInertia)")
    base = CHAINS.get(designation)
    own = {}
    for key in OWN_CHAIN_FIELDS:
        if key in obj or key + "_mm" in obj or base is None:
            read = rd.length if key in ("pitch", "rollerDiameter", "plateHeight") else rd.number
            own[key] = read(obj, key, "chain.", positive=True)
    rd.known(obj, "chain.", ("designation", "standard", "numberOfLinks", "joint") + OWN_CHAIN_FIELDS)
    joint = obj.get("joint", {})
    rd.known(joint, "chain.joint.", ("stiffness", "damping"))
    stiffness = rd.number(joint, "stiffness", "chain.joint.", default=base.joint_stiffness if base else None,
                          positive=True)
    damping = rd.number(joint, "damping", "chain.joint.", default=JOINT_DAMPING, low=0.0)
    sources = dict(base.sources) if base else {}
    sources.update({key: "the layout file" for key in own})
    sources.update({f"joint.{key}": "the layout file" for key in joint})
    pick = lambda key, attr: own.get(key, getattr(base, attr) if base else None)  # noqa: E731
    return ChainData(designation or obj.get("standard", "own chain"), pick("pitch", "pitch"),
                     pick("rollerDiameter", "roller_d"), pick("plateHeight", "plate_h"), pick("linkMass", "link_mass"),
                     pick("linkInertia", "link_inertia"), stiffness, damping, sources)


def read_links(rd, chain):
    links = chain.get("numberOfLinks")
    if links is None:
        return None
    if isinstance(links, bool) or not isinstance(links, int) or links < 4 or links % 2:
        rd.fail("chain.numberOfLinks", f"{json.dumps(links)} is not an even integer of at least 4 (or leave it out: "
                                       "the nearest even count to the path)")
    return links


def read_sprockets(rd, items):
    if not isinstance(items, list) or not items:
        rd.fail("sprockets", "missing (a list of {name, center_mm, teeth, motion, inertia})")
    out = []
    for k, obj in enumerate(items):
        where = f"sprockets[{k}]."
        name = obj.get("name") if isinstance(obj, dict) else None
        if not isinstance(name, str) or not name:
            rd.fail(f"{where}name", f"{json.dumps(name)} is not a name")
        motion = rd.choice(obj, "motion", where, ("prescribed", "free", "idler"), default="free")
        teeth = obj.get("teeth")
        if isinstance(teeth, bool) or not isinstance(teeth, int) or not 7 <= teeth <= 200:
            rd.fail(f"{where}teeth", f"{json.dumps(teeth)} is not an integer from 7 to 200")
        inertia = rd.number(obj, "inertia", where, positive=True) if motion != "prescribed" else None
        form = rd.choice(obj, "toothForm", where, ("min", "mean", "max"), default="mean")
        out.append(dict(name=name, center=rd.point(obj, "center", where), teeth=teeth, motion=motion,
                        inertia=inertia, form=form))
    if sum(s["motion"] == "prescribed" for s in out) != 1:
        rd.fail("sprockets", "exactly one sprocket has motion \"prescribed\" (the crankshaft: its speed drives the chain)")
    for k, (obj, sprocket) in enumerate(zip(items, out)):
        rd.known(obj, f"sprockets[{k}].", ("name", "center", "teeth", "motion", "toothForm")
                 + (("inertia",) if sprocket["motion"] != "prescribed" else ()))
    return tuple(out)


def read_guide(rd, obj, where, sprocket_names):
    name = obj.get("name") if isinstance(obj, dict) else None
    if not isinstance(name, str) or not name:
        rd.fail(f"{where}name", f"{json.dumps(name)} is not a name")
    pivoting = rd.choice(obj, "motion", where, ("fixed", "pivoting")) == "pivoting"
    rd.known(obj, where, PIVOTING_FIELDS if pivoting else GUIDE_FIELDS)
    d = TENSION_GUIDE_DEFAULTS if pivoting else FIXED_GUIDE_DEFAULTS
    face = dict(face_r=rd.length(obj, "radius", where, default=d["face_r"], positive=True),
                deflect=rd.length(obj, "push", where, default=d["deflect"]),
                at=rd.number(obj, "at", where, default=d["at"], low=0.05, high=0.95),
                margin=rd.length(obj, "margin", where, default=d["margin"]))
    if not pivoting:
        return GuideSpec(name, False, face)
    pivot = obj.get("pivot", {})
    rd.known(pivot, where + "pivot.", ("near", "before", "behind"))
    near = pivot.get("near")
    if near is not None and near not in sprocket_names:
        rd.fail(f"{where}pivot.near", f"{json.dumps(near)} is not a sprocket ({', '.join(sprocket_names)})")
    angles = obj.get("angleRange_deg", list(ANGLE_RANGE_DEG))
    if not (isinstance(angles, list) and len(angles) == 2 and angles[0] < 0.0 < angles[1]):
        rd.fail(f"{where}angleRange_deg", f"{json.dumps(angles)} is not [low, high] with low < 0 < high")
    return GuideSpec(name, True, face, rd.number(obj, "inertia", where, default=TENSION_GUIDE_INERTIA, positive=True),
                     tuple(float(a) for a in angles), near or "",
                     rd.length(pivot, "before", where + "pivot.", default=PIVOT_BEFORE),
                     rd.length(pivot, "behind", where + "pivot.", default=PIVOT_BEHIND))


def read_guides(rd, items, sprocket_names):
    if not isinstance(items, list):
        rd.fail("guides", "not a list of guides")
    return tuple(read_guide(rd, obj, f"guides[{k}].", sprocket_names) for k, obj in enumerate(items))


def read_tensioner(rd, obj, guides):
    """The tensioner on its pivoting guide (left out: the default drive's, on the pivoting guide)."""
    pivoting = [g.name for g in guides if g.pivoting]
    if not pivoting:   # (the solver closes the chain with the tensioner's guide)
        rd.fail("guides", "no pivoting guide: a drive needs a tension guide with its tensioner (motion \"pivoting\")")
    obj = {} if obj is None else obj   # (the default drive's tensioner on the one pivoting guide)
    rd.known(obj, "tensioner.", TENSIONER_FIELDS)
    guide = obj.get("guide", pivoting[0] if len(pivoting) == 1 else None)
    if guide not in pivoting:
        rd.fail("tensioner.guide", f"{json.dumps(guide)} is not a pivoting guide ({', '.join(pivoting) or 'none'})")
    fields = {k: v for k, v in obj.items() if k not in ("guide", "padAt", "padBehind", "padBehind_mm", "housing",
                                                          "housing_mm")}
    fields = {**TENSIONER_DEFAULTS, **fields}
    return TensionerSpec(guide, rd.number(obj, "padAt", "tensioner.", default=PAD_AT, low=0.1, high=1.0),
                         rd.length(obj, "padBehind", "tensioner.", default=PAD_BEHIND),
                         rd.length(obj, "housing", "tensioner.", default=HOUSING_OUT, positive=True), fields)


def read_route(rd, route, sprockets, guides):
    names = [s["name"] for s in sprockets] + [g.name for g in guides]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        rd.fail("sprockets/guides", f"the name '{duplicates[0]}' is given twice: names are unique")
    if not isinstance(route, list) or len(route) < 2:
        rd.fail("route", "missing (the sprocket and guide names in running order)")
    for name in route:
        if name not in names:
            rd.fail("route", f"{json.dumps(name)} is neither a sprocket nor a guide ({', '.join(names)})")
    unrouted = [n for n in names if n not in route]
    if unrouted or len(set(route)) != len(route):
        rd.fail("route", f"every sprocket and guide once: {', '.join(unrouted) or 'a name repeats'}")
    for k, name in enumerate(route):
        if name not in [s["name"] for s in sprockets] and route[k - 1] not in [s["name"] for s in sprockets]:
            rd.fail("route", f"guide '{name}' follows guide '{route[k - 1]}': a guide lies on a span between sprockets")
    return tuple(route)


def read_closure(rd, obj, sprockets):
    """{"kind": "tensioner"} (default: the tension guide takes up the chain at the centres as drawn)
    or {"kind": "sprocket-shift", "sprockets": [...], "direction": [dx, dy]}: these sprockets move
    together along the direction until the chain closes with the tension guide at its drawn pose."""
    obj = {"kind": "tensioner"} if obj is None else obj
    rd.known(obj, "closure.", ("kind", "sprockets", "direction"))
    kind = rd.choice(obj, "kind", "closure.", ("tensioner", "sprocket-shift"))
    if kind == "tensioner":
        return {"kind": kind}
    names = [s["name"] for s in sprockets]
    moved = obj.get("sprockets")
    if not isinstance(moved, list) or not moved or any(n not in names for n in moved):
        rd.fail("closure.sprockets", f"{json.dumps(moved)} is not a list of sprockets ({', '.join(names)})")
    if any(s["motion"] == "prescribed" for s in sprockets if s["name"] in moved):
        rd.fail("closure.sprockets", "the prescribed sprocket stays where it is drawn: shift the others")
    dx, dy = rd.point(obj, "direction", "closure.")
    norm = math.hypot(dx, dy)
    if norm == 0.0:
        rd.fail("closure.direction", "[0, 0] has no direction")
    return {"kind": kind, "sprockets": tuple(moved), "direction": (dx / norm, dy / norm)}


def default_measurement(sprockets, route, tensioner):
    """The test drives' spans: the tight span leaves the last of the largest sprockets (the
    camshafts) along the route, the slack span leaves the tension guide."""
    free = [n for n in route if any(s["name"] == n and s["motion"] != "prescribed" for s in sprockets)]
    largest = max(s["teeth"] for s in sprockets if s["name"] in free)
    last = [n for n in free if next(s for s in sprockets if s["name"] == n)["teeth"] == largest][-1]
    after = lambda name: route[(route.index(name) + 1) % len(route)]  # noqa: E731
    return {"tightSpan": [last, after(last)], "slackSpan": [tensioner.guide, after(tensioner.guide)]}


def read_layout(path):
    """The LayoutSpec of a layout file."""
    rd = Reader(path)
    try:
        with open(path) as f:
            obj = json.load(f)
    except (OSError, ValueError) as e:
        raise UserError(f"{path}: {e}")
    if not isinstance(obj, dict) or obj.get("schema") != SCHEMA:
        rd.fail("schema", f"{json.dumps(obj.get('schema') if isinstance(obj, dict) else None)} is not \"{SCHEMA}\"")
    rd.known(obj, "", TOP_FIELDS)
    sense = {"clockwise": -1.0, "counterclockwise": 1.0}[rd.choice(obj, "rotation", "", ("clockwise", "counterclockwise"))]
    chain = obj.get("chain")
    sprockets = read_sprockets(rd, obj.get("sprockets"))
    names = [s["name"] for s in sprockets]
    guides = read_guides(rd, obj.get("guides", []), names)
    if obj.get("measurement") is not None:   # (its spans are checked by the drive's reader)
        rd.known(obj["measurement"], "measurement.", ("tightSpan", "slackSpan", "monitoredLink"))
    tensioner = read_tensioner(rd, obj.get("tensioner"), guides)
    route = read_route(rd, obj.get("route"), sprockets, guides)
    name = obj.get("name")
    if not isinstance(name, str) or not name.strip():
        rd.fail("name", f"{json.dumps(name)} is not a name (it names the drive's FMU)")
    return LayoutSpec(str(path), name, obj.get("description") or f"Made by python -m harness layout {path}.", sense,
                      read_chain(rd, chain),
                      read_links(rd, chain), sprockets, route, guides, tensioner,
                      obj.get("contact", drive_json()["contact"]), read_closure(rd, obj.get("closure"), sprockets),
                      obj["measurement"] if obj.get("measurement") is not None
                      else default_measurement(sprockets, route, tensioner),
                      obj.get("gravity", [0.0, -9.81]))
