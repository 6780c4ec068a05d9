#include <chrono>
#include <cstdio>
#include <vector>
#include <algorithm>
#include "linear/cyclic_block_tridiagonal.h"
#include "linear/cyclic_tridiagonal.h"
using namespace chaindrive;
int main() {
  const int n = 120;
  CyclicBlockTridiagonal3 w(n);
  std::vector<double> b(3 * n, 1.0);
  std::vector<double> times, times2;
  for (int rep = 0; rep < 2000; ++rep) {
    std::fill(b.begin(), b.end(), 1.0 + rep * 1e-3);
    auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) {
      double a = 0.01 * i + rep * 1e-6;
      w.diagonal(i) = Eigen::Matrix3d::Identity() * 4.0;
      w.diagonal(i)(0, 2) = w.diagonal(i)(2, 0) = 0.1 * a;
      w.upper(i) = -Eigen::Matrix3d::Identity();
      w.upper(i)(0, 2) = 0.2 * a; w.upper(i)(1, 2) = -0.1;
      w.lower(i) = w.upper((i + n - 1) % n).transpose();
    }
    bool ok = w.factor();
    w.solve(b.data());
    auto t1 = std::chrono::steady_clock::now();
    if (!ok) return 1;
    times.push_back(std::chrono::duration<double>(t1 - t0).count());
    CyclicTridiagonal r(n, 3.0, -1.0);
    std::fill(b.begin(), b.end(), 1.0 + rep * 1e-3);
    auto t2 = std::chrono::steady_clock::now();
    r.solve(b.data()); r.solve(b.data() + n); r.solve(b.data() + 2 * n);
    auto t3 = std::chrono::steady_clock::now();
    times2.push_back(std::chrono::duration<double>(t3 - t2).count());
  }
  std::sort(times.begin(), times.end()); std::sort(times2.begin(), times2.end());
  std::printf("3x3 block ring n=%d fill+factor+solve: median %.2f us, min %.2f us; 3 scalar ring solves: median %.3f us (b0=%g)\n", n,
              1e6 * times[times.size() / 2], 1e6 * times[0], 1e6 * times2[times2.size() / 2], b[0]);
}
