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
def printed():
    """The table as the build's chaindrive-info prints it: {scene: {fidelity: row}}, the row of drives
    with joints with clearance or rigid contacts under its fidelity's as "clearanceOrRigid"."""
    text = subprocess.run([paths.executable("chaindrive-info"), "--defaults"], capture_output=True, text=True,
                          check=True).stdout
    return json.loads(text)


def solver_of(row):
    return Solver(row["method"], row["step_s"], row["tolerance"])


@functools.cache
def table():
    """{scene: {fidelity: Solver}}."""
    return {scene: {fidelity: solver_of(row) for fidelity, row in rows.items()} for scene, rows in printed().items()}


def solver(scene, fidelity="link", clearance_or_rigid=False):
    """The defaults of a scene ("timing" or "cvt") and fidelity ("link" or "span"), for a drive whose
    joints have clearance or whose contacts are rigid where the table has a row for them (the link
    fidelity's real-time method needs joints without clearance and integrates compliant contacts)."""
    row = printed()[scene][fidelity]
    return solver_of(row["clearanceOrRigid"] if clearance_or_rigid and "clearanceOrRigid" in row else row)


def step_for(scene, fidelity, method, clearance_or_rigid=False):
    """The fixed step [s] of `method` where none is given (run/defaults.h: defaultStep): the own row's
    for its method, else the step of the scene and fidelity's row of that method, else that of its
    row for joints with clearance or rigid contacts (plain Verlet's checked step), else the own row's."""
    own = solver(scene, fidelity, clearance_or_rigid)
    if method == own.method:
        return own.step
    row = printed()[scene][fidelity]
    rows = [row] + ([row["clearanceOrRigid"]] if "clearanceOrRigid" in row else [])
    return next((r["step_s"] for r in rows if r["method"] == method), solver(scene, fidelity, True).step)


def described(scene):
    """The scene's defaults in words for help texts: "link: fixed-verlet-implicit-joint-damping at 3.57143e-06 s, span: ..."."""
    try:
        rows = table()[scene]
    except (FileNotFoundError, subprocess.CalledProcessError):  # (not built yet: the help still shows)
        return "the table of chaindrive-info --defaults"
    return ", ".join(f"{fidelity}: {s.method} at {s.step:g} s" for fidelity, s in rows.items())
