"""python -m harness fidelity (harness/study/fidelity.py): its options refused with the option and
the allowed forms named, a short run of both fidelities through ChainDrive.fmu with its
comparison and recommendation, and the accuracy table of the report from saved comparisons."""
import json
import subprocess
import sys

import pytest

from harness import cli, paths


def refused(capsys, *argv):
    """The error message of a command line that the fidelity command refuses."""
    with pytest.raises(SystemExit) as e:
        cli.main(["fidelity", *argv])
    assert e.value.code == 2
    return capsys.readouterr().err


@pytest.mark.parametrize("spec", ["tensioner.F.mean", "tensioner.F.mean=3dB", "orders=3%", "nosuch=3%",
                                  "tensioner.F.mean=-2%"])
def test_bad_tolerances_name_the_option_and_the_allowed_forms(capsys, spec):
    err = refused(capsys, "--tolerance", "tensioner.F.mean=2%", "--tolerance", spec)
    assert f"--tolerance {spec!r}" in err
    assert "allowed forms: KEY=X%" in err and "KEY=XdB" in err and "orders=XdB" in err


def test_link_summary_must_be_a_link_run_at_the_speed(capsys, tmp_path):
    err = refused(capsys, "--link-summary", str(tmp_path / "missing.json"))
    assert "--link-summary" in err and "not readable" in err
    (tmp_path / "summary.json").write_text(json.dumps({"tensioner.F.mean": {}}))
    assert "missing" in refused(capsys, "--link-summary", str(tmp_path / "summary.json"))


def test_cycles_and_report_options_are_checked(capsys, tmp_path):
    assert "--link-cycles 1" in refused(capsys, "--link-cycles", "1")
    assert "--study goes with --report" in refused(capsys, "--study", str(tmp_path))
    assert "--report" in refused(capsys, "--report", str(tmp_path))  # no fidelity.json there


@pytest.fixture(scope="module")
def short_ladder(tmp_path_factory):
    """Both fidelities at 6000 rpm after the main job's run-in (8 cycles): 2 counted cycles of the
    link model (a few seconds) and 4 of the span model."""
    out = tmp_path_factory.mktemp("fidelity")
    p = subprocess.run([sys.executable, "-m", "harness", "fidelity", "--rpm", "6000", "--cycles", "4",
                        "--link-cycles", "2", "--tolerance", "tensioner.F.mean=50%", "--tolerance", "orders=40dB",
                        "--out", str(out)], cwd=paths.ROOT, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    return out, p.stdout, json.loads((out / "fidelity.json").read_text())


def test_a_short_ladder_compares_both_fidelities(short_ladder):
    out, text, c = short_ladder
    assert c["span"]["cycles"] == 4 and c["link"]["cycles"] == 2
    keys = [r["key"] for r in c["rows"]]
    assert keys[0] == "tensioner.F.mean" and any(".order" in k for k in keys)
    for side in ("link", "span"):
        assert c[side]["cpuPerSimulatedSecond"] > 0
        assert json.loads((out / side / "run.json").read_text())["fidelity"] == side
        assert set(json.loads((out / side / "summary.json").read_text())) == set(c["summaries"][side])
    # the span model is the cheaper: it is recommended exactly when it meets every tolerance
    assert c["span"]["cpuPerSimulatedSecond"] < c["link"]["cpuPerSimulatedSecond"]
    assert c["recommendation"] == ("span" if c["spanMeetsAll"] else "link")
    assert "recommendation: " + c["recommendation"] in text and "within scatter" in text


def test_the_report_table_from_saved_comparisons(short_ladder, tmp_path):
    out, _, c = short_ladder
    p = subprocess.run([sys.executable, "-m", "harness", "fidelity", "--report", str(out),
                        "--out", str(tmp_path / "fidelity.md")], cwd=paths.ROOT, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    text = (tmp_path / "fidelity.md").read_text()
    assert text.startswith("## Fidelity ladder: span model against link model")
    assert "| tensioner.F.mean |" in text and "6000 rpm: link" in text
