"""Solves LCP files (Siconos dense format) with Siconos numerics' lexicographic Lemke, for the
comparison in harness/bench/benchmark_lcp.py. Run it with the system Python that has the Debian
package python3-siconos:  /usr/bin/python3 harness/bench/siconos_lcp.py REPEAT FILE...
Prints one line per file: file, info, pivots, error, median CPU time per solve [s]."""
import sys
import time

import numpy as np
import siconos.numerics as sn


def read(path):
    tokens = open(path).read().split()
    n = int(tokens[0])
    # n, storage (0), rows, cols, rows, cols, then n*n column-major, then q
    vals = [float(t) for t in tokens[6:6 + n * n + n]]
    M = np.array(vals[:n * n]).reshape((n, n), order="F")
    q = np.array(vals[n * n:n * n + n])
    return M, q


def main():
    repeat = int(sys.argv[1])
    for path in sys.argv[2:]:
        M, q = read(path)
        n = len(q)
        lcp = sn.LCP(M, q)
        times = []
        info, pivots, z = None, None, None
        for _ in range(repeat):
            opts = sn.SolverOptions(sn.SICONOS_LCP_LEMKE)
            opts.iparam[0] = max(10000, 50 * n)  # iteration cap
            z = np.zeros(n)
            w = np.zeros(n)
            t0 = time.process_time()
            info = sn.lcp_lexicolemke(lcp, z, w, opts)
            times.append(time.process_time() - t0)
            pivots = opts.iparam[sn.SICONOS_IPARAM_ITER_DONE]
        r = z - np.maximum(0.0, z - (M @ z + q))
        nq = np.linalg.norm(q)
        err = np.linalg.norm(r) / (nq if nq > np.finfo(float).eps else 1.0)
        print(f"{path}\t{info}\t{pivots}\t{err:.3e}\t{sorted(times)[len(times) // 2]:.9g}", flush=True)


if __name__ == "__main__":
    main()
