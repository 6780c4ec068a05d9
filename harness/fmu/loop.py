"""The closed loop at compiled speed: the loop of harness/job.py (the sprockets' angles read, the
inputs looked up in their tables at those angles, fmi2DoStep, the row recorded) in C
(closed_loop.c, built with the system's C compiler at its first use into the build), on the
instance an fmu.Slave has made. The same bits as the Python loop: the C code does np.interp's and
math.degrees' arithmetic in their order, on the tables as np.interp prepares them (periodic());
tests/python/test_loop.py holds both loops to the same records.

An input is a Term: a constant, or a periodic table looked up at one of the angles read (shifted,
scaled, or a crankshaft speed)."""
import ctypes
import dataclasses
import functools
import hashlib
import os
import pathlib
import subprocess
import tempfile

import numpy as np

from .. import paths
from ..errors import UserError
from ..package.binaries import fmi2_include_dir

SOURCE = pathlib.Path(__file__).with_name("closed_loop.c")
FLAGS = ["-O2", "-std=c11", "-D_POSIX_C_SOURCE=200809L", "-fPIC", "-shared", "-ffp-contract=off", "-Wall",
         "-Werror"]
KINDS = {"constant": 0, "shifted": 1, "scaled": 2, "speed": 3}
REFUSED_CALLS = {1: "fmi2SetReal", 2: "fmi2DoStep", 3: "fmi2GetReal"}


def periodic(x, y, period):
    """(x, y) of a table over one period as np.interp extends them (numpy's own steps: the
    abscissae modulo the period, sorted, one point added beyond each end)."""
    x = np.asarray(x, dtype=np.float64) % period
    y = np.asarray(y, dtype=np.float64)
    order = np.argsort(x)
    x, y = x[order], y[order]
    return (np.ascontiguousarray(np.concatenate((x[-1:] - period, x, x[0:1] + period))),
            np.ascontiguousarray(np.concatenate((y[-1:], y, y[0:1]))))


@dataclasses.dataclass
class Term:
    """One input: `kind` constant (value), shifted (the table at angle + a), scaled (at angle * a)
    or speed (a times the table at the angle, rpm converted to rad/s when rpm); `angle` the index of
    the angle it reads; the table (x, y) over `period` [deg]."""
    kind: str
    angle: int = 0
    x: np.ndarray | None = None
    y: np.ndarray | None = None
    period: float = 0.0
    a: float = 0.0
    value: float = 0.0
    rpm: bool = False

    @classmethod
    def table(cls, kind, angle, x, y, period, a=0.0, rpm=False):
        px, py = periodic(x, y, period)
        return cls(kind, angle, px, py, float(period), float(a), rpm=rpm)


class _Term(ctypes.Structure):
    _fields_ = [("kind", ctypes.c_int), ("angle", ctypes.c_int), ("rpm", ctypes.c_int), ("n", ctypes.c_int),
                ("x", ctypes.c_void_p), ("y", ctypes.c_void_p), ("period", ctypes.c_double),
                ("a", ctypes.c_double), ("value", ctypes.c_double)]


class _RunUp(ctypes.Structure):
    _fields_ = [("nSpeeds", ctypes.c_int), ("speedInput", ctypes.c_int), ("speeds", ctypes.c_void_p),
                ("terms", ctypes.c_void_p), ("rpm", ctypes.c_double), ("rpmEnd", ctypes.c_double),
                ("rampStart", ctypes.c_double), ("rampTime", ctypes.c_double)]


@dataclasses.dataclass
class RunUp:
    """A run-up's inputs (harness/sweep/cases.py runup_inputs): {input: Term} at each tabulated
    speed `speeds` [rpm] (ascending; the same inputs in the same order), the mean speed ramped from
    rpm to rpm_end over ramp_s [s] from ramp_start [s]; `speed` the crankshaft speed's input."""
    speeds: list
    terms: list
    speed: str
    rpm: float
    rpm_end: float
    ramp_start: float
    ramp_s: float


class _Loop(ctypes.Structure):
    _fields_ = [("component", ctypes.c_void_p), ("doStep", ctypes.c_void_p), ("setReal", ctypes.c_void_p),
                ("getReal", ctypes.c_void_p), ("getInteger", ctypes.c_void_p), ("step", ctypes.c_double),
                *[(n, ctypes.c_int) for n in ("nAngles", "nInputs", "nReals", "nIntegers", "nColumns")],
                *[(n, ctypes.c_void_p) for n in ("angleRefs", "inputRefs", "realRefs", "integerRefs",
                                                  "realColumns", "integerColumns")],
                ("firstInputColumn", ctypes.c_int), ("terms", ctypes.c_void_p), ("runUp", ctypes.c_void_p),
                *[(n, ctypes.c_void_p) for n in ("angles", "inputs", "reals", "integers")],
                ("wallClock", ctypes.c_int)]


@functools.lru_cache(maxsize=None)
def library():
    """The compiled loop, built once per source and flags into the build (an atomic rename: several
    processes of a sweep may build it at once)."""
    key = hashlib.sha256(SOURCE.read_bytes() + " ".join(FLAGS).encode()).hexdigest()[:16]
    path = paths.BUILD / "loop" / f"closed_loop-{key}.so"
    if not path.exists():
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, temporary = tempfile.mkstemp(suffix=".so", dir=path.parent)
        os.close(fd)
        command = ["cc", *FLAGS, f"-I{fmi2_include_dir()}", str(SOURCE), "-o", temporary, "-lm"]
        try:
            built = subprocess.run(command, capture_output=True, text=True)
            problem = built.stderr.strip() if built.returncode != 0 else None
        except FileNotFoundError:
            problem = "no C compiler 'cc' on the PATH (./run.sh installs Debian's build-essential)"
        if problem:
            os.unlink(temporary)
            raise UserError(f"the compiled master loop ({SOURCE.name}) did not build: {problem}; "
                            f"--master-loop python runs the same loop through fmpy's calls") from None
        os.replace(temporary, path)
    lib = ctypes.CDLL(str(path))
    lib.runSteps.restype = ctypes.c_long
    lib.runSteps.argtypes = [ctypes.POINTER(_Loop), ctypes.c_long, ctypes.c_long, ctypes.c_int, ctypes.c_double,
                             ctypes.c_void_p, ctypes.c_void_p, ctypes.POINTER(ctypes.c_int),
                             ctypes.POINTER(ctypes.c_int)]
    lib.inputValue.restype = ctypes.c_double
    lib.inputValue.argtypes = [ctypes.POINTER(_Term), ctypes.c_void_p]
    return lib


def _c_term(t):
    """A Term as the C structure (pointing into the Term's own arrays)."""
    c = _Term(kind=KINDS[t.kind], angle=t.angle, rpm=int(t.rpm), a=t.a, value=t.value, period=t.period)
    if t.x is not None:
        c.n, c.x, c.y = len(t.x), t.x.ctypes.data, t.y.ctypes.data
    return c


def value_of(term, angles):
    """The compiled loop's value of one input at the angles [deg] (a check of its arithmetic)."""
    at = _array(angles, np.float64)
    return library().inputValue(ctypes.byref(_c_term(term)), at.ctypes.data)


def _array(values, dtype):
    return np.ascontiguousarray(np.asarray(values, dtype=dtype))


class CompiledLoop:
    """The loop on one fmu.Slave (instantiated and initialized): `angles` the output names read
    before each step (radians, turned to degrees), `terms` {input name: Term} (or a run_up's,
    blended), the row's columns: time, `outputs` (the slave's output names), then the inputs."""

    def __init__(self, slave, step, angles, terms, outputs, run_up=None):
        self.lib, self.slave = library(), slave
        fmu2 = slave.slave
        reals = [i for i, n in enumerate(outputs) if slave.type[n] == "Real"]
        integers = [i for i, n in enumerate(outputs) if slave.type[n] == "Integer"]
        self.n_columns = 1 + len(outputs) + len(terms)
        uint = np.uint32
        self._keep = {  # (the C structure points into these: kept alive with the loop)
            "angleRefs": _array([slave.vr[n] for n in angles], uint),
            "inputRefs": _array([slave.vr[n] for n in terms], uint),
            "realRefs": _array([slave.vr[outputs[i]] for i in reals], uint),
            "integerRefs": _array([slave.vr[outputs[i]] for i in integers], uint),
            "realColumns": _array([1 + i for i in reals], np.int32),
            "integerColumns": _array([1 + i for i in integers], np.int32),
            "angles": np.zeros(len(angles)), "inputs": np.zeros(len(terms)), "reals": np.zeros(len(reals)),
            "integers": np.zeros(len(integers), np.int32)}
        c_terms = (_Term * max(len(terms), 1))(*[_c_term(t) for t in terms.values()])
        self._terms, self._tables = c_terms, list(terms.values())
        self._run_up = self._c_run_up(run_up, list(terms)) if run_up else None
        functions = {f: ctypes.cast(getattr(fmu2.dll, "fmi2" + f[0].upper() + f[1:]), ctypes.c_void_p).value
                     for f in ("doStep", "setReal", "getReal", "getInteger")}  # (the FMU's, as fmpy loaded it)
        self.loop = _Loop(component=fmu2.component, **functions, step=step,
                          nAngles=len(angles), nInputs=len(terms), nReals=len(reals), nIntegers=len(integers),
                          nColumns=self.n_columns, firstInputColumn=1 + len(outputs),
                          terms=ctypes.addressof(c_terms),
                          runUp=ctypes.addressof(self._run_up[0]) if run_up else None,
                          **{k: v.ctypes.data for k, v in self._keep.items()}, wallClock=int(slave.wall_clock))

    def _c_run_up(self, run_up, names):
        """(the C structure, what it points into) of a RunUp whose inputs are `names`."""
        if any(list(at) != names for at in run_up.terms):
            raise ValueError(f"a run-up's inputs at every speed are the loop's: {names}")
        speeds = _array(run_up.speeds, np.float64)
        flat = [t for at in run_up.terms for t in at.values()]
        c_terms = (_Term * len(flat))(*[_c_term(t) for t in flat])
        c = _RunUp(nSpeeds=len(speeds), speedInput=names.index(run_up.speed), speeds=speeds.ctypes.data,
                   terms=ctypes.addressof(c_terms), rpm=run_up.rpm, rpmEnd=run_up.rpm_end,
                   rampStart=run_up.ramp_start, rampTime=run_up.ramp_s)
        return c, speeds, c_terms, flat

    def run(self, rows, cpus, k0, steps, stop_column=-1, stop_at=0.0):
        """Steps k0 .. k0 + steps - 1 into rows[k + 1] and cpus[k] (float64 arrays, C order, long
        enough); stops after the row whose column stop_column reaches stop_at. Returns (steps done,
        the refused call's name and status, or None)."""
        assert rows.flags.c_contiguous and rows.dtype == np.float64 and rows.shape[1] == self.n_columns
        assert rows.shape[0] >= k0 + steps + 1 and cpus.shape[0] >= k0 + steps
        status, call = ctypes.c_int(0), ctypes.c_int(0)
        done = self.lib.runSteps(ctypes.byref(self.loop), k0, steps, stop_column, stop_at, rows.ctypes.data,
                                 cpus.ctypes.data, ctypes.byref(status), ctypes.byref(call))
        refused = (REFUSED_CALLS[call.value], status.value) if status.value else None
        return int(done), refused
