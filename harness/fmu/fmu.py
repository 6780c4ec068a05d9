"""ChainDrive.fmu (and CVTChain.fmu) from Python: a thin wrapper around fmpy's FMU2Slave for master
loops, with the FMU's log messages collected. A call the FMU refuses raises Refusal: fmpy's
FMICallException (function, status) and a UserError whose one line is the FMU's reason."""
import contextlib
import functools
import math
import os
import time

from fmpy import calloc, extract, free, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)

from .. import paths
from ..errors import MissingBuild, UserError

def fmu_path(name="ChainDrive"):
    """The built FMU: ChainDrive (the timing drive) or CVTChain (the chain CVT)."""
    path = paths.BUILD / f"{name}.fmu"
    if not path.exists():
        raise MissingBuild(f"{path} not found; build first (./run.sh builds it)")
    return path


@functools.lru_cache(maxsize=None)
def unpacked(path=None):
    """(model description, unzip directory) of the FMU, extracted once per process (a folder is
    taken as the FMU already unpacked)."""
    path = str(path or fmu_path())
    return read_model_description(path), path if os.path.isdir(path) else extract(path)


class Refusal(UserError, FMICallException):
    """An FMI call the FMU refused (fmi2Discard, fmi2Error, or an instance it did not create):
    str() is one line with the FMU, the reasons it logged during the call and the call."""

    def __init__(self, fmu_name, function, status, reasons):
        FMICallException.__init__(self, function, status)
        self.fmu_name, self.reasons = fmu_name, list(reasons)
        reason = " | ".join(self.reasons) or "no reason logged"
        label = {2: "fmi2Discard", 3: "fmi2Error", 4: "fmi2Fatal"}.get(status, f"status {status}")
        self.args = (f"{fmu_name}: {reason} ({function} returned {label})",)

    def __reduce__(self):  # (pickled by Dask workers: the constructor's arguments, not the message)
        return type(self), (self.fmu_name, self.function, self.status, self.reasons)


class Slave:
    """One FMU instance driven step by step (a co-simulation master's view)."""

    def __init__(self, name="chaindrive", fmu=None, logging_on=False, parameters=None, guid=None, wall_clock=False):
        # the clock of each step's time (step_cpus): this thread's CPU time, or, where the FMU's step
        # runs on several threads (solver.threads), the wall clock
        self.wall_clock = wall_clock
        self.clock = time.perf_counter if wall_clock else time.thread_time
        self.md, self.unzipdir = unpacked(fmu)
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.type = {v.name: v.type for v in self.md.modelVariables}
        self.outputs = [v.name for v in self.md.modelVariables if v.causality == "output"]
        self.fmu_name = f"{self.md.coSimulation.modelIdentifier}.fmu"
        self.messages = []  # (status, category, message)
        self._callbacks = fmi2CallbackFunctions()
        self._logger = fmi2CallbackLoggerTYPE(self._log)
        self._callbacks.logger = self._logger
        self._callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self._callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self.slave = FMU2Slave(guid=guid or self.md.guid, unzipDirectory=self.unzipdir,
                               modelIdentifier=self.md.coSimulation.modelIdentifier, instanceName=name)
        with self.refusals("fmi2Instantiate"):
            self.slave.instantiate(callbacks=self._callbacks, loggingOn=logging_on)
        self.parameters = dict(parameters or {})
        self.time = 0.0
        self.step_cpus = []  # [s] CPU time inside each fmi2DoStep: the FMU's own cost, without the master's

    def _log(self, component, instance, status, category, message):
        # the message is a printf format (FMI 2.0 2.1.5); the FMU passes no arguments and doubles
        # every '%' of its text, which formatting undoes
        text = message.decode(errors="replace").replace("%%", "%")
        self.messages.append((status, category.decode(), text))

    @contextlib.contextmanager
    def refusals(self, function):
        """FMI calls in the block: a refusal raised as Refusal with the errors the FMU logged
        meanwhile (fmpy's FMICallException; fmi2Instantiate's plain Exception, for `function`)."""
        first = len(self.messages)
        try:
            yield
        except FMICallException as e:
            if isinstance(e, Refusal):
                raise
            raise Refusal(self.fmu_name, e.function, e.status, self.errors(first)) from e
        except Exception as e:
            if function != "fmi2Instantiate":
                raise
            raise Refusal(self.fmu_name, function, 3, self.errors(first)) from e

    def set(self, name, value):
        t = self.type[name]
        vr = [self.vr[name]]
        if t == "Real":
            self.slave.setReal(vr, [float(value)])
        elif t == "Integer":
            self.slave.setInteger(vr, [int(value)])
        elif t == "Boolean":
            self.slave.setBoolean(vr, [bool(value)])
        else:
            self.slave.setString(vr, [str(value)])

    def get(self, names=None):
        names = list(names or self.outputs)
        reals = [n for n in names if self.type[n] == "Real"]
        ints = [n for n in names if self.type[n] == "Integer"]
        out = {}
        if reals:
            out.update(zip(reals, self.slave.getReal([self.vr[n] for n in reals])))
        if ints:
            out.update(zip(ints, self.slave.getInteger([self.vr[n] for n in ints])))
        return out

    def initialize(self, start_time=0.0, inputs=None, stop_time=None):
        with self.refusals("initialization"):
            self.slave.setupExperiment(startTime=start_time, stopTime=stop_time)
            for k, v in self.parameters.items():
                self.set(k, v)
            for k, v in (inputs or {}).items():
                self.set(k, v)
            self.slave.enterInitializationMode()
            self.slave.exitInitializationMode()
        self.time = start_time

    def step(self, h, inputs=None, t=None):
        t = self.time if t is None else t
        with self.refusals("fmi2DoStep"):
            for k, v in (inputs or {}).items():
                self.set(k, v)
            # the CPU time of this thread, where the FMU computes (the process's would count numpy's
            # BLAS threads too, which spin on the other core after the master's array work)
            cpu0 = self.clock()
            self.slave.doStep(currentCommunicationPoint=t, communicationStepSize=h)
            self.step_cpus.append(self.clock() - cpu0)
        self.time = t + h

    @property
    def step_cpu(self):
        """[s] CPU time inside fmi2DoStep over all steps."""
        return math.fsum(self.step_cpus)

    def close(self):
        try:
            self.slave.terminate()
        finally:
            self.slave.freeInstance()

    def errors(self, first=0):
        """The messages of status fmi2Discard and worse, from the first-th message logged on."""
        return [m for s, c, m in self.messages[first:] if s >= 2]


def rpm_to_rad_s(rpm):
    return rpm * 2.0 * math.pi / 60.0
