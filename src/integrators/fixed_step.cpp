#include "integrators/fixed_step.h"

namespace chaindrive {

__attribute__((target_clones("avx2", "default"))) void addScaled(double* __restrict y, const double* __restrict x,
                                                                 double a, int n) {
  for (int i = 0; i < n; ++i) y[i] += a * x[i];
}

__attribute__((target_clones("avx2", "default"))) void addScaledBy(double* __restrict y, const double* __restrict x,
                                                                   const double* __restrict factor, int n) {
  for (int i = 0; i < n; ++i) y[i] += factor[i] * x[i];
}

__attribute__((target_clones("avx2", "default"))) void dampedKick(double* factor, double a, int n) {
  for (int i = 0; i < n; ++i) factor[i] = a / (1.0 + a * factor[i]);
}

}  // namespace chaindrive
