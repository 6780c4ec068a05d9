"""The cases of a sweep and their run: a stationary engine speed or a run-up through
ChainDrive.fmu in closed loop with the measured-torque tables (the main job's own loop and cycle
statistics, harness/job.py and harness/cycle_stats.py), reduced to what a sweep keeps per engine
speed: the headline cycle statistics, the minima and maxima of the chain forces and the engine-order
spectra of the tensioner force and the tension-guide angle (the Campbell diagram's columns).

A case is a plain value (Case): it travels to a Dask worker, which runs it with run_case (the FMU
is instantiated there) and returns a plain dict. Its cache key (case_key) covers every input that
changes the result: the case's fields, the contents of the drive file and of the tables, and the
code version (the FMU binary and the harness's sources)."""
import contextlib
import dataclasses
import hashlib
import io
import json
import math
import pathlib
import time
import traceback

import numpy as np

from .. import cycle_stats, job, paths
from ..drive.description import elements as drive_elements
from ..fmu import export, fmu, loop
from ..tables import tables

SPECTRUM_STEP = 0.5         # engine orders per bin of the spectra (half orders: the camshafts')
SPECTRUM_BEYOND_MESHING = 4  # the spectra reach this many orders beyond the meshing order
FORCE_SIGNALS = ("tensioner.F", "chain.Ftight", "chain.Fslack")  # minima and maxima per speed [N], those the drive has
# a hydraulic tensioner's chamber: its lowest and highest pressure over a point's counted cycles
# [bar] (the summary's min_bar is the mean of each cycle's minimum)
CHAMBER_EXTREMES = {cycle_stats.CHAMBER + ".lowest_bar": np.min, cycle_stats.CHAMBER + ".highest_bar": np.max}


@dataclasses.dataclass(frozen=True)
class Case:
    """One run of a sweep. Stationary: `rpm` held (the tables' fluctuation about it), `cycles`
    engine cycles counted after the main job's run-in. Run-up (rpm_end given): the run-in at
    `rpm`, then the mean speed ramped linearly to rpm_end over ramp_s seconds; every engine cycle
    of the ramp is one point over speed."""
    rpm: float
    fidelity: str = "link"
    method: str = "fixed-verlet"  # (the sweep and its benchmark pass the fidelity's default, harness/defaults.py)
    solver_step: float | None = None  # [s]; None: the fidelity's default (harness/job.py)
    cycles: int = 8
    drive: str | None = None
    tables: str | None = None
    rpm_end: float | None = None
    ramp_s: float | None = None
    supply_pressure: float | None = None  # [Pa] gauge, the hydraulic tensioner's oil; None: the main job's
    oil_temperature: float | None = None  # [K]; None: the main job's
    loads: tuple = ()                     # ((sprocket, torque [N m]), ...): constant loads instead of tables

    @property
    def runup(self):
        return self.rpm_end is not None

    def label(self):
        speed = f"run-up {self.rpm:g}-{self.rpm_end:g} rpm in {self.ramp_s:g} s" if self.runup else f"{self.rpm:g} rpm"
        oil = []  # the hydraulic tensioner's, when the case sets them
        if self.supply_pressure is not None:
            oil.append(f"{self.supply_pressure / job.BAR:g} bar")
        if self.oil_temperature is not None:
            oil.append(f"{self.oil_temperature - job.ZERO_CELSIUS:g} degC")
        return ", ".join([speed] + oil + [self.fidelity, self.method])

    def config(self):
        """The main job's configuration of this case (harness/job.py): closed loop, the run-in and
        every option the case does not set at the main job's defaults."""
        return job.run_config(rpm=self.rpm, fidelity=self.fidelity, method=self.method, solver_step=self.solver_step,
                              cycles=self.cycles, drive=self.drive, tables=self.tables,
                              supply_pressure=self.supply_pressure, oil_temperature=self.oil_temperature,
                              loads=self.loads)


def _digest_files(paths_, h):
    for p in paths_:
        h.update(str(p.name).encode())
        h.update(p.read_bytes())


def code_version():
    """sha256 of the FMU binary and of the harness's Python sources: results computed by other
    code are not taken from the cache. (Every drive's FMU carries the same binary.)"""
    h = hashlib.sha256()
    _digest_files([paths.BUILD / export.NATIVE_BINARY], h)
    _digest_files(sorted(pathlib.Path(paths.ROOT / "harness").rglob("*.py")), h)
    return h.hexdigest()


def case_key(case, version):
    """The cache key of a case: its fields, the contents of its drive file and tables, the code."""
    h = hashlib.sha256(json.dumps(dataclasses.asdict(case), sort_keys=True).encode())
    h.update(version.encode())
    if case.drive:
        _digest_files([pathlib.Path(case.drive)], h)
    _digest_files(sorted(pathlib.Path(case.tables or tables.DATA_DIR).glob("*.csv")), h)
    return h.hexdigest()[:32]


def spectrum_orders(meshing):
    """The orders of the spectra: SPECTRUM_STEP to the meshing order + SPECTRUM_BEYOND_MESHING."""
    n = int(round((meshing + SPECTRUM_BEYOND_MESHING) / SPECTRUM_STEP))
    return [SPECTRUM_STEP * (i + 1) for i in range(n)]


def run_case(case):
    """Runs a case (in a Dask worker or here) and returns its result as a plain dict: status "ok"
    with its rows (one per speed: the stationary speed, or every engine cycle of a run-up), or
    status "failed" with the error; a failing case never raises, so the sweep goes on."""
    try:
        with contextlib.redirect_stdout(io.StringIO()):  # the main job's report lines: the sweep reports
            return _run_runup(case) if case.runup else _run_stationary(case)
    except Exception as e:  # a method failure, a bad parameter, a table out of range: reported
        return {"status": "failed", "error": f"{type(e).__name__}: {e}", "trace": traceback.format_exc(limit=4)}


def _run_stationary(case):
    config = case.config()
    scene_run = job.simulate(config, progress=False)
    _, summary = job.cycle_statistics(config, scene_run)
    d, elements = scene_run.record, scene_run.elements
    spans = cycle_stats.cycle_spans(d[elements.crank + ".phi"], scene_run.run_in)[:case.cycles]
    row = {"rpm": case.rpm, "cycles": len(spans), "runInCycles": scene_run.run_in}
    row.update({k: s["mean"] for k, s in summary.items()})
    row.update({k + ".ci95": s["ci95"] for k, s in summary.items()})
    counted = slice(spans[0][0], spans[-1][1])
    row.update(extremes(d, counted))
    orders = spectrum_orders(elements.meshing_order)
    spectra = {name: np.mean(cycle_stats.order_amplitudes_per_cycle(d, spans, name, orders, scale, elements.crank),
                             axis=0).tolist()
               for name, _, scale, _ in cycle_stats.order_signals(elements)}
    return {"status": "ok", "rows": [row], "orders": orders, "spectra": {k: [v] for k, v in spectra.items()},
            "spectrumUnits": spectrum_units(elements),
            "units": _with_force_units({k: s["unit"] for k, s in summary.items()}), "cpu_s": scene_run.cpu,
            "simulated_s": scene_run.duration}


def extremes(d, samples):
    """The forces' minima and maxima [N] over the samples (a slice) of the record, and a hydraulic
    chamber's lowest and highest pressure [bar]."""
    out = {}
    for name in (n for n in FORCE_SIGNALS if n in d):
        out[name + ".min"] = float(np.min(d[name][samples]))
        out[name + ".max"] = float(np.max(d[name][samples]))
    if cycle_stats.has_chamber(d):
        out.update({key: float(f(d[cycle_stats.CHAMBER][samples])) / cycle_stats.BAR
                    for key, f in CHAMBER_EXTREMES.items()})
    return out


def spectrum_units(elements):
    """{signal: unit} of the spectra of a drive's case (cycle_stats.order_signals)."""
    return {name: unit for name, unit, _, _ in cycle_stats.order_signals(elements)}


def _with_force_units(units):
    """The units of the headline quantities, of the forces' minima and maxima and of the chamber's
    extremes."""
    return dict(units, **{name + stat: "N" for name in FORCE_SIGNALS for stat in (".min", ".max")},
                **{key: "bar" for key in CHAMBER_EXTREMES})


def runup_inputs(case, ramp_start, elements):
    """The run-up's inputs for a drive (drive.description.Elements): the mean speed held at
    case.rpm up to ramp_start [s], then ramped linearly to case.rpm_end over case.ramp_s; the load
    torques and the crankshaft speed's fluctuation (relative to its table's speed) interpolated
    linearly in engine speed between the tables of the two nearest tabulated speeds (the tables'
    own speed dependence), and those of the lowest or highest tabulated speed below or above the
    tables' range."""
    speeds = sorted(tables.available_speeds(case.tables, "crankshaft_speed"))
    if not speeds:
        raise ValueError(f"run-up: no crankshaft_speed_<n>rpm.csv tables in {case.tables or tables.DATA_DIR}")
    config = case.config()
    at_speed = {r: job.table_inputs(job.drive_loads(dataclasses.replace(config, rpm=r), elements),
                                    tables.crankshaft_speed(r, case.tables), elements, config.supply_pressure)
                for r in speeds}
    speed = elements.crank + ".w"

    def inputs(t, angles):
        ramp = min(max((t - ramp_start) / case.ramp_s, 0.0), 1.0)
        rpm = case.rpm + (case.rpm_end - case.rpm) * ramp
        i = min(max(int(np.searchsorted(speeds, rpm)) - 1, 0), max(len(speeds) - 2, 0))
        r1, r2 = speeds[i], speeds[min(i + 1, len(speeds) - 1)]
        w = min(max((rpm - r1) / (r2 - r1), 0.0), 1.0) if r2 > r1 else 0.0  # held beyond the tables
        at = [at_speed[r](t, angles) for r in (r1, r2)]
        fluctuation = [u[speed] / fmu.rpm_to_rad_s(r) for u, r in zip(at, (r1, r2))]
        out = {k: (1.0 - w) * at[0][k] + w * at[1][k] for k in at[0]}
        out[speed] = fmu.rpm_to_rad_s(rpm) * ((1.0 - w) * fluctuation[0] + w * fluctuation[1])
        return out
    inputs.angles = at_speed[speeds[0]].angles
    # (the same inputs for the compiled loop: every tabulated speed's terms, blended there)
    inputs.terms = at_speed[speeds[0]].terms
    inputs.run_up = loop.RunUp(speeds, [at_speed[r].terms for r in speeds], speed, float(case.rpm),
                               float(case.rpm_end), float(ramp_start), float(case.ramp_s))
    return inputs


def _run_runup(case):
    if not (case.ramp_s and case.ramp_s > 0.0):
        raise ValueError(f"run-up: ramp time {case.ramp_s} s must be positive")
    config, elements = case.config(), drive_elements(case.drive)
    run_in = job.run_in_cycles(case.rpm)  # (fixed: the ramp starts at a known time)
    ramp_start = run_in * 120.0 / case.rpm
    cpu0 = time.process_time()
    d, _, _ = job.run_closed(config, ramp_start + case.ramp_s, runup_inputs(case, ramp_start, elements),
                             progress=False)
    cpu = time.process_time() - cpu0
    per_cycle = cycle_stats.per_cycle(d, run_in, elements)
    spans = cycle_stats.cycle_spans(d[elements.crank + ".phi"], run_in)
    if not spans:
        raise ValueError(f"run-up: the ramp of {case.ramp_s:g} s holds no whole engine cycle")
    rows = []
    for j, (i0, i1, _) in enumerate(spans):
        row = {"rpm": float(np.mean(d[f"input.{elements.crank}.w"][i0:i1])) * 60.0 / (2.0 * math.pi), "cycles": 1}
        row.update({k: float(v[j]) for k, (_, v) in per_cycle.items()})
        row.update(extremes(d, slice(i0, i1)))
        rows.append(row)
    orders = spectrum_orders(elements.meshing_order)
    spectra = {name: cycle_stats.order_amplitudes_per_cycle(d, spans, name, orders, scale, elements.crank).tolist()
               for name, _, scale, _ in cycle_stats.order_signals(elements)}
    return {"status": "ok", "rows": rows, "orders": orders, "spectra": spectra, "spectrumUnits": spectrum_units(elements),
            "units": _with_force_units({k: u for k, (u, _) in per_cycle.items()}), "cpu_s": cpu,
            "simulated_s": ramp_start + case.ramp_s}
