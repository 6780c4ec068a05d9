"""Where things are: the repository, the build directory and the executables.

ROOT is the folder above the package: the repository, with the package installed editable
(pip install -e ., as ./run.sh does) or used from the repository itself."""
import os
import pathlib

from .errors import MissingBuild

ROOT = pathlib.Path(__file__).resolve().parent.parent
BUILD = pathlib.Path(os.environ.get("CHAINDRIVE_BUILD", ROOT / "build"))
RESULTS = pathlib.Path(os.environ.get("CHAINDRIVE_RESULTS", ROOT / "results"))


def executable(name):
    path = BUILD / name
    if not path.exists():
        raise MissingBuild(f"{path} not found; build first (./run.sh builds into {BUILD})")
    return str(path)
