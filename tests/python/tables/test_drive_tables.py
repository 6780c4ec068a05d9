"""The test drives' tables folders, tests/drives/tables/<drive>/ (SYNTHESIZED by
harness.tables.make_tables.write_drive_tables, `python -m harness tables --drive-tables
tests/drives`; tests/drives/tables/README.md): the generator reproduces them, each loads for its
drive with tables.sprocket_loads, and the loads are those designed (the shipped camshaft loads
over the sprocket's own angle, a single camshaft's sum, the high-pressure pump's pulses)."""
import re

import numpy as np
import pytest

from harness import cli, paths
from harness.drive.description import elements
from harness.tables import make_tables, tables, valvetrain

DRIVES = paths.ROOT / "tests" / "drives"
FOLDERS = DRIVES / "tables"
DATA = paths.ROOT / "harness" / "tables" / "data"
RPMS = (1000, 3000, 6000)
LOADED = {  # the files of each folder per engine speed, and the drive's loaded sprockets
    "dohc_8mm": (["crankshaft_speed", "torque_intakeCam", "torque_exhaustCam"], ["intakeCam", "exhaustCam"]),
    "sohc_single_cam": (["crankshaft_speed", "torque_camshaft"], ["camshaft"]),
    "idler": (["crankshaft_speed", "torque_camshaft"], ["camshaft"]),
    "diesel_pump": (["crankshaft_speed", "camshaft_torque", "torque_hpPump"],
                    ["hpPump", "camshaftIntake", "camshaftExhaust"]),
}


def drive(name):
    return elements(DRIVES / f"{name}.json")


def artefacts(table):
    """(noise sigma, offset) [N m] of a one-column torque table's `artefacts:` header line."""
    line = table.header["artefacts"]
    sigma = float(re.search(r"sensor noise (?:\S+ )?([0-9.]+) N\.m RMS", line).group(1))
    offset = float(re.search(r"offset (?:\S+ )?([-+][0-9.]+) N\.m", line).group(1))
    return sigma, offset


def test_the_generator_reproduces_the_committed_folders_byte_for_byte(tmp_path):
    cli.main(["tables", "--drive-tables", str(DRIVES), "--out", str(tmp_path), "--quiet"])
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(LOADED)
    for name, (stems, _) in LOADED.items():
        committed = sorted(p.name for p in (FOLDERS / name).glob("*.csv"))
        assert committed == sorted(f"{s}_{rpm}rpm.csv" for s in stems for rpm in RPMS), name
        assert sorted(p.name for p in (tmp_path / name).glob("*.csv")) == committed, name
        for f in committed:
            assert (tmp_path / name / f).read_bytes() == (FOLDERS / name / f).read_bytes(), \
                f"{name}/{f}: regenerate with python -m harness tables --drive-tables tests/drives"


def test_the_speed_tables_and_the_diesels_camshaft_tables_are_the_shipped_ones():
    for name in LOADED:
        for p in FOLDERS.glob(f"{name}/c*_*rpm.csv"):   # crankshaft_speed, camshaft_torque
            assert p.read_bytes() == (DATA / p.name).read_bytes(), p


def test_every_table_is_synthesized_and_says_how_it_was_made():
    for p in sorted(FOLDERS.glob("*/*.csv")):
        t = tables.load(p)
        assert "SYNTHESIZED" in t.provenance, p
        assert t.rpm == float(re.search(r"_(\d+)rpm", p.name).group(1)), p
        assert t.header["generator"].startswith("python -m harness tables"), p
        assert {"chaindrive table", "units", "sampling", "artefacts"} <= set(t.header), p
        if p.name.startswith("torque_"):
            name = re.fullmatch(r"torque_(.+)_\d+rpm\.csv", p.name).group(1)
            assert t.kind == "sprocket" and list(t.columns) == [name + ".tau"], p
            # one turn at 0.5 deg: 0.0 ... 359.5, 720 rows
            assert len(t.x) == 720 and t.x[0] == 0.0 and np.allclose(np.diff(t.x), 0.5), p
            assert t.header["phase"] == "0 deg", p
            assert t.header["generator"] == "python -m harness tables --drive-tables tests/drives --seed 20240601", p
            assert t.header["drive"].startswith(f"tests/drives/{p.parent.name}.json, sprocket {name}:"), p


@pytest.mark.parametrize("name", sorted(LOADED))
def test_every_folder_loads_for_its_drive_at_tabulated_and_interpolated_speeds(name):
    el = drive(name)
    folder = FOLDERS / name
    assert sorted(el.loaded) == sorted(LOADED[name][1])
    for rpm in (1000, 2000, 3000, 6000):       # 2000: interpolated between 1000 and 3000 rpm
        assert tables.speed_problem(rpm, folder) is None
        loads = tables.sprocket_loads(el, rpm, folder)
        assert sorted(loads) == sorted(el.loaded), (name, rpm)
        for sprocket, load in loads.items():
            assert load.table is not None and (load.table.path is None) == (rpm == 2000), (sprocket, rpm)
            if sprocket.startswith("camshaft") and name == "diesel_pump":
                assert load.table.kind == "angle" and load.ratio == 2.0   # the crank-angle camshaft_torque table
            else:
                assert load.table.kind == "sprocket" and load.phase_deg == 0.0
            y = load.at(np.linspace(-360.0, 720.0, 2161))
            assert np.all(np.isfinite(y)), (name, sprocket, rpm)
            assert 0.5 < y.mean() < 12.0 and y.max() - y.min() > 5.0, (name, sprocket, rpm, y.mean())
        speed = tables.crankshaft_speed(rpm, folder).columns["crankshaft.speed_rpm"]
        assert np.all(np.isfinite(speed)) and abs(speed.mean() - rpm) < 0.01
    ts = tables.time_series(3000, 0.01, 1e-4, folder, elements=el)
    assert sorted(k[:-4] for k in ts if k.endswith(".tau")) == sorted(el.loaded)
    assert all(np.all(np.isfinite(v)) for v in ts.values())


def test_a_folder_loads_only_its_own_drive():
    for name in LOADED:
        for other in LOADED:
            if LOADED[other][1] != LOADED[name][1]:
                with pytest.raises(ValueError, match="matches no loaded sprocket|has no load"):
                    tables.sprocket_loads(drive(other), 3000, FOLDERS / name)


@pytest.mark.parametrize("rpm", RPMS)
def test_the_dohc_camshafts_see_the_default_drives_loads(rpm):
    """dohc_8mm's own-angle tables are the shipped crank-angle columns at crank angle 2 x sprocket
    angle: the same load at the same camshaft angle as the default drive's camshafts."""
    own = tables.sprocket_loads(drive("dohc_8mm"), rpm, FOLDERS / "dohc_8mm")
    default = tables.sprocket_loads(elements(), rpm)
    phi = make_tables.sprocket_angles()
    for mine, theirs in (("intakeCam", "camshaftIntake"), ("exhaustCam", "camshaftExhaust")):
        shipped = default[theirs].table.columns[theirs + ".tau"]
        assert np.array_equal(own[mine].table.columns[mine + ".tau"], shipped[::2])
        assert np.array_equal(own[mine].at(phi), default[theirs].at(phi))


@pytest.mark.parametrize("name", ("sohc_single_cam", "idler"))
@pytest.mark.parametrize("rpm", RPMS)
def test_the_single_camshaft_is_the_sum_of_the_models_intake_and_exhaust_loads(name, rpm):
    t = tables.load(FOLDERS / name / f"torque_camshaft_{rpm}rpm.csv")
    y = t.columns["camshaft.tau"]
    theta = 2.0 * t.x                                    # crank angle = 2 x camshaft angle
    clean = sum(valvetrain.camshaft_load(c, theta, rpm).total for c in valvetrain.CAMSHAFTS)
    sigma, offset = artefacts(t)
    assert sigma == pytest.approx(make_tables.NOISE_FRACTION * 0.5 * (clean.max() - clean.min()), abs=1e-3)
    assert abs(offset) < 4.0 * make_tables.TORQUE_OFFSET_SD
    # the artefacts: the known low-pass (at the camshaft's orders over its turn, 720 deg crank)
    # and offset taken away, what is left is the averaged noise (sigma / 4 for 16 cycles, less
    # after the low-pass), the cycle-to-cycle variation and the quantization
    low_passed = make_tables.lowpass_periodic(clean, rpm, make_tables.TORQUE_BANDWIDTH_HZ, 720.0)
    rest = y - low_passed - offset
    noise = sigma / np.sqrt(make_tables.CYCLES)
    assert np.sqrt(np.mean(rest ** 2)) < 1.2 * noise, (rpm, np.sqrt(np.mean(rest ** 2)), noise)
    assert np.max(np.abs(rest)) < 5.0 * noise + make_tables.TORQUE_STEP
    # and all artefacts together: within the low-pass's own change, the noise, offset and step
    bound = np.max(np.abs(low_passed - clean)) + 5.0 * noise + abs(offset) + make_tables.TORQUE_STEP
    assert np.max(np.abs(y - clean)) < bound
    # a sum of the two, not one of them twice: that is far off
    for c in valvetrain.CAMSHAFTS:
        twice = make_tables.lowpass_periodic(2.0 * valvetrain.camshaft_load(c, theta, rpm).total, rpm,
                                             make_tables.TORQUE_BANDWIDTH_HZ, 720.0)
        assert np.sqrt(np.mean((y - twice - offset) ** 2)) > 10.0 * noise


@pytest.mark.parametrize("rpm", RPMS)
def test_the_pump_table_has_its_designed_mean_and_two_pulses_per_turn(rpm):
    pump = valvetrain.HP_PUMP
    t = tables.load(FOLDERS / "diesel_pump" / f"torque_hpPump_{rpm}rpm.csv")
    y = t.columns["hpPump.tau"]
    # designed [E]: V_g 0.25 cm^3/turn, rail 1000 bar + 300 bar per 1000 rpm (at most 1800 bar),
    # efficiency 0.85, drag 0.3 N m: mean 4.98, 7.79, 8.73 N m; peak pi x the hydraulic mean
    assert pump.mean(rpm) == pytest.approx({1000: 4.981, 3000: 7.790, 6000: 8.726}[rpm], abs=1e-3)
    assert pump.peak(rpm) == pytest.approx(np.pi * (pump.mean(rpm) - pump.drag))
    # the table's mean: the design's, within the offset and the averaged delivery variation
    # (3 % / 4 of the hydraulic mean)
    _, offset = artefacts(t)
    assert abs(y.mean() - pump.mean(rpm) - offset) < 3.0 * 0.0075 * pump.hydraulic_mean(rpm) + 0.02
    assert 4.5 < y.mean() < 9.5
    # two half-sine pulses per turn, 90 deg long from 0 and 180 deg: rising through half height
    # at 15 and 195 deg (sin = 1/2), the low-pass delaying them by a few tenths of a degree to 2 deg
    half = y.min() + 0.5 * (y.max() - y.min())
    up = np.nonzero((y >= half) & (np.roll(y, 1) < half))[0]
    assert len(up) == 2, t.x[up]
    assert np.allclose(t.x[up], (15.0, 195.0), atol=3.0), t.x[up]
    amp = np.abs(np.fft.rfft(y)) / len(y) * 2.0        # bin k: k per pump turn
    assert np.argmax(amp[1:20]) + 1 == 2
    # a half-wave rectified sine: 1st harmonic of the pulse train 0.5 x peak, its 2nd 0.21 x peak
    assert amp[2] == pytest.approx(0.5 * pump.peak(rpm), rel=0.06)
    assert amp[4] == pytest.approx(2.0 / (3.0 * np.pi) * pump.peak(rpm), rel=0.1)
    # two identical lobes: the odd orders are noise
    assert max(amp[1:40:2]) < 0.03 * amp[2]
    # between the pulses (filling stroke) only the drag is left
    between = (t.x > 110.0) & (t.x < 170.0) | (t.x > 290.0) & (t.x < 350.0)
    assert abs(np.mean(y[between]) - pump.drag - offset) < 0.25


def test_a_users_drive_gets_tables_by_sprocket_and_kind(tmp_path):
    """tables --drive FILE --sprocket-load NAME=KIND: a user's drive gets the same loads the test
    drives' generator gives (the diesel pump's table's rows are the committed ones, only the
    generator line differs); a sprocket left without a kind, or one the drive does not load, is
    one line naming the drive's loaded sprockets."""
    from harness_cli import harness, one_error_line
    drive = paths.ROOT / "tests" / "drives" / "diesel_pump.json"
    status, out, err = harness("tables", "--drive", str(drive), "--sprocket-load", "hpPump=pump", "--sprocket-load",
                               "camshaftIntake=intake", "--sprocket-load", "camshaftExhaust=exhaust", "--rpm", "3000",
                               "--out", str(tmp_path), "--quiet")
    assert status == 0, err
    mine = (tmp_path / "torque_hpPump_3000rpm.csv").read_text().splitlines()
    committed = (paths.ROOT / "tests" / "drives" / "tables" / "diesel_pump" / "torque_hpPump_3000rpm.csv").read_text()
    committed = committed.splitlines()
    assert [l for l in mine if not l.startswith("# generator")] == [l for l in committed if not l.startswith("# generator")]
    assert any("--sprocket-load hpPump=pump" in l for l in mine)
    assert (tmp_path / "torque_camshaftIntake_3000rpm.csv").exists()
    line = one_error_line(*harness("tables", "--drive", str(drive), "--sprocket-load", "hpPump=pump",
                                   "--out", str(tmp_path))[::2])
    assert "no load for camshaftIntake, camshaftExhaust" in line and "intake+exhaust" in line, line
    line = one_error_line(*harness("tables", "--drive", str(paths.ROOT / "tests" / "drives" / "idler.json"),
                                   "--sprocket-load", "idler=pump", "--out", str(tmp_path))[::2])
    assert "'idler' is not a loaded sprocket" in line and "(camshaft)" in line, line
