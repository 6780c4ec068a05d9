"""Integrator benchmark of the solver alone (no FMU): the default drive at several engine speeds
for two engine cycles with every integrator, each at a setting and at the halved setting.

Prints, per speed and integrator: CPU seconds per simulated second (median of repeated runs),
steps, right-hand-side evaluations, and how much the tensioner force changes when the step or
tolerance is halved; then the fastest integrator whose tensioner force changes by less than 1 %
at 3000 rpm. Writes the same as Markdown.

    python -m harness bench [--rpm 1000 3000 6000] [--repeats 3] [--out results/benchmark.md]

How the change is measured. Link-level chain dynamics with impacts are highly sensitive to
perturbations: two runs whose crankshaft speed differs by 1e-9 (relative) drift apart within
about 20 ms (the script measures this too, as "divergence"). So point-by-point differences over
two cycles say nothing about the step size once the runs have drifted apart. The change is
therefore measured on the tensioner-force quantities engineers read, which stay well defined:
its RMS level over the two cycles and its amplitudes at engine orders 2, 4, 6, 8; the
point-by-point difference is reported over the first 5 ms, before the drift.
"""
import datetime
import pathlib
import statistics
import subprocess
import tempfile

import numpy as np

from .. import paths, runs
from ..plots import plots
from ..tables import tables

# integrator, option, setting, halved setting
CONFIGS = [
    ("fixed-verlet", "step", 3e-6, 1.5e-6),
    ("arkode-erk-fixed", "step", 2e-6, 1e-6),
    ("arkode-erk", "rtol", 1e-5, 5e-6),
    ("cvode-bdf-klu", "rtol", 1e-4, 5e-5),
    ("cvode-bdf-band", "rtol", 1e-4, 5e-5),
]
ORDERS = (2, 4, 6, 8)
# [s] a whole number of steps of every fixed step above (the runner rounds the output interval
# to whole steps), so that a setting and its halved setting write the same output times
OUTPUT_STEP = 6e-5


def one_run(tmp, rpm, duration, inputs, integrator, option, value, timeout, tag=""):
    out = pathlib.Path(tmp) / f"{integrator}_{rpm:g}_{value:g}{tag}.csv"
    kw = {option: value}
    try:
        code, text, s = runs_with_timeout(out, rpm, duration, inputs, integrator, kw, timeout)
    except subprocess.TimeoutExpired:
        return {"failure": f"exceeded {timeout:g} s wall time"}, None
    if code != 0:
        return {"failure": s.get("failure", text.strip()[-200:])} | s, None
    return s, runs.read_csv(out)


def runs_with_timeout(out, rpm, duration, inputs, integrator, kw, timeout):
    cmd = [paths.executable("chaindrive-run"), "--rpm", str(rpm), "--duration", repr(duration), "--integrator",
           integrator, "--inputs", str(inputs), "--output-step", repr(OUTPUT_STEP), "--out", str(out), "--quiet"]
    for k, v in kw.items():
        cmd += [f"--{k}", repr(v)]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout + p.stderr, runs.parse_summary(p.stdout)


def perturbed_inputs(path, out, rel):
    """The input table with the crankshaft speed scaled by (1 + rel)."""
    lines = open(path).read().splitlines()
    with open(out, "w") as f:
        for line in lines:
            if line.startswith("#") or line.startswith("time"):
                f.write(line + "\n")
                continue
            cells = line.split(",")
            cells[1] = repr(float(cells[1]) * (1.0 + rel))
            f.write(",".join(cells) + "\n")
    return out


def measures(d, rpm):
    F = d["tensioner.F"]
    o, amp = plots.order_spectrum(d["time"], F, rpm)
    return {"rms": float(np.sqrt(np.mean(F ** 2))),
            "orders": [float(amp[np.argmin(np.abs(o - k))]) for k in ORDERS]}


def pct(a, b):
    return 100.0 * abs(a - b) / abs(b)


def add_arguments(ap):
    ap.add_argument("--rpm", type=float, nargs="+", default=[1000.0, 3000.0, 6000.0])
    ap.add_argument("--cycles", type=float, default=2.0)
    ap.add_argument("--repeats", type=int, default=3, help="timed repetitions per point (median reported)")
    ap.add_argument("--timeout", type=float, default=120.0, help="wall-time limit per run [s]")
    ap.add_argument("--integrators", nargs="+", help="subset of integrators")
    ap.add_argument("--out", default=str(paths.RESULTS / "benchmark.md"))


def run(args):
    configs = [c for c in CONFIGS if not args.integrators or c[0] in args.integrators]
    lines = []

    def emit(s=""):
        print(s, flush=True)
        lines.append(s)

    emit(f"# Integrator benchmark ({datetime.date.today().isoformat()})")
    emit()
    emit(f"machine: {runs.machine()}")
    emit(f"command: python -m harness bench {' '.join(args.argv)}")
    emit(f"scene: default drive, {args.cycles:g} engine cycles, open-loop inputs from the crankshaft-speed and "
         "camshaft-torque tables of harness/tables/data (synthesized); CPU time of the integration (start-state "
         f"solve excluded), median of {args.repeats} runs")
    emit()
    best = None
    with tempfile.TemporaryDirectory() as tmp:
        for rpm in args.rpm:
            best = speed_section(tmp, rpm, args, configs, emit, best)
    if best:
        emit(f"fastest integrator at 3000 rpm whose tensioner-force RMS changes by less than 1 % when its "
             f"step/tolerance is halved: {best[0]}, {best[1]:.2f} CPU s per simulated s (target: at most 10)")
    runs.write_lines(args.out, lines)


def speed_section(tmp, rpm, args, configs, emit, best):
    """One engine speed: the divergence of two runs and the table of the integrators; returns the
    fastest integrator so far (name, CPU s per simulated s) that passes at 3000 rpm."""
    duration = args.cycles * 120.0 / rpm
    inputs = tables.write_inputs_csv(pathlib.Path(tmp) / f"in_{rpm:g}.csv", rpm, duration)
    # divergence of two runs whose inputs differ by 1e-9 (same integrator and step)
    inputs_b = perturbed_inputs(inputs, pathlib.Path(tmp) / f"inb_{rpm:g}.csv", 1e-9)
    sa, da = one_run(tmp, rpm, duration, inputs, "fixed-verlet", "step", 1.5e-6, args.timeout)
    sb, db = one_run(tmp, rpm, duration, inputs_b, "fixed-verlet", "step", 1.5e-6, args.timeout, tag="_perturbed")
    emit(f"## {rpm:g} rpm ({duration * 1e3:.1f} ms simulated)")
    emit()
    if da is not None and db is not None:
        diff = np.abs(da["tensioner.F"] - db["tensioner.F"])
        t = da["time"]
        marks = [0.005, 0.01, 0.02, duration]
        parts = [f"{np.sqrt(np.mean(diff[t <= m] ** 2)):.2g} N up to {m * 1e3:.0f} ms" for m in marks]
        emit("divergence (tensioner force, RMS difference of two fixed-verlet 1.5 us runs whose crankshaft speed "
             "differs by 1e-9): " + ", ".join(parts))
        emit()
    emit("| integrator | setting | CPU s per sim. s | steps | RHS evals | Jacobians | tensioner RMS [N] "
         "| RMS change halved [%] | order 2/4/6/8 amplitude change [%] | first-5-ms difference [N] | status |")
    emit("|---|---|---|---|---|---|---|---|---|---|---|")
    for integrator, option, value, halved in configs:
        row, cpu, ok = integrator_row(tmp, rpm, duration, inputs, args, (integrator, option, value, halved))
        emit(row)
        if abs(rpm - 3000.0) < 1e-9 and ok and (best is None or cpu < best[1]):
            best = (f"{integrator} ({option} {value:g})", cpu)
    emit()
    return best


def timed_runs(tmp, rpm, duration, inputs, args, integrator, option, value):
    """The setting's run, repeated: (CPU s per simulated s of each run, the last summary, its
    outputs or None when a run failed)."""
    timed = []
    s0, d0 = None, None
    for _ in range(args.repeats):
        s, d = one_run(tmp, rpm, duration, inputs, integrator, option, value, args.timeout)
        if d is None:
            return timed, s, None
        timed.append(s["cpu_per_sim_s"])
        s0, d0 = s, d
    return timed, s0, d0


def integrator_row(tmp, rpm, duration, inputs, args, config):
    """One integrator at its setting and at the halved setting: (table row, median CPU s per
    simulated s or None if it failed, whether the tensioner-force RMS changes by less than 1 %)."""
    integrator, option, value, halved = config
    timed, s0, d0 = timed_runs(tmp, rpm, duration, inputs, args, integrator, option, value)
    if d0 is None:
        return (f"| {integrator} | {option} {value:g} | - | {s0.get('steps', '-')} | {s0.get('rhs', '-')} | - | - | - "
                f"| - | - | FAILED: {s0.get('failure', '')[:140]} |"), None, False
    s1, d1 = one_run(tmp, rpm, duration, inputs, integrator, option, halved, args.timeout)
    m0 = measures(d0, rpm)
    cpu = statistics.median(timed)
    change, orders, early, status, ok = halved_change(s1, d1, d0, m0, rpm)
    return (f"| {integrator} | {option} {value:g} | {cpu:.2f} | {s0['steps']} | {s0['rhs']} | {s0.get('jacobians', 0)} "
            f"| {m0['rms']:.2f} | {change} | {orders} | {early} | {status} |"), cpu, ok


def halved_change(s1, d1, d0, m0, rpm):
    """How the tensioner force changes with the halved setting: (RMS change [%], order amplitude
    changes [%], first-5-ms RMS difference [N], status, ok) as table cells."""
    if d1 is None:
        return "-", "-", "-", f"halved setting FAILED: {s1.get('failure', '')[:100]}", False
    m1 = measures(d1, rpm)
    rms_change = pct(m0["rms"], m1["rms"])
    order_changes = [pct(a, b) for a, b in zip(m0["orders"], m1["orders"])]
    sel = d0["time"] <= 0.005
    early = f"{np.sqrt(np.mean((d0['tensioner.F'][sel] - d1['tensioner.F'][sel]) ** 2)):.3f}"
    ok = rms_change < 1.0
    return (f"{rms_change:.2f}", "/".join(f"{c:.1f}" for c in order_changes), early,
            "ok" if ok else "changes by 1 % or more", ok)
