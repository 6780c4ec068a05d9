"""The span model's cost benchmark (harness/bench/fidelity_cost.py), its step study
(harness/study/span_steps.py) and the pulse response (harness/study/pulse_response.py): the
report's ratio, the C master's replay with the fmpy run's bits, short runs and the option checks."""
import argparse
import json
import math

import pytest

from harness import cli
from harness.bench import fidelity_cost
from harness.study import pulse_response, span_steps


def parse(module, argv):
    ap = argparse.ArgumentParser()
    module.add_arguments(ap)
    return module.check(ap, ap.parse_args(argv))


def test_ratio_lines_judge_the_c_masters_figures():
    config = argparse.Namespace(method="fixed-verlet-implicit-joint-damping", solver_step=1e-4 / 28)
    meets = fidelity_cost.lines_of(1e-4, {"link": (1.0, 1.1, config), "span": (0.04, 0.07, None)})[0]
    assert "ratio **1/25.0**" in meets and "meets" in meets and "1/15.7" in meets
    misses = fidelity_cost.lines_of(1e-3, {"link": (1.0, 1.0, config), "span": (0.06, 0.06, None)})[0]
    assert "ratio **1/16.7**" in misses and "MISSES" in misses


@pytest.mark.parametrize("module, argv, message", [
    (fidelity_cost, ["--cycles", "0"], "--cycles 0"),
    (fidelity_cost, ["--repeats", "0"], "--repeats 0"),
    (span_steps, ["--cycles", "1"], "--cycles 1"),
    (span_steps, ["--steps", "1e-5"], "a reference and at least one more"),
    (span_steps, ["--steps", "1e-5", "2e-3"], "each in (0, 1e-3] s"),
])
def test_option_errors_name_the_option(module, argv, message, capsys):
    with pytest.raises(SystemExit):
        parse(module, argv)
    assert message in capsys.readouterr().err


def test_short_benchmark_replays_with_the_same_bits(tmp_path):
    out = tmp_path / "cost.md"
    # (a replay whose outputs differ from the fmpy run's raises: the run returning 0 says they agree)
    assert cli.main(["bench-fidelity", "--rpm", "3000", "--cycles", "1", "--repeats", "1", "--out", str(out)]) == 0
    report = out.read_text()
    assert "## 3000 rpm" in report and "C master" in report
    assert report.count("span model RTF") == 2 and "0.1 ms communication steps" in report


def test_benchmark_of_another_drive_replays_that_drives_fmu(tmp_path):
    # (the replay on the default drive's FMU differs from the drive's run at its first step)
    out = tmp_path / "cost.md"
    drive = "tests/data/drives/default_drive_spring_damper.json"
    assert cli.main(["bench-fidelity", "--rpm", "3000", "--cycles", "1", "--repeats", "1", "--drive", drive,
                     "--out", str(out)]) == 0
    assert f"Drive: {drive}." in out.read_text()


def test_short_step_study_compares_with_the_reference(tmp_path):
    out = tmp_path / "steps"
    assert cli.main(["span-steps", "--rpm", "3000", "--steps", "2.5e-5", "5e-5", "--cycles", "2",
                     "--out", str(out)]) == 0
    found = json.loads((out / "steps.json").read_text())["speeds"]["3000"]
    rows = found[repr(5e-5)]["rows"]
    assert {r["key"] for r in rows} >= {"tensioner.F.mean", "tensionGuide.phi.peakToPeak_deg"}
    assert "## 3000 rpm (reference: 25 us)" in (out / "steps.md").read_text()


@pytest.mark.parametrize("argv, message", [(["--rpm", "50"], "--rpm 50"), (["--pulse", "0"], "--pulse 0"),
                                           (["--replicas", "1"], "--replicas 1")])
def test_pulse_response_option_errors_name_the_option(argv, message, capsys):
    with pytest.raises(SystemExit):
        parse(pulse_response, argv)
    assert message in capsys.readouterr().err


def test_pulse_response_gives_each_models_mode_and_decay(tmp_path):
    out = tmp_path / "pulse"
    assert cli.main(["pulse-response", "--replicas", "2", "--out", str(out)]) == 0
    found = json.loads((out / "pulse.json").read_text())["fidelities"]
    for fidelity in ("link", "span"):
        f = found[fidelity]
        assert f["largest_rad"] > 0.0 and f["frequency_Hz"] > pulse_response.HIGH_PASS
        assert math.isfinite(f["decayRate_per_s"]) and max(f["envelopeOverLargest"].values()) <= 1.0
        fitted = f["fitted"]
        assert len(fitted["pairs"]) == 2 and fitted["frequency_Hz"]["mean"] > pulse_response.HIGH_PASS
        assert fitted["frequency_Hz"]["ci95"] >= 0.0 and 0.0 < fitted["dampingRatio"]["mean"] < 1.0
    assert "| link |" in (out / "pulse.md").read_text()
