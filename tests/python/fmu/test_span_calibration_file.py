"""An exported FMU that carries its span model's calibration (python -m harness export
--span-calibration: resources/span_calibration.json, the calibration cache's file of the drive's
key) instantiates in the span fidelity without calibrating: with an empty cache folder nothing is
computed or written, its log says the laws came from the file, and its outputs have the bits of an
instance that takes the calibration from the cache. An instance whose parameters change the drive
(another key) passes the file over with a warning that says why, and calibrates. The SOHC test
drive: one loaded sprocket, 30 static poses, a few seconds."""
import json
import struct
import zipfile

from harness import paths
from harness.fmu import fmu
from harness_cli import harness

SOHC = paths.ROOT / "tests" / "drives" / "sohc_single_cam.json"
INPUTS = {"crankshaft.w": fmu.rpm_to_rad_s(3000.0), "camshaft.tau": 5.0}
H = 1e-4


def span_run(location, cache, monkeypatch, parameters=None, steps=20, log=None):
    """Communication steps of the FMU (a file or an unpacked folder) in the span fidelity with the
    calibration cache in `cache`: its outputs after each, Reals as their bits; its log messages
    (status, category, message) appended to `log`."""
    monkeypatch.setenv("CHAINDRIVE_CACHE_DIR", str(cache))
    s = fmu.Slave("span", fmu=location, logging_on=True, parameters={"fidelity": "span", **(parameters or {})})
    s.initialize(inputs=INPUTS)
    rows = []
    for k in range(steps):
        s.step(H, t=k * H)
        values = s.get()
        rows.append(tuple(struct.pack("<d", values[n]) if s.type[n] == "Real" else values[n] for n in s.outputs))
    s.close()
    if log is not None:
        log += s.messages
    return rows


def files_in(folder):
    return sorted(p.name for p in folder.iterdir()) if folder.exists() else []


def test_an_exported_fmu_instantiates_in_the_span_fidelity_from_its_calibration(tmp_path, monkeypatch):
    cache = tmp_path / "cache"
    monkeypatch.setenv("CHAINDRIVE_CACHE_DIR", str(cache))  # (the export's chaindrive-info calibrates into it)
    status, out, err = harness("export", "--drive", str(SOHC), "--out", str(tmp_path / "out"), "--span-calibration")
    assert status == 0, err
    (exported,) = (tmp_path / "out").glob("*.fmu")
    with zipfile.ZipFile(exported) as z:
        shipped = z.read("resources/span_calibration.json")
        z.extractall(tmp_path / "unpacked")
    key = json.loads(shipped)["key"]
    assert files_in(cache) == [f"span-{key}.json"]
    assert (cache / f"span-{key}.json").read_bytes() == shipped  # the cache's format and key

    empty = tmp_path / "empty"
    log = []
    with_file = span_run(exported, empty, monkeypatch, log=log)
    assert files_in(empty) == []  # nothing calibrated, nothing written
    assert any(f"calibration: key {key}, from the file " in m and m.endswith("span_calibration.json")
               for _, _, m in log), log
    assert not any(status != 0 for status, _, _ in log), log

    (tmp_path / "unpacked" / "resources" / "span_calibration.json").unlink()
    log = []  # an FMU without the file: the cache's laws, nothing passed over
    assert span_run(tmp_path / "unpacked", cache, monkeypatch, log=log) == with_file
    assert any(f"calibration: key {key}, from the cache " in m for _, _, m in log), log
    assert not any(status != 0 for status, _, _ in log), log

    other = tmp_path / "other"  # another preload: another key, the file is passed over
    log = []
    span_run(exported, other, monkeypatch, parameters={"tensioner.preload": 30.0}, steps=1, log=log)
    written = files_in(other)
    assert len(written) == 1 and written != [f"span-{key}.json"], written
    warnings = [m for status, _, m in log if status == 1]
    assert any("span_calibration.json passed over: key" in m and key in m for m in warnings), log
