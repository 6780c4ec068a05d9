"""python -m harness drive-steps: its judgement on ensembles with known answers (no runs)."""
import math

from harness.study import drive_steps
from harness.study.errors import joint_limit


def stat(mean, ci95):
    return {"mean": mean, "ci95": ci95, "cycles": 240, "unit": "N"}


def test_agreement_is_z_against_the_combined_interval_within_the_joint_limit():
    reference = {"a": stat(100.0, 3.0), "b": stat(10.0, 0.3), "c": stat(1.0, math.nan)}
    found = {"a": stat(104.0, 4.0), "b": stat(12.0, 0.4), "c": stat(1.0, 0.1)}
    a = drive_steps.agreement(found, reference)
    assert set(a["z"]) == {"a", "b"}  # (no interval: not judged)
    assert math.isclose(a["z"]["a"], 4.0 / 5.0) and math.isclose(a["z"]["b"], 2.0 / 0.5)
    assert math.isclose(a["limit"], joint_limit(2)) and a["outside"] == ["b"]
    assert math.isclose(a["maxAbsZ"], 4.0)


def point(energy, reference_energy, outside=()):
    summary = {"a": stat(100.0, 3.0)}
    return {"default": {"summary": summary, "energyBalance": energy, "runIn": [8, 8], "cpu": 10.0},
            "reference": {"summary": summary, "energyBalance": reference_energy, "runIn": [8, 8], "cpu": 20.0},
            "agreement": {"z": {"a": 0.0}, "limit": 1.0, "outside": list(outside), "maxAbsZ": 0.0}}


def test_the_verdict_names_the_worst_energy_balance_and_what_lies_outside():
    good = drive_steps.verdict(point([-0.01, -0.03], [-0.01, 0.0]))
    assert "energy balance -3.00 %" in good and "beyond" not in good and "outside" not in good
    bad = drive_steps.verdict(point([-0.02, -0.09], [-0.02, -0.01], outside=["tensioner.F.mean"]))
    assert "-9.00 % (**beyond the limit**)" in bad and "half step -2.00 %" in bad
    assert "**outside**: tensioner.F.mean" in bad
    blown = drive_steps.verdict({"default": {"failed": "joint 21 stretched", "replica": 0}, "reference": {}})
    assert blown.startswith("**blow-up**") and "joint 21 stretched" in blown
