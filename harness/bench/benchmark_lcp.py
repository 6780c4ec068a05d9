"""Our Lemke solver against Siconos numerics' lexicographic Lemke on the same problems: the LCP
collection of tests/data/lcp and LCPs recorded from the chain drive (time stepping at 3000 rpm:
normal contacts with friction). Prints, per problem, status, pivots, error and the median CPU
time per solve of each, and the time ratio, with the machine. Needs the Debian package
python3-siconos for /usr/bin/python3.

    python -m harness bench-lcp [--repeat 30] [--chain 8] [--out results/benchmark_lcp.md]

Timing: ours inside chaindrive-lcp (solver sized once, the solve alone); Siconos inside Python
around the call of lcp_lexicolemke (includes the small Python-to-C call overhead, a few
microseconds, and Siconos' own set-up per call).
"""
import datetime
import glob
import os
import pathlib
import re
import subprocess
import tempfile

from .. import paths, runs

SICONOS_SCRIPT = pathlib.Path(__file__).resolve().with_name("siconos_lcp.py")  # run by the system Python


def ours(path, repeat):
    p = subprocess.run([paths.executable("chaindrive-lcp"), str(path), "--repeat", str(repeat)], capture_output=True,
                       text=True)
    out = p.stdout
    status = re.search(r"status: (\S+)", out).group(1)
    pivots = int(re.search(r"pivots: (\d+)", out).group(1))
    error = float(re.search(r"error: (\S+)", out).group(1))
    t = float(re.search(r"time per solve: (\S+)", out).group(1))
    return status, pivots, error, t


def siconos(files, repeat, python="/usr/bin/python3"):
    p = subprocess.run([python, str(SICONOS_SCRIPT), str(repeat)] + [str(f) for f in files],
                       capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("Siconos run failed (is python3-siconos installed?): " + p.stderr[-500:])
    res = {}
    for line in p.stdout.splitlines():
        f, info, piv, err, t = line.split("\t")
        res[f] = (int(info), int(piv), float(err), float(t))
    return res


def size_of(path):
    with open(path) as f:
        return int(f.read().split()[0])


def add_arguments(ap):
    ap.add_argument("--repeat", type=int, default=30)
    ap.add_argument("--chain", type=int, default=8, help="LCPs recorded from the chain drive")
    ap.add_argument("--out", default=str(paths.RESULTS / "benchmark_lcp.md"))


def run(args):
    lines = []

    def emit(s=""):
        print(s, flush=True)
        lines.append(s)

    with tempfile.TemporaryDirectory() as tmp:
        files = sorted(glob.glob(str(paths.ROOT / "tests" / "data" / "lcp" / "lcp_*.dat")))
        if args.chain > 0:
            # record LCPs of time stepping on the default drive (3000 rpm, 2 us steps), every 25th
            rec = pathlib.Path(tmp) / "chain"
            rec.mkdir()
            subprocess.run([paths.executable("chaindrive-run"), "--rpm", "3000", "--duration", repr(25 * args.chain * 2e-6),
                            "--contact-method", "time-stepping", "--step", "2e-6", "--load", "camshaftIntake=3",
                            "--load", "camshaftExhaust=3", "--record-lcps", f"{rec}:{25 * args.chain}", "--quiet"],
                           check=True, capture_output=True)
            chain = sorted(rec.glob("lcp_[0-9]*.dat"), key=lambda p: int(p.stem.split("_")[1]))[::25][:args.chain]
            for k, c in enumerate(chain):
                dst = pathlib.Path(tmp) / f"chain_ts_{k}.dat"
                dst.write_text(c.read_text())
                files.append(str(dst))
            # LCPs that our solver failed on as posed (solved after regularization), if any
            for k, c in enumerate(sorted(rec.glob("lcp_failed_*.dat"))[:args.chain]):
                dst = pathlib.Path(tmp) / f"chain_ts_hard_{k}.dat"
                dst.write_text(c.read_text())
                files.append(str(dst))
        sic = siconos(files, args.repeat)
        emit(f"# LCP solvers: ours against Siconos numerics ({datetime.date.today().isoformat()})")
        emit()
        emit(f"machine: {runs.machine()}")
        emit(f"command: python -m harness bench-lcp --repeat {args.repeat} --chain {args.chain}")
        emit("Siconos numerics 4.4.0 (Debian python3-siconos), lcp_lexicolemke; ours: src/lcp/lemke.cpp; "
             f"CPU time per solve, median of {args.repeat}")
        emit()
        emit("| problem | n | ours: status | pivots | error | time [us] | Siconos: info | pivots | error | time [us] | "
             "time ratio Siconos/ours |")
        emit("|---|---|---|---|---|---|---|---|---|---|---|")
        ratios = []
        for f in files:
            st, piv, err, t = ours(f, args.repeat)
            si, sp, se, stime = sic[f]
            ratio = stime / t if t > 0 else float("nan")
            if size_of(f) >= 20:
                ratios.append(ratio)
            name = os.path.basename(f).replace(".dat", "")
            emit(f"| {name} | {size_of(f)} | {st} | {piv} | {err:.1e} | {t * 1e6:.1f} | {si} | {sp} | {se:.1e} | "
                 f"{stime * 1e6:.1f} | {ratio:.2f} |")
        emit()
        if ratios:
            ratios.sort()
            emit(f"median time ratio Siconos/ours over the problems with n >= 20: {ratios[len(ratios) // 2]:.2f}")
    runs.write_lines(args.out, lines)
