"""The stages of src/ form a layered order (docs/layers.md): every #include of src/ points to its own
stage or one listed below it, numerics never include mechanics, and nothing includes fmu/."""
import pathlib
import re
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SRC = ROOT / "src"
STAGE_LINE = re.compile(r"^\d+\. `src/([\w/]*)`[^—]*— (\w+):")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)


def stages():
    """{folder relative to src ('' for the top level): (rank, kind)} from docs/layers.md."""
    listed = {}
    for line in (ROOT / "docs" / "layers.md").read_text(encoding="utf-8").splitlines():
        match = STAGE_LINE.match(line)
        if match:
            listed[match.group(1).rstrip("/")] = (len(listed), match.group(2))
    return listed


def folder_of(path):
    return "" if path.parent == SRC else path.parent.relative_to(SRC).as_posix()


def includes():
    """(including file, included file or None when it resolves nowhere in src/, the text)."""
    for path in sorted(SRC.rglob("*")):
        if path.suffix not in (".h", ".cpp"):
            continue
        for name in INCLUDE.findall(path.read_text(encoding="utf-8")):
            beside, from_src = path.parent / name, SRC / name
            target = beside if beside.exists() else from_src if from_src.exists() else None
            yield path, target, name


def arrows():
    """{(from folder, to folder): [example include]} between different folders."""
    found = {}
    for path, target, name in includes():
        if target is not None and folder_of(target) != folder_of(path):
            found.setdefault((folder_of(path), folder_of(target)), []).append(f"{path.relative_to(SRC.parent)}: {name}")
    return found


def test_every_folder_with_code_is_a_listed_stage():
    code_folders = {folder_of(p) for p in SRC.rglob("*") if p.suffix in (".h", ".cpp")}
    missing = sorted(code_folders - set(stages()))
    assert not missing, f"folders of src/ not placed in docs/layers.md: {missing}"


def test_includes_resolve_inside_src_and_never_reach_fmu():
    wrong = [f"{path.relative_to(ROOT)}: {name}" for path, target, name in includes()
             if target is None or name.startswith("fmu/")]
    assert not wrong, f"includes that do not resolve inside src/ (the FMI glue is above src/): {wrong}"


def test_no_arrow_climbs_the_stages():
    rank = stages()
    climbing = [f"{a or 'src/'} -> {b}: {where[0]}" for (a, b), where in arrows().items() if rank[b][0] > rank[a][0]]
    assert not climbing, "includes of a stage listed above the including one (docs/layers.md):\n" + "\n".join(climbing)


def test_numerics_include_no_mechanics():
    kind = {folder: k for folder, (_, k) in stages().items()}
    wrong = [f"{a} -> {b}: {where[0]}" for (a, b), where in arrows().items()
             if kind[a] == "numerics" and kind[b] == "mechanics"]
    assert not wrong, "numerics stages that include mechanics:\n" + "\n".join(wrong)


def test_the_folders_form_no_cycle():
    graph = {}
    for a, b in arrows():
        graph.setdefault(a, set()).add(b)
    state = {}

    def visit(node, path):
        state[node] = "open"
        for nxt in graph.get(node, ()):
            if state.get(nxt) == "open":
                pytest.fail("folder cycle: " + " -> ".join(path[path.index(nxt):] + [nxt]))
            if nxt not in state:
                visit(nxt, path + [nxt])
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node, [node])


def test_the_check_sees_a_climbing_include(tmp_path, monkeypatch):
    """The test itself: an include from math/ of dynamics/ is found as climbing and as mechanics."""
    fake = tmp_path / "src"
    (fake / "math").mkdir(parents=True)
    (fake / "dynamics").mkdir()
    (fake / "dynamics" / "data.h").write_text("#pragma once\n")
    (fake / "math" / "vec.h").write_text('#include "dynamics/data.h"\n')
    monkeypatch.setattr(sys.modules[__name__], "SRC", fake)
    found = arrows()
    assert ("math", "dynamics") in found
    rank = stages()
    assert rank["dynamics"][0] > rank["math"][0] and rank["math"][1] == "numerics"
