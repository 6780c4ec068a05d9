"""The documentation against what it describes: README.md stays a front door of at most 200 lines,
every figure quoted from a committed result file equals the file's value at the printed precision,
every relative link points to an existing file (and heading), and the FMU variable tables match
the model descriptions.

Figures: a quoted figure is followed by a marker naming its source,

    85.30 ± 0.65 N<!-- figure: docs/main_job/summary.json tensioner.F.mean/mean tensioner.F.mean/ci95 -->

one key path per number: the last numbers of the text before the marker (in its table cell or
line) are compared in order. A key path is a chain of `/`-separated steps: a dictionary key (keys
may hold dots), a list index, or `[field=value]` for the element of a list whose field has that
value; `*100` at its end scales the value (a fraction printed in %). A source that is itself a
result written by a script in Markdown (docs/benchmark_*.md) is quoted by a text it contains,

    0.787<!-- figure: docs/benchmark_realtime.md "RTF (CPU s inside fmi2DoStep per simulated s): **0.787**" -->

and every number of the figure must occur in that text. A sweep's dataset (.nc) is quoted by
VARIABLE@COORDINATE=VALUE per number, several coordinates joined by commas
(tensioner.F.mean@rpm=3000,supply_pressure_bar=5).

The variable tables of docs/fmu.md are generated from the model descriptions between
`<!-- variables: FILE -->` and `<!-- end variables -->`; `python tests/python/test_docs.py`
writes them again after a model description changed, and the marked figures from their result
files after a result file changed (at the printed precision; the text around them is read anew).
"""
import json
import pathlib
import re
import sys
import xml.etree.ElementTree as ET
import zipfile

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
MAX_README_LINES = 200


def documents():
    """README.md and every Markdown file under docs/."""
    return [README] + sorted((ROOT / "docs").rglob("*.md"))


def rel(path):
    return path.relative_to(ROOT).as_posix()


# ---------------------------------------------------------------------------------------------
# figures

MARKER = re.compile(r"<!--\s*figure:\s*(\S+)\s+(.*?)\s*-->")
NUMBER = re.compile(r"(?<![\w.])[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?(?![\w.])")


def markers():
    """(document, line number, source, arguments, the figure's text) for every figure marker."""
    found = []
    for doc in documents():
        for number, line in enumerate(doc.read_text(encoding="utf-8").splitlines(), start=1):
            start = 0
            for match in MARKER.finditer(line):
                before = line[start:match.start()]
                before = before[before.rfind("|") + 1:]      # the table cell the figure stands in
                found.append((doc, number, match.group(1), match.group(2), before))
                start = match.end()
    return found


def resolve(data, path):
    """The value at a key path (see the module's docstring)."""
    scale = 1.0
    if "*" in path:
        path, factor = path.rsplit("*", 1)
        scale = float(factor)
    value = data
    for step in path.split("/"):
        selector = re.fullmatch(r"\[(\w+)=([^\]]+)\]", step)
        if selector:
            field, wanted = selector.groups()
            matches = [item for item in value if str(item.get(field)) == wanted
                       or (_is_number(wanted) and _is_number(item.get(field))
                           and float(item[field]) == float(wanted))]
            assert len(matches) == 1, f"{step}: {len(matches)} elements match"
            value = matches[0]
        elif isinstance(value, list):
            value = value[int(step)]
        else:
            value = value[step]
    return value * scale


def _is_number(x):
    try:
        float(x)
        return True
    except (TypeError, ValueError):
        return False


def agrees(printed, value):
    """Whether value, printed at the precision of `printed`, gives `printed`."""
    mantissa = printed.lower().split("e")[0]
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    exponent = int(printed.lower().split("e")[1]) if "e" in printed.lower() else 0
    half_unit = 0.5 * 10.0 ** (exponent - decimals)
    return abs(value - float(printed)) <= half_unit * (1 + 1e-9)


def nc_value(ds, key):
    """The value of VARIABLE@COORDINATE=VALUE[,COORDINATE=VALUE...] in a sweep's dataset: the one
    point whose coordinates (along `point`: rpm, supply_pressure_bar, ...) have those values."""
    name, selectors = key.split("@")
    variable = ds[name]
    for selector in selectors.split(","):
        coordinate, wanted = selector.split("=")
        variable = variable.where(variable[coordinate] == float(wanted), drop=True)
    assert variable.size == 1, f"{key}: {variable.size} values match"
    return float(variable.item())


def test_there_are_figure_markers():
    assert len(markers()) >= 10


@pytest.mark.parametrize("doc, line, source, arguments, figure",
                         [pytest.param(*m, id=f"{rel(m[0])}:{m[1]}") for m in markers()])
def test_figure_equals_its_source(doc, line, source, arguments, figure):
    where = f"{rel(doc)}:{line}"
    path = ROOT / source
    assert path.is_file(), f"{where}: the source {source} does not exist"
    numbers = NUMBER.findall(figure)
    if path.suffix == ".json":
        keys = arguments.split()
        assert len(numbers) >= len(keys), f"{where}: {len(keys)} key paths but the figure {figure!r} has {numbers}"
        data = json.loads(path.read_text(encoding="utf-8"))
        for printed, key in zip(numbers[-len(keys):], keys):
            value = resolve(data, key)
            assert agrees(printed, value), f"{where}: {printed} but {source} {key} is {value}"
    elif path.suffix == ".nc":  # a sweep's dataset: VARIABLE@COORDINATE=VALUE[,COORDINATE=VALUE...] per number
        import xarray
        keys = arguments.split()
        with xarray.open_dataset(path) as ds:
            for printed, key in zip(numbers[-len(keys):], keys):
                value = nc_value(ds, key)
                assert agrees(printed, value), f"{where}: {printed} but {source} {key} is {value}"
    else:
        quoted = re.fullmatch(r'"(.*)"', arguments)
        assert quoted, f"{where}: a Markdown source is quoted by a text in double quotes"
        text = quoted.group(1)
        assert text in path.read_text(encoding="utf-8"), f"{where}: {source} no longer says {text!r}"
        assert numbers, f"{where}: no number before the marker"
        for printed in numbers:
            assert printed.lstrip("+") in NUMBER.findall(text) or printed in text, \
                f"{where}: {printed} is not in the quoted text {text!r}"


# ---------------------------------------------------------------------------------------------
# README

def test_readme_is_at_most_200_lines():
    lines = README.read_text(encoding="utf-8").count("\n")
    assert lines <= MAX_README_LINES, f"README.md has {lines} lines; the reference belongs in docs/"


# ---------------------------------------------------------------------------------------------
# links

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def slug(heading):
    """GitHub's anchor of a heading."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower().replace("`", ""))
    return text.replace(" ", "-")


def anchors(path):
    out = set()
    inside_code = False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            inside_code = not inside_code
        elif not inside_code and line.startswith("#"):
            out.add(slug(line.lstrip("#")))
    return out


def links():
    found = []
    for doc in documents():
        inside_code = False
        for number, line in enumerate(doc.read_text(encoding="utf-8").splitlines(), start=1):
            if line.startswith("```"):
                inside_code = not inside_code
                continue
            if inside_code:
                continue
            for target in LINK.findall(line):
                if re.match(r"^[a-z]+:", target):     # http:, https:, mailto:
                    continue
                found.append((doc, number, target))
    return found


def test_relative_links_point_to_existing_files():
    broken = []
    for doc, number, target in links():
        name, _, anchor = target.partition("#")
        path = (doc.parent / name).resolve() if name else doc
        if not path.exists():
            broken.append(f"{rel(doc)}:{number}: {target} (no such file)")
        elif anchor and path.suffix == ".md" and anchor not in anchors(path):
            broken.append(f"{rel(doc)}:{number}: {target} (no such heading)")
    assert not broken, "broken links:\n" + "\n".join(broken)


# ---------------------------------------------------------------------------------------------
# FMU variables

def variables(xml):
    """[(name, causality, variability, type, unit, start, description)] of a model description: a
    file of the repository, or ChainDrive.fmu's (generated from the default drive: the build's)."""
    if xml == "ChainDrive.fmu":
        from harness.fmu import fmu
        root = ET.fromstring(zipfile.ZipFile(fmu.fmu_path()).read("modelDescription.xml"))
    else:
        root = ET.parse(ROOT / xml).getroot()
    declared = {t.get("name"): t[0] for t in root.iter("SimpleType")}
    out = []
    for var in root.iter("ScalarVariable"):
        kind = var[0]
        unit = kind.get("unit") or (declared[kind.get("declaredType")].get("unit")
                                    if kind.get("declaredType") else None)
        out.append((var.get("name"), var.get("causality"), var.get("variability"), kind.tag,
                    unit or "", kind.get("start", ""), var.get("description", "")))
    return out


def variable_table(xml):
    rows = ["| variable | causality | type | unit | start | description |", "|---|---|---|---|---|---|"]
    for name, causality, _, kind, unit, start, description in variables(xml):
        start = f'"{start}"' if kind == "String" else start
        rows.append(f"| `{name}` | {causality} | {kind} | {unit} | {start} | {description.replace('|', '/')} |")
    return "\n".join(rows)


BLOCK = re.compile(r"(<!-- variables: (\S+) -->\n)(.*?)(<!-- end variables -->)", re.DOTALL)


def fmu_reference(write=False):
    path = ROOT / "docs" / "fmu.md"
    text = path.read_text(encoding="utf-8")
    renewed = BLOCK.sub(lambda m: m.group(1) + variable_table(m.group(2)) + "\n" + m.group(4), text)
    if write:
        path.write_text(renewed, encoding="utf-8")
    return text, renewed


def test_fmu_reference_lists_every_variable_of_both_model_descriptions():
    text, renewed = fmu_reference()
    described = {m.group(2) for m in BLOCK.finditer(text)}
    assert described == {"ChainDrive.fmu", "modelDescription/CVTChain.xml"}
    assert text == renewed, "docs/fmu.md's variable tables differ from the model descriptions: " \
                            "python tests/python/test_docs.py writes them again"


INTERFACE = re.compile(r"<!-- interface: (\S+) -->\n((?:\|.*\n)+)")


def test_readme_interface_table_matches_the_model_description():
    text = README.read_text(encoding="utf-8")
    tables = INTERFACE.findall(text)
    assert tables, "README.md has no FMU interface table (<!-- interface: FILE --> before it)"
    for xml, table in tables:
        known = {v[0]: v for v in variables(xml)}
        rows = [r for r in table.splitlines()[2:] if r.strip()]
        assert rows
        listed = set()
        for row in rows:
            cells = [c.strip() for c in row.strip().strip("|").split("|")]
            names, causality, start = re.findall(r"`([^`]+)`", cells[0]), cells[1], cells[3]
            units = [u.strip() for u in cells[2].split(",")]
            assert names, row
            for i, name in enumerate(names):
                assert name in known, f"README: {name} is not a variable of {xml}"
                _, c, _, _, u, s, _ = known[name]
                assert causality == c, f"README: {name} is {c} in {xml}, not {causality}"
                unit = units[i] if len(units) == len(names) else units[0]
                assert unit in (u, "-") if not u else unit == u, \
                    f"README: {name} has the unit {u!r} in {xml}, not {unit!r}"
                if start:
                    assert start == s or (_is_number(start) and _is_number(s) and agrees(start, float(s))), \
                        f"README: {name} starts at {s!r} in {xml}, not {start!r}"
                listed.add(name)
        inputs = {n for n, v in known.items() if v[1] == "input"}
        assert inputs <= listed, f"README's interface table lacks the inputs {sorted(inputs - listed)}"


def source_values(path, keys):
    """The values of the key paths in a result file (.json or a sweep's .nc), in order."""
    if path.suffix == ".json":
        data = json.loads(path.read_text(encoding="utf-8"))
        return [resolve(data, key) for key in keys]
    import xarray
    with xarray.open_dataset(path) as ds:
        return [nc_value(ds, key) for key in keys]


def printed_like(printed, value):
    """value printed as `printed` is: as many decimals, its sign shown when `printed` shows one."""
    decimals = len(printed.split(".")[1]) if "." in printed else 0
    return ("+" if printed.startswith("+") and value >= 0 else "") + f"{value:.{decimals}f}"


def update_figures(doc):
    """Writes the marked figures of a document again from their result files (.json, .nc; figures
    quoted from Markdown and those with an exponent stay); returns how many changed."""
    changed = 0
    lines = doc.read_text(encoding="utf-8").split("\n")
    for n, line in enumerate(lines):
        start, out = 0, []
        for m in MARKER.finditer(line):
            path, keys = ROOT / m.group(1), m.group(2).split()
            cell = max(start, line.rfind("|", 0, m.start()) + 1)
            out.append(line[start:cell])
            segment = line[cell:m.start()]
            found = list(NUMBER.finditer(segment))[-len(keys):] if path.suffix in (".json", ".nc") else []
            if found and all("e" not in f.group().lower() for f in found):
                values = source_values(path, keys[-len(found):])
                for f, value in reversed(list(zip(found, values))):
                    new = printed_like(f.group(), value)
                    changed += new != f.group()
                    segment = segment[:f.start()] + new + segment[f.end():]
            out.append(segment + m.group(0))
            start = m.end()
        lines[n] = "".join(out) + line[start:]
    doc.write_text("\n".join(lines), encoding="utf-8")
    return changed


if __name__ == "__main__":
    # after a model description or a committed result file changed: the generated tables and the
    # marked figures written again (then read the text around each changed figure)
    before, after = fmu_reference(write=True)
    print("docs/fmu.md: variable tables " + ("unchanged" if before == after else "written"))
    for doc in documents():
        count = update_figures(doc)
        if count:
            print(f"{rel(doc)}: {count} figures written from their result files")
    sys.exit(0)
