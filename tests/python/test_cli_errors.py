"""A user's mistake on the command line of the harness ends in one line on stderr, `error: ...`,
naming the option or field, the value and what is allowed, with exit status 2 and no traceback;
--debug (before or after the command) shows the traceback too (harness/cli.py, harness/errors.py)."""
import json

import pytest

from harness import paths
from harness.errors import UserError, tool_failure
from harness_cli import harness, one_error_line

DEFAULT_DRIVE = paths.ROOT / "src" / "drives" / "default_drive.json"


def misspelled_drive(tmp_path):
    """The default drive with the key chain.pitch spelled chain.pitchh."""
    drive = json.loads(DEFAULT_DRIVE.read_text())
    drive["chain"]["pitchh"] = drive["chain"].pop("pitch")
    path = tmp_path / "misspelled.json"
    path.write_text(json.dumps(drive))
    return path


@pytest.mark.parametrize("rpm", ["99999", "-5"])
def test_speed_outside_the_tables_names_the_option_value_and_range(rpm, tmp_path):
    line = one_error_line(*harness("run", "--rpm", rpm, "--out", str(tmp_path))[::2])
    assert f"--rpm {rpm}: outside the tabulated engine speeds [1000, 6000] rpm" in line, line


def test_missing_tables_folder_is_named(tmp_path):
    missing = tmp_path / "no-such-tables"
    line = one_error_line(*harness("run", "--tables", str(missing), "--out", str(tmp_path))[::2])
    assert f"--tables {missing}: no such folder" in line, line


def test_tables_folder_without_tables_is_named(tmp_path):
    line = one_error_line(*harness("run", "--tables", str(tmp_path), "--out", str(tmp_path))[::2])
    assert f"--tables {tmp_path}: no crankshaft_speed_<n>rpm.csv tables there" in line, line


def test_misspelled_drive_field_is_named_by_its_export(tmp_path):
    drive = misspelled_drive(tmp_path)
    line = one_error_line(*harness("run", "--drive", str(drive), "--cycles", "2", "--out", str(tmp_path))[::2])
    assert line.startswith("error: chaindrive-info: "), line
    assert "chain.pitchh: unknown key" in line and "chain.pitch: missing" in line, line


def test_a_blow_up_names_the_step_and_keeps_the_outputs_up_to_it(tmp_path):
    """A step far beyond the stable one: one error line with the FMU's reason, and outputs.csv
    holding every step up to the failure."""
    line = one_error_line(*harness("run", "--rpm", "6000", "--solver-step", "2e-5", "--cycles", "2", "--run-in", "1",
                                   "--out", str(tmp_path))[::2])
    assert "fmi2DoStep" in line and "fmi2Discard" in line and "every output up to the failure" in line, line
    with open(tmp_path / "outputs.csv") as f:
        rows = f.read().splitlines()
    assert rows[0].startswith("time,") and len(rows) >= 2


def test_solver_step_refused_by_the_fmu_is_written_with_its_unit(tmp_path):
    line = one_error_line(*harness("run", "--solver-step", "1e-10", "--cycles", "2", "--out", str(tmp_path))[::2])
    assert "solver.step = 1e-10 s is outside [1e-9 s, 0.001 s]" in line, line


def test_unknown_option_after_run_is_runs_error(tmp_path):
    line = one_error_line(*harness("run", "--bogus", "3", "--out", str(tmp_path))[::2])
    assert "unrecognized arguments: --bogus 3" in line and "python -m harness run --help" in line, line


def test_unknown_command_is_one_line():
    line = one_error_line(*harness("runn")[::2])
    assert "invalid choice: 'runn'" in line, line


@pytest.mark.parametrize("where", ["before", "after"])
def test_debug_shows_the_traceback(where, tmp_path):
    argv = ["run", "--rpm", "99999", "--out", str(tmp_path)]
    status, _, err = harness(*(["--debug"] + argv if where == "before" else argv + ["--debug"]))
    assert status == 2
    assert "Traceback (most recent call last)" in err and "harness.errors.UserError" in err, err
    assert err.splitlines()[-1].startswith("error: --rpm 99999"), err


def test_run_help_shows_run_in_as_cycles():
    status, out, _ = harness("run", "--help")
    assert status == 0
    assert "--run-in CYCLES" in out and "--run-in S" not in out


def test_cvt_description_error_of_the_tool_is_one_line(tmp_path):
    cvt = json.loads((paths.ROOT / "src" / "drives" / "default_cvt.json").read_text())
    cvt["chain"]["pitchh"] = cvt["chain"].pop("pitch")
    path = tmp_path / "misspelled_cvt.json"
    path.write_text(json.dumps(cvt))
    line = one_error_line(*harness("run", "--scene", "cvt", "--cvt", str(path), "--out", str(tmp_path))[::2])
    assert line.startswith("error: chaindrive-cvt: ") and "chain.pitchh: unknown key" in line, line


def test_tool_failure_joins_the_tools_lines_and_caps_them():
    e = tool_failure("chaindrive-cvt", "chaindrive-cvt: error: a | b\nc\n\nd\ne\n", limit=4)
    assert isinstance(e, UserError) and isinstance(e, RuntimeError)
    assert str(e) == "chaindrive-cvt: a | b | c | d | and 1 more"


def test_design_drive_writes_over_no_tracked_file_unless_asked():
    """design-drive's --out names a file of the repository (the default drive): refused before any
    design run, the file untouched; --overwrite-tracked is the way to replace it."""
    if not (paths.ROOT / ".git").exists():
        pytest.skip("not a git checkout: nothing is tracked")
    default_drive = paths.ROOT / "src" / "drives" / "default_drive.json"
    before = default_drive.read_bytes()
    line = one_error_line(*harness("design-drive", "--info", paths.executable("chaindrive-info"),
                                   "--out", str(default_drive))[::2])
    assert "a file of the repository (git tracks it); give --overwrite-tracked" in line, line
    assert default_drive.read_bytes() == before
