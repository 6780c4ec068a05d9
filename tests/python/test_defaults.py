"""The solver defaults are one table (src/run/defaults.h, printed by chaindrive-info --defaults) that
every entry point uses: the command-line tools, both FMUs (their model descriptions and their
runs) and the harness's jobs."""
import json
import re
import subprocess
import xml.etree.ElementTree as ET
import zipfile

import pytest

from harness import defaults, job, paths
from harness.cvt import job as cvt_job
from harness.fmu import fmu


@pytest.fixture(scope="module")
def table():
    text = subprocess.run([paths.executable("chaindrive-info"), "--defaults"], capture_output=True, text=True,
                          check=True).stdout
    return json.loads(text)


def help_text(tool):
    p = subprocess.run([paths.executable(tool), "--help"], capture_output=True, text=True)
    return p.stdout + p.stderr


def parameter_starts(description):
    """The solver parameters' starts and descriptions of a model description: CVTChain's written by
    hand, ChainDrive's generated from the default drive (the built FMU's)."""
    if description == "ChainDrive":
        root = ET.fromstring(zipfile.ZipFile(fmu.fmu_path()).read("modelDescription.xml"))
    else:
        root = ET.parse(paths.ROOT / "modelDescription" / description).getroot()
    starts = {}
    for sv in root.iter("ScalarVariable"):
        if sv.get("name").startswith("solver."):
            typ = [c for c in sv if c.tag in ("Real", "Integer", "Boolean", "String")][0]
            starts[sv.get("name")] = (typ.get("start"), sv.get("description"))
    return starts


def test_the_table_has_every_scene_and_fidelity(table):
    assert set(table) == {"timing", "cvt"}
    assert set(table["timing"]) == {"link", "span"} and set(table["cvt"]) == {"link"}
    for rows in table.values():
        for row in rows.values():
            assert row["step_s"] > 0.0 and 0.0 < row["tolerance"] < 1.0 and row["method"]


@pytest.mark.parametrize("fidelity", ["link", "span"])
def test_the_timing_job_defaults_to_the_table(table, fidelity):
    config = job.run_config(fidelity=fidelity)
    row = table["timing"][fidelity]
    assert (config.method, config.solver_step, config.rtol) == (row["method"], row["step_s"], row["tolerance"])


def test_the_cvt_job_defaults_to_the_table(table):
    config = cvt_job.CVTConfig()
    row = table["cvt"]["link"]
    assert (config.method, config.solver_step, config.rtol) == (row["method"], row["step_s"], row["tolerance"])


def test_the_command_line_tools_default_to_the_table(table):
    link, span, cvt = table["timing"]["link"], table["timing"]["span"], table["cvt"]["link"]
    run = help_text("chaindrive-run")
    assert re.search(rf"--integrator NAME .*\(default {link['method']}\)", run)
    assert f"link {link['step_s']:g}, span {span['step_s']:g}" in run
    assert f"(default {link['tolerance']:g})" in run
    text = help_text("chaindrive-cvt")
    assert f"default {cvt['method']}\n" in text
    assert f"--step S             fixed step [s] (default {cvt['step_s']:g})" in text
    assert f"(default {cvt['tolerance']:g})" in text


def test_the_model_descriptions_start_from_the_table(table):
    link, span, cvt = table["timing"]["link"], table["timing"]["span"], table["cvt"]["link"]
    clearance = link["clearanceOrRigid"]
    chain = parameter_starts("ChainDrive")
    method, text = chain["solver.method"]
    assert method == ""  # empty: the fidelity's own method, named in the description
    assert f"the fidelity's own, {link['method']} (link) or {span['method']} (span); a drive whose joints have " \
           f"clearance, or rigid contacts: {clearance['method']} (link)" in text
    assert float(chain["solver.tolerance"][0]) == link["tolerance"]
    step, text = chain["solver.step"]
    assert float(step) == 0.0  # 0: the drive's own step, the default drive's named in the description
    named = {fidelity: float(value) for value, fidelity in re.findall(r"([0-9.e+-]+) s \((link|span)\)", text)}
    assert named == {"link": link["step_s"], "span": span["step_s"]}
    named = re.findall(r"([0-9.e+-]+) s \(link, a drive whose joints have clearance, or rigid contacts\)", text)
    assert [float(value) for value in named] == [clearance["step_s"]]
    belt = parameter_starts("CVTChain.xml")
    assert belt["solver.method"][0] == cvt["method"]
    assert float(belt["solver.tolerance"][0]) == cvt["tolerance"]
    assert float(belt["solver.step"][0]) == cvt["step_s"]


@pytest.mark.parametrize("fidelity", ["link", "span"])
def test_the_fmu_steps_with_the_fidelitys_default_step(table, fidelity):
    """Without solver.step the FMU takes the fidelity's step: a 0.1 ms communication step is 0.1 ms /
    step integrator steps."""
    slave = fmu.Slave(f"defaults-{fidelity}", parameters={"fidelity": fidelity})
    slave.initialize(inputs={"crankshaft.w": fmu.rpm_to_rad_s(3000.0)})
    slave.step(1e-4, t=0.0)
    steps = slave.get(["solver.steps"])["solver.steps"]
    slave.close()
    assert steps == round(1e-4 / table["timing"][fidelity]["step_s"])


def test_the_defaults_page_shows_the_table(table):
    """docs/defaults.md's table rows are the table's, row by row."""
    page = (paths.ROOT / "docs" / "defaults.md").read_text()
    rows = re.findall(r"^\| (timing|cvt) \| (link|span)( \(joints with clearance, or rigid contacts\))? \| ([\w-]+) \| ([0-9.e+-]+) s \| "
                      r"([0-9.e+-]+) \|", page, re.M)
    shown = {(scene, fidelity, bool(clearance)): (method, float(step), float(tol))
             for scene, fidelity, clearance, method, step, tol in rows}
    expected = {}
    for scene, fidelities in table.items():
        for fidelity, row in fidelities.items():
            for clearance, r in ((False, row), (True, row.get("clearanceOrRigid"))):
                if r:
                    expected[scene, fidelity, clearance] = (r["method"], r["step_s"], r["tolerance"])
    assert shown == expected


def test_time_stepping_takes_the_rigid_contacts_row(table, tmp_path):
    """Time stepping integrates rigid contacts, which the real-time method does not: without
    solver.step the FMU steps it at the table's row for rigid contacts, chosen by its parameter
    contact.method or by the drive's contact method; the harness's job takes that row for such a
    drive too."""
    row = table["timing"]["link"]["clearanceOrRigid"]
    drive = json.loads((paths.ROOT / "src" / "drives" / "default_drive.json").read_text())
    drive["contact"]["method"] = "time-stepping"
    rigid_drive = tmp_path / "rigid_drive.json"
    rigid_drive.write_text(json.dumps(drive))
    for name, parameters in (("parameter", {"contact.method": "time-stepping"}), ("drive", {"driveFile": str(rigid_drive)})):
        slave = fmu.Slave(f"defaults-rigid-{name}", parameters=parameters)
        slave.initialize(inputs={"crankshaft.w": fmu.rpm_to_rad_s(3000.0)})
        slave.step(1e-4, t=0.0)
        steps = slave.get(["solver.steps"])["solver.steps"]
        slave.close()
        assert steps == round(1e-4 / row["step_s"]), name
    config = job.run_config(drive=str(rigid_drive))
    assert (config.method, config.solver_step) == (row["method"], row["step_s"])


@pytest.fixture(scope="module")
def clearance_drive(tmp_path_factory):
    """The default drive with 20 um of clearance in its joints."""
    drive = json.loads((paths.ROOT / "src" / "drives" / "default_drive.json").read_text())
    drive["chain"]["joint"]["clearance"] = 2e-5
    path = tmp_path_factory.mktemp("clearance") / "clearance_drive.json"
    path.write_text(json.dumps(drive))
    return path


def test_a_drive_with_joint_clearance_takes_its_own_row(table, clearance_drive):
    """The link fidelity's real-time method needs joints without clearance: a drive whose joints
    have clearance runs the table's row for it in the FMU, chaindrive-run and the harness's job."""
    row = drive_table(clearance_drive)["timing"]["link"]["clearanceOrRigid"]  # (its own step: not the default drive)
    assert row["method"] != table["timing"]["link"]["method"]
    slave = fmu.Slave("defaults-clearance", parameters={"driveFile": str(clearance_drive)})
    slave.initialize(inputs={"crankshaft.w": fmu.rpm_to_rad_s(3000.0)})
    slave.step(1e-4, t=0.0)
    steps = slave.get(["solver.steps"])["solver.steps"]
    slave.close()
    assert steps == round(1e-4 / row["step_s"])
    summary = clearance_drive.parent / "summary.json"
    subprocess.run([paths.executable("chaindrive-run"), "--drive", str(clearance_drive), "--duration", "1e-4",
                    "--quiet", "--summary", str(summary)], check=True, capture_output=True)
    assert json.loads(summary.read_text())["method"] == row["method"]
    config = job.run_config(drive=str(clearance_drive))
    assert (config.method, config.solver_step) == (row["method"], row["step_s"])


def test_a_method_given_without_a_step_takes_its_rows_step(table, tmp_path):
    """A run that names the method of another row (plain Verlet, the row for joints with clearance
    or rigid contacts) but no step takes that row's step, not the real-time method's, which plain
    Verlet would not hold: in the FMU, chaindrive-run and the harness's job."""
    row = table["timing"]["link"]["clearanceOrRigid"]
    slave = fmu.Slave("defaults-method", parameters={"solver.method": row["method"]})
    slave.initialize(inputs={"crankshaft.w": fmu.rpm_to_rad_s(3000.0)})
    slave.step(1e-4, t=0.0)
    steps = slave.get(["solver.steps"])["solver.steps"]
    slave.close()
    assert steps == round(1e-4 / row["step_s"])
    summary = tmp_path / "summary.json"
    subprocess.run([paths.executable("chaindrive-run"), "--integrator", row["method"], "--duration", "1e-4",
                    "--quiet", "--summary", str(summary)], check=True, capture_output=True)
    assert json.loads(summary.read_text())["step"] == row["step_s"]
    config = job.run_config(method=row["method"])
    assert (config.method, config.solver_step) == (row["method"], row["step_s"])


def test_a_method_without_a_row_takes_plain_verlets_step(table, tmp_path):
    """A method with no row of its own (fixed-newmark), named without a step, takes the step of the
    row for joints with clearance or rigid contacts, plain Verlet's checked step, not the real-time
    method's longer one, at which it is not checked: in chaindrive-run and the harness's job."""
    row = table["timing"]["link"]["clearanceOrRigid"]
    summary = tmp_path / "summary.json"
    subprocess.run([paths.executable("chaindrive-run"), "--integrator", "fixed-newmark", "--duration", "1e-4",
                    "--quiet", "--summary", str(summary)], check=True, capture_output=True)
    assert json.loads(summary.read_text())["step"] == row["step_s"]
    assert job.run_config(method="fixed-newmark").solver_step == row["step_s"]


TEST_DRIVES = paths.ROOT / "tests" / "drives"


def drive_table(drive):
    text = subprocess.run([paths.executable("chaindrive-info"), "--defaults", "--drive", str(drive)],
                          capture_output=True, text=True, check=True).stdout
    return json.loads(text)


def test_the_default_drive_file_has_the_tables_steps(table):
    """The default drive given as a file has the table's steps bit for bit (its stability estimate is
    what the margins are calibrated on), each with the reason; the harness reads the same."""
    own = drive_table(paths.ROOT / "src" / "drives" / "default_drive.json")
    assert own["drive"]["clearanceOrRigid"] is False
    for fidelity in ("link", "span"):
        rows = [(own["timing"][fidelity], table["timing"][fidelity])]
        if fidelity == "link":
            rows.append((own["timing"]["link"]["clearanceOrRigid"], table["timing"]["link"]["clearanceOrRigid"]))
        for mine, default in rows:
            assert (mine["method"], mine["step_s"]) == (default["method"], default["step_s"])
            assert mine["step_s"] == 1e-4 / mine["divisions"]
            assert mine["reason"].startswith(f"step {mine['step_s']:.4g} s = 1e-4/{mine['divisions']}: ")
            assert "the default drive's margin" in mine["reason"]
    assert table["timing"]["link"]["divisions"] == 28 and table["timing"]["span"]["divisions"] == 3
    assert table["timing"]["link"]["clearanceOrRigid"]["divisions"] == 40
    assert defaults.drive_solver(paths.ROOT / "src" / "drives" / "default_drive.json") == defaults.solver("timing")


def test_a_lighter_chains_drive_takes_a_shorter_step(table, tmp_path):
    """tests/drives/dohc_8mm.json (05B chain, 1.44 g links, the default's roller contact): every link
    row shorter than the default's, from its stability estimate, with the reason naming the link; the
    harness's drive functions read the same rows; chaindrive-run without --step runs at it and says why."""
    drive = TEST_DRIVES / "dohc_8mm.json"
    own = drive_table(drive)
    link, plain = own["timing"]["link"], own["timing"]["link"]["clearanceOrRigid"]
    assert link["step_s"] < table["timing"]["link"]["step_s"] and plain["step_s"] < 2.5e-6
    assert link["step_s"] == 1e-4 / link["divisions"] <= link["margin"] * link["estimate_s"]
    assert link["margin"] == table["timing"]["link"]["margin"]
    assert "on a 1.44 g link" in link["reason"]
    assert defaults.drive_solver(drive) == defaults.Solver(link["method"], link["step_s"], link["tolerance"])
    assert defaults.drive_step_for(drive, "link", "fixed-newmark") == plain["step_s"]
    assert defaults.solver("timing", "link", drive=drive).step == link["step_s"]
    assert defaults.step_reason("link", drive=drive) == link["reason"]
    summary = tmp_path / "summary.json"
    out = subprocess.run([paths.executable("chaindrive-run"), "--drive", str(drive), "--duration", "1e-4",
                          "--summary", str(summary)], check=True, capture_output=True, text=True).stdout
    s = json.loads(summary.read_text())
    assert s["step"] == link["step_s"] and s["stepReason"] == link["reason"]
    assert link["reason"] in out


def test_the_fmu_of_a_test_drive_steps_at_its_own_step():
    """The FMU of tests/drives/dohc_8mm.json with solver.step 0 steps at the drive's own step, and logs
    the step and the reason (category logEvents) at its initialization."""
    from harness.fmu import export
    drive = TEST_DRIVES / "dohc_8mm.json"
    link = drive_table(drive)["timing"]["link"]
    slave = fmu.Slave("defaults-dohc", fmu=export.fmu_for(str(drive)), logging_on=True)
    slave.initialize(inputs={"crank.w": fmu.rpm_to_rad_s(3000.0)})
    slave.step(1e-4, t=0.0)
    steps = slave.get(["solver.steps"])["solver.steps"]
    slave.close()
    assert steps == link["divisions"]
    logged = [m for status, category, m in slave.messages if category == "logEvents"]
    assert f"solver: {link['method']}, {link['reason']}" in logged, logged


def test_a_blow_up_names_its_step_and_the_step_to_try(table):
    """An explicit step beyond the stable one: the FMU's fmi2Discard names the step it ran with and the
    drive's stable step, as solver.step; chaindrive-run's failure the same as --step."""
    link = table["timing"]["link"]
    slave = fmu.Slave("defaults-blow-up", parameters={"solver.step": 8e-6})
    slave.initialize(inputs={"crankshaft.w": fmu.rpm_to_rad_s(3000.0)})
    with pytest.raises(Exception):
        for k in range(200):
            slave.step(1e-4, t=k * 1e-4)
    advice = f"the step was 8 us, above this drive's estimated stable step: try solver.step = {link['step_s']:.4g} s " \
             f"(1e-4/{link['divisions']})"
    assert any(advice in m for m in slave.errors()), slave.errors()
    slave.slave.freeInstance()
    p = subprocess.run([paths.executable("chaindrive-run"), "--step", "8e-6", "--duration", "0.02", "--quiet"],
                       capture_output=True, text=True)
    assert p.returncode == 3
    assert f"above this drive's estimated stable step: try --step {link['step_s']:.4g} (1e-4/{link['divisions']})" \
        in p.stdout, p.stdout


@pytest.mark.parametrize("name", ["diesel_pump", "idler"])
def test_a_test_drives_step_is_its_probes_first_passing_rung(name, table):
    """chaindrive-info --defaults --drive shows the probe of each link row (run/step_probe.h): its runs
    from the estimate's division up, every one before the last beyond the balance limit, the last
    within it and the row's step; the pump and idler drives' real-time rows start at the default's
    1e-4/28 and end shorter; the default drive is not probed."""
    link = drive_table(TEST_DRIVES / f"{name}.json")["timing"]["link"]
    for row in (link, link["clearanceOrRigid"]):
        probe = row["probe"]
        runs = probe["runs"]
        assert probe["passed"] and runs[0]["divisions"] == row["estimateDivisions"], row
        assert runs[-1]["divisions"] == row["divisions"] and row["step_s"] == 1e-4 / row["divisions"]
        assert abs(runs[-1]["energyBalance"]) <= probe["balanceLimit"]
        assert all(r["blewUp"] or abs(r["energyBalance"]) > probe["balanceLimit"] for r in runs[:-1])
        assert not runs[-1]["blewUp"]
    assert link["estimateDivisions"] == 28 and link["divisions"] > 28
    assert "probe" not in table["timing"]["link"]  # (the default drive: its measured steps)
