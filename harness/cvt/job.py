"""The main job on the chain CVT (`python -m harness run --scene cvt`, `./run.sh main --scene cvt`):
a stationary run of the default CVT (src/drives/default_cvt.json, or --cvt FILE) at a driving
speed and an output torque, through the solver alone (build/chaindrive-cvt). The run starts from
the nominal state (the chain moving with the pulleys, pre-tensioned by the clamping force); the
first chain revolutions (--run-in-revolutions, RUN_IN_REVOLUTIONS) carry the start transient, the
pins' slow radial settling among it, and are discarded. Every headline
quantity is reported per chain revolution, as the mean over the counted revolutions with its 95 %
confidence half-width (harness/cycle_stats.interval), with the checks of a stationary state:

  speed ratio   driving over driven speed against the geometric ratio r2 / r1 (slip = 1 - their ratio)
  torque        (F_tight - F_slack) r2 against the chain's torque on the driven pulley
  energy        input minus output work against the energy dissipated (in the chain's joints, the
                pins' axial damping and the friction), over the counted revolutions

    python -m harness run --scene cvt [--rpm 2000] [--load-torque 80] [--revolutions 8] [--cvt FILE]
                                      [--run-in-revolutions 24] [--method M] [--solver-step S] [--strict]

Writes to --out: cvt_outputs.csv (every output step), cvt_summary.json (the statistics, the
checks, the assembly and the cost) and the plots: the paper's Figure 9 for one pin over one chain
revolution (cvt_figure9.png) and the time histories (cvt_time_histories.png).
"""
import dataclasses
import json
import math
import pathlib
import subprocess

import numpy as np

from .. import checks as run_checks
from .. import cycle_stats, defaults, paths
from ..errors import tool_failure
from . import plots

DEFAULT_RPM = 2000.0        # driving-pulley speed of the cost figure (CPU s per chain revolution)
DEFAULT_LOAD = 80.0         # [N m] about half the default CVT's torque capacity (2 mu F r / cos beta = 169 N m)
DEFAULT_REVOLUTIONS = 8     # counted chain revolutions
# discarded: the start transient. From the nominal state the chain takes up the load within a
# revolution, but its tension and the clamping forces then creep for about 21 revolutions (1.3 s at
# 2000 rpm, 100 N m: the tight strand 3.93 -> 4.13 kN, the driven clamping force 19.3 -> 21.3 kN,
# the power loss 189 -> 157 W; measured per revolution) while the pins settle radially against
# their friction; stationary after that (per-revolution values within 0.2 %)
RUN_IN_REVOLUTIONS = 24
MAX_RPM = 10000.0           # the driving speeds accepted lie in (0, MAX_RPM]
# the stationary checks' limits (relative errors): beyond them the run is not accurate (the default
# step meets both, a 2 us step misses both by far: docs/defaults.md)
TORQUE_BALANCE_LIMIT, ENERGY_BALANCE_LIMIT = 0.02, 0.01
OUTPUT_STEP = 5e-5          # [s]
# the timing drive's options (harness/job.py) with their defaults: the CVT's run (the solver alone,
# link fidelity) has no use for them, so they are refused when set
TIMING_OPTIONS = (("--drive", "drive", None), ("--fidelity", "fidelity", "link"), ("--coupling", "coupling", "closed"),
                  ("--tables", "tables", None), ("--supply-pressure-bar", "supply_pressure_bar", None),
                  ("--oil-temperature-c", "oil_temperature_c", None), ("--replicas", "replicas", 1))

# per-revolution quantities: (CSV column, unit)
QUANTITIES = {"slip": ("slip", ""), "drivenSpeed": ("drivenSpeed", "rad/s"),
              "tightStrandForce": ("tightStrandForce", "N"), "slackStrandForce": ("slackStrandForce", "N"),
              "clampingForceDriving": ("clampingForceDriving", "N"), "clampingForceDriven": ("clampingForceDriven", "N"),
              "drivingTorque": ("drivingTorque", "N m"), "drivenTorque": ("drivenTorque", "N m")}


@dataclasses.dataclass(frozen=True)
class CVTConfig:
    """What a run of the CVT does, every default resolved: built once (config_of from the command
    line, or by the study) and read, never changed, by the run."""
    rpm: float = DEFAULT_RPM                # [rpm] driving-pulley speed
    load_torque: float = DEFAULT_LOAD       # [N m] on the driven pulley
    revolutions: int = DEFAULT_REVOLUTIONS  # chain revolutions counted after the run-in
    run_in_revolutions: int = RUN_IN_REVOLUTIONS  # chain revolutions discarded first
    # chaindrive-cvt's integration method, its step [s] (the adaptive methods: their largest) and
    # tolerance; default: the CVT's row of the one defaults table (harness/defaults.py)
    method: str = dataclasses.field(default_factory=lambda: defaults.solver("cvt").method)
    solver_step: float = dataclasses.field(default_factory=lambda: defaults.solver("cvt").step)
    rtol: float = dataclasses.field(default_factory=lambda: defaults.solver("cvt").tolerance)
    cvt: str | None = None                  # CVT description file; None: the embedded default CVT
    out: pathlib.Path = paths.RESULTS       # output directory
    # the study's (harness/study/cvt.py): time stepping's friction polygon, a run continued from a
    # saved state or saving its last
    friction_facets: int | None = None
    state_in: pathlib.Path | None = None
    state_out: pathlib.Path | None = None
    strict: bool = False                    # a missed check makes the exit status 1 (harness/checks.py)


# the fields of CVTConfig the command line sets (besides --out), named as its options' destinations
COMMAND_LINE_FIELDS = ("rpm", "load_torque", "revolutions", "run_in_revolutions", "method", "solver_step", "rtol",
                       "cvt", "strict")


def add_arguments(ap):
    """The CVT's own options; those it shares with the timing drive (--rpm, --method,
    --solver-step, --rtol, --out) are harness/run.py's."""
    ap.add_argument("--cvt", help="cvt: the CVT description (default: the embedded default CVT)")
    ap.add_argument("--load-torque", type=float, default=DEFAULT_LOAD,
                    help=f"cvt: the load torque on the driven pulley [N m] (default {DEFAULT_LOAD:g})")
    ap.add_argument("--revolutions", type=int, default=DEFAULT_REVOLUTIONS,
                    help=f"cvt: chain revolutions counted after the run-in (default {DEFAULT_REVOLUTIONS})")
    ap.add_argument("--run-in-revolutions", type=int, default=RUN_IN_REVOLUTIONS,
                    help=f"cvt: chain revolutions discarded first (default {RUN_IN_REVOLUTIONS})")


def config_of(ap, args):
    """The run's configuration from the command line's options (harness/run.py; the shared ones None
    where not given): the timing drive's options refused when set, misuse reported by ap.error."""
    for option, name, default in TIMING_OPTIONS:
        if getattr(args, name) != default:
            ap.error(f"{option} {getattr(args, name)}: does not apply to the CVT scene (solver alone, link fidelity)")
    if args.revolutions < 2:
        ap.error(f"--revolutions {args.revolutions}: at least 2 counted revolutions are needed for a confidence "
                 "interval")
    if args.run_in_revolutions < 0:
        ap.error(f"--run-in-revolutions {args.run_in_revolutions}: must be >= 0")
    if args.rpm is not None and not 0.0 < args.rpm <= MAX_RPM:
        ap.error(f"--rpm {args.rpm:g}: the driving speed must lie in (0, {MAX_RPM:g}] rpm")
    given = {name: getattr(args, name) for name in COMMAND_LINE_FIELDS if getattr(args, name) is not None}
    return CVTConfig(out=pathlib.Path(args.out), **given)


def command(config, csv):
    """The chaindrive-cvt command line of a run writing its outputs to csv."""
    revolutions = config.run_in_revolutions + config.revolutions
    # (chaindrive-cvt simulates the revolutions and an output step more: the last one's end on the grid)
    cmd = [paths.executable("chaindrive-cvt"), "--rpm", repr(config.rpm), "--load-torque", repr(config.load_torque),
           "--revolutions", repr(float(revolutions)), "--output-step", repr(OUTPUT_STEP), "--method", config.method,
           "--step", repr(config.solver_step), "--rtol", repr(config.rtol), "--csv", str(csv)]
    if config.cvt:
        cmd += ["--cvt", config.cvt]
    for option, value in (("--friction-facets", config.friction_facets), ("--state-in", config.state_in),
                          ("--state-out", config.state_out)):
        if value is not None:
            cmd += [option, str(value)]
    return cmd


def simulate(config, quiet=False):
    """Runs chaindrive-cvt over the run-in and the counted revolutions, its outputs into config.out;
    returns (record, its JSON). A failed run raises UserError with the solver's message in one line."""
    csv = config.out / "cvt_outputs.csv"
    if not quiet:
        print(f"chaindrive-cvt: {config.cvt or 'default CVT'}, {config.rpm:g} rpm driving, load torque "
              f"{config.load_torque:g} N m, run-in {config.run_in_revolutions} + {config.revolutions} chain "
              f"revolutions, {config.method} at {config.solver_step * 1e6:g} us")
    done = subprocess.run(command(config, csv), capture_output=True, text=True)
    if done.returncode != 0:
        raise tool_failure("chaindrive-cvt", done.stderr)
    result = json.loads(done.stdout)
    data = np.genfromtxt(csv, delimiter=",", names=True)
    return {name: data[name] for name in data.dtype.names}, result


def revolution_spans(time, revolution, run_in):
    """(start, end) sample indices of the counted chain revolutions (whole ones only)."""
    spans = []
    k = run_in
    while (k + 1) * revolution <= time[-1] + 1e-12:
        a, b = np.searchsorted(time, [k * revolution - 1e-12, (k + 1) * revolution - 1e-12])
        spans.append((int(a), int(b)))
        k += 1
    return spans


def per_revolution(record, spans):
    """{key: (unit, values per revolution)}: means of the quantities, and the powers and checks
    from the works over each revolution."""
    out = {key: (unit, [float(np.mean(record[col][a:b])) for a, b in spans]) for key, (col, unit) in QUANTITIES.items()}
    t, w_in, w_diss = record["time"], record["inputWork"], record["dissipatedEnergy"]
    out["powerLoss"] = ("W", [(w_diss[b] - w_diss[a]) / (t[b] - t[a]) for a, b in spans])
    out["netInputPower"] = ("W", [(w_in[b] - w_in[a]) / (t[b] - t[a]) for a, b in spans])
    return out


def checks(summary, result):
    """The stationary checks from the means (relative errors; see the module docstring)."""
    r1, r2 = result["assembly"]["runningRadius"]
    driven = summary["drivenTorque"]["mean"]
    balance = (summary["tightStrandForce"]["mean"] - summary["slackStrandForce"]["mean"]) * r2
    return {"speedRatioError": result["checks"]["speedRatioError"],
            "torqueBalanceError": (balance - driven) / driven if driven else math.nan,
            "energyBalanceError": result["checks"]["energyBalanceError"],
            "pinsInContact": result["checks"]["pinsInContact"], "geometricRatio": r2 / r1}


def check_warnings(check):
    """The warning lines of the balances that miss their limits (none when both hold)."""
    found = {"torque": (check["torqueBalanceError"], TORQUE_BALANCE_LIMIT, "(F_tight - F_slack) r2 off the driven "
                        "torque by"),
             "energy": (check["energyBalanceError"], ENERGY_BALANCE_LIMIT, "energy balance")}
    return [f"{text} {100 * error:+.2f} % misses its limit {100 * limit:g} %: the run is not accurate (a smaller "
            f"--solver-step)" for error, limit, text in found.values() if not abs(error) <= limit]


def report(summary, check, result, cpu_per_revolution):
    a = result["assembly"]
    print(f"\nassembly: running radii {a['runningRadius'][0] * 1e3:.2f} / {a['runningRadius'][1] * 1e3:.2f} mm, "
          f"pre-tension {a['pretension']:.0f} N, clamping forces {a['clampingForce'][0] / 1e3:.2f} / "
          f"{a['clampingForce'][1] / 1e3:.2f} kN (driving / driven)")
    print("summary: mean over chain revolutions after the run-in, +- the 95 % confidence half-width")
    for key, s in summary.items():
        print(cycle_stats.format_line(key, cycle_stats.in_percent(s) if key == "slip" else s, periods="revolutions"))
    print(f"checks: speed ratio {1 + check['speedRatioError']:.5f} x the geometric {check['geometricRatio']:.4f}; "
          f"(F_tight - F_slack) r2 off the driven torque by {100 * check['torqueBalanceError']:+.2f} % (limit 2 %); "
          f"energy balance {100 * check['energyBalanceError']:+.3f} % of the dissipated energy (limit 1 %); pins in "
          f"contact {check['pinsInContact'][0]:.1f} / {check['pinsInContact'][1]:.1f}")
    print(f"  CPU {cpu_per_revolution:.3g} s per chain revolution ({result['run']['cpuSeconds']:.2f} s in all)")


def run(config):
    """The main job of the CVT: the run, its statistics, checks and plots in config.out."""
    out = config.out
    out.mkdir(parents=True, exist_ok=True)
    record, result = simulate(config)
    revolution = result["run"]["chainRevolution"]
    spans = revolution_spans(record["time"], revolution, config.run_in_revolutions)
    summary = cycle_stats.summarize(per_revolution(record, spans))
    check = checks(summary, result)
    warnings = check_warnings(check)
    cpu_per_revolution = result["run"]["cpuPerChainRevolution"]
    (out / "cvt_summary.json").write_text(json.dumps({"statistics": summary, "checks": check, "warnings": warnings,
                                                      "assembly": result["assembly"], "run": result["run"]},
                                                     indent=1) + "\n")
    title = f"{config.rpm:g} rpm, {config.load_torque:g} N m, {config.method} at {config.solver_step * 1e6:g} us"
    pictures = [plots.figure9(out / "cvt_figure9.png", record, spans[-1], title),
                plots.time_histories(out / "cvt_time_histories.png", record, spans, title)]
    report(summary, check, result, cpu_per_revolution)
    run_checks.print_lines(warnings, [])
    print(f"  outputs: {out / 'cvt_outputs.csv'}, {out / 'cvt_summary.json'}")
    print("  plots: " + ", ".join(str(p) for p in pictures))
    return run_checks.EXIT_STRICT if config.strict and warnings else 0
