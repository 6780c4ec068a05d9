"""The hydraulic tensioner's oil through the harness: the main job's --supply-pressure-bar and
--oil-temperature-c (validated, reaching ChainDrive.fmu, recorded, a note for a drive without a
hydraulic tensioner), the chamber pressure's statistics in the summary, the sweep's oil settings as
coordinates and the tensioner study. Short runs: seconds each."""
import json

import numpy as np
import pytest

from harness import cycle_stats, job
from harness.drive import design
from harness.drive.description import drive_json, elements
from harness.errors import UserError
from harness.tables import tables
from harness_cli import harness, one_error_line

CHAMBER = cycle_stats.CHAMBER


@pytest.fixture(scope="module")
def spring_damper_drive(tmp_path_factory):
    """The default drive with the spring-damper law (a file)."""
    path = tmp_path_factory.mktemp("drive") / "spring_damper.json"
    path.write_text(json.dumps(design.spring_damper_variant(drive_json())))
    return path


@pytest.mark.parametrize("argv, message", [
    (("run", "--supply-pressure-bar", "300"), "--supply-pressure-bar 300: outside [-1.01325, 200] bar"),
    (("run", "--supply-pressure-bar", "-2"), "--supply-pressure-bar -2: outside [-1.01325, 200] bar"),
    (("run", "--oil-temperature-c", "10"), "--oil-temperature-c 10: outside the oil viscosity law's range [20, 150] degC"),
    (("sweep", "--oil-temperature-c", "40,200"), "--oil-temperature-c 200: outside the oil viscosity law's range"),
    (("sweep", "--supply-pressure-bar", "1,x"), "--supply-pressure-bar '1,x': expected a comma list of numbers"),
])
def test_oil_options_out_of_range_are_one_line(argv, message, tmp_path):
    line = one_error_line(*harness(*argv, "--out", str(tmp_path))[::2])
    assert message in line, line


def test_oil_options_in_si_and_their_defaults():
    oil = job.hydraulic_options(None, 2.5, 40.0)
    assert oil == {"supply_pressure": 2.5e5, "oil_temperature": pytest.approx(313.15), "notes": ()}
    assert job.hydraulic_options(None, None, None)["supply_pressure"] == job.SUPPLY_PRESSURE == 3e5
    config = job.run_config(oil_temperature=313.15)
    assert job.parameters_of(config)["tensioner.oilTemperature"] == pytest.approx(313.15)
    with pytest.raises(UserError, match="outside"):
        job.oil_temperature_of(151.0, drive_json())


def short_run(supply_bar=3.0, celsius=90.0):
    """10 ms of the span model at 1000 rpm in closed loop: its record."""
    config = job.run_config(rpm=1000.0, fidelity="span", supply_pressure=supply_bar * 1e5,
                            oil_temperature=celsius + 273.15)
    inputs = job.table_inputs(job.drive_loads(config, elements()), tables.crankshaft_speed(1000.0), elements(),
                              config.supply_pressure)
    record, _, _ = job.run_closed(config, 0.01, inputs, progress=False)
    return record


def test_supply_pressure_and_oil_temperature_reach_the_fmu():
    low, high = short_run(supply_bar=2.0), short_run(supply_bar=5.0)
    # the chamber starts at the supply pressure less the check valve's cracking pressure (0.1 bar)
    # and, before the drive pumps it up, stays near it: 3 bar more supply, about 3 bar more chamber
    assert high[CHAMBER][0] - low[CHAMBER][0] == pytest.approx(3e5, rel=1e-6)
    assert np.mean(high[CHAMBER]) > np.mean(low[CHAMBER]) + 2e5
    # the oil is about ten times thinner at 120 degC than at 40 degC: it leaks down faster
    cold, hot = short_run(celsius=40.0), short_run(celsius=120.0)
    assert np.mean(hot["tensioner.leakFlow"]) > 3.0 * np.mean(cold["tensioner.leakFlow"]) > 0.0


def test_chamber_statistics_in_the_summary_only_with_the_hydraulic_tensioner(tmp_path, spring_damper_drive):
    keys = {CHAMBER + s for s in (".mean_bar", ".peakToPeak_bar", ".min_bar")}
    status, out, err = harness("run", "--fidelity", "span", "--cycles", "2", "--run-in", "1",
                               "--supply-pressure-bar", "4", "--out", str(tmp_path / "hydraulic"))
    assert status == 0, err
    summary = json.loads((tmp_path / "hydraulic" / "summary.json").read_text())
    assert keys <= set(summary) and all(summary[k]["unit"] == "bar" for k in keys)
    assert list(summary) == cycle_stats.headline_keys(elements())
    assert summary[CHAMBER + ".min_bar"]["mean"] < summary[CHAMBER + ".mean_bar"]["mean"]
    run = json.loads((tmp_path / "hydraulic" / "run.json").read_text())
    assert run["supplyPressure_Pa"] == 4e5 and run["oilTemperature_K"] == 363.15 and run["tensionerModel"] == "hydraulic"
    assert "oil supply 4 bar" in out and "no effect" not in out

    status, out, err = harness("run", "--fidelity", "span", "--cycles", "2", "--run-in", "1", "--drive",
                               str(spring_damper_drive), "--oil-temperature-c", "40", "--out", str(tmp_path / "sd"))
    assert status == 0, err
    summary = json.loads((tmp_path / "sd" / "summary.json").read_text())
    assert not keys & set(summary) and list(summary) == cycle_stats.headline_keys(elements(spring_damper_drive))
    notes = [line for line in out.splitlines() if "no effect" in line]
    assert notes == ["note: --oil-temperature-c 40: no effect, the drive's tensioner is not hydraulic "
                     "(tensioner.model 'spring-damper')"]


def test_a_zero_chamber_column_is_no_chamber():
    phi = np.linspace(0.0, 3 * cycle_stats.ENGINE_CYCLE, 300)
    record = {name: np.ones_like(phi) for name in ("tensioner.F", "chain.Ftight", "chain.Fslack", "tensionGuide.phi",
                                                   "camshaftIntake.phi", "camshaftExhaust.phi")}
    record.update({"crankshaft.phi": phi, CHAMBER: np.zeros_like(phi)})
    assert not any(k.startswith(CHAMBER) for k in cycle_stats.per_cycle(record, 0, elements()))
    record[CHAMBER] = 3e5 + 1e5 * np.sin(phi)
    stats = cycle_stats.summarize(cycle_stats.per_cycle(record, 0, elements()))
    assert stats[CHAMBER + ".mean_bar"]["mean"] == pytest.approx(3.0, abs=0.01)
    assert stats[CHAMBER + ".min_bar"]["mean"] == pytest.approx(2.0, abs=0.01)
    assert stats[CHAMBER + ".peakToPeak_bar"]["mean"] == pytest.approx(2.0, abs=0.01)


def test_sweep_over_speeds_and_supply_pressures(tmp_path):
    import xarray as xr
    status, out, err = harness("sweep", "--rpm", "2000,4000", "--supply-pressure-bar", "2,5", "--cycles", "2",
                               "--fidelity", "span", "--workers", "1", "--no-progress", "--out", str(tmp_path))
    assert status == 0, err + out
    with xr.open_dataset(tmp_path / "sweep.nc", engine="h5netcdf") as ds:
        assert ds.sizes["point"] == 4 and "oil_temperature_c" not in ds.coords
        points = sorted(zip(ds["supply_pressure_bar"].values.tolist(), ds["rpm"].values.tolist()))
        assert points == [(2.0, 2000.0), (2.0, 4000.0), (5.0, 2000.0), (5.0, 4000.0)]
        assert ds["supply_pressure_bar"].attrs["units"] == "bar"
        lowest, mean = ds[CHAMBER + ".lowest_bar"].values, ds[CHAMBER + ".mean_bar"].values
        assert np.all(lowest < mean) and np.all(mean < ds[CHAMBER + ".highest_bar"].values)
    assert (tmp_path / "sweep" / "hydraulic_over_speed.png").stat().st_size > 10000
    # the cache key holds the oil: four cases, none shared
    assert len(list((tmp_path / "cache").glob("*.json"))) == 4


def test_tensioner_study_on_a_tiny_run(tmp_path):
    status, out, err = harness("tensioner-study", "--rpm", "3000", "--cycles", "2", "--out", str(tmp_path))
    assert status == 0, err
    result = json.loads((tmp_path / "tensioner.json").read_text())
    (speed,) = result["speeds"]
    assert speed["rpm"] == 3000.0
    hydraulic, spring_damper = speed["hydraulic"]["summary"], speed["springDamper"]["summary"]
    assert CHAMBER + ".mean_bar" in hydraulic and not any(k.startswith(CHAMBER) for k in spring_damper)
    assert set(spring_damper) <= set(hydraulic) and all(s["cycles"] == 2 for s in hydraulic.values())
    rows = {r["key"]: r for r in speed["rows"]}
    assert set(rows) == set(spring_damper)
    F = rows["tensioner.F.mean"]
    assert F["difference"] == pytest.approx(100.0 * (hydraulic["tensioner.F.mean"]["mean"] /
                                                     spring_damper["tensioner.F.mean"]["mean"] - 1.0))
    assert F["beyondScatter"] == (abs(F["z"]) > 1.0)
    report = (tmp_path / "tensioner.md").read_text()
    assert "| `tensioner.F.order8` |" in report and "typical values" in report.lower()
