"""Loads by sprocket name (harness/tables/tables.py, sprocket_loads): a constant, a sprocket's own
table over its own angle with its phase, the shipped crank-angle table's columns by the tooth
ratio; a loaded sprocket without a load and a table that matches none are errors naming them."""
import math

import numpy as np
import pytest

from harness import paths
from harness.drive.description import elements
from harness.tables import tables

DRIVES = paths.ROOT / "tests" / "drives"


def own_table(folder, name, rpm, values, phase=None, angle="sprocket_angle_deg"):
    """torque_<name>_<rpm>rpm.csv: values at the angles 0, 360/n, ... of a turn."""
    x = np.arange(len(values)) * 360.0 / len(values) if angle == "sprocket_angle_deg" else \
        np.arange(len(values)) * 720.0 / len(values)
    head = f"# phase: {phase} deg\n" if phase is not None else ""
    body = "\n".join(f"{a:g},{v:g}" for a, v in zip(x, values))
    (folder / f"torque_{name}_{rpm:g}rpm.csv").write_text(f"{head}{angle},{name}.tau\n{body}\n")


@pytest.fixture
def folder(tmp_path):
    """A tables folder with the shipped crankshaft speed at 3000 rpm."""
    (tmp_path / "crankshaft_speed_3000rpm.csv").write_bytes((tables.DATA_DIR / "crankshaft_speed_3000rpm.csv").read_bytes())
    return tmp_path


def test_the_shipped_tables_serve_the_default_names_by_the_tooth_ratio():
    loads = tables.sprocket_loads(elements(), 3000.0)
    table = tables.camshaft_torque(3000.0)
    for name in ("camshaftIntake", "camshaftExhaust"):
        # a camshaft turned by 40 deg: the crank-angle table at 80 deg crank
        assert loads[name].at(40.0) == tables.lookup(table, name + ".tau", 80.0)


def test_an_own_angle_table_is_looked_up_at_the_sprockets_angle_plus_its_phase(folder):
    drive = elements(DRIVES / "sohc_single_cam.json")
    own_table(folder, "camshaft", 3000, [0.0, 10.0, 20.0, 30.0], phase=90)
    load = tables.sprocket_loads(drive, 3000.0, folder)["camshaft"]
    assert load.at(0.0) == pytest.approx(10.0) and load.at(45.0) == pytest.approx(15.0)
    assert load.at(270.0 + 360.0) == pytest.approx(0.0)  # periodic over a turn of the sprocket


def test_a_crank_angle_table_of_one_sprocket_turns_with_the_ratio(folder):
    drive = elements(DRIVES / "diesel_pump.json")  # the 28-tooth pump on a 21-tooth crankshaft
    own_table(folder, "hpPump", 3000, np.linspace(0.0, 71.9, 720), angle="crank_angle_deg")
    loads = tables.sprocket_loads(drive, 3000.0, folder, {"camshaftIntake": 1.0, "camshaftExhaust": 2.0})
    # the pump turned by 30 deg: the crankshaft turned by 40 deg
    assert loads["hpPump"].at(30.0) == pytest.approx(4.0)
    assert loads["camshaftExhaust"].at(123.0) == 2.0 and loads["camshaftExhaust"].source == "--load camshaftExhaust=2"


def test_a_loaded_sprocket_without_a_load_is_named_with_what_the_tables_have(folder):
    drive = elements(DRIVES / "diesel_pump.json")
    with pytest.raises(ValueError) as e:
        tables.sprocket_loads(drive, 3000.0, None, {})
    message = str(e.value)
    assert "sprocket 'hpPump' has no load" in message and "camshaftIntake, camshaftExhaust" in message


def test_an_idler_takes_no_load_and_a_typo_is_refused(folder):
    drive = elements(DRIVES / "idler.json")
    assert drive.loaded == ["camshaft"]
    with pytest.raises(ValueError, match="--load idler: not a loaded sprocket of the drive; its loaded sprockets: "
                                         "camshaft"):
        tables.sprocket_loads(drive, 3000.0, folder, {"idler": 1.0, "camshaft": 2.0})
    own_table(folder, "camshaft", 3000, [1.0, 2.0])
    own_table(folder, "camshft", 3000, [1.0, 2.0])
    with pytest.raises(ValueError, match="the load table of 'camshft' matches no loaded sprocket"):
        tables.sprocket_loads(drive, 3000.0, folder)


def test_the_open_loop_time_series_carry_every_loaded_sprocket(folder):
    drive = elements(DRIVES / "diesel_pump.json")
    own_table(folder, "hpPump", 3000, [5.0, 5.0])
    loads = tables.sprocket_loads(drive, 3000.0, folder, {"camshaftIntake": 1.0, "camshaftExhaust": 2.0})
    ts = tables.time_series(3000.0, 0.01, 1e-4, folder, loads=loads, elements=drive)
    assert set(ts) == {"time", "crankshaft.w", "hpPump.tau", "camshaftIntake.tau", "camshaftExhaust.tau",
                       "crank_angle_deg"}
    assert np.all(ts["hpPump.tau"] == 5.0) and math.isclose(ts["crankshaft.w"].mean(), 314.16, rel_tol=0.01)
