"""The layout aid (harness/drive/layout.py): the test drives made again from their layout files bit
for bit, a layout that does not close answered by a sketch and one line, the path model that the
link counts, shifts and tensioner figures come from checked against the solver's closure, and the
layout file's mistakes named."""
import copy
import json
import math

import pytest

from harness import paths
from harness.drive import geometry as geo
from harness.drive.layout_drive import Layout, close_by_shift, closure_angle, guide_turn_for_links
from harness.drive.layout_file import read_layout
from harness.errors import UserError
from harness_cli import harness, one_error_line

LAYOUTS = paths.ROOT / "tests" / "drives" / "layouts"
DRIVES = ["dohc_8mm", "sohc_single_cam", "diesel_pump", "idler", "v6_primary", "v6_bank"]


def info():
    return str(paths.executable("chaindrive-info"))


@pytest.mark.parametrize("name", DRIVES)
def test_the_layout_aid_makes_each_test_drive_bit_for_bit(name, tmp_path):
    """From centres, teeth, a chain designation and guides on the spans to the committed drive: the
    same bytes; its report closes the chain, checks the geometry and draws the picture."""
    out, picture = tmp_path / f"{name}.json", tmp_path / f"{name}.png"
    status, stdout, stderr = harness("layout", str(LAYOUTS / f"{name}.json"), "--out", str(out), "--picture",
                                     str(picture))
    assert status == 0, stderr
    assert out.read_bytes() == (paths.ROOT / "tests" / "drives" / f"{name}.json").read_bytes()
    assert picture.stat().st_size > 10_000
    assert "the solver closes" in stdout and "checks: every guide face" in stdout, stdout
    assert "teeth in mesh" in stdout and "tensioner, worn chain (0.5% longer)" in stdout, stdout


def test_a_layout_that_does_not_close_gets_a_sketch_with_its_gap_and_one_line(tmp_path):
    """120 links on a layout whose path holds 115.9 and the tension guide to close it: no drive
    written, the sketch with the gap marked, one error line with the solver's reason."""
    layout = json.loads((LAYOUTS / "sohc_single_cam.json").read_text())
    layout["chain"]["numberOfLinks"] = 120
    layout["closure"] = {"kind": "tensioner"}
    path = tmp_path / "open.json"
    path.write_text(json.dumps(layout))
    status, stdout, stderr = harness("layout", str(path), "--out", str(tmp_path / "drive.json"))
    line = one_error_line(status, stderr)
    assert "does not close with 120 links" in line and "holds 115.94" in line and "gap 36." in line, line
    assert "114 and 0.0" in line, line  # (the solver's advice: the even counts around the path)
    assert not (tmp_path / "drive.json").exists() and (tmp_path / "drive.png").stat().st_size > 10_000
    assert "sketch with the gap marked" in stdout


@pytest.mark.parametrize("name", ["sohc_single_cam", "idler"])
def test_the_path_model_holds_the_solvers_link_count_and_is_continuous(name):
    """A known answer for the tool behind every figure: at the committed drive's closing shift the
    Python path holds its link count to 1e-6 links (the solver closes it with the tension guide within
    1e-8 rad of its drawn pose); over shifts of 0.1 um around it the count moves smoothly (the chord
    walk's end no longer jumps by an arc's excess over its chord, 0.0037 links on a 21-tooth wrap)."""
    spec = read_layout(LAYOUTS / f"{name}.json")
    drive = json.loads((paths.ROOT / "tests" / "drives" / f"{name}.json").read_text())
    shift = drive["sprockets"][1]["center"][1] - spec.sprocket(drive["sprockets"][1]["name"])["center"][1]
    held = [geo.links_held(Layout(spec, shift + k * 1e-7).route_circles(), spec.chain.pitch) for k in range(-5, 6)]
    assert held[5] == pytest.approx(drive["chain"]["numberOfLinks"], abs=1e-6)
    steps = [b - a for a, b in zip(held, held[1:])]
    assert max(steps) < 1.2 * min(steps) and min(steps) > 0.0, steps


def test_the_tension_guide_turn_agrees_with_the_solvers_closure(tmp_path):
    """The take-up figures come from turning the tension guide in the Python path: closing 116 links
    on the single-camshaft layout with its camshaft 0.1 mm lower than the committed drive's, the guide
    turn the path gives agrees with the solver's closure angle within 2e-5 rad."""
    spec = read_layout(LAYOUTS / "sohc_single_cam.json")
    drive = json.loads((paths.ROOT / "tests" / "drives" / "sohc_single_cam.json").read_text())
    layout = Layout(spec, drive["sprockets"][1]["center"][1] - 0.4 - 1e-4)
    solver, _ = closure_angle(info(), layout.drive(116))
    path = guide_turn_for_links(layout, 116)
    assert solver is not None and path is not None
    assert abs(solver) > 1e-3 and path == pytest.approx(solver, abs=2e-5)


def test_the_default_style_tension_guide_cannot_take_up_a_worn_chain():
    """The tension guide of the default's design (face margins 20 mm) leaves the chain off its face's
    end after about a degree of turn: the path model and the solver both find no closure of one link
    more than the drawn pose takes (the solver's closure range holds at most 0.05 link more)."""
    spec = read_layout(LAYOUTS / "sohc_single_cam.json")
    shift, angle, _ = close_by_shift(info(), spec, 116)
    layout = Layout(spec, shift)
    assert guide_turn_for_links(layout, 116, spec.chain.pitch * 1.005) is None
    assert guide_turn_for_links(layout, 116, spec.chain.pitch * 1.0003) is not None


def mutate(layout, where, value):
    d = copy.deepcopy(layout)
    keys = where.split(".")
    target = d
    for key in keys[:-1]:
        target = target[int(key)] if key.isdigit() else target[key]
    last = keys[-1]
    if value is KeyError:
        del target[last]
    else:
        target[int(last) if last.isdigit() else last] = value
    return d


@pytest.mark.parametrize("where, value, named", [
    ("chain.designation", "07B-1", "chain.designation: \"07B-1\" is not one of 05B-1, 06B-1, 08B-1"),
    ("chain.numberOfLinks", 115, "chain.numberOfLinks: 115 is not an even integer"),
    ("sprockets.1.motion", "prescribed", "sprockets: exactly one sprocket has motion \"prescribed\""),
    ("sprockets.1.teeth", 4.5, "sprockets[1].teeth: 4.5 is not an integer from 7 to 200"),
    ("sprockets.1.center", [0, 0.4], "sprockets[1].center: given twice (center and center_mm)"),
    ("route", ["crankshaft", "tensionGuide", "camshaft", "fixedguide"], "route: \"fixedguide\" is neither"),
    ("route", ["crankshaft", "tensionGuide", "fixedGuide", "camshaft"], "guide 'fixedGuide' follows guide"),
    ("guides.0.radius_mm", float("nan"), "guides[0].radius_mm: NaN is not a finite number"),
    ("guides.0.at", 1.5, "guides[0].at: 1.5 lies outside [0.05, 0.95]"),
    ("closure.sprockets", ["crankshaft"], "closure.sprockets: the prescribed sprocket stays"),
    ("closure.direction", [0, 0], "closure.direction: [0, 0] has no direction"),
    ("rotation", "left", "rotation: \"left\" is not one of clockwise, counterclockwise"),
    ("guides.0.motion", "fixed", "guides: no pivoting guide: a drive needs a tension guide"),
    ("guides.1.radiuss_mm", 500, "guides[1].radiuss_mm: not a field here; the fields: at, margin, margin_mm"),
    ("guides.1.inertia", 1e-3, "guides[1].inertia: not a field here"),
    ("sprockets.0.inertia", 1e-3, "sprockets[0].inertia: not a field here"),
    ("chain.linkmass", 0.004, "chain.linkmass: not a field here"),
    ("tensioner.preLoad", 30.0, "tensioner.preLoad: not a field here"),
    ("closure", [], "closure: [] is not an object"),
    ("measurement", ["camshaft"], "measurement: [\"camshaft\"] is not an object"),
])
def test_a_layout_files_mistake_is_named(where, value, named, tmp_path):
    layout = json.loads((LAYOUTS / "sohc_single_cam.json").read_text())
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(mutate(layout, where, value)))
    with pytest.raises(UserError) as e:
        read_layout(path)
    assert str(e.value).startswith(f"{path}: ") and named in str(e.value), str(e.value)
    assert "\n" not in str(e.value)


def test_a_layout_files_mistake_through_the_command_is_one_line(tmp_path):
    layout = json.loads((LAYOUTS / "sohc_single_cam.json").read_text())
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(mutate(layout, "chain.designation", "10B-1")))
    line = one_error_line(*harness("layout", str(path), "--out", str(tmp_path / "d.json"))[::2])
    assert "chain.designation" in line and "05B-1, 06B-1, 08B-1" in line


def test_the_catalogue_says_where_each_number_comes_from():
    """Each chain's mass, inertia and joint data are marked sourced or estimated (the drive's stable
    step depends on them); 06B-1 is the default drive's chain to the digit."""
    from harness.drive.chains import CHAINS
    default = json.loads((paths.ROOT / "src" / "drives" / "default_drive.json").read_text())["chain"]
    c = CHAINS["06B-1"]
    assert (c.pitch, c.roller_d, c.plate_h, c.link_mass, c.link_inertia, c.joint_stiffness, c.joint_damping) == (
        default["pitch"], default["rollerDiameter"], default["plateHeight"], default["linkMass"],
        default["linkInertia"], default["joint"]["stiffness"], default["joint"]["damping"])
    for chain in CHAINS.values():
        assert {"pitch", "linkMass", "linkInertia", "joint.stiffness"} <= set(chain.sources)
        assert chain.sources["joint.stiffness"].startswith("estimated")
    assert math.isclose(CHAINS["08B-1"].pitch, 0.0127)


def test_the_pages_sketch_is_the_committed_layout_and_closes(tmp_path):
    """docs/model_your_drive.md's layout file is docs/model_your_drive/my_dohc.json, and the layout
    aid closes it with the link count and shift its committed report quotes."""
    page = (paths.ROOT / "docs" / "model_your_drive.md").read_text()
    block = page.split("```json\n", 1)[1].split("```", 1)[0]
    committed = paths.ROOT / "docs" / "model_your_drive" / "my_dohc.json"
    assert json.loads(block) == json.loads(committed.read_text())
    status, stdout, stderr = harness("layout", str(committed), "--out", str(tmp_path / "d.json"))
    assert status == 0, stderr
    report = (paths.ROOT / "docs" / "model_your_drive" / "layout.md").read_text()
    for line in stdout.splitlines():
        if line.startswith(("path at the drawn centres", "closure:", "wraps:")):
            assert line in report, line


def test_the_take_up_measures_a_known_elongation():
    """A known answer for the worn-chain figures: turn the tension guide by the angle that closes a
    chain 0.02 % longer (the path model), and the elongation the guide takes up at that angle is
    0.02 % to 1e-6; at the drawn pose it is 0 (the drive closes there with the new chain)."""
    from harness.drive.layout_drive import elongation_taken_up
    spec = read_layout(LAYOUTS / "sohc_single_cam.json")
    drive = json.loads((paths.ROOT / "tests" / "drives" / "sohc_single_cam.json").read_text())
    layout = Layout(spec, drive["sprockets"][1]["center"][1] - spec.sprocket("camshaft")["center"][1])
    turn = guide_turn_for_links(layout, 116, spec.chain.pitch * 1.0002)
    assert turn is not None and abs(turn) > 1e-3
    assert elongation_taken_up(layout, 116, turn) == pytest.approx(2e-4, abs=1e-6)
    assert elongation_taken_up(layout, 116, 0.0) == pytest.approx(0.0, abs=1e-6)
