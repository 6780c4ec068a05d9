"""Benchmark of a sweep on Dask: the same cases (default 12 speeds, span fidelity) in a plain
loop in this process, on a LocalCluster of 1 worker and of 2 workers (single-threaded worker
processes), nothing cached. Prints the machine, the wall times, the speed-up of 2 workers over 1
and Dask's overhead per case (1 worker against the plain loop).

    python -m harness bench-sweep [--cases 12] [--fidelity span] [--cycles 8] [--out results/benchmark_sweep.md]

Run nothing else on the machine meanwhile (wall times of shared cores are noisy)."""
import dataclasses
import pathlib
import tempfile
import time

import numpy as np

from .. import job, paths, runs
from ..sweep.cases import Case, run_case
from ..sweep.execute import dask_client, run_cases


def add_arguments(ap):
    ap.add_argument("--cases", type=int, default=12, help="number of speeds, evenly from 1000 to 6000 rpm")
    ap.add_argument("--fidelity", choices=("link", "span"), default="span")
    ap.add_argument("--cycles", type=int, default=8, help="engine cycles counted per speed")
    ap.add_argument("--out", default=str(paths.RESULTS / "benchmark_sweep.md"))


def check(ap, args):
    if args.cases < 2:
        ap.error(f"--cases {args.cases}: at least 2")
    if args.cycles < 2:
        ap.error(f"--cycles {args.cycles}: at least 2")
    return args


def timed(f):
    t0 = time.perf_counter()
    out = f()
    return out, time.perf_counter() - t0


def run(args):
    base = Case(rpm=0.0, fidelity=args.fidelity, method=job.run_config(fidelity=args.fidelity).method, cycles=args.cycles)
    cases = [dataclasses.replace(base, rpm=float(r)) for r in np.linspace(1000.0, 6000.0, args.cases)]
    loop, t_loop = timed(lambda: [run_case(c) for c in cases])
    starts, walls = {}, {}
    for workers in (1, 2):
        with tempfile.TemporaryDirectory() as cache:  # nothing cached: every case computed
            t0 = time.perf_counter()
            with dask_client(workers) as client:
                starts[workers] = time.perf_counter() - t0
                (results, _), walls[workers] = timed(lambda: run_cases(cases, cache, client=client, progress=False))
        if [r["rows"] for r in results] != [r["rows"] for r in loop]:
            raise RuntimeError(f"{workers} worker(s): results differ from the plain loop's")
    n = len(cases)
    lines = [f"# Sweep benchmark: {n} cases ({args.fidelity} fidelity, {args.cycles} cycles each) on Dask",
             "", f"Machine: {runs.machine()}", "",
             "| run | cluster start | wall time of the cases | per case |", "|---|---|---|---|",
             f"| plain loop, this process | | {t_loop:.1f} s | {t_loop / n:.2f} s |"]
    lines += [f"| LocalCluster, {w} worker{'s' if w > 1 else ''} | {starts[w]:.1f} s | {walls[w]:.1f} s | "
              f"{walls[w] / n:.2f} s |" for w in (1, 2)]
    lines += ["", f"- speed-up of 2 workers over 1: {walls[1] / walls[2]:.2f} (cluster start excluded), "
              f"{(starts[1] + walls[1]) / (starts[2] + walls[2]):.2f} (included)",
              f"- Dask's overhead per case (1 worker against the plain loop, cluster start excluded): "
              f"{(walls[1] - t_loop) / n:.3f} s",
              "- every case's statistics identical in the three runs (bit for bit)"]
    text = "\n".join(lines) + "\n"
    print(text)
    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text)
    print(f"written: {out}")
