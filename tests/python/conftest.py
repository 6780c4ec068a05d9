"""Test helpers shared between test modules (harness_cli.py) are imported from this folder."""
import pathlib
import sys

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).parent))

# The test files that take minutes, longest first (their time in ./run.sh test on a clean clone).
# ./run.sh test gives each worker whole files in the order collected (--no-loadscope-reorder;
# xdist's default sends the files with the most tests first): with these last, one worker ran the
# two quick studies for the last minutes while the other had little left. First, the short files
# fill the gaps at the end instead.
SLOW_FILES_FIRST = ("package/test_package.py", "study/test_study.py", "fmu/test_grid.py",
                    "study/test_cvt_study.py", "sweep/test_sweep.py", "test_hydraulic_harness.py",
                    "study/test_chaos.py")


def pytest_collection_modifyitems(session, config, items):
    here = pathlib.Path(__file__).parent
    missing = [name for name in SLOW_FILES_FIRST if not (here / name).is_file()]
    if missing:  # (a renamed file would quietly fall back to the end of the order)
        raise pytest.UsageError(f"tests/python/conftest.py: SLOW_FILES_FIRST names {', '.join(missing)}, "
                                "which is not a test file under tests/python")

    def rank(item):
        path = pathlib.Path(str(item.fspath)).as_posix()
        ranks = [i for i, name in enumerate(SLOW_FILES_FIRST) if path.endswith("/tests/python/" + name)]
        return ranks[0] if ranks else len(SLOW_FILES_FIRST)
    items.sort(key=rank)  # (a stable sort: the order within a file and among the rest is kept)
