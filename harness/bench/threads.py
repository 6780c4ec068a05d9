"""solver.threads: what several threads give one instance's step on this machine, and what they
cost, by turns in one run.

    python -m harness bench-threads [--threads 1 2] [--rpm 3000] [--duration 0.3] [--repeats 5]
                                    [--out results/benchmark_threads.md]

1. The pool's own cost (src/threads.h, timed by harness/bench/stage_pool_timing.cpp, built with
   c++ into the build folder): a run of an empty task on 2 threads (the start and the end: the
   calling thread's signal and its wait for the others), and each barrier within a run, from runs
   without and with 4 barriers; medians over the repeats.
2. The link model with the real-time method (chaindrive-run, the default drive, constant loads, the
   preload left out) with each number of threads, by turns, --repeats times: wall-clock and CPU
   seconds (every thread's) per simulated second, their medians, the wall clock's ratio to one
   thread's, the barriers each step crosses (its rhs and its damping sweep), and the state at the
   end compared bit for bit with one thread's.
"""
import hashlib
import json
import pathlib
import statistics
import subprocess
import tempfile

from .. import paths, runs
from ..errors import UserError

DRIVER = paths.ROOT / "harness" / "bench" / "stage_pool_timing.cpp"
POOL_SOURCES = [paths.ROOT / "src" / "threads.cpp", DRIVER]
FLAGS = ["-O2", "-std=c++17", "-pthread"]


def add_arguments(ap):
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2], help="numbers of threads (the first: the base)")
    ap.add_argument("--rpm", type=float, default=3000.0, help="engine speed [rpm]")
    ap.add_argument("--duration", type=float, default=0.3, help="simulated seconds per run")
    ap.add_argument("--repeats", type=int, default=5, help="runs of each number of threads, by turns")
    ap.add_argument("--out", default=str(paths.RESULTS / "benchmark_threads.md"))


def check(ap, args):
    if args.repeats < 1:
        ap.error(f"--repeats {args.repeats}: at least 1")
    if min(args.threads) < 1:
        ap.error(f"--threads {args.threads}: at least 1 each")
    return args


def pool_timer():
    """The pool's timing program, built once per source into the build folder."""
    key = hashlib.sha256(b"".join(p.read_bytes() for p in POOL_SOURCES) + " ".join(FLAGS).encode()).hexdigest()[:16]
    path = paths.BUILD / "loop" / f"stage_pool_timing-{key}"
    if not path.exists():
        path.parent.mkdir(parents=True, exist_ok=True)
        command = ["c++", *FLAGS, f"-I{paths.ROOT / 'src'}", *map(str, POOL_SOURCES), "-o", str(path)]
        try:
            built = subprocess.run(command, capture_output=True, text=True)
        except FileNotFoundError:
            raise UserError("no C++ compiler 'c++' on the PATH (./run.sh installs Debian's build-essential)") from None
        if built.returncode != 0:
            raise UserError(f"{DRIVER.name} did not build: {built.stderr.strip()}")
    return path


def pool_costs(repeats):
    """(run [us], barrier [us]) of 2 threads: medians over the repeats."""
    timer = pool_timer()

    def per_run(barriers):
        out = subprocess.run([str(timer), "2", str(barriers), "20000", str(repeats)], capture_output=True,
                             text=True, check=True).stdout
        return statistics.median(float(line.split()[2]) for line in out.splitlines())

    empty, four = per_run(0), per_run(4)
    return empty, (four - empty) / 4.0


def one_run(args, threads, folder):
    """chaindrive-run's summary and final state (bytes) with `threads` threads."""
    state = folder / f"state-{threads}.json"
    summary = folder / f"summary-{threads}.json"
    command = [paths.executable("chaindrive-run"), "--rpm", repr(args.rpm), "--duration", repr(args.duration),
               "--output-step", "1e-3", "--quiet", "--out", str(folder / "out.csv"), "--threads", str(threads),
               "--summary", str(summary), "--save-state", str(state)]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        raise UserError(f"chaindrive-run --threads {threads}: {done.stderr.strip()}")
    return json.loads(summary.read_text()), state.read_bytes()


def run(args):
    command, machine = f"python -m harness bench-threads {' '.join(args.argv)}", runs.machine()
    lines = ["# solver.threads: one instance's step on several threads", "",
             f"Machine: {machine}; command: {command}", ""]
    print("\n".join(lines))
    run_us, barrier_us = pool_costs(args.repeats)
    lines += [f"The pool on 2 threads (src/threads.h; {DRIVER.name}, medians of {args.repeats}): a run's start and "
              f"end {run_us:.3f} us, each barrier within it {barrier_us:.3f} us", ""]
    found = {n: [] for n in args.threads}
    with tempfile.TemporaryDirectory() as folder:
        folder = pathlib.Path(folder)
        base = None
        for _ in range(args.repeats):
            for n in args.threads:
                summary, state = one_run(args, n, folder)
                base = base if base is not None else state
                if state != base:
                    lines.append(f"error: the state after {args.threads[0]} and {n} threads differs")
                    runs.write_lines(args.out, lines)
                    return 1
                found[n].append(summary)
    lines += [f"The link model, {found[args.threads[0]][0]['method']} at {found[args.threads[0]][0]['step'] * 1e6:.4g} "
              f"us, {args.rpm:g} rpm, {args.duration:g} s simulated (chaindrive-run, the default drive, constant "
              f"loads; medians of {args.repeats} runs by turns; the end states bit-identical):", "",
              "| threads | wall clock [s per simulated s] | ratio to the first | CPU, every thread [s per simulated s] "
              "| barriers per step | wall clock per step [us] |", "|---|---|---|---|---|---|"]
    first = statistics.median(s["wallPerSimulatedSecond"] for s in found[args.threads[0]])
    record = dict(machine=machine, command=command, poolRunMicroseconds=run_us, barrierMicroseconds=barrier_us, rows=[])
    for n in args.threads:
        wall = statistics.median(s["wallPerSimulatedSecond"] for s in found[n])
        cpu = statistics.median(s["cpuPerSimulatedSecond"] for s in found[n])
        barriers = statistics.median(s["barriersPerStep"] for s in found[n])
        per_step = wall * found[n][0]["step"] * 1e6
        lines.append(f"| {n} | {wall:.3f} | {wall / first:.2f} | {cpu:.3f} | {barriers:.2f} | {per_step:.2f} |")
        record["rows"].append(dict(threads=n, wallPerSimulatedSecond=wall, ratio=wall / first,
                                   cpuPerSimulatedSecond=cpu, barriersPerStep=barriers, wallPerStepMicroseconds=per_step))
    print("\n".join(lines[-len(args.threads) - 4:]))
    runs.write_lines(args.out, lines)
    runs.write_json(pathlib.Path(args.out).with_suffix(".json"), record)
    return 0
