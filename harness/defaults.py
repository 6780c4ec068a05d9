"""The solver defaults per scene and fidelity: the one table of every entry point (src/run/defaults.h),
read from `chaindrive-info --defaults`, so that a run started here is the run the FMUs and the
command-line tools make with the same options. The timing rows' steps are a drive's own
(src/run/drive_defaults.h, docs/defaults.md#a-step-that-fits-the-drive): without a drive the default
drive's, the table's; with `drive=FILE` that drive's, read from `chaindrive-info --defaults --drive FILE`.

    solver("timing", "span")  ->  Solver(method="fixed-verlet", step=3.3333333333333335e-05, tolerance=1e-05)
    drive_solver("tests/drives/dohc_8mm.json")  ->  the drive's own link row (its step from its stability estimate)
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
def printed(drive=None):
    """The table as the build's chaindrive-info prints it: {scene: {fidelity: row}}, the row of drives
    with joints with clearance or rigid contacts under its fidelity's as "clearanceOrRigid"; each
    timing row with its "divisions" of 0.1 ms, "estimate_s", "margin" and "reason". With a drive file
    the timing rows are that drive's, and "drive" holds its name and whether its joints have clearance
    or its contacts are rigid ("clearanceOrRigid")."""
    command = [paths.executable("chaindrive-info"), "--defaults"] + (["--drive", str(drive)] if drive else [])
    return json.loads(subprocess.run(command, capture_output=True, text=True, check=True).stdout)


def solver_of(row):
    return Solver(row["method"], row["step_s"], row["tolerance"])


@functools.cache
def table():
    """{scene: {fidelity: Solver}} (the default drive's)."""
    return {scene: {fidelity: solver_of(row) for fidelity, row in rows.items()} for scene, rows in printed().items()}


def row_of(scene, fidelity="link", clearance_or_rigid=False, drive=None):
    """The printed row of a scene and fidelity (for a drive whose joints have clearance or whose contacts are
    rigid, its row where the table has one), of `drive`'s table when given."""
    row = printed(drive)[scene][fidelity]
    return row["clearanceOrRigid"] if clearance_or_rigid and "clearanceOrRigid" in row else row


def solver(scene, fidelity="link", clearance_or_rigid=False, drive=None):
    """The defaults of a scene ("timing" or "cvt") and fidelity ("link" or "span"), for a drive whose
    joints have clearance or whose contacts are rigid where the table has a row for them (the link
    fidelity's real-time method needs joints without clearance and integrates compliant contacts);
    with `drive` (a drive file) the timing steps of that drive."""
    return solver_of(row_of(scene, fidelity, clearance_or_rigid, drive))


def step_for(scene, fidelity, method, clearance_or_rigid=False, drive=None):
    """The fixed step [s] of `method` where none is given (run/defaults.h: defaultStepRow): the own row's
    for its method, else the step of the scene and fidelity's row of that method, else that of its
    row for joints with clearance or rigid contacts (plain Verlet's checked step), else the own row's;
    with `drive` that drive's steps."""
    own = solver(scene, fidelity, clearance_or_rigid, drive)
    if method == own.method:
        return own.step
    row = printed(drive)[scene][fidelity]
    rows = [row] + ([row["clearanceOrRigid"]] if "clearanceOrRigid" in row else [])
    return next((r["step_s"] for r in rows if r["method"] == method), solver(scene, fidelity, True, drive).step)


def drive_clearance_or_rigid(drive):
    """Whether the drive file's own link row is the one of joints with clearance or rigid contacts
    (as chaindrive-info reads the drive)."""
    return bool(printed(drive)["drive"]["clearanceOrRigid"])


def drive_solver(drive, fidelity="link"):
    """A drive file's own Solver of a fidelity of the timing scene: its row (the one of joints with
    clearance or rigid contacts where its joints or contacts call for it) with the drive's step."""
    return solver("timing", fidelity, drive_clearance_or_rigid(drive), drive)


def drive_step_for(drive, fidelity, method):
    """The step [s] a drive file's run takes for `method` named without a step (step_for on its own row)."""
    return step_for("timing", fidelity, method, drive_clearance_or_rigid(drive), drive)


def step_reason(fidelity="link", clearance_or_rigid=False, drive=None):
    """Why a timing row has its step, one line ("step 3.571e-06 s = 1e-4/28: the drive's stability estimate ...")."""
    return row_of("timing", fidelity, clearance_or_rigid, drive)["reason"]


def described(scene):
    """The scene's defaults in words for help texts: "link: fixed-verlet-implicit-joint-damping at 3.57143e-06 s, span: ..."."""
    try:
        rows = table()[scene]
    except (FileNotFoundError, subprocess.CalledProcessError):  # (not built yet: the help still shows)
        return "the table of chaindrive-info --defaults"
    return ", ".join(f"{fidelity}: {s.method} at {s.step:g} s" for fidelity, s in rows.items())
