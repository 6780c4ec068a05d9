"""The drive description from Python: its JSON (the default drive or a file), what the
analyses need from it, and its assembled geometry (chaindrive-info)."""
import dataclasses
import json
import os
import subprocess
import tempfile

from .. import paths
from ..errors import tool_failure

DEFAULT_DRIVE = paths.ROOT / "src" / "drives" / "default_drive.json"


def drive_json(path=None):
    """The drive description as a dict (the default drive when path is None)."""
    with open(path or DEFAULT_DRIVE) as f:
        return json.load(f)


# the oil viscosity law's range of temperatures where a drive's hydraulic tensioner gives none
# (src/description/hydraulic_tensioner.h, OilDesc: 20-150 C)
OIL_TEMPERATURE_RANGE = (293.15, 423.15)  # [K]


def is_hydraulic(drive):
    """Whether the drive's tensioner is the hydraulic device (tensioner.model "hydraulic"; the
    spring-damper law is the schema's default)."""
    return drive.get("tensioner", {}).get("model", "spring-damper") == "hydraulic"


# a hydraulic tensioner's gauge supply pressure where the drive gives none (src/description/
# hydraulic_tensioner.h, HydraulicDesc::supplyPressure)
SUPPLY_PRESSURE = 3e5  # [Pa]


def supply_pressure(drive):
    """The gauge supply pressure [Pa] of the drive's hydraulic tensioner (tensioner.hydraulic.supplyPressure)."""
    return drive.get("tensioner", {}).get("hydraulic", {}).get("supplyPressure", SUPPLY_PRESSURE)


def oil_temperature_range(drive):
    """(lowest, highest) oil temperature [K] of the drive's hydraulic tensioner: its oil law's range,
    where the FMU accepts the parameter tensioner.oilTemperature."""
    oil = drive.get("tensioner", {}).get("hydraulic", {}).get("oil", {})
    return (oil.get("temperatureMin", OIL_TEMPERATURE_RANGE[0]), oil.get("temperatureMax", OIL_TEMPERATURE_RANGE[1]))


def clearance_or_rigid(drive):
    """Whether the drive's joints have clearance (chain.joint.clearance > 0) or its contacts are rigid
    (contact.method other than compliant): its solver defaults are then the table's row for such
    drives (harness/defaults.py)."""
    clearance = drive.get("chain", {}).get("joint", {}).get("clearance", 0.0)
    rigid = drive.get("contact", {}).get("method", "compliant") != "compliant"
    return (isinstance(clearance, (int, float)) and clearance > 0.0) or rigid


def meshing_order(drive):
    """The crankshaft meshing order: the number of teeth of the prescribed (crankshaft) sprocket,
    in engine orders per crankshaft revolution."""
    return elements(drive).crank_teeth


@dataclasses.dataclass(frozen=True)
class Sprocket:
    name: str
    teeth: int
    loaded: bool      # a load-torque input (motion "free"); False: an idler


@dataclasses.dataclass(frozen=True)
class Elements:
    """A drive's elements by role, named as its FMU's variables are (src/interface/): what the
    master loop, the cycle statistics and the plots need of a drive."""
    crank: str                    # the prescribed sprocket (its speed input <crank>.w, angle <crank>.phi)
    crank_teeth: int
    free: tuple                   # Sprocket of every free sprocket, in the interface's order (tight side first)
    tension_guide: str | None     # the tensioner's guide (<name>.phi), None without a tensioner
    hydraulic: bool               # the tensioner is hydraulic (its chamber and supply pressure)
    tight_span: bool              # the drive measures a tight span (output chain.Ftight)
    slack_span: bool              # and a slack span (chain.Fslack)

    @property
    def meshing_order(self):
        """The crankshaft meshing order: the prescribed sprocket's teeth, orders per crankshaft revolution."""
        return self.crank_teeth

    @property
    def loaded(self):
        """The names of the sprockets with a load-torque input."""
        return [s.name for s in self.free if s.loaded]

    def ratio(self, name):
        """Crankshaft revolutions per revolution of sprocket `name` (its teeth over the crankshaft's)."""
        return next(s.teeth for s in self.free if s.name == name) / self.crank_teeth


def elements(drive=None):
    """The Elements of a drive (a dict, a file, or None: the default drive); the free sprockets and
    pivoting guides in the order of the FMU interface (src/interface/drive_interface.cpp: from the
    prescribed sprocket against the running direction along the route)."""
    d = drive if isinstance(drive, dict) else drive_json(drive)
    sprockets = {s["name"]: s for s in d["sprockets"]}
    crank = next((s for s in d["sprockets"] if s.get("motion") == "prescribed"), None)
    if crank is None:
        raise ValueError("the drive has no prescribed sprocket")
    route = d["chain"]["route"]
    start = route.index(crank["name"]) if crank["name"] in route else 0
    order = [route[(start - i) % len(route)] for i in range(1, len(route))]
    free = tuple(Sprocket(n, int(sprockets[n]["teeth"]), sprockets[n].get("motion") == "free")
                 for n in order if n in sprockets)
    tensioner = d.get("tensioner")
    measured = d.get("measurement", {})
    return Elements(crank["name"], int(crank["teeth"]), free, tensioner["guide"] if tensioner else None,
                    is_hydraulic(d), len(measured.get("tightSpan", [])) == 2, len(measured.get("slackSpan", [])) == 2)


def geometry(drive=None, info=None):
    """Assembled geometry of a drive (a file, a description dict, or None: the default drive), from
    chaindrive-info (`info`: its executable; default the build's)."""
    fd, tmp = tempfile.mkstemp(suffix=".json")
    os.close(fd)
    written = None
    try:
        if isinstance(drive, dict):
            fd, written = tempfile.mkstemp(suffix=".json")
            with os.fdopen(fd, "w") as f:
                json.dump(drive, f)
        cmd = [info or paths.executable("chaindrive-info"), "--geometry", tmp, "--quiet"]
        if drive:
            cmd += ["--drive", str(written or drive)]
        done = subprocess.run(cmd, capture_output=True, text=True)
        if done.returncode != 0:  # (a drive that does not load or close: its one line, no traceback)
            raise tool_failure("chaindrive-info", done.stderr)
        with open(tmp) as f:
            return json.load(f)
    finally:
        for path in (tmp, written):
            if path:
                os.unlink(path)
