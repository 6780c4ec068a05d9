"""The drive files the tests use beside the default drive are what they say they are."""
import json

from harness import paths
from harness.drive import design


def test_the_spring_damper_variant_is_the_default_drive_with_the_spring_damper_law():
    """tests/data/drives/default_drive_spring_damper.json (the FMI call fuzz's drive file) is
    design.spring_damper_variant of the default drive, so it follows the default drive."""
    default = json.loads((paths.ROOT / "src" / "drives" / "default_drive.json").read_text())
    variant = json.loads((paths.ROOT / "tests" / "data" / "drives" / "default_drive_spring_damper.json").read_text())
    assert default["tensioner"]["model"] == "hydraulic"
    assert variant == design.spring_damper_variant(default)
    assert "model" not in variant["tensioner"] and variant["tensioner"]["damping"] > 0.0
