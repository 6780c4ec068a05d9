// The stage pool's own cost (src/threads.h), for `python -m harness bench-threads`: runs of an
// empty task on N threads, without and with B barriers in each, timed by the wall clock. Prints one
// line per repeat: threads, barriers per run, microseconds per run.
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "threads.h"

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: stage_pool_timing THREADS BARRIERS RUNS REPEATS\n");
    return 2;
  }
  const int threads = std::atoi(argv[1]), barriers = std::atoi(argv[2]), runs = std::atoi(argv[3]);
  const int repeats = std::atoi(argv[4]);
  chaindrive::StagePool pool(threads);
  auto task = [&](int t) {
    for (int b = 0; b < barriers; ++b) pool.barrier(t);
  };
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < runs; ++k) pool.run(task);
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    std::printf("%d %d %.6f\n", threads, barriers, us / runs);
  }
  return 0;
}
