"""Integrator benchmark of the solver alone (no FMU): the default drive at several engine speeds
for two engine cycles with every integrator, each at a setting and at the halved setting.

Prints, per speed and integrator: CPU seconds per simulated second (median of repeated runs),
steps, right-hand-side evaluations, and how much the tensioner force changes when the step or
tolerance is halved; then the fastest integrator whose tensioner force changes by less than 1 %
at 3000 rpm. Writes the same as Markdown.

    python -m harness.benchmark [--rpm 1000 3000 6000] [--repeats 3] [--out results/benchmark.md]

How the change is measured. Link-level chain dynamics with impacts are highly sensitive to
perturbations: two runs whose crankshaft speed differs by 1e-9 (relative) drift apart within
about 20 ms (the script measures this too, as "divergence"). So point-by-point differences over
two cycles say nothing about the step size once the runs have drifted apart. The change is
therefore measured on the tensioner-force quantities engineers read, which stay well defined:
its RMS level over the two cycles and its amplitudes at engine orders 2, 4, 6, 8; the
point-by-point difference is reported over the first 5 ms, before the drift.
"""
import argparse
import datetime
import math
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile

import numpy as np

from . import paths, plots, runs, tables

# integrator, option, setting, halved setting
CONFIGS = [
    ("fixed-verlet", "step", 3e-6, 1.5e-6),
    ("arkode-erk-fixed", "step", 2e-6, 1e-6),
    ("arkode-erk", "rtol", 1e-5, 5e-6),
    ("cvode-bdf-klu", "rtol", 1e-4, 5e-5),
    ("cvode-bdf-band", "rtol", 1e-4, 5e-5),
]
ORDERS = (2, 4, 6, 8)


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
           integrator, "--inputs", str(inputs), "--output-step", "2e-5", "--out", str(out), "--quiet"]
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


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rpm", type=float, nargs="+", default=[1000.0, 3000.0, 6000.0])
    ap.add_argument("--cycles", type=float, default=2.0)
    ap.add_argument("--repeats", type=int, default=3, help="timed repetitions per point (median reported)")
    ap.add_argument("--timeout", type=float, default=120.0, help="wall-time limit per run [s]")
    ap.add_argument("--integrators", nargs="+", help="subset of integrators")
    ap.add_argument("--out", default=str(paths.RESULTS / "benchmark.md"))
    args = ap.parse_args(argv)

    configs = [c for c in CONFIGS if not args.integrators or c[0] in args.integrators]
    lines = []

    def emit(s=""):
        print(s, flush=True)
        lines.append(s)

    emit(f"# Integrator benchmark ({datetime.date.today().isoformat()})")
    emit()
    emit(f"machine: {runs.machine()}")
    emit(f"command: python -m harness.benchmark {' '.join(sys.argv[1:]) if argv is None else ' '.join(argv)}")
    emit(f"scene: default drive, {args.cycles:g} engine cycles, open-loop inputs from the crankshaft-speed and "
         "camshaft-torque tables of harness/data (synthesized); CPU time of the integration (start-state solve "
         f"excluded), median of {args.repeats} runs")
    emit()
    best = None
    with tempfile.TemporaryDirectory() as tmp:
        for rpm in args.rpm:
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
                timed = []
                s0, d0 = None, None
                for _ in range(args.repeats):
                    s, d = one_run(tmp, rpm, duration, inputs, integrator, option, value, args.timeout)
                    if d is None:
                        s0, d0 = s, None
                        break
                    timed.append(s["cpu_per_sim_s"])
                    s0, d0 = s, d
                if d0 is None:
                    emit(f"| {integrator} | {option} {value:g} | - | {s0.get('steps', '-')} | {s0.get('rhs', '-')} | - | - | - "
                         f"| - | - | FAILED: {s0.get('failure', '')[:140]} |")
                    continue
                s1, d1 = one_run(tmp, rpm, duration, inputs, integrator, option, halved, args.timeout)
                m0 = measures(d0, rpm)
                cpu = statistics.median(timed)
                if d1 is None:
                    change = "-"
                    orders = "-"
                    early = "-"
                    status = f"halved setting FAILED: {s1.get('failure', '')[:100]}"
                    ok = False
                else:
                    m1 = measures(d1, rpm)
                    rms_change = pct(m0["rms"], m1["rms"])
                    order_changes = [pct(a, b) for a, b in zip(m0["orders"], m1["orders"])]
                    sel = d0["time"] <= 0.005
                    early = f"{np.sqrt(np.mean((d0['tensioner.F'][sel] - d1['tensioner.F'][sel]) ** 2)):.3f}"
                    change = f"{rms_change:.2f}"
                    orders = "/".join(f"{c:.1f}" for c in order_changes)
                    ok = rms_change < 1.0
                    status = "ok" if ok else "changes by 1 % or more"
                emit(f"| {integrator} | {option} {value:g} | {cpu:.2f} | {s0['steps']} | {s0['rhs']} | {s0.get('jacobians', 0)} "
                     f"| {m0['rms']:.2f} | {change} | {orders} | {early} | {status} |")
                if abs(rpm - 3000.0) < 1e-9 and ok and (best is None or cpu < best[1]):
                    best = (f"{integrator} ({option} {value:g})", cpu)
            emit()
    if best:
        emit(f"fastest integrator at 3000 rpm whose tensioner-force RMS changes by less than 1 % when its "
             f"step/tolerance is halved: {best[0]}, {best[1]:.2f} CPU s per simulated s (target: at most 10)")
    runs.write_lines(args.out, lines)


if __name__ == "__main__":
    main()
