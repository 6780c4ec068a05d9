"""The main job of the timing drive: a scene run through ChainDrive.fmu with the measured-torque tables.

Runs a drive (default: the FMU's default drive) at a mean engine speed, driven by the
camshaft-torque and crankshaft-speed tables of harness/tables/data (synthesized, see
harness/tables/data/README.md), writes all outputs as CSV, makes the plots engineers read and reports
every headline quantity as a mean over engine cycles with its 95 % confidence half-width
(harness/cycle_stats.py), printed and written to summary.json.

Run-in: the run starts from the kinetostatic preload; the first engine cycles carry the start
transient and the creep of the tension guide from the static to the dynamic mean of the chain
forces (set by the tensioner's retraction damping: about 50 ms at 3000 rpm, 100 ms at 6000
rpm). The run-in, the smallest whole number of engine cycles that is at least 2 cycles and at
least 0.15 s long (4 cycles at 3000 rpm, 8 at 6000 rpm, 2 at 1000 rpm), is discarded; the
counted cycles (--cycles) follow.

Two fidelities (--fidelity, the FMU parameter `fidelity`): link (default), the link-by-link model,
and span, the span model (rotors and longitudinal spans, src/span/, a small fraction of the cost
inside fmi2DoStep: python -m harness bench-fidelity measures it; not as accurate: python -m harness
fidelity compares them). Both give the same
outputs, so the same cycle statistics, plots and summary; the fidelity is named in the header line
and the plot titles. The solver defaults to each fidelity's own (harness/defaults.py).

The hydraulic tensioner (the default drive's, docs/hydraulic_tensioner.md): the oil gallery's
gauge pressure (--supply-pressure-bar, default 3) is the FMU's input tensioner.supplyPressure,
held at every communication step; the oil temperature (--oil-temperature-c, default 90, within
the oil law's range of the drive) is its parameter tensioner.oilTemperature. A drive whose
tensioner is the spring-damper law ignores both (a note says so when they were given).

Two couplings:
  closed (default)  the way an engine simulator couples: a master loop (fmpy FMU2Slave) looks the
                    camshaft torques up at the FMU's own camshaft angles and the crankshaft speed
                    at its crankshaft angle, at every communication step;
  open              the tables turned into time series at the mean speed and passed to
                    fmpy.simulate_fmu as input.

    python -m harness run [--rpm 3000] [--fidelity link|span] [--cycles N] [--run-in CYCLES]
                          [--coupling closed|open] [--step 1e-4] [--method M]
                          [--solver-step S] [--newmark-gamma G] [--drive FILE] [--out results]
                          [--supply-pressure-bar 3] [--oil-temperature-c 90]

Writes to --out: outputs.csv, summary.json (the cycle statistics), run.json (what ran and its
cost: fidelity, speed, cycles, CPU seconds of the loop and of fmi2DoStep alone) and the plots.
"""
import dataclasses
import json
import math
import pathlib
import subprocess
import sys
import time

import numpy as np

from . import checks, cycle_stats, defaults, paths, runin
from .drive.description import clearance_or_rigid, drive_json, is_hydraulic, oil_temperature_range
from .drive import description
from .drive.description import elements as drive_elements
from .errors import UserError
from .fmu import export, fmu, loop
from .plots import drive_picture, plots
from .tables import tables

RUN_IN_CYCLES = 2          # the run-in: at least this many engine cycles ...
RUN_IN_TIME = 0.15         # [s] ... and at least this long
DEFAULT_RPM = 3000.0       # [rpm] mean engine speed of the default run
DEFAULT_CYCLES = 120       # counted engine cycles of the default run (see docs/run.md: 1 % confidence)
# the tables' mean speed over time (the harmonic mean of the speed over crank angle) lies up to
# 0.2 % below the nominal speed (at 1000 rpm): 120 cycles then take a quarter of a cycle longer
SPEED_MARGIN = 0.005
FIDELITIES = ("link", "span")  # values of the FMU parameter `fidelity`: the reference, then the cheaper
# (the solver's defaults per fidelity: method, step, tolerance are the one table of every entry
# point, harness/defaults.py)
# the real-time method of the link fidelity: Verlet with the joints' damping implicit, 28 steps per
# 0.1 ms communication step (about three quarters of its stable step; docs/benchmark_realtime.md)
REALTIME_METHOD, REALTIME_STEP = "fixed-verlet-implicit-joint-damping", 1e-4 / 28
MASTER_LOOPS = ("compiled", "python")  # run_closed's loop: in C, or through fmpy's calls (the same bits)
COUPLINGS = ("closed", "open")  # this module's master loop (the default), fmpy.simulate_fmu
COMMUNICATION_STEP = 1e-4  # [s] the default communication step
NEWMARK_GAMMA = 0.5  # the FMU parameter solver.newmarkGamma's default
# the hydraulic tensioner's oil: the FMU's defaults (the input tensioner.supplyPressure and the
# parameter tensioner.oilTemperature), an engine's oil gallery warm at part load
SUPPLY_PRESSURE = description.SUPPLY_PRESSURE  # [Pa] gauge (the drive description's default)
OIL_TEMPERATURE = 363.15     # [K] (90 C)
SUPPLY_PRESSURE_RANGE = (-101325.0, 2e7)  # [Pa] gauge: what the FMU accepts, from vacuum to 200 bar
BAR, ZERO_CELSIUS = 1e5, 273.15           # [Pa], [K]: the options' units


@dataclasses.dataclass(frozen=True)
class RunConfig:
    """What a run of the timing drive does, every default resolved: built once (run_config, or
    config_of from the command line) and read, never changed, by every step of the run."""
    run_in: int | None                   # engine cycles discarded before the counted ones; None: until the
                                         # tensioner has settled, at least run_in_cycles (harness/runin.py)
    solver_step: float                   # [s] FMU parameter solver.step
    method: str                          # FMU parameter solver.method
    rtol: float                          # FMU parameter solver.tolerance
    rpm: float = DEFAULT_RPM             # [rpm] mean engine speed
    fidelity: str = FIDELITIES[0]        # FMU parameter fidelity
    cycles: int = DEFAULT_CYCLES         # engine cycles counted after the run-in
    coupling: str = COUPLINGS[0]         # closed (the master loop run_closed) or open (run_open)
    step: float = COMMUNICATION_STEP     # [s] communication step
    newmark_gamma: float = NEWMARK_GAMMA  # FMU parameter solver.newmarkGamma (fixed-newmark)
    drive: str | None = None             # drive description file; None: the FMU's default drive
    tables: str | None = None            # directory of the torque/speed tables; None: harness/tables/data
    out: pathlib.Path = paths.RESULTS    # output directory
    strict: bool = False                 # a missed check (harness/checks.py) makes the exit status 1
    supply_pressure: float = SUPPLY_PRESSURE  # [Pa] gauge, FMU input tensioner.supplyPressure (held)
    oil_temperature: float = OIL_TEMPERATURE  # [K] FMU parameter tensioner.oilTemperature
    speed_perturbation: float = 0.0      # relative change of the crankshaft-speed input (a replica's, harness/replicas.py)
    replicas: int = 1                    # runs of the ensemble (harness/replicas.py); 1: the run alone
    notes: tuple = ()                    # note lines on the options (given, but without effect on this drive)
    loads: tuple = ()                    # ((sprocket, torque [N m]), ...): constant loads (--load NAME=VALUE)
    master_loop: str = MASTER_LOOPS[0]   # the closed loop's: compiled (fmu/loop.py) or python (fmpy's calls)
    threads: int = 1                     # FMU parameter solver.threads (more than 1: steps timed by the wall clock)


def drive_clearance_or_rigid(path):
    """Whether the drive file's joints have clearance or its contacts are rigid (False for the default
    drive, and for a file that cannot be read: the run's own checks name that problem)."""
    try:
        return path is not None and clearance_or_rigid(drive_json(path))
    except (OSError, ValueError, AttributeError):
        return False


def run_config(**options):
    """A RunConfig from options named as its fields (None or left out: the default), with the
    defaults that depend on other options: the run-in from the speed (run_in_cycles), the solver
    from the fidelity (harness/defaults.py)."""
    given = {name: value for name, value in options.items() if value is not None}
    fidelity, drive = given.get("fidelity", FIDELITIES[0]), given.get("drive")
    plain = drive_clearance_or_rigid(drive)
    # (the drive's own steps, docs/defaults.md; a drive that cannot be read: the table's, its problem
    # named by the run's own checks)
    own = drive if drive is not None and readable(drive) else None
    solver = defaults.solver("timing", fidelity, clearance_or_rigid=plain, drive=own)
    method = given.get("method", solver.method)
    return RunConfig(**{"run_in": None, "method": method, "rtol": solver.tolerance,
                        "solver_step": defaults.step_for("timing", fidelity, method, plain, drive=own), **given})


def readable(drive):
    """Whether chaindrive-info reads the drive file (its steps can be found)."""
    try:
        defaults.printed(drive)
        return True
    except subprocess.CalledProcessError:
        return False


class Progress:
    """A text progress bar on stderr."""

    def __init__(self, total, label):
        self.total, self.label, self.last = total, label, -1
        self.t0 = time.time()

    def update(self, t):
        pct = int(100 * t / self.total + 1e-9)
        tty = sys.stderr.isatty()
        if pct != self.last and (tty or pct % 10 == 0):
            self.last = pct
            bar = "#" * (pct // 4) + "." * (25 - pct // 4)
            sys.stderr.write(f"{chr(13) if tty else ''}{self.label} [{bar}] {pct:3d} %  t = {t * 1e3:7.2f} ms  "
                             f"({time.time() - self.t0:5.1f} s){'' if tty else chr(10)}")
            sys.stderr.flush()
        return True

    def done(self):
        if sys.stderr.isatty():
            sys.stderr.write("\n")


def parameters_of(config):
    """The FMU's parameters of a run."""
    p = {"fidelity": config.fidelity, "solver.method": config.method, "solver.step": config.solver_step,
         "solver.tolerance": config.rtol, "solver.newmarkGamma": config.newmark_gamma}
    if config.threads != 1:  # (left out at 1, its default: the FMUs of every drive take it)
        p["solver.threads"] = config.threads
    if is_hydraulic(drive_json(config.drive)):  # (a drive with another tensioner has no such parameter)
        p["tensioner.oilTemperature"] = config.oil_temperature
    return p


def table_inputs(loads, speed, elements, supply_pressure=SUPPLY_PRESSURE, speed_factor=1.0):
    """The closed loop's inputs from the tables of one engine speed for a drive
    (drive.description.Elements): a function of (time, {sprocket: its angle from the start [deg]})
    giving the FMU's inputs: the prescribed sprocket's speed from the speed table at its angle (times
    speed_factor, a replica's perturbation), each loaded sprocket's torque (tables.Load) at its own
    angle, and a hydraulic tensioner's oil supply pressure [Pa] held constant (the gallery's pressure
    changes slowly against a cycle). Its `angles` are the sprockets whose angles it needs."""
    def inputs(t, angles):
        u = {elements.crank + ".w": speed_factor * speed_at(speed, angles[elements.crank])}
        for name, load in loads.items():
            u[name + ".tau"] = float(load.at(angles[name]))
        if elements.hydraulic:
            u["tensioner.supplyPressure"] = supply_pressure
        return u
    inputs.angles = [elements.crank] + list(loads)
    # (the same inputs for the compiled loop: {input: loop.Term}, in the order of inputs()' keys)
    column = speed_column(speed)
    inputs.terms = {elements.crank + ".w": loop.Term.table("speed", 0, speed.x, speed.columns[column],
                                                           tables.PERIODS[speed.kind], speed_factor,
                                                           rpm=column.endswith("_rpm"))}
    inputs.terms.update({name + ".tau": load_term(load, 1 + k) for k, (name, load) in enumerate(loads.items())})
    if elements.hydraulic:
        inputs.terms["tensioner.supplyPressure"] = loop.Term("constant", value=float(supply_pressure))
    return inputs


def load_term(load, angle):
    """A tables.Load as the compiled loop's loop.Term, reading the angle of index `angle`."""
    if load.table is None:
        return loop.Term("constant", value=float(load.constant))
    x, y, period = load.table.x, load.table.columns[load.name + ".tau"], tables.PERIODS[load.table.kind]
    if load.table.kind == "sprocket":
        return loop.Term.table("shifted", angle, x, y, period, load.phase_deg)
    return loop.Term.table("scaled", angle, x, y, period, load.ratio)


def run_closed(config, duration, inputs, progress=True, fmu_file=None, run_in=None, compiled=True):
    """Master loop: inputs (table_inputs) looked up at the FMU's own angles before every step.
    duration [s]; or None: until the run-in (a runin.RunIn, fed each engine cycle's tensioner
    stroke) has ended and config.cycles counted cycles followed. fmu_file: the FMU (a file or an
    unpacked folder; default the drive's: export.fmu_for). The loop runs compiled (fmu/loop.py) when
    the inputs say how (their `terms`) and `compiled`, else in Python (fmpy's calls): the same bits.
    Returns (record, CPU seconds spent inside each fmi2DoStep, the thread's CPU seconds from the
    first fmi2DoStep to the last: the FMU's and the loop's own). A step the FMU refuses (a blow-up:
    fmi2Discard) raises RunFailed with the record up to the failure."""
    s = fmu.Slave("chaindrive", fmu=fmu_file or export.fmu_for(config.drive), parameters=parameters_of(config),
                  wall_clock=config.threads > 1)
    angles = [f"{name}.phi" for name in inputs.angles]
    u0 = inputs(0.0, {name: 0.0 for name in inputs.angles})
    s.initialize(inputs=u0)
    names, applied = s.outputs, list(u0)  # (every input the loop sets, recorded as input.<name>)
    first = [0.0] + [s.get(names)[k] for k in names] + [u0[n] for n in applied]
    watch = CycleWatch(names, angles[0], run_in, config.cycles) if duration is None else None
    total = duration or duration_of(dataclasses.replace(config, run_in=run_in_cycles(config.rpm)))
    prog = Progress(total, "closed loop") if progress else None
    cols = ["time"] + names + [f"input.{n}" for n in applied]
    # (the longest the run can be: the compiled loop's record is made that long at once, untouched
    # memory costing nothing, so that no copy of it between two steps cools the FMU's caches)
    longest = duration or duration_of(dataclasses.replace(config, run_in=run_in.maximum))
    loop_of = compiled_loop if compiled and getattr(inputs, "terms", None) is not None else python_loop
    try:
        return loop_of(s, config.step, inputs, angles, first, cols, longest, watch, prog)
    finally:
        if prog:
            prog.done()
        s.close()


def python_loop(s, step, inputs, angles, first, cols, duration, watch, prog):
    """run_closed's loop through fmpy's calls, one step at a time (--master-loop python, and the
    compiled loop's oracle in tests/python/test_loop.py): over `duration` [s], or (a watch) until the
    watch is done."""
    names, applied = s.outputs, [c[len("input."):] for c in cols[1 + len(s.outputs):]]
    rows, k = [first], 0
    cpu0 = s.clock()
    try:
        while (k < int(round(duration / step))) if watch is None else not watch.done(rows):
            o = s.get(angles)
            u = inputs(k * step, {name: math.degrees(o[a]) for name, a in zip(inputs.angles, angles)})
            s.step(step, inputs=u, t=k * step)
            v = s.get(names)
            rows.append([(k + 1) * step] + [v[x] for x in names] + [u[n] for n in applied])
            k += 1
            if prog:
                prog.update(min((k * step), prog.total))
    except fmu.Refusal as e:
        raise RunFailed(str(e), {c: np.array([r[i] for r in rows]) for i, c in enumerate(cols)}) from None
    loop_cpu = s.clock() - cpu0
    return {c: np.array([r[i] for r in rows]) for i, c in enumerate(cols)}, s.step_cpus, loop_cpu


COMPILED_CHUNK = 2000  # steps per call of the compiled loop between progress updates


def compiled_loop(s, step, inputs, angles, first, cols, duration, watch, prog):
    """run_closed's loop in C (fmu/loop.py), as python_loop; called once per engine cycle while a
    watch waits (it stops on the watch's crank angle) and at most every COMPILED_CHUNK steps; the
    record as python_loop's (integer outputs as integers)."""
    if [f"input.{n}" for n in inputs.terms] != cols[1 + len(s.outputs):]:
        raise ValueError(f"the compiled loop's inputs {list(inputs.terms)} are not the loop's {cols}")
    runner = loop.CompiledLoop(s, step, angles, inputs.terms, s.outputs, getattr(inputs, "run_up", None))
    steps = int(round(duration / step))  # (a watch's: the longest it can run, room grows beyond it)
    rows, cpus = np.empty((steps + 1, len(cols))), np.empty(steps + 1)
    rows[0] = first
    cpu0 = s.clock()
    return compiled_steps(s, runner, inputs, rows, cpus, step, cols, steps, watch, prog, cpu0)


def compiled_steps(s, runner, inputs, rows, cpus, step, cols, steps, watch, prog, cpu0):
    """compiled_loop's steps from row 0 on, each call's last step's inputs checked against the
    inputs function's: (record, step CPUs, loop CPU)."""
    k = 0
    done = watch.done(rows[:1]) if watch else steps == 0
    while not done:
        if k + 1 == rows.shape[0]:  # (the watch's run-in went on longer than foreseen)
            rows, cpus = np.resize(rows, (2 * rows.shape[0], len(cols))), np.resize(cpus, 2 * rows.shape[0])
        chunk = min(COMPILED_CHUNK, rows.shape[0] - 1 - k)
        logged = len(s.messages)
        ran, refused = runner.run(rows, cpus, k, chunk, *((watch.phi, watch.next - 1e-9) if watch else (-1, 0.0)))
        k += ran
        if refused:  # (the FMU logged its reasons during the call)
            error = fmu.Refusal(s.fmu_name, refused[0], refused[1], s.errors(logged))
            raise RunFailed(str(error), record_of(rows[:k + 1], cols, s)) from None
        if ran:
            same_inputs(inputs, rows, k - 1, step, cols)
        if prog:
            prog.update(min(k * step, prog.total))
        done = watch.done(rows[:k + 1]) if watch else k == steps
    loop_cpu = s.clock() - cpu0
    return record_of(rows[:k + 1], cols, s), cpus[:k].tolist(), loop_cpu


def same_inputs(inputs, rows, j, step, cols):
    """Step j's inputs as the compiled loop set them (row j + 1) against the Python look-up at the
    angles it read (row j), bit for bit: terms that no longer say what the inputs function says
    stop the run instead of driving it with other inputs."""
    angles = {name: math.degrees(rows[j][cols.index(f"{name}.phi")]) for name in inputs.angles}
    expected = inputs(j * step, angles)
    for name, value in expected.items():
        got = rows[j + 1][cols.index(f"input.{name}")]
        if got != value:
            raise RuntimeError(f"the compiled loop's input {name} at step {j} is {got!r}, the inputs' look-up "
                               f"{value!r}: its terms (harness/fmu/loop.py) do not match the inputs function")


def record_of(rows, cols, s):
    """The record {column: array} of the compiled loop's rows (its integer outputs as integers)."""
    integers = {n for n in s.outputs if s.type[n] == "Integer"}
    return {c: rows[:, i].astype(np.int64) if c in integers else rows[:, i].copy() for i, c in enumerate(cols)}


class RunFailed(UserError):
    """A step the FMU refused in the master loop (a blow-up): the FMU's reason, and the record up to
    the last successful step (written by the main job before it stops)."""

    def __init__(self, message, record):
        super().__init__(message)
        self.record = record


class CycleWatch:
    """The closed loop's end when it runs until the run-in has ended (runin.RunIn): feeds it each
    completed engine cycle's tensioner stroke, then waits for the counted cycles."""

    def __init__(self, names, crank_phi, run_in, cycles):
        self.phi = 1 + names.index(crank_phi)  # (columns of a row: time, then the outputs)
        self.stroke = 1 + names.index(runin.SIGNAL) if runin.SIGNAL in names else None
        self.run_in, self.cycles = run_in, cycles
        self.start, self.next = 0, cycle_stats.ENGINE_CYCLE  # the current cycle's first row, its end angle
        if run_in.ended:  # (a fixed run-in: only the end of the counted cycles to wait for)
            self.next = (run_in.result.cycles + cycles) * cycle_stats.ENGINE_CYCLE

    def done(self, rows):
        phi = rows[-1][self.phi]
        if phi < self.next - 1e-9:
            return False
        if not self.run_in.ended:
            stroke = [r[self.stroke] for r in rows[self.start:]] if self.stroke else [0.0]
            if self.run_in.cycle(stroke):
                self.next = (self.run_in.result.cycles + self.cycles) * cycle_stats.ENGINE_CYCLE
                return phi >= self.next - 1e-9
        else:
            return True
        self.start, self.next = len(rows) - 1, self.next + cycle_stats.ENGINE_CYCLE
        return False


def speed_column(speed):
    return "crankshaft.speed_rpm" if "crankshaft.speed_rpm" in speed.columns else "crankshaft.w"


def speed_at(speed, crank_deg):
    col = speed_column(speed)
    v = float(tables.lookup(speed, col, crank_deg))
    return v * 2.0 * math.pi / 60.0 if col.endswith("_rpm") else v


def run_open(config, duration, loads, speed, elements, fmu_file):
    """fmpy.simulate_fmu with the tables as time series (tables.time_series). Returns (record, None):
    fmpy's loop does not tell the time spent inside fmi2DoStep."""
    from fmpy import simulate_fmu
    ts = tables.time_series(config.rpm, duration, min(2e-5, config.step), speed_table=speed, loads=loads,
                            elements=elements)
    names = [c for c in ts if c not in ("time", "crank_angle_deg")]
    supply = ["tensioner.supplyPressure"] if elements.hydraulic else []
    arr = np.zeros(len(ts["time"]), dtype=[("time", float)] + [(n, float) for n in names + supply])
    arr["time"] = ts["time"]
    for n in names:
        arr[n] = ts[n]
    arr[elements.crank + ".w"] *= 1.0 + config.speed_perturbation
    for n in supply:
        arr[n] = config.supply_pressure
    prog = Progress(duration, "open loop")
    res = simulate_fmu(str(fmu_file), stop_time=duration, output_interval=config.step, input=arr,
                       start_values=parameters_of(config), step_finished=lambda t, rec: prog.update(t))
    prog.done()
    out = {n: np.asarray(res[n], dtype=float) for n in res.dtype.names}
    for n in names:
        out["input." + n] = np.interp(out["time"], arr["time"], arr[n])
    return out, None


def write_csv(path, d):
    cols = list(d)
    with open(path, "w") as f:
        f.write(",".join(cols) + "\n")
        np.savetxt(f, np.column_stack([d[c] for c in cols]), delimiter=",", fmt="%.10g")


def add_arguments(ap):
    """The timing drive's own options; those it shares with the CVT (--rpm, --method, --solver-step,
    --rtol, --out) are harness/run.py's."""
    ap.add_argument("--drive", help="drive description (default: the FMU's default drive)")
    ap.add_argument("--fidelity", choices=FIDELITIES, default=FIDELITIES[0],
                    help="FMU parameter fidelity: link (link-by-link model, default) or span (span model)")
    ap.add_argument("--cycles", type=int, default=DEFAULT_CYCLES,
                    help=f"engine cycles (720 deg crank) counted after the run-in (default {DEFAULT_CYCLES})")
    ap.add_argument("--run-in", type=int, help=f"engine cycles discarded before the first counted one (default: "
                    f"until the tensioner has settled, harness/runin.py, at least {RUN_IN_CYCLES} cycles and "
                    f"{RUN_IN_TIME:g} s, at most {MAX_RUN_IN_TIME:g} s)", metavar="CYCLES")
    ap.add_argument("--load", action="append", default=[], metavar="NAME=VALUE",
                    help="a constant load torque [N m, positive opposing the rotation] on the loaded sprocket NAME, "
                    "instead of its table (repeatable)")
    ap.add_argument("--coupling", choices=COUPLINGS, default=COUPLINGS[0])
    ap.add_argument("--master-loop", choices=MASTER_LOOPS, default=MASTER_LOOPS[0],
                    help="the closed loop in C (default) or through fmpy's calls one by one (the same bits)")
    ap.add_argument("--replicas", type=int, default=1, metavar="K",
                    help="K runs, replica k with the crankshaft-speed input perturbed by a factor 1 + k * 1e-9: "
                    "summary.json then holds the ensemble's statistics, each interval from the spread between "
                    "the replicas' means (harness/replicas.py), and each replica's outputs are in replica<k>/ "
                    "(default 1: the run alone)")
    ap.add_argument("--tables", help="directory of the torque/speed tables (default harness/tables/data)")
    ap.add_argument("--step", type=float, default=COMMUNICATION_STEP, help="communication step [s]")
    ap.add_argument("--newmark-gamma", type=float, default=NEWMARK_GAMMA,
                    help="FMU parameter solver.newmarkGamma (fixed-newmark)")
    lo, hi = (p / BAR for p in SUPPLY_PRESSURE_RANGE)
    ap.add_argument("--supply-pressure-bar", type=float, metavar="BAR",
                    help=f"hydraulic tensioner: gauge pressure of the oil supply [bar], {lo:g} to {hi:g} (FMU input "
                    f"tensioner.supplyPressure; default {SUPPLY_PRESSURE / BAR:g})")
    ap.add_argument("--oil-temperature-c", type=float, metavar="DEGC",
                    help=f"hydraulic tensioner: oil temperature [degC] within the drive's oil law (default "
                    f"{OIL_TEMPERATURE - ZERO_CELSIUS:g}; FMU parameter tensioner.oilTemperature)")


def supply_pressure_of(bar):
    """[Pa] of --supply-pressure-bar (None: the default); UserError outside what the FMU accepts."""
    if bar is None:
        return SUPPLY_PRESSURE
    lo, hi = SUPPLY_PRESSURE_RANGE
    if not lo <= bar * BAR <= hi:
        raise UserError(f"--supply-pressure-bar {bar:g}: outside [{lo / BAR:g}, {hi / BAR:g}] bar (gauge: from "
                        f"vacuum to the FMU's limit)")
    return bar * BAR


def oil_temperature_of(celsius, drive):
    """[K] of --oil-temperature-c (None: the default) for the drive (a dict); UserError outside its
    oil's viscosity law."""
    if celsius is None:
        return OIL_TEMPERATURE
    lo, hi = oil_temperature_range(drive)
    if not lo <= celsius + ZERO_CELSIUS <= hi:
        raise UserError(f"--oil-temperature-c {celsius:g}: outside the oil viscosity law's range "
                        f"[{lo - ZERO_CELSIUS:g}, {hi - ZERO_CELSIUS:g}] degC")
    return celsius + ZERO_CELSIUS


def hydraulic_options(drive_file, supply_pressure_bar, oil_temperature_c):
    """{supply_pressure [Pa], oil_temperature [K], notes} of the hydraulic tensioner's options for
    a drive file (None: the default drive): validated, and a note when they were given for a drive
    whose tensioner is not hydraulic (they change nothing there)."""
    try:
        drive = drive_json(drive_file)
    except (OSError, ValueError) as e:
        raise UserError(f"--drive {drive_file}: not readable as a drive description ({e})") from None
    given = [f"{option} {value:g}" for option, value in (("--supply-pressure-bar", supply_pressure_bar),
                                                        ("--oil-temperature-c", oil_temperature_c)) if value is not None]
    return dict(supply_pressure=supply_pressure_of(supply_pressure_bar),
                oil_temperature=oil_temperature_of(oil_temperature_c, drive), notes=inert_oil_notes(drive, given))


def inert_oil_notes(drive, given):
    """The note on the hydraulic tensioner's options given (["--supply-pressure-bar 3", ...]) for a
    drive (a dict) whose tensioner is not hydraulic: they change nothing; () otherwise."""
    if is_hydraulic(drive) or not given:
        return ()
    model = drive.get("tensioner", {}).get("model", "spring-damper")
    return (f"{' and '.join(given)}: no effect, the drive's tensioner is not hydraulic (tensioner.model {model!r})",)


def config_of(ap, args):
    """The run's configuration from the command line's options (harness/run.py; the shared ones None
    where not given); misuse reported by ap.error."""
    if args.cycles < 2:
        ap.error(f"--cycles {args.cycles}: at least 2 counted cycles are needed for a confidence interval")
    if args.replicas < 1:
        ap.error(f"--replicas {args.replicas}: at least 1 run")
    if args.run_in is not None and args.run_in < 0:
        ap.error(f"--run-in {args.run_in}: must be >= 0 cycles")
    if not args.step > 0.0:
        ap.error(f"--step {args.step:g}: the communication step must be > 0 s")
    options = {field.name: getattr(args, field.name, None) for field in dataclasses.fields(RunConfig)}
    options.update(hydraulic_options(args.drive, args.supply_pressure_bar, args.oil_temperature_c))
    options["loads"] = tuple(constant_load(ap, text) for text in args.load)
    config = run_config(**dict(options, out=pathlib.Path(args.out)))
    problem = tables.speed_problem(config.rpm, config.tables)
    if problem:
        ap.error(problem)
    drive_loads(config, drive_elements(config.drive))  # (a sprocket without a load: named before the run)
    return config


def constant_load(ap, text):
    """(name, torque [N m]) of --load NAME=VALUE."""
    name, _, value = text.partition("=")
    try:
        torque = float(value)
    except ValueError:
        torque = math.nan
    if not name or not math.isfinite(torque):
        ap.error(f"--load {text}: expected NAME=VALUE, a sprocket's name and a finite torque in N m")
    return name, torque


def drive_loads(config, elements):
    """{sprocket: tables.Load} of the run's loaded sprockets (tables.sprocket_loads); a sprocket
    without a load, or a load or table that matches none, is a UserError naming them."""
    try:
        return tables.sprocket_loads(elements, config.rpm, config.tables, dict(config.loads))
    except (ValueError, KeyError) as e:
        raise UserError(str(e).strip('"')) from None


SHOWN_CYCLES = 4  # counted cycles shown in the time histories after the run-in


def write_plots(out, d, config, scene_run, per_cycle, summary):
    """The plots of a run into out (counted cycles from the end of the run-in); returns their files."""
    rpm, elements = config.rpm, scene_run.elements
    spans = counted_spans(config, scene_run)
    t0 = d["time"][spans[0][0]]
    title = f"{rpm:g} rpm, {config.fidelity} fidelity, {config.coupling} loop, {config.method}"
    drive_picture.drive_picture(out / "drive.png", config.drive)
    plots.time_histories(out / "time_histories.png", d, rpm, title + f" (run-in and {SHOWN_CYCLES} cycles)", elements,
                         t_end=t0 + SHOWN_CYCLES * 120.0 / rpm, t_counted=t0)
    plots.cycle_statistics(out / "cycle_statistics.png", per_cycle, summary, title + ", per engine cycle")
    plots.spectra(out / "spectra.png", d, spans, elements, title + " (counted cycles)")
    plots.link_cycle(out / "link_cycle.png", d, rpm, title, t0=t0, drive=config.drive, fidelity=config.fidelity)
    return [out / n for n in ("drive.png", "time_histories.png", "cycle_statistics.png", "spectra.png",
                              "link_cycle.png")]


def run_in_cycles(rpm):
    """The default run-in: whole engine cycles, at least RUN_IN_CYCLES and at least RUN_IN_TIME."""
    return max(RUN_IN_CYCLES, math.ceil(RUN_IN_TIME * rpm / 120.0 - 1e-9))


@dataclasses.dataclass
class SceneRun:
    """A scene run through the FMU: its record and what it cost."""
    record: dict            # output and input columns over time
    settling: runin.Settling  # the run-in: engine cycles discarded before the counted ones, and why
    duration: float         # [s] simulated
    cpu: float              # [s] CPU time of the whole loop (FMU and master)
    step_cpus: list | None  # [s] CPU time inside each fmi2DoStep (closed loop only)
    loop_cpu: float | None = None  # [s] the thread's CPU from the first fmi2DoStep to the last (closed loop)
    elements: object = None  # drive.description.Elements of the drive that ran
    loads: dict = dataclasses.field(default_factory=dict)  # {sprocket: where its load came from}

    @property
    def run_in(self):
        """Engine cycles discarded before the counted ones."""
        return self.settling.cycles

    @property
    def step_cpu(self):
        """[s] CPU time inside fmi2DoStep over the run (None in open loop)."""
        return None if self.step_cpus is None else math.fsum(self.step_cpus)

    def cost(self, config):
        """What ran (config) and its cost (run.json): CPU seconds per simulated second of the loop
        and of fmi2DoStep alone (the FMU's own cost; None in open loop)."""
        per_s = None if self.step_cpu is None else self.step_cpu / self.duration
        return {"fidelity": config.fidelity, "rpm": config.rpm, "drive": config.drive, "coupling": config.coupling,
                "method": config.method, "solverStep_s": config.solver_step, "communicationStep_s": config.step,
                "tensionerModel": "hydraulic" if is_hydraulic(drive_json(config.drive)) else "spring-damper",
                "supplyPressure_Pa": config.supply_pressure, "oilTemperature_K": config.oil_temperature,
                "runIn": self.settling.json(), "loads": self.loads,
                "runInCycles": self.run_in, "cycles": config.cycles, "simulated_s": self.duration, "cpu_s": self.cpu,
                "doStepCpu_s": self.step_cpu, "cpuPerSimulatedSecond": self.cpu / self.duration,
                "doStepCpuPerSimulatedSecond": per_s, "masterLoop": config.master_loop if self.loop_cpu else None,
                "loopCpu_s": self.loop_cpu}


def duration_of(config):
    """[s] simulated with a fixed run-in: the run-in and the counted cycles, a tenth of a cycle and
    SPEED_MARGIN more so that the last counted cycle is complete with the speed fluctuation."""
    cycle = 2.0 * 60.0 / config.rpm
    return ((config.run_in + config.cycles) * (1.0 + SPEED_MARGIN) + 0.1) * cycle


MAX_RUN_IN_TIME = 1.5  # [s] the longest run-in waiting for the tensioner to settle (harness/runin.py)
OPEN_RUN_IN_EXTRA = 2 * runin.WINDOW  # engine cycles the open loop runs beyond the least run-in, to find it in


def run_in_of(config):
    """The run-in the configuration asks for: a runin.RunIn deciding it cycle by cycle, from
    run_in_cycles(rpm) to MAX_RUN_IN_TIME, or the fixed number of --run-in."""
    if config.run_in is not None:
        return runin.RunIn(config.run_in, config.run_in, watches=False)
    return runin.RunIn(run_in_cycles(config.rpm), math.ceil(MAX_RUN_IN_TIME * config.rpm / 120.0))


def describe(config, fmu_file, elements, loads):
    """Prints what runs: the FMU and its drive, the speed, the cycles, the solver, the tables and loads."""
    fixed = f"run-in {config.run_in}" if config.run_in is not None else "run-in until the tensioner has settled"
    print(f"{pathlib.Path(fmu_file).name}, {config.fidelity} fidelity: {config.drive or 'default drive'}, "
          f"{config.rpm:g} rpm, {fixed}, then "
          f"{config.cycles} engine cycles, {config.coupling}-loop coupling, communication step {config.step * 1e6:g} us, "
          f"{config.method} at {config.solver_step * 1e6:g} us")
    print(f"solver step: {step_text(config)}")
    print(f"crankshaft speed ({elements.crank}.w): {tables.crankshaft_speed(config.rpm, config.tables).path}")
    for name, load in loads.items():
        print(f"load of {name}: {load.source}")
    if config.speed_perturbation:
        print(f"crankshaft speed input perturbed by a factor 1 {config.speed_perturbation:+.3g} (a replica)")
    if elements.hydraulic:
        print(f"hydraulic tensioner: oil supply {config.supply_pressure / BAR:g} bar (gauge), "
              f"{config.oil_temperature - ZERO_CELSIUS:g} degC")


def step_text(config):
    """Why the run's solver step is what it is: the drive's own (its reason) or as given."""
    plain = drive_clearance_or_rigid(config.drive)
    own_drive = config.drive if config.drive is not None and readable(config.drive) else None
    own = defaults.solver("timing", config.fidelity, plain, own_drive)
    if config.method == own.method and config.solver_step == own.step:
        return defaults.step_reason(config.fidelity, plain, own_drive)
    return f"{config.solver_step:.6g} s as given (the drive's own for {own.method}: {own.step:.6g} s)"


def simulate(config, progress=True):
    """Runs the timing drive through its FMU over the run-in and the counted cycles; prints what
    runs (and a progress bar when progress). The closed loop runs until the tensioner has settled
    (or the fixed --run-in) and the counted cycles followed; the open loop a fixed run-in, and
    whether the tensioner had settled is found afterwards."""
    elements = drive_elements(config.drive)
    loads = drive_loads(config, elements)
    speed = tables.crankshaft_speed(config.rpm, config.tables)
    fmu_file = export.fmu_for(config.drive)
    describe(config, fmu_file, elements, loads)
    run_in = run_in_of(config)
    cpu0 = time.process_time()
    if config.coupling == "closed":
        inputs = table_inputs(loads, speed, elements, config.supply_pressure, 1.0 + config.speed_perturbation)
        d, step_cpus, loop_cpu = run_closed(config, None, inputs, progress, fmu_file, run_in,
                                            compiled=config.master_loop == "compiled")
        settling = run_in.result
    else:  # (the run-in found afterwards, within the OPEN_RUN_IN_EXTRA cycles the open loop runs more)
        longest = run_in.maximum if run_in.ended else run_in.minimum + OPEN_RUN_IN_EXTRA
        loop_cpu = None
        d, step_cpus = run_open(config, duration_of(dataclasses.replace(config, run_in=longest)), loads, speed,
                                elements, fmu_file)
        settling = run_in.result or runin.detect(d, elements.crank, run_in.minimum, longest)
    return SceneRun(d, settling, float(d["time"][-1]), time.process_time() - cpu0, step_cpus, loop_cpu, elements,
                    {name: load.source for name, load in loads.items()})


def cycle_statistics(config, scene_run):
    """(per-cycle values, summary) of the counted cycles of a scene run (harness/cycle_stats.py)."""
    per_cycle = cycle_stats.per_cycle(scene_run.record, scene_run.run_in, scene_run.elements, config.cycles)
    return per_cycle, cycle_stats.summarize(per_cycle)


def counted_spans(config, scene_run):
    """(first, end) sample indices of each counted engine cycle of a scene run."""
    crank_angle = scene_run.record[scene_run.elements.crank + ".phi"]
    return cycle_stats.counted_spans(crank_angle, scene_run.run_in, config.cycles)


def run_checks(config, scene_run, per_cycle_spans):
    """The run's checks over its counted cycles (harness/checks.py): (checks for run.json, warning
    lines, note lines)."""
    first, last = per_cycle_spans[0][0], per_cycle_spans[-1][1] - 1
    error = checks.energy_balance_error(scene_run.record, first, last)
    found = {"energyBalanceError": error, "energyBalanceLimit": checks.ENERGY_BALANCE_LIMIT}
    notes = list(config.notes) + checks.fidelity_notes(config.fidelity, config.drive)
    fixed_step = config.solver_step if config.method.startswith("fixed") else None
    settling = [scene_run.settling.note()] if scene_run.settling.note() else []
    warnings = checks.energy_warnings(error, fixed_step) + settling
    return found, warnings, notes


def write_summary(out, summary, cost):
    """summary.json (the cycle statistics) and run.json (what ran, its cost) in out."""
    out.mkdir(parents=True, exist_ok=True)
    (out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    (out / "run.json").write_text(json.dumps(cost, indent=1) + "\n")


def report(summary, scene_run, config):
    """Prints the cycle statistics and the cost; says so when the confidence half-width of the
    tensioner-force mean exceeds 1 %, with the number of cycles that would bring it to 1 %."""
    print(f"\nsummary: mean over engine cycles after a run-in of {scene_run.run_in} cycles, +- the 95 % confidence "
          f"half-width")
    for key, s in summary.items():
        print(cycle_stats.format_line(key, s))
    F = summary.get("tensioner.F.mean")
    rel = F["ci95"] / abs(F["mean"]) if F else 0.0
    if rel > 0.01:
        need = math.ceil(F["cycles"] * (rel / 0.01) ** 2)
        print(f"  note: the tensioner-force mean is known to {100 * rel:.2f} %; about {need} cycles give 1 %")
    cpu, duration = scene_run.cpu, scene_run.duration
    print(f"  CPU time {cpu:.2f} s for {duration * 1e3:.1f} ms simulated: {cpu / duration:.3g} CPU s per simulated s "
          f"(real-time factor, FMU and master loop)")
    if scene_run.step_cpu is not None:
        print(f"  of which inside fmi2DoStep {scene_run.step_cpu:.2f} s: {scene_run.step_cpu / duration:.3g} CPU s per "
              f"simulated s (the FMU alone)")
    if scene_run.loop_cpu:
        print(f"  from the first fmi2DoStep to the last {scene_run.loop_cpu:.2f} s: "
              f"{scene_run.loop_cpu / scene_run.step_cpu:.3g} times the FMU's (its {config.master_loop} master loop)")


def run(config):
    """The main job of the timing drive: the run, its outputs, statistics and plots in config.out."""
    out = config.out
    out.mkdir(parents=True, exist_ok=True)
    csv = out / "outputs.csv"
    try:
        scene_run = simulate(config)
    except RunFailed as failure:
        write_csv(csv, failure.record)
        raise UserError(f"{failure} (every output up to the failure, {failure.record['time'][-1] * 1e3:.1f} ms: "
                        f"{csv})") from None
    write_csv(csv, scene_run.record)
    per_cycle, summary = cycle_statistics(config, scene_run)
    d = scene_run.record
    found, warnings, notes = run_checks(config, scene_run, counted_spans(config, scene_run))
    write_summary(out, summary, dict(scene_run.cost(config), checks=found, warnings=warnings, notes=notes))
    pictures = write_plots(out, d, config, scene_run, per_cycle, summary)
    report(summary, scene_run, config)
    print(f"  checks: energy balance {100 * found['energyBalanceError']:+.2f} % of the dissipated energy (limit "
          f"{100 * checks.ENERGY_BALANCE_LIMIT:g} %)")
    checks.print_lines(warnings, notes)
    print(f"  outputs: {csv}, {out / 'summary.json'}, {out / 'run.json'}")
    print("  plots: " + ", ".join(str(p) for p in pictures))
    return checks.EXIT_STRICT if config.strict and warnings else 0
