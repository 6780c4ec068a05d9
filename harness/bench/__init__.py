"""Benchmarks: the integrators of the solver alone (benchmark), the LCP solver against Siconos
numerics (benchmark_lcp, with the script siconos_lcp run by the system Python)."""
