"""The solver defaults per scene and fidelity: the one table of every entry point (src/run/defaults.h),
read from `chaindrive-info --defaults`, so that a run started here is the run the FMUs and the
command-line tools make with the same options.

    solver("timing", "span")  ->  Solver(method="fixed-verlet", step=3.3333333333333335e-05, tolerance=1e-05)
"""
import dataclasses
import functools
import json
import subprocess

from . import paths


@dataclasses.dataclass(frozen=True)
class Solver:
    method: str        # FMU parameter solver.method
    step: float        # [s] FMU parameter solver.step
    tolerance: float   # FMU parameter solver.tolerance


@functools.cache
def table():
    """{scene: {fidelity: Solver}} as the build's chaindrive-info prints it."""
    text = subprocess.run([paths.executable("chaindrive-info"), "--defaults"], capture_output=True, text=True,
                          check=True).stdout
    return {scene: {fidelity: Solver(row["method"], row["step_s"], row["tolerance"]) for fidelity, row in rows.items()}
            for scene, rows in json.loads(text).items()}


def solver(scene, fidelity="link"):
    """The defaults of a scene ("timing" or "cvt") and fidelity ("link" or "span")."""
    return table()[scene][fidelity]


def described(scene):
    """The scene's defaults in words for help texts: "link fixed-verlet at 2.5e-06 s, span ..."."""
    try:
        rows = table()[scene]
    except (FileNotFoundError, subprocess.CalledProcessError):  # (not built yet: the help still shows)
        return "the table of chaindrive-info --defaults"
    return ", ".join(f"{fidelity}: {s.method} at {s.step:g} s" for fidelity, s in rows.items())
