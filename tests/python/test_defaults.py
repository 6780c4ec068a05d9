"""The solver defaults are one table (src/run/defaults.h, printed by chaindrive-info --defaults) that
every entry point uses: the command-line tools, both FMUs (their model descriptions and their
runs) and the harness's jobs."""
import json
import re
import subprocess
import xml.etree.ElementTree as ET

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
    chain = parameter_starts("modelDescription.xml")
    assert chain["solver.method"][0] == link["method"]
    assert float(chain["solver.tolerance"][0]) == link["tolerance"]
    step, text = chain["solver.step"]
    assert float(step) == 0.0  # 0: the fidelity's own step, named in the description
    named = {fidelity: float(value) for value, fidelity in re.findall(r"([0-9.e+-]+) s \((link|span)\)", text)}
    assert named == {"link": link["step_s"], "span": span["step_s"]}
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
    rows = re.findall(r"^\| (timing|cvt) \| (link|span) \| ([\w-]+) \| ([0-9.e+-]+) s \| ([0-9.e+-]+) \|", page, re.M)
    shown = {(scene, fidelity): (method, float(step), float(tol)) for scene, fidelity, method, step, tol in rows}
    expected = {(scene, fidelity): (row["method"], row["step_s"], row["tolerance"])
                for scene, fidelities in table.items() for fidelity, row in fidelities.items()}
    assert shown == expected
