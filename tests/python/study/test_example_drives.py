"""The example drives (harness/study/example_drives.py): the physics checks' measurement on signals
with known answers, each example's exported interface against its committed model description,
and a brief main job of each example that runs alone, through the same checks."""
import json
import math
import pathlib
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from harness import cycle_stats, paths
from harness.drive import geometry as geo
from harness.drive.description import drive_json, elements
from harness.study import example_drives as ex


def synthetic_record(drive, cycles=6, per_cycle=400):
    """A record of the drive's outputs with known answers, sampled as the main job samples at
    3000 rpm (0.1 ms: 400 samples per engine cycle): the crankshaft at constant speed; each
    loaded sprocket's load a constant plus a cycle-periodic ripple, the span after it pulling
    exactly the load over its pitch radius more than the span before it (plus a ripple), its chain
    torque the load; the slack span's force 500 N plus 30 N at the meshing order and 3 N at each
    other half order from 1 to 40."""
    el, route = elements(drive), drive["chain"]["route"]
    phi = np.linspace(0.0, cycles * 4.0 * math.pi, cycles * per_cycle + 1)
    d = {el.crank + ".phi": phi, "time": phi / 300.0}
    spans = [f"chain.{a}.{route[(i + 1) % len(route)]}.F" for i, a in enumerate(route)]
    for name in spans:
        d[name] = np.full_like(phi, 800.0)
    teeth = {s["name"]: s["teeth"] for s in drive["sprockets"]}
    for k, name in enumerate(sorted(el.loaded, key=route.index)):  # (along the route: each span set once)
        load = 3.0 + k
        d[f"input.{name}.tau"] = load + 2.0 * np.sin(2.0 * phi)
        d[f"{name}.tauChain"] = d[f"input.{name}.tau"].copy()
        i = route.index(name)
        d[f"chain.{name}.{route[(i + 1) % len(route)]}.F"] = d[f"chain.{route[i - 1]}.{name}.F"] + \
            load / geo.pitch_radius(drive["chain"]["pitch"], teeth[name]) + 40.0 * np.sin(4.0 * phi)
    z = el.meshing_order
    d["chain.Fslack"] = 500.0 + 30.0 * np.cos(z * phi) + sum(3.0 * np.cos(0.5 * j * phi + j) for j in range(2, 81)
                                                              if 0.5 * j != z)
    return d


@pytest.mark.parametrize("name", ["diesel_pump", "dohc_8mm"])
def test_the_checks_measure_known_answers(name):
    """Through the same path as a main job's record: the pull equals each load (errors below 1e-9);
    the meshing order's amplitude is 30 N against neighbours of 3 N, each seen through the order
    analysis's linear interpolation of samples 1.8 deg apart, which passes order k by
    sinc^2(k / 200) (order 21: 0.982; at 6000 rpm, 200 samples per cycle, 0.93), to 1e-3."""
    drive = drive_json(ex.DRIVES / f"{name}.json")
    d = synthetic_record(drive)
    el = elements(drive)
    spans = cycle_stats.counted_spans(d[el.crank + ".phi"], 1, None)
    assert len(spans) == 5
    for row in ex.torque_balance(d, drive, el, spans[0][0], spans[-1][1]).values():
        assert abs(row["error"]) < 1e-9 and abs(row["chainTorqueError"]) < 1e-9, row
    m = ex.meshing_prominence(d, el, spans)
    z = el.meshing_order
    passed = lambda k: np.sinc(k / 200.0) ** 2  # noqa: E731
    neighbours = [3.0 * passed(0.5 * j) for j in range(2 * (z - 4), 2 * (z + 4) + 1) if 0.5 * j != z]
    assert m["amplitude_N"] == pytest.approx(30.0 * passed(z), rel=1e-3), m
    assert m["ratio"] == pytest.approx(30.0 * passed(z) / np.median(neighbours), rel=1e-3), m


def variables(xml):
    root = ET.fromstring(xml)
    return [(v.get("name"), v.get("valueReference"), v.get("causality")) for v in root.iter("ScalarVariable")]


@pytest.mark.parametrize("example", ex.EXAMPLES, ids=lambda e: e.name)
def test_each_example_exports_its_committed_interface(example, tmp_path):
    """The export's model description of each example drive has the committed variables (names,
    value references, causalities) and GUID: docs/examples/<name>/modelDescription.xml."""
    ex.model_description(example, tmp_path)
    committed = (ex.OUT / example.name / "modelDescription.xml").read_text()
    mine = (tmp_path / "modelDescription.xml").read_text()
    assert variables(mine) == variables(committed)
    assert ET.fromstring(mine).get("guid") == ET.fromstring(committed).get("guid")


@pytest.mark.parametrize("example", [e for e in ex.EXAMPLES if e.runs_alone], ids=lambda e: e.name)
def test_each_example_runs_briefly_within_its_checks(example, tmp_path):
    """Each example that runs alone: made by the layout aid bit for bit, its main job at 3000 rpm
    over 6 counted cycles with its own tables, the chain torque on each loaded sprocket within 5 %
    of its load, the pull across it within 15 %, the meshing order standing out, the energy
    balance within the main job's limit (looser than the committed 120-cycle checks: 6 cycles)."""
    row = ex.run_example(example, 3000.0, 6, tmp_path)
    assert row["layoutMatches"]
    c = row["checks"]
    for name, r in c["torqueBalance"].items():
        assert abs(r["chainTorqueError"]) < 0.05 and abs(r["error"]) < 0.15, (name, r)
    assert c["meshingOrder"]["ratio"] >= ex.MESHING_PROMINENCE, c["meshingOrder"]
    assert abs(c["energyBalanceError"]) <= c["energyBalanceLimit"]
    assert json.loads((tmp_path / example.name / "checks.json").read_text()) == c
