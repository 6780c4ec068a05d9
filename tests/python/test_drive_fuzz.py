"""Random drive descriptions through the exporter, as a user runs it (python -m harness export): a
valid drive (the default or a test drive) with one to three mutations, plausible or degenerate
(numbers made NaN, infinite, zero, negative, tiny or huge, written as a hand or Python's json module
writes them; sprockets moved onto each other, mirrored across the chain or shifted; guides moved
across the chain; tiny and huge link counts; duplicate, reserved and non-FMI names; keys removed,
elements duplicated, values of another type). Each export either writes the FMU or stops with
exit status 2 and one line `error: ...`; never a traceback, a hang or another status. The C++ side
(the description reader, the export's files, the FMU's instantiation and initialization) is fuzzed
under the sanitizers by fmi_call_fuzz --drives (tests/fuzz/drive_mutations.h)."""
import copy
import json
import math
import random
import subprocess
import sys

import pytest

from harness import paths

DRIVES = [paths.ROOT / "src" / "drives" / "default_drive.json"] + sorted((paths.ROOT / "tests" / "drives").glob("*.json"))
SEEDS = range(1, 41)
BAD_NAMES = ["", " ", "hp pump", "1cam", "cam.shaft", "der(x)", "tensioner", "solver", "link", "driveFile",
             "Nockenwelle ä", 'a"b', "cam\nshaft", "x[1]", "crankshaft"]
BAD_NUMBERS = [math.nan, math.inf, -math.inf, 0, -1, 1e300, 1e-300, 2.5, "3", True, [], {}]


def leaves(node, path=()):
    """(path, value) of every number, string and boolean."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield from leaves(value, path + (key,))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from leaves(value, path + (i,))
    else:
        yield path, node


def set_at(drive, path, value):
    node = drive
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value


def mutate(rng, drive):
    """One mutation, in words."""
    kind = rng.randrange(6)
    sprockets, guides = drive.get("sprockets", []), drive.get("guides", [])
    if kind == 0 and sprockets:
        a, b = rng.choice(sprockets), rng.choice(sprockets)
        a["center"] = copy.deepcopy(b.get("center"))
        return f"sprocket {a.get('name')!r} onto {b.get('name')!r}"
    if kind == 1 and guides:
        g = rng.choice(guides)
        dx, dy = rng.uniform(-0.06, 0.06), rng.uniform(-0.06, 0.06)
        for path, value in list(leaves(g)):
            if path and path[-1] in (0, 1) and isinstance(value, float) and "_deg" not in str(path):
                set_at(g, path, value + (dx if path[-1] == 0 else dy))
        return f"guide {g.get('name')!r} moved"
    if kind == 2:
        drive.setdefault("chain", {})["numberOfLinks"] = rng.choice([0, 1, 3, 7, 61, 5000, 100000, -4, 2.5, 1e12])
        return f"numberOfLinks {drive['chain']['numberOfLinks']}"
    if kind == 3 and sprockets + guides:
        element = rng.choice(sprockets + guides)
        element["name"] = rng.choice(BAD_NAMES + [e.get("name") for e in sprockets + guides])
        return f"a name {element['name']!r}"
    found = list(leaves(drive))
    path, value = rng.choice(found)
    if kind == 4 and len(path) > 1:
        parent = drive
        for key in path[:-2]:
            parent = parent[key]
        del parent[path[-2]]
        return f"{path[:-1]} removed"
    new = rng.choice(BAD_NUMBERS) if isinstance(value, (int, float)) else rng.choice(BAD_NAMES)
    set_at(drive, path, new)
    return f"{path} = {new!r}"


def mutated(seed):
    rng = random.Random(seed)
    drive = json.loads(rng.choice(DRIVES).read_text())
    what = []
    for _ in range(rng.randint(1, 3)):
        try:
            what.append(mutate(rng, drive))
        except (KeyError, IndexError, TypeError, AttributeError):  # (an earlier mutation changed the shape)
            what.append("skipped")
    return drive, "; ".join(what)


@pytest.mark.parametrize("seed", SEEDS)
def test_a_random_drive_exports_or_stops_with_one_line(seed, tmp_path):
    drive, what = mutated(seed)
    file = tmp_path / "drive.json"
    file.write_text(json.dumps(drive, indent=1))  # (NaN and Infinity as Python's json writes them)
    done = subprocess.run([sys.executable, "-m", "harness", "export", "--drive", str(file), "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=300, cwd=paths.ROOT)
    assert "Traceback" not in done.stderr, what
    assert done.returncode in (0, 2), f"{what}: status {done.returncode}: {done.stderr}"
    if done.returncode == 2:
        lines = done.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("error: "), f"{what}: {done.stderr}"
    else:
        assert list((tmp_path / "out").glob("*.fmu")), what
