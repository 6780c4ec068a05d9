"""Speed sweeps and run-ups of a drive through ChainDrive.fmu on Dask, with Campbell diagrams
and order cuts.

Two studies, one command:
  speed sweep  every speed of --rpm (FROM:TO:STEP or a comma list) held, --cycles engine cycles
               counted after the main job's run-in (harness/job.py), one case per speed;
  run-up       --runup FROM:TO: the run-in at FROM, then the mean speed ramped linearly to TO over
               --ramp-time seconds, one case; every engine cycle of the ramp is a point over speed.
The hydraulic tensioner's oil (the default drive's): --supply-pressure-bar and --oil-temperature-c,
comma lists, each value combined with every speed (and with each other's: the cartesian product);
not given, the main job's defaults (3 bar, 90 degC). Both run ChainDrive.fmu in closed loop at 0.1 ms communication steps with the measured-torque
tables (between tabulated speeds interpolated in speed), at any --fidelity and --method.

Execution: one Dask task per case on a LocalCluster of --workers single-threaded worker processes
(default: one per core), or on the cluster at --scheduler ADDRESS (start it with `dask scheduler`
and `dask worker ADDRESS --nthreads 1` on every machine; harness/sweep/execute.py). A progress bar
counts the cases. Every case's result is cached in --cache under a key of its inputs and the code
version: a sweep stopped and started again computes only the missing cases. A failing case (a
method failure, a bad parameter, a worker lost on every retry) is reported with its error and the
sweep goes on.

    python -m harness sweep [--rpm 1000:6000:500] [--runup 1000:6000 --ramp-time 5] [--fidelity link|span]
                            [--method M] [--solver-step S] [--cycles 8] [--drive FILE]
                            [--tables DIR] [--supply-pressure-bar 1,3,5] [--oil-temperature-c 40,90,120]
                            [--workers N | --scheduler ADDRESS] [--cache DIR] [--out DIR]

Writes to --out: sweep.nc (speed sweep) and runup.nc (run-up), xarray Datasets in netCDF with
units and the drive's parameters as attributes, and per study the plots campbell_tensioner_F.png,
campbell_tensionGuide_phi.png, order_cuts.png and forces_over_speed.png (in sweep/ and runup/), and
with a hydraulic tensioner hydraulic_over_speed.png (tensioner force and chamber pressure over
speed, a line per supply pressure and oil temperature). The oil settings given are coordinates
along `point` (supply_pressure_bar, oil_temperature_c).
"""
import dataclasses
import itertools
import math
import pathlib
import sys
import time

from .. import checks, cycle_stats, job, paths
from ..drive.description import drive_json, meshing_order
from ..drive.description import elements as drive_elements
from .cases import Case, code_version
from .execute import run_cases
from .results import attributes, dataset, plots, write_netcdf

DEFAULT_RPM = "1000:6000:500"


def speeds(text):
    """Engine speeds [rpm] of FROM:TO:STEP (TO included) or a comma list; ValueError names the text."""
    try:
        if ":" in text:
            lo, hi, step = (float(x) for x in text.split(":"))
            if not step > 0.0 or hi < lo:
                raise ValueError
            n = int(round((hi - lo) / step))
            return [lo + i * step for i in range(n + 1) if lo + i * step <= hi + 1e-9 * step]
        return [float(x) for x in text.split(",")]
    except ValueError:
        raise ValueError(f"'{text}': expected FROM:TO:STEP with STEP > 0 and TO >= FROM, or a comma list of speeds "
                         f"[rpm]") from None


def speed_range(text):
    """(FROM, TO) [rpm] of FROM:TO; ValueError names the text."""
    try:
        lo, hi = (float(x) for x in text.split(":"))
        return lo, hi
    except ValueError:
        raise ValueError(f"--runup {text}: expected FROM:TO [rpm]") from None


def values(option, text):
    """The numbers of a comma list; ValueError names the option and the text."""
    try:
        return [float(x) for x in text.split(",")]
    except ValueError:
        raise ValueError(f"{option} '{text}': expected a comma list of numbers") from None


def add_arguments(ap):
    ap.add_argument("--rpm", help=f"speed sweep: FROM:TO:STEP or a comma list [rpm] (default {DEFAULT_RPM} "
                    "unless --runup is given)")
    ap.add_argument("--runup", help="run-up FROM:TO [rpm] (TO < FROM: a run-down; beyond the tables' speeds, the "
                    "nearest table's torques and relative speed fluctuation)")
    ap.add_argument("--ramp-time", type=float, default=5.0, help="run-up: duration of the ramp [s] (default 5)")
    ap.add_argument("--fidelity", choices=job.FIDELITIES, default="link")
    ap.add_argument("--method", help="FMU parameter solver.method (default: the fidelity's, harness/defaults.py)")
    ap.add_argument("--solver-step", type=float, help="FMU parameter solver.step [s] (default: the fidelity's)")
    ap.add_argument("--cycles", type=int, default=8, help="speed sweep: engine cycles counted per speed (default 8)")
    ap.add_argument("--drive", help="drive description (default: the FMU's default drive)")
    ap.add_argument("--tables", help="directory of the torque/speed tables (default harness/tables/data)")
    ap.add_argument("--load", action="append", default=[], metavar="NAME=VALUE",
                    help="a constant load torque [N m] on the loaded sprocket NAME instead of its table (repeatable)")
    ap.add_argument("--supply-pressure-bar", metavar="LIST",
                    help=f"hydraulic tensioner: oil supply pressures [bar, gauge], a comma list (default "
                    f"{job.SUPPLY_PRESSURE / job.BAR:g}), each with every speed")
    ap.add_argument("--oil-temperature-c", metavar="LIST",
                    help=f"hydraulic tensioner: oil temperatures [degC], a comma list (default "
                    f"{job.OIL_TEMPERATURE - job.ZERO_CELSIUS:g}), each with every speed")
    ap.add_argument("--workers", type=int, help="LocalCluster worker processes (default: one per core)")
    ap.add_argument("--scheduler", help="address of a running Dask scheduler instead of a LocalCluster")
    ap.add_argument("--cache", help="cache directory (default OUT/cache)")
    ap.add_argument("--out", default=str(paths.RESULTS / "sweep"), help="output directory")
    ap.add_argument("--no-progress", action="store_true", help="no progress bar")


def check(ap, args):
    try:
        args.speeds = speeds(args.rpm) if args.rpm else ([] if args.runup else speeds(DEFAULT_RPM))
        args.runup_speeds = speed_range(args.runup) if args.runup else None
        pressures = values("--supply-pressure-bar", args.supply_pressure_bar) if args.supply_pressure_bar else [None]
        temperatures = values("--oil-temperature-c", args.oil_temperature_c) if args.oil_temperature_c else [None]
    except ValueError as e:
        ap.error(str(e))
    if not args.ramp_time > 0.0:
        ap.error(f"--ramp-time {args.ramp_time}: must be > 0 s")
    if args.cycles < 2:
        ap.error(f"--cycles {args.cycles}: at least 2 counted cycles per speed are needed for a confidence interval")
    if args.workers is not None and args.workers < 1:
        ap.error(f"--workers {args.workers}: must be >= 1")
    if args.solver_step is not None and not args.solver_step > 0.0:
        ap.error(f"--solver-step {args.solver_step}: must be > 0 s")
    if args.drive:
        args.drive = str(pathlib.Path(args.drive).resolve())
    if args.tables:
        args.tables = str(pathlib.Path(args.tables).resolve())
    args.oil_settings = oil_settings(args.drive, pressures, temperatures)
    args.loads = tuple(job.constant_load(ap, text) for text in args.load)
    for rpm in args.speeds + list(args.runup_speeds or []):  # (a sprocket without a load: named before the sweep)
        job.drive_loads(job.run_config(rpm=rpm, drive=args.drive, tables=args.tables, loads=args.loads),
                        drive_elements(args.drive))
    given = [f"{option} {text}" for option, text in (("--supply-pressure-bar", args.supply_pressure_bar),
                                                    ("--oil-temperature-c", args.oil_temperature_c)) if text]
    checks.print_lines([], job.inert_oil_notes(drive_json(args.drive), given))
    return args


def oil_settings(drive, pressures, temperatures):
    """[(supply pressure [Pa], oil temperature [K])] of the lists in bar and degC (None: not given,
    the case's default), each validated as the main job's options (UserError)."""
    settings = []
    for bar, celsius in itertools.product(pressures, temperatures):
        oil = job.hydraulic_options(drive, bar, celsius)
        settings.append((None if bar is None else oil["supply_pressure"],
                         None if celsius is None else oil["oil_temperature"]))
    return settings


def cases_of(args):
    """(speed-sweep cases, run-up cases) of the options."""
    method = args.method or job.run_config(fidelity=args.fidelity, drive=args.drive).method
    base = Case(rpm=0.0, fidelity=args.fidelity, method=method, solver_step=args.solver_step, cycles=args.cycles,
                drive=args.drive, tables=args.tables, loads=getattr(args, "loads", ()))
    settings = getattr(args, "oil_settings", [(None, None)])
    sweep = [dataclasses.replace(base, rpm=r, supply_pressure=p, oil_temperature=T)
             for (p, T), r in itertools.product(settings, args.speeds)]
    runup = []
    if args.runup_speeds:
        lo, hi = args.runup_speeds
        runup = [dataclasses.replace(base, rpm=lo, rpm_end=hi, ramp_s=args.ramp_time, supply_pressure=p,
                                     oil_temperature=T) for p, T in settings]
    return sweep, runup


def report(name, cases, results, computed, seconds):
    print(f"\n{name}: {len(cases)} case(s), {computed} computed now, {len(cases) - computed} from the cache, "
          f"{seconds:.1f} s wall time")
    for case, r in zip(cases, results):
        if r["status"] == "ok":
            rows = r["rows"]
            F = [row.get("tensioner.F.mean", math.nan) for row in rows]
            what = (f"tensioner F mean {F[0]:.1f} +- {rows[0].get('tensioner.F.mean.ci95', math.nan):.1f} N"
                    if not case.runup else f"{len(rows)} engine cycles, tensioner F mean {min(F):.1f}-{max(F):.1f} N")
            chamber = cycle_stats.CHAMBER + ".mean_bar"
            if chamber in rows[0] and not case.runup:
                what += f", chamber {rows[0][chamber]:.1f} +- {rows[0][chamber + '.ci95']:.1f} bar"
            print(f"  ok      {case.label()}: {what}, {r['cpu_s']:.1f} CPU s")
        else:
            print(f"  FAILED  {case.label()}: {r['error']}")
    return sum(r["status"] != "ok" for r in results)


def run_study(name, cases, args, version, out):
    """Runs one study's cases, writes its dataset and plots; returns the number of failed cases."""
    t0 = time.time()
    results, computed = run_cases(cases, args.cache or out / "cache", workers=args.workers, scheduler=args.scheduler,
                                  progress=not args.no_progress)
    failed = report(name, cases, results, computed, time.time() - t0)
    drive = drive_json(args.drive)
    command = "python -m harness sweep " + " ".join(getattr(args, "argv", []))
    ds = dataset(cases, results, attributes(drive, cases[0], version, command))
    study_out = out / name
    study_out.mkdir(parents=True, exist_ok=True)
    nc = out / f"{name}.nc"
    write_netcdf(ds, nc)
    written = [nc]
    if failed < len(cases):
        written += plots(ds, study_out, meshing_order(drive), f"{args.fidelity} fidelity, {cases[0].method}")
    print("  written: " + ", ".join(str(p) for p in written))
    return failed


def run(args):
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    version = code_version()
    sweep, runup = cases_of(args)
    failed = 0
    for name, cases in (("sweep", sweep), ("runup", runup)):
        if cases:
            failed += run_study(name, cases, args, version, out)
    if failed:
        print(f"\n{failed} case(s) failed (see above); the others are in the results", file=sys.stderr)
    return 1 if failed else 0
