"""The same bits on every platform: an FMU of dist/ run with each of its binaries and a binary
built from its sources/, the outputs of every communication step compared bit for bit.

- linux64: in this process through fmpy, in closed loop with the measured-torque tables (the
  main job's master loop, harness/job.py); the inputs it applied are recorded.
- win64: under wine, by a small FMI master of our own (fmi2_master.c, built with zig) that replays
  exactly those inputs, step by step, and names the resources folder as Windows importers do
  (file:///Z:/...; wine's drive Z: is the Linux root). Replaying is the closed loop: the loop's
  inputs are a function of the outputs, so equal outputs at every step mean equal inputs too.
  (fmpy's own win64 remoting is not used: its server watches a lock file that wine can always
  open, and it quits in the middle of a run.)
- sources: the linux64 binary built by fmpy from sources/ (fmpy.build, as an importer builds a
  source FMU), run as linux64 is.
The package command prints the comparison (--compare); tests/python/package asserts it.
"""
import concurrent.futures
import contextlib
import dataclasses
import os
import pathlib
import shutil
import struct
import subprocess
import zipfile
from urllib.parse import quote

import numpy as np
from fmpy import read_model_description

from .. import job
from ..drive.description import elements as drive_elements
from ..tables import tables
from ..fmu import fmu
from .binaries import fmi2_include_dir

WINE_DIR = "/usr/lib/wine"  # Debian's wine64
MASTER_SOURCE = pathlib.Path(__file__).with_name("fmi2_master.c")
MINGW_GCC = "x86_64-w64-mingw32-gcc"
TIMING_RPM = 3000.0
CVT_INPUTS = {"drivingPulley.w": fmu.rpm_to_rad_s(2000.0), "drivenPulley.tauLoad": 60.0}
COMMUNICATION_STEP = 1e-4


@dataclasses.dataclass
class Run:
    """What a run did and gave: parameters {name: value}, the inputs applied (row 0 before the
    initialization, row k before step k), the outputs after the initialization and every step."""
    parameters: dict
    inputs: dict   # name: array of steps + 1
    outputs: dict  # name: array of steps + 1
    log: list = dataclasses.field(default_factory=list)  # the FMU's messages


def unpack(fmu_file, dest):
    dest = pathlib.Path(dest)
    if dest.exists():
        shutil.rmtree(dest)
    with zipfile.ZipFile(fmu_file) as z:
        z.extractall(dest)
    return dest


def source_built(unzipped, dest):
    """A copy of the unpacked FMU whose linux64 binary is built from its sources/ by fmpy, as an
    importer builds a source FMU (its own CMake project, sources/ the only include directory), with
    one option: all its sources compiled as one translation unit (CMAKE_UNITY_BUILD with no batch
    limit), which parses and instantiates the Eigen and JSON headers once (ChainDrive here: 327
    CPU s against 480 CPU s in batches of 8); one process, so sources_built builds the FMUs
    side by side."""
    from fmpy.build import build_platform_binary
    dest = pathlib.Path(dest)
    if dest.exists():
        shutil.rmtree(dest)
    shutil.copytree(unzipped, dest, ignore=shutil.ignore_patterns("binaries"))
    build = dest.parent / f"{dest.name}-build"
    shutil.rmtree(build, ignore_errors=True)
    build.mkdir(parents=True)
    build_platform_binary(dest, build_dir=build,
                          cmake_options={"CMAKE_UNITY_BUILD": "ON", "CMAKE_UNITY_BUILD_BATCH_SIZE": "0"})
    binary = dest / "binaries" / "linux64" / f"{model_identifier(dest)}.so"
    if not binary.exists():
        raise FileNotFoundError(f"the source build wrote no {binary}")
    return dest


def sources_built(unpacked, work):
    """{FMU: folder}: source_built for each of {FMU: unpacked folder}, all at once (a thread each
    waiting for its compiler); the folders are work/<FMU>-sources."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=len(unpacked)) as pool:
        futures = {f: pool.submit(source_built, folder, pathlib.Path(work) / f"{f}-sources")
                   for f, folder in unpacked.items()}
        return {f: future.result() for f, future in futures.items()}


def model_identifier(fmu_dir):
    return read_model_description(str(fmu_dir)).coSimulation.modelIdentifier


# ---- linux64 in this process ----

def run_timing(fmu_dir, duration, method=None):
    """ChainDrive in closed loop with the measured-torque tables at 3000 rpm, the main job's
    options and master loop (default method unless `method`)."""
    return run_recorded(job.run_config(rpm=TIMING_RPM, method=method or None), duration, fmu_dir)[0]


def run_recorded(config, duration, fmu_dir=None):
    """ChainDrive run as `config` says over `duration`, in the main job's closed loop with the
    measured-torque tables: (Run, the CPU seconds inside each fmi2DoStep)."""
    elements = drive_elements(config.drive)
    inputs = job.table_inputs(job.drive_loads(config, elements), tables.crankshaft_speed(config.rpm, config.tables),
                              elements)
    record, step_cpus, _ = job.run_closed(config, duration, inputs, progress=False, fmu_file=fmu_dir)
    # (the record's inputs of row 0 are those of the initialization, looked up at zero angles)
    applied = {name: np.array(record[f"input.{name}"]) for name in inputs(0.0, {n: 0.0 for n in inputs.angles})}
    outputs = {k: v for k, v in record.items() if k != "time" and not k.startswith("input.")}
    return Run(job.parameters_of(config), applied, outputs), step_cpus


def run_cvt(fmu_dir, duration):
    """CVTChain at constant driving speed and load (the inputs set before every step)."""
    s = fmu.Slave("cvt", fmu=fmu_dir)
    s.initialize(inputs=CVT_INPUTS)
    rows = [s.get()]
    steps = int(round(duration / COMMUNICATION_STEP))
    for k in range(steps):
        s.step(COMMUNICATION_STEP, inputs=CVT_INPUTS, t=k * COMMUNICATION_STEP)
        rows.append(s.get())
    s.close()
    inputs = {name: np.full(steps + 1, value) for name, value in CVT_INPUTS.items()}
    return Run({}, inputs, {name: np.array([r[name] for r in rows]) for name in rows[0]}, s.messages)


# ---- win64 under wine ----

@contextlib.contextmanager
def wine(prefix):
    """wine64 ready while the block runs: on the PATH (Debian keeps it in /usr/lib/wine), its
    prefix (the Windows folders) in `prefix`, its diagnostics off, and its server kept running
    (wine starts and stops its server around each program otherwise, and a program started while
    the server stops now and then does not run)."""
    if not os.path.exists(os.path.join(WINE_DIR, "wine64")):
        raise FileNotFoundError(f"{WINE_DIR}/wine64 not found: install Debian's wine64 (./run.sh test does)")
    if WINE_DIR not in os.environ["PATH"].split(os.pathsep):
        os.environ["PATH"] = WINE_DIR + os.pathsep + os.environ["PATH"]
    os.environ["WINEPREFIX"] = str(prefix)
    os.environ["WINEDEBUG"] = "-all"
    pathlib.Path(prefix).mkdir(parents=True, exist_ok=True)
    subprocess.run(["wineserver", "-p"], check=True)
    try:
        yield
    finally:
        subprocess.run(["wineserver", "-k"])


def build_linux_master(work):
    """fmi2_master.c for linux64, with the system's C compiler."""
    exe = pathlib.Path(work) / "fmi2_master"
    exe.parent.mkdir(parents=True, exist_ok=True)
    subprocess.run(["cc", "-O2", "-Wall", "-Werror", f"-I{fmi2_include_dir()}", str(MASTER_SOURCE), "-o", str(exe),
                    "-ldl"], check=True)
    return exe


def build_master(work):
    """fmi2_master.c for win64, with Debian's MinGW-w64 GCC (gcc-mingw-w64-x86-64-win32, which
    ./run.sh test installs): a test program, not a shipped binary, so not with zig, whose cache
    missed the MinGW runtime of an executable after the FMUs' cross build on a clean clone (540 s
    of CI's pytest; the Debian package installs in 86 s here, the master compiles in 6 s)."""
    if shutil.which(MINGW_GCC) is None:
        raise FileNotFoundError(f"{MINGW_GCC} not found: install Debian's gcc-mingw-w64-x86-64-win32 "
                                "(./run.sh test does)")
    exe = pathlib.Path(work) / "fmi2_master.exe"
    exe.parent.mkdir(parents=True, exist_ok=True)
    subprocess.run([MINGW_GCC, "-O2", "-s", "-Wall", "-Werror", f"-I{fmi2_include_dir()}", str(MASTER_SOURCE),
                    "-o", str(exe)], check=True)
    return exe


def windows_uri(path):
    return "file:///Z:" + quote(pathlib.Path(path).resolve().as_posix())


def replay_on_windows(master, fmu_dir, run, work):
    """The run's parameters and inputs replayed on the FMU's win64 binary under wine; returns
    the Run it gives (its outputs and the FMU's log)."""
    dll = pathlib.Path(fmu_dir) / "binaries" / "win64" / f"{model_identifier(fmu_dir)}.dll"
    return replay(["wine64", str(master)], dll, windows_uri(pathlib.Path(fmu_dir) / "resources"), fmu_dir, run, work)


def replay(master, binary, resources_uri, fmu_dir, run, work, step=COMMUNICATION_STEP):
    """The run's parameters and inputs (one row per communication step of `step`) replayed by
    fmi2_master.c (the command `master`) on `binary`; returns the Run it gives (its outputs and
    the FMU's log, whose last line is the master's, with the CPU time inside fmi2DoStep)."""
    md = read_model_description(str(fmu_dir))
    variables = {v.name: v for v in md.modelVariables}
    reals = [n for n in run.outputs if variables[n].type == "Real"]
    integers = [n for n in run.outputs if variables[n].type == "Integer"]
    scenario, outputs = pathlib.Path(work) / "scenario.txt", pathlib.Path(work) / "outputs.txt"
    scenario.write_text(scenario_text(run, variables, reals, integers, step))
    command = [*master, str(binary), md.guid, resources_uri, str(scenario), str(outputs)]
    returncode, log, errors = run_to_files(command, pathlib.Path(work) / "master")
    if returncode != 0 and not log:
        # (the master says why whenever it fails; no word at all means wine did not run it)
        returncode, log, errors = run_to_files(command, pathlib.Path(work) / "master")
    if returncode != 0:
        raise RuntimeError(f"fmi2_master failed ({returncode}): {' | '.join(log[-5:])} {errors[-500:]}")
    rows = [line.split() for line in outputs.read_text().splitlines()]
    got = {n: np.array([bits_to_float(r[i]) for r in rows]) for i, n in enumerate(reals)}
    got.update({n: np.array([int(r[len(reals) + i]) for r in rows]) for i, n in enumerate(integers)})
    return Run(run.parameters, run.inputs, got, log)


def run_to_files(command, stem):
    """Runs command with its output in files (stem.out, stem.err); returns (exit code, lines of
    standard output, standard error). Files, not pipes: wine's own background processes inherit
    the program's output and would hold a pipe open after the program ends."""
    out, err = stem.with_suffix(".out"), stem.with_suffix(".err")
    with open(out, "w") as o, open(err, "w") as e:
        returncode = subprocess.run(command, stdout=o, stderr=e, timeout=1800).returncode
    return returncode, out.read_text().splitlines(), err.read_text()


def scenario_text(run, variables, reals, integers, step=COMMUNICATION_STEP):
    """The scenario file of fmi2_master.c."""
    lines = [f"parameters {len(run.parameters)}"]
    for name, value in run.parameters.items():
        v = variables[name]
        if v.type == "Real":
            lines.append(f"{v.valueReference} r {float_to_bits(value)}")
        elif v.type in ("Integer", "Boolean"):
            lines.append(f"{v.valueReference} {v.type[0].lower()} {int(value)}")
        else:
            if not value or any(c.isspace() for c in str(value)):
                raise ValueError(f"parameter {name}: '{value}' cannot be replayed (empty or with spaces)")
            lines.append(f"{v.valueReference} s {value}")
    names = list(run.inputs)
    lines.append(f"inputs {len(names)} " + " ".join(str(variables[n].valueReference) for n in names))
    lines.append(f"reals {len(reals)} " + " ".join(str(variables[n].valueReference) for n in reals))
    lines.append(f"integers {len(integers)} " + " ".join(str(variables[n].valueReference) for n in integers))
    steps = len(run.inputs[names[0]]) - 1
    lines.append(f"steps {steps} {float_to_bits(step)}")
    for k in range(steps + 1):
        lines.append(" ".join(float_to_bits(run.inputs[n][k]) for n in names))
    return "\n".join(lines) + "\n"


def float_to_bits(x):
    return struct.pack(">d", float(x)).hex()


def bits_to_float(text):
    return struct.unpack(">d", bytes.fromhex(text))[0]


# ---- comparison ----

@dataclasses.dataclass
class Comparison:
    """Two runs' outputs compared bit for bit."""
    variables: int
    steps: int
    differing: list  # names of the variables that differ somewhere
    first: str       # the first difference (step, variable, both values), or ""

    @property
    def identical(self):
        return not self.differing


def compare(a, b):
    names = sorted(a.outputs)
    if sorted(b.outputs) != names:
        raise ValueError(f"the runs have different outputs: {sorted(set(a.outputs) ^ set(b.outputs))}")
    differing, first, first_step = [], "", None
    for name in names:
        x, y = np.asarray(a.outputs[name], dtype=float), np.asarray(b.outputs[name], dtype=float)
        same = x.view(np.int64) == y.view(np.int64)  # (bits: NaN equals NaN, -0 differs from 0)
        if len(x) == len(y) and same.all():
            continue
        differing.append(name)
        k = int(np.argmin(same)) if len(x) == len(y) else min(len(x), len(y))
        if first_step is None or k < first_step:
            first_step, first = k, f"step {k}: {name} {x[k] if k < len(x) else None!r} against " \
                                   f"{y[k] if k < len(y) else None!r}"
    return Comparison(len(names), len(a.outputs[names[0]]) - 1, differing, first)
