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

Writes to --out: cvt_outputs.csv (every output step), cvt_summary.json (the statistics, the
checks, the assembly and the cost) and the plots: the paper's Figure 9 for one pin over one chain
revolution (cvt_figure9.png) and the time histories (cvt_time_histories.png).
"""
import json
import math
import subprocess

import numpy as np

from .. import cycle_stats, paths
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
DEFAULT_STEP = 5e-7         # [s] fixed-verlet: the energy balance within 0.3 % (1 us: 0.7 %, 2 us: 22 %)
OUTPUT_STEP = 5e-5          # [s]

# per-revolution quantities: (CSV column, unit)
QUANTITIES = {"slip": ("slip", ""), "drivenSpeed": ("drivenSpeed", "rad/s"),
              "tightStrandForce": ("tightStrandForce", "N"), "slackStrandForce": ("slackStrandForce", "N"),
              "clampingForceDriving": ("clampingForceDriving", "N"), "clampingForceDriven": ("clampingForceDriven", "N"),
              "drivingTorque": ("drivingTorque", "N m"), "drivenTorque": ("drivenTorque", "N m")}


def simulate(args, out, quiet=False):
    """Runs chaindrive-cvt over the run-in and the counted revolutions; returns (record, its JSON).
    A failed run raises RuntimeError with the solver's message."""
    csv = out / "cvt_outputs.csv"
    revolutions = args.run_in_revolutions + args.revolutions
    if not quiet:
        print(f"chaindrive-cvt: {args.cvt or 'default CVT'}, {args.rpm:g} rpm driving, load torque "
              f"{args.load_torque:g} N m, run-in {args.run_in_revolutions} + {args.revolutions} chain revolutions, "
              f"{args.method} at {args.solver_step * 1e6:g} us")
    # (chaindrive-cvt simulates the revolutions and an output step more: the last one's end on the grid)
    cmd = [paths.executable("chaindrive-cvt"), "--rpm", repr(args.rpm), "--load-torque", repr(args.load_torque),
           "--revolutions", repr(float(revolutions)), "--output-step", repr(OUTPUT_STEP), "--method", args.method,
           "--step", repr(args.solver_step), "--rtol", repr(args.rtol), "--csv", str(csv)]
    if args.cvt:
        cmd += ["--cvt", args.cvt]
    # (the study's: time stepping's friction polygon, a run continued from a saved state)
    for option, attribute in (("--friction-facets", "friction_facets"), ("--state-in", "state_in"),
                              ("--state-out", "state_out")):
        if getattr(args, attribute, None) is not None:
            cmd += [option, str(getattr(args, attribute))]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"chaindrive-cvt failed: {done.stderr.strip()}")
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


def report(summary, check, result, cpu_per_revolution):
    a = result["assembly"]
    print(f"\nassembly: running radii {a['runningRadius'][0] * 1e3:.2f} / {a['runningRadius'][1] * 1e3:.2f} mm, "
          f"pre-tension {a['pretension']:.0f} N, clamping forces {a['clampingForce'][0] / 1e3:.2f} / "
          f"{a['clampingForce'][1] / 1e3:.2f} kN (driving / driven)")
    print("summary: mean over chain revolutions after the run-in, +- the 95 % confidence half-width")
    for key, s in summary.items():
        print(cycle_stats.format_line(key, s, periods="revolutions"))
    print(f"checks: speed ratio {1 + check['speedRatioError']:.5f} x the geometric {check['geometricRatio']:.4f}; "
          f"(F_tight - F_slack) r2 off the driven torque by {100 * check['torqueBalanceError']:+.2f} % (limit 2 %); "
          f"energy balance {100 * check['energyBalanceError']:+.3f} % of the dissipated energy (limit 1 %); pins in "
          f"contact {check['pinsInContact'][0]:.1f} / {check['pinsInContact'][1]:.1f}")
    print(f"  CPU {cpu_per_revolution:.3g} s per chain revolution ({result['run']['cpuSeconds']:.2f} s in all)")


def run(args):
    out = args.out_path
    out.mkdir(parents=True, exist_ok=True)
    record, result = simulate(args, out)
    revolution = result["run"]["chainRevolution"]
    spans = revolution_spans(record["time"], revolution, args.run_in_revolutions)
    summary = cycle_stats.summarize(per_revolution(record, spans))
    check = checks(summary, result)
    cpu_per_revolution = result["run"]["cpuPerChainRevolution"]
    (out / "cvt_summary.json").write_text(json.dumps({"statistics": summary, "checks": check, "assembly":
                                                      result["assembly"], "run": result["run"]}, indent=1) + "\n")
    title = f"{args.rpm:g} rpm, {args.load_torque:g} N m, {args.method} at {args.solver_step * 1e6:g} us"
    pictures = [plots.figure9(out / "cvt_figure9.png", record, spans[-1], title),
                plots.time_histories(out / "cvt_time_histories.png", record, spans[0][0], title)]
    report(summary, check, result, cpu_per_revolution)
    print(f"  outputs: {out / 'cvt_outputs.csv'}, {out / 'cvt_summary.json'}")
    print("  plots: " + ", ".join(str(p) for p in pictures))
