"""The drive description from Python: its JSON (the default drive or a file), what the
analyses need from it, and its assembled geometry (chaindrive-info)."""
import json
import os
import subprocess
import tempfile

from .. import paths

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
    for s in drive["sprockets"]:
        if s.get("motion") == "prescribed":
            return int(s["teeth"])
    raise ValueError("the drive has no prescribed sprocket")


def geometry(drive=None):
    """Assembled geometry of a drive, from chaindrive-info."""
    fd, tmp = tempfile.mkstemp(suffix=".json")
    os.close(fd)
    try:
        cmd = [paths.executable("chaindrive-info"), "--geometry", tmp, "--quiet"]
        if drive:
            cmd += ["--drive", str(drive)]
        subprocess.run(cmd, check=True, capture_output=True, text=True)
        with open(tmp) as f:
            return json.load(f)
    finally:
        os.unlink(tmp)
