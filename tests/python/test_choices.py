"""Choices are parsed once: below the boundary (the description reader, the command-line tools),
src/ and fmu/ compare enums, never the names of a choice (src/choice.h)."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]
BOUNDARY = ("src/description/", "src/cli/")
TABLE_ENTRY = re.compile(r'\{\s*[A-Z]\w*::\w+,\s*"([^"]+)"\s*\}')
LITERAL = r'"([^"\\]*)"'
EQUALITIES = (re.compile(r'(?:==|!=)\s*' + LITERAL), re.compile(LITERAL + r'\s*(?:==|!=)'))
PREFIX_TESTS = re.compile(r'\.(?:compare|rfind|find|starts_with)\([^;]*?' + LITERAL)


def code_files():
    for folder in ("src", "fmu"):
        for path in sorted((ROOT / folder).rglob("*")):
            if path.suffix in (".h", ".cpp"):
                yield path, path.relative_to(ROOT).as_posix()


def choice_names():
    """Every name in a choice table (ChoiceNames<E>::table entries: {E::Value, "name"})."""
    names = set()
    for path, _ in code_files():
        names.update(TABLE_ENTRY.findall(path.read_text(encoding="utf-8")))
    return names


def compared_names(text, names):
    """The choice names (or prefixes of one) that the text compares a string with."""
    found = [literal for pattern in EQUALITIES for literal in pattern.findall(text) if literal in names]
    return found + [literal for literal in PREFIX_TESTS.findall(text)
                    if literal and any(name.startswith(literal) for name in names)]


def test_the_tables_hold_the_choices():
    names = choice_names()
    for expected in ("fixed-verlet-implicit-joint-damping", "time-stepping", "journal-bearing", "span",
                     "hunt-crossley", "time-stepping-rigid-pins"):
        assert expected in names


def test_no_choice_name_is_compared_below_the_boundary():
    names = choice_names()
    wrong = []
    for path, rel in code_files():
        if rel.startswith(BOUNDARY):
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            wrong += [f"{rel}:{number}: {literal}" for literal in compared_names(line, names)]
    assert not wrong, "choice names compared as strings below the boundary:\n" + "\n".join(wrong)


def test_the_check_sees_a_comparison():
    names = {"time-stepping", "fixed-verlet-implicit-damping"}
    assert compared_names('if (method == "time-stepping") return;', names) == ["time-stepping"]
    assert compared_names('m.rfind("fixed-verlet-implicit", 0) == 0', names) == ["fixed-verlet-implicit"]
    assert compared_names('if (header[0] != "time")', names) == []
