"""Integrator benchmark of the solver alone (no FMU): the default drive at several engine speeds
with every integrator, each at a setting and at the halved setting, for both fidelities: the link
model over two engine cycles, the span model (rotors and spans, more than a hundred times
cheaper) over about SPAN_TIME of engine time, so that its CPU time is long enough to measure.

Prints, per speed, fidelity and integrator: CPU seconds per simulated second (median of repeated
runs, one run at a time, without writing outputs: see timed_runs), steps, right-hand-side
evaluations, and how much the tensioner force changes when the step or tolerance is halved; then
the fastest link-model integrator whose tensioner force changes by less than 1 % at 3000 rpm;
then the fidelity ladder's cost, the span model's CPU s per simulated s next to the link model's
at every speed with their ratio; then the wall time per fmi2DoStep of ChainDrive.fmu with the
span fidelity at 0.1 ms and 1 ms communication steps (median, p99, max over --fmu-time of engine
time, constant inputs). The machine (CPU model, cores) heads the report. Writes the same as
Markdown.

    python -m harness bench [--rpm 1000 3000 6000] [--fidelities link span] [--integrators ...]
                            [--repeats 3] [--span-time 2] [--fmu-time 2] [--out results/benchmark.md]

The link model at three speeds takes several minutes; `--fidelities span` alone takes about a
minute, `--integrators fixed-verlet` shortens either.

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
from ..study.realtime import dostep_timings
from ..tables import tables

# per fidelity: integrator, option, setting, halved setting
CONFIGS = {
    "link": [
        ("fixed-verlet", "step", 3e-6, 1.5e-6),
        ("arkode-erk-fixed", "step", 2e-6, 1e-6),
        ("arkode-erk", "rtol", 1e-5, 5e-6),
        ("cvode-bdf-klu", "rtol", 1e-4, 5e-5),
        # (not cvode-bdf-band: the link model's Jacobian has no band, src/run/simulation.h)
    ],
    # the span model has no link masses (rotors on span springs): Verlet runs at 100 us and blows up
    # at 200 us on the default drive, so 20 us keeps a factor 5; BDF's Jacobian is small here (rotor
    # states only)
    "span": [
        ("fixed-verlet", "step", 2e-5, 1e-5),
        ("cvode-bdf-klu", "rtol", 1e-4, 5e-5),
    ],
}
SPAN_TIME = 2.0          # [s] engine time of a span-model run (whole cycles): about 0.1 s CPU or less
FMU_STEPS = (1e-4, 1e-3)  # [s] communication steps of the span fidelity's doStep timings
# the FMU parameters of the span fidelity in the doStep timings: its Verlet setting above
SPAN_FMU_PARAMETERS = {"fidelity": "span", "solver.method": "fixed-verlet", "solver.step": 2e-5}
ORDERS = (2, 4, 6, 8)
# [s] a whole number of steps of every fixed step above (the runner rounds the output interval
# to whole steps), so that a setting and its halved setting write the same output times
OUTPUT_STEP = 6e-5


def one_run(tmp, rpm, duration, inputs, integrator, option, value, timeout, tag="", fidelity="link", write=True):
    """One chaindrive-run: (parsed summary, with "failure" if it failed; its outputs, None when it
    failed or wrote none)."""
    out = pathlib.Path(tmp) / f"{fidelity}_{integrator}_{rpm:g}_{value:g}{tag}.csv" if write else None
    kw = {option: value, "fidelity": fidelity}
    try:
        code, text, s = runs_with_timeout(out, rpm, duration, inputs, integrator, kw, timeout)
    except subprocess.TimeoutExpired:
        return {"failure": f"exceeded {timeout:g} s wall time"}, None
    if code != 0:
        return {"failure": s.get("failure", text.strip()[-200:])} | s, None
    return s, runs.read_csv(out) if write else None


def runs_with_timeout(out, rpm, duration, inputs, integrator, kw, timeout):
    """chaindrive-run with the options kw, writing its outputs to out (None: no CSV)."""
    cmd = [paths.executable("chaindrive-run"), "--rpm", str(rpm), "--duration", repr(duration), "--integrator",
           integrator, "--inputs", str(inputs), "--output-step", repr(OUTPUT_STEP), "--quiet"]
    cmd += ["--out", str(out)] if out is not None else []
    for k, v in kw.items():
        cmd += [f"--{k}", v if isinstance(v, str) else repr(v)]
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
    ap.add_argument("--fidelities", nargs="+", choices=tuple(CONFIGS), default=list(CONFIGS),
                    help="models to benchmark (default: both, side by side)")
    ap.add_argument("--cycles", type=float, default=2.0, help="engine cycles of a link-model run")
    ap.add_argument("--span-time", type=float, default=SPAN_TIME,
                    help=f"engine time of a span-model run [s], whole cycles (default {SPAN_TIME:g})")
    ap.add_argument("--fmu-time", type=float, default=2.0,
                    help="engine time of the span fidelity's doStep timings per communication step [s] (0: none)")
    ap.add_argument("--repeats", type=int, default=3, help="timed repetitions per point (median reported)")
    ap.add_argument("--timeout", type=float, default=120.0, help="wall-time limit per run [s]")
    ap.add_argument("--integrators", nargs="+", help="subset of integrators")
    ap.add_argument("--out", default=str(paths.RESULTS / "benchmark.md"))


def run(args):
    lines = []

    def emit(s=""):
        print(s, flush=True)
        lines.append(s)

    emit(f"# Integrator benchmark ({datetime.date.today().isoformat()})")
    emit()
    emit(f"machine: {runs.machine()}")
    emit(f"command: python -m harness bench {' '.join(args.argv)}")
    models = {"link": f"the link model over {args.cycles:g} engine cycles",
             "span": f"the span model over about {args.span_time:g} s (whole cycles)"}
    emit(f"scene: default drive, {', '.join(models[f] for f in args.fidelities)}, open-loop inputs from the "
         "crankshaft-speed and camshaft-torque tables of harness/tables/data (synthesized); CPU time of the integration "
         f"(start-state solve excluded), median of {args.repeats} runs without writing outputs, one run at a time")
    emit()
    costs = {}  # (fidelity, rpm): [(config, median CPU s per simulated s or None, halving changes < 1 %)]
    with tempfile.TemporaryDirectory() as tmp:
        for rpm in args.rpm:
            for fidelity in args.fidelities:
                costs[fidelity, rpm] = speed_section(tmp, rpm, args, fidelity, emit)
    best = fastest_passing(costs.get(("link", 3000.0), []))
    if best:
        emit(f"fastest link-model integrator at 3000 rpm whose tensioner-force RMS changes by less than 1 % when its "
             f"step/tolerance is halved: {best[0]}, {best[1]:.2f} CPU s per simulated s (target: at most 10)")
        emit()
    if set(CONFIGS) <= set(args.fidelities):
        ladder_section(costs, args.rpm, emit)
    if "span" in args.fidelities and args.fmu_time > 0:
        fmu_timings_section(args.fmu_time, emit)
    runs.write_lines(args.out, lines)


def configs_of(fidelity, args):
    return [c for c in CONFIGS[fidelity] if not args.integrators or c[0] in args.integrators]


def fastest_passing(results):
    """(label, CPU s per simulated s) of the cheapest configuration whose halving changes the
    tensioner-force RMS by less than 1 %, or None."""
    passing = [(cpu, f"{c[0]} ({c[1]} {c[2]:g})") for c, cpu, ok in results if ok and cpu is not None]
    return min(passing)[::-1] if passing else None


def run_duration(rpm, args, fidelity):
    """[s] simulated per run: the link model's cycles, or the whole cycles nearest to --span-time."""
    cycle = 120.0 / rpm
    return args.cycles * cycle if fidelity == "link" else max(args.cycles, round(args.span_time / cycle)) * cycle


def speed_section(tmp, rpm, args, fidelity, emit):
    """One engine speed and fidelity: for the link model the divergence of two runs, then the
    table of the integrators; returns [(config, median CPU s per simulated s or None, halving
    changes the tensioner-force RMS by less than 1 %)]."""
    duration = run_duration(rpm, args, fidelity)
    inputs = tables.write_inputs_csv(pathlib.Path(tmp) / f"in_{fidelity}_{rpm:g}.csv", rpm, duration)
    emit(f"## {rpm:g} rpm, {fidelity} model ({duration * 1e3:.1f} ms simulated)")
    emit()
    if fidelity == "link":
        divergence_line(tmp, rpm, duration, inputs, args, emit)
    emit("| integrator | setting | CPU s per sim. s | steps | RHS evals | Jacobians | tensioner RMS [N] "
         "| RMS change halved [%] | order 2/4/6/8 amplitude change [%] | first-5-ms difference [N] | status |")
    emit("|---|---|---|---|---|---|---|---|---|---|---|")
    results = []
    for config in configs_of(fidelity, args):
        row, cpu, ok = integrator_row(tmp, rpm, duration, inputs, args, config, fidelity)
        emit(row)
        results.append((config, cpu, ok))
    emit()
    return results


def divergence_line(tmp, rpm, duration, inputs, args, emit):
    """The divergence of two link-model runs whose inputs differ by 1e-9 (same integrator and step)."""
    inputs_b = perturbed_inputs(inputs, pathlib.Path(tmp) / f"inb_{rpm:g}.csv", 1e-9)
    sa, da = one_run(tmp, rpm, duration, inputs, "fixed-verlet", "step", 1.5e-6, args.timeout)
    sb, db = one_run(tmp, rpm, duration, inputs_b, "fixed-verlet", "step", 1.5e-6, args.timeout, tag="_perturbed")
    if da is None or db is None:
        return
    diff = np.abs(da["tensioner.F"] - db["tensioner.F"])
    t = da["time"]
    marks = [0.005, 0.01, 0.02, duration]
    parts = [f"{np.sqrt(np.mean(diff[t <= m] ** 2)):.2g} N up to {m * 1e3:.0f} ms" for m in marks]
    emit("divergence (tensioner force, RMS difference of two fixed-verlet 1.5 us runs whose crankshaft speed "
         "differs by 1e-9): " + ", ".join(parts))
    emit()


def ladder_section(costs, speeds, emit):
    """The span model's cost next to the link model's per speed: each configuration's median CPU s
    per simulated s, and the ratio of the link model's cheapest to each span configuration."""
    link_labels = [f"{c[0]} {c[2]:g}" for c, _, _ in costs["link", speeds[0]]]
    span_labels = [f"{c[0]} {c[2]:g}" for c, _, _ in costs["span", speeds[0]]]
    emit("## Fidelity ladder: CPU s per simulated s, span model against link model")
    emit()
    emit("| speed | " + " | ".join(f"link: {x}" for x in link_labels) + " | " + " | ".join(f"span: {x}" for x in
         span_labels) + " | " + " | ".join(f"link (cheapest) / span {x}" for x in span_labels) + " |")
    emit("|---|" + "---|" * (len(link_labels) + 2 * len(span_labels)))
    for rpm in speeds:
        link = [cpu for _, cpu, _ in costs["link", rpm]]
        span = [cpu for _, cpu, _ in costs["span", rpm]]
        cheapest = min((c for c in link if c is not None), default=None)
        ratios = [f"{cheapest / c:.0f}" if cheapest and c else "-" for c in span]
        emit(f"| {rpm:g} rpm | " + " | ".join(cost_cell(c) for c in link + span) + " | " + " | ".join(ratios) + " |")
    emit()


def cost_cell(cpu):
    return "fails" if cpu is None else f"{cpu:.3g}"


def fmu_timings_section(engine_time, emit, rpm=3000.0):
    """Wall time per fmi2DoStep of ChainDrive.fmu with the span fidelity (fmpy FMU2Slave, constant
    inputs: the tables' values at the start) at each of FMU_STEPS over engine_time seconds."""
    ts = {k: v[:1] for k, v in tables.time_series(rpm, 1e-4, 1e-5).items()}  # the first sample only: constant
    emit(f"## ChainDrive.fmu, span fidelity: wall time per fmi2DoStep ({rpm:g} rpm, constant inputs, "
         f"{engine_time:g} s of engine time per step size; fixed-verlet at "
         f"{SPAN_FMU_PARAMETERS['solver.step'] * 1e6:g} us)")
    emit()
    emit("| communication step | steps | median [ms] | p99 [ms] | max [ms] | median / step | deadline misses "
         "| status |")
    emit("|---|---|---|---|---|---|---|---|")
    for h in FMU_STEPS:
        r = dostep_timings(SPAN_FMU_PARAMETERS, h, int(round(engine_time / h)), ts)
        if "wall_median" not in r:
            emit(f"| {h * 1e3:g} ms | 0 | - | - | - | - | - | FAILED: {r['failure']} |")
            continue
        emit(f"| {h * 1e3:g} ms | {r['steps']} | {r['wall_median'] * 1e3:.4f} | {r['wall_p99'] * 1e3:.4f} | "
             f"{r['wall_max'] * 1e3:.4f} | {r['wall_median'] / h:.4f} | {r['misses']} | "
             f"{'FAILED: ' + r['failure'] if r['failure'] else 'ok'} |")
    emit()


def timed_runs(tmp, rpm, duration, inputs, args, integrator, option, value, fidelity):
    """The setting's run with its outputs, then args.repeats runs timed without them: writing the
    CSV (an output every 60 us) costs more than the span model's integration (0.2 against 0.04 CPU s
    per simulated s). Returns (CPU s per simulated s of each timed run, the summary, the outputs
    or None when a run failed)."""
    s0, d0 = one_run(tmp, rpm, duration, inputs, integrator, option, value, args.timeout, fidelity=fidelity)
    if d0 is None:
        return [], s0, None
    timed = []
    for _ in range(args.repeats):
        s, _ = one_run(tmp, rpm, duration, inputs, integrator, option, value, args.timeout, fidelity=fidelity,
                       write=False)
        if "failure" in s:
            return timed, s, None
        timed.append(s["cpu_per_sim_s"])
    return timed, s0, d0


def integrator_row(tmp, rpm, duration, inputs, args, config, fidelity):
    """One integrator at its setting and at the halved setting: (table row, median CPU s per
    simulated s or None if it failed, whether the tensioner-force RMS changes by less than 1 %)."""
    integrator, option, value, halved = config
    timed, s0, d0 = timed_runs(tmp, rpm, duration, inputs, args, integrator, option, value, fidelity)
    if d0 is None:
        return (f"| {integrator} | {option} {value:g} | - | {s0.get('steps', '-')} | {s0.get('rhs', '-')} | - | - | - "
                f"| - | - | FAILED: {s0.get('failure', '')[:140]} |"), None, False
    s1, d1 = one_run(tmp, rpm, duration, inputs, integrator, option, halved, args.timeout, fidelity=fidelity)
    m0 = measures(d0, rpm)
    cpu = statistics.median(timed)
    change, orders, early, status, ok = halved_change(s1, d1, d0, m0, rpm)
    return (f"| {integrator} | {option} {value:g} | {cpu:.3g} | {s0['steps']} | {s0['rhs']} | {s0.get('jacobians', 0)} "
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
