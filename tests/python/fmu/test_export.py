"""Every drive its own FMU (python -m harness export, harness/fmu/export.py): the default drive's
export is ChainDrive.fmu (names, value references, GUID, output bits, and every variable the FMU
had before); the test drives' interfaces carry their own elements by name; loads reach the
crankshaft by the tooth ratio; two exports run in one process; what is refused at instantiation."""
import json
import pathlib
import shutil
import zipfile
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from fmpy import extract
from fmpy.validation import validate_fmu

from harness import paths
from harness.errors import UserError
from harness.fmu import export, fmu

DRIVES = paths.ROOT / "tests" / "drives"
TEST_DRIVES = ("dohc_8mm", "sohc_single_cam", "diesel_pump", "idler")
BEFORE = json.loads((paths.ROOT / "tests" / "data" / "fmu" / "chaindrive_variables_682b6e6.json").read_text())
H = 1e-4


@pytest.fixture(scope="module")
def exports(tmp_path_factory):
    """The default drive's and the four test drives' exports, from the native build."""
    out = tmp_path_factory.mktemp("exports")
    made = {"default": export.export(paths.ROOT / "src" / "drives" / "default_drive.json", out / "default", native=True)}
    for name in TEST_DRIVES:
        made[name] = export.export(DRIVES / f"{name}.json", out, native=True)
    return made


def variables(fmu_file):
    """{name: (value reference, type, causality, variability, start)} of an FMU's model description."""
    with zipfile.ZipFile(fmu_file) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
    out = {}
    for sv in root.iter("ScalarVariable"):
        typed = [c for c in sv if c.tag in ("Real", "Integer", "Boolean", "String")][0]
        out[sv.get("name")] = (int(sv.get("valueReference")), typed.tag, sv.get("causality"), sv.get("variability"),
                               typed.get("start"))
    return root, out


def test_the_default_drives_export_is_chaindrive_fmu(exports):
    e = exports["default"]
    assert e.path.name == "ChainDrive.fmu" and e.model_identifier == "ChainDrive"
    built_root, built = variables(fmu.fmu_path())
    root, exported = variables(e.path)
    assert exported == built and root.get("guid") == built_root.get("guid") == BEFORE["guid"]
    # every variable the FMU had before its interface was generated, unchanged
    for v in BEFORE["variables"]:
        assert exported[v["name"]] == (v["valueReference"], v["type"], v["causality"], v["variability"], v["start"])


def run(fmu_file, inputs, steps, parameters=None, name="run"):
    """Every output after each of `steps` communication steps of H with constant inputs."""
    s = fmu.Slave(name, fmu=fmu_file, parameters=parameters)
    s.initialize(inputs=inputs)
    rows = []
    for k in range(steps):
        s.step(H, t=k * H)
        rows.append([s.get()[n] for n in s.outputs])
    s.close()
    return np.array(rows)


def test_the_default_drives_export_gives_chaindrive_fmus_bits(exports):
    inputs = {"crankshaft.w": 250.0, "camshaftIntake.tau": 4.0, "camshaftExhaust.tau": 3.0}
    built = run(fmu.fmu_path(), inputs, 20)
    again = run(exports["default"].path, inputs, 20)
    assert built.tobytes() == again.tobytes()


@pytest.mark.parametrize("name", TEST_DRIVES)
def test_each_test_drive_exports_its_own_interface(exports, name):
    e = exports[name]
    assert validate_fmu(str(e.path)) == []
    drive = json.loads((DRIVES / f"{name}.json").read_text())
    inputs, outputs = set(e.variables("input")), set(e.variables("output"))
    for s in drive["sprockets"]:
        n = s["name"]
        if s["motion"] == "prescribed":
            assert {f"{n}.w"} <= inputs and {f"{n}.phi", f"{n}.tau"} <= outputs
        else:
            assert (f"{n}.tau" in inputs) == (s["motion"] == "free")
            assert {f"{n}.phi", f"{n}.w", f"{n}.tauChain"} <= outputs
    for g in drive["guides"]:
        assert ({f"{g['name']}.phi", f"{g['name']}.w"} <= outputs) == (g["motion"] == "pivoting")
    route = drive["chain"]["route"]
    assert {f"chain.{a}.{b}.F" for a, b in zip(route, route[1:] + route[:1])} <= outputs
    assert {"tensioner.F", "tensioner.chamberPressure", "chain.Ftight", "chain.Fslack"} <= outputs
    assert e.interface["guid"] != export.DEFAULT_GUID


def mean_over(fmu_file, inputs, steps, names, parameters=None):
    out = run(fmu_file, inputs, steps, parameters)
    outputs = [v.name for v in fmu.unpacked(fmu_file)[0].modelVariables if v.causality == "output"]
    return out[steps // 2:, [outputs.index(n) for n in names]].mean(axis=0)


def test_a_pump_load_reaches_the_crankshaft_by_the_tooth_ratio(exports):
    """Drive C at 1000 rpm: 12 N m on the 28-tooth pump changes the chain's mean torque on the
    21-tooth crankshaft by -12 x 21/28 N m, and the chain's torque on the pump balances the load."""
    path = exports["diesel_pump"].path
    w = 1000.0 * np.pi / 30.0
    idle = {"crankshaft.w": w, "camshaftIntake.tau": 2.0, "camshaftExhaust.tau": 2.0, "hpPump.tau": 0.0}
    loaded = dict(idle, **{"hpPump.tau": 12.0})
    steps = 1200  # 0.12 s: a crankshaft revolution is 60 ms; the second half is averaged
    names = ["crankshaft.tau", "hpPump.tauChain"]
    crank0, pump0 = mean_over(path, idle, steps, names)
    crank1, pump1 = mean_over(path, loaded, steps, names)
    assert crank1 - crank0 == pytest.approx(-12.0 * 21.0 / 28.0, rel=0.05)
    assert pump1 - pump0 == pytest.approx(12.0, rel=0.05)


def test_two_exports_of_different_drives_run_in_one_process(exports):
    b, d = exports["sohc_single_cam"].path, exports["idler"].path
    inputs = {"crankshaft.w": 300.0, "camshaft.tau": 5.0}
    solo_b, solo_d = run(b, inputs, 10), run(d, inputs, 10)
    sb, sd = fmu.Slave("b", fmu=b), fmu.Slave("d", fmu=d)
    sb.initialize(inputs=inputs)
    sd.initialize(inputs=inputs)
    rb, rd = [], []
    for k in range(10):
        sb.step(H, t=k * H)
        sd.step(H, t=k * H)
        rb.append([sb.get()[n] for n in sb.outputs])
        rd.append([sd.get()[n] for n in sd.outputs])
    sb.close()
    sd.close()
    assert np.array(rb).tobytes() == solo_b.tobytes() and np.array(rd).tobytes() == solo_d.tobytes()
    assert len(sb.outputs) != len(sd.outputs)  # (the idler's outputs)


def refusal(fmu_dir, guid=None, parameters=None):
    """The one-line refusal of an FMU (an unpacked folder) at instantiation or initialization."""
    with pytest.raises(UserError) as e:
        s = fmu.Slave("refused", fmu=str(fmu_dir), guid=guid, parameters=parameters)
        s.initialize(inputs={})
    return str(e.value)


@pytest.fixture
def unpacked(exports, tmp_path):
    return pathlib.Path(extract(str(exports["idler"].path), unzipdir=str(tmp_path / "idler")))


def test_a_missing_resources_folder_is_an_error(unpacked):
    shutil.rmtree(unpacked / "resources")
    assert "no resources folder" in refusal(unpacked) or "has no interface.json" in refusal(unpacked)


def test_a_drive_changed_in_the_resources_is_an_error_naming_the_table(unpacked):
    drive = unpacked / "resources" / "drive.json"
    drive.write_text(drive.read_text().replace('"motion": "idler"', '"motion": "free"'))
    assert "does not match the interface of resources/drive.json" in refusal(unpacked)


def test_another_guid_is_an_error(unpacked):
    assert "does not match this FMU's" in refusal(unpacked, guid="{00000000-0000-0000-0000-000000000000}")


def test_drive_file_takes_a_drive_of_the_same_interface_only(exports, tmp_path):
    text = (DRIVES / "idler.json").read_text()
    heavier = tmp_path / "heavier.json"
    heavier.write_text(text.replace('"linkMass": 0.0039', '"linkMass": 0.0045'))
    path = exports["idler"].path
    out = run(path, {"crankshaft.w": 300.0, "camshaft.tau": 5.0}, 3, parameters={"driveFile": str(heavier)})
    assert np.all(np.isfinite(out))
    other = tmp_path / "other.json"
    other.write_text(text.replace('"motion": "idler"', '"motion": "free"'))
    assert "has another interface than this FMU's drive" in refusal(
        extract(str(path), unzipdir=str(tmp_path / "u")), parameters={"driveFile": str(other)})


@pytest.mark.parametrize("name, problem", [("chain", "is reserved"), ("hp pump", "cannot name the FMU's variables")])
def test_export_refuses_element_names_an_fmu_cannot_have(tmp_path, name, problem):
    text = (DRIVES / "diesel_pump.json").read_text().replace('"hpPump"', json.dumps(name))
    drive = tmp_path / "drive.json"
    drive.write_text(text)
    with pytest.raises(UserError) as e:
        export.export(drive, tmp_path, native=True)
    assert problem in str(e.value) and "sprockets[3].name" in str(e.value)


def test_export_writes_no_shipped_fmu_but_the_default_drives(tmp_path):
    with pytest.raises(UserError, match="would replace the shipped CVTChain.fmu"):
        export.destination(tmp_path, "CVTChain", False)
    assert export.destination(tmp_path, "ChainDrive", True) == tmp_path / "ChainDrive.fmu"
