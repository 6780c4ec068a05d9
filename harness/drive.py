"""The drive description from Python: its JSON (the default drive or a file) and what the
analyses need from it."""
import json

from . import paths

DEFAULT_DRIVE = paths.ROOT / "src" / "drives" / "default_drive.json"


def drive_json(path=None):
    """The drive description as a dict (the default drive when path is None)."""
    with open(path or DEFAULT_DRIVE) as f:
        return json.load(f)


def meshing_order(drive):
    """The crankshaft meshing order: the number of teeth of the prescribed (crankshaft) sprocket,
    in engine orders per crankshaft revolution."""
    for s in drive["sprockets"]:
        if s.get("motion") == "prescribed":
            return int(s["teeth"])
    raise ValueError("the drive has no prescribed sprocket")
