#include "integrators/fixed_step.h"

namespace chaindrive {

__attribute__((target_clones("avx2", "default"))) void addScaled(double* __restrict y, const double* __restrict x,
                                                                 double a, int n) {
  for (int i = 0; i < n; ++i) y[i] += a * x[i];
}

__attribute__((target_clones("avx2", "default"))) void kickAndDrift(double* __restrict x, double* __restrict v,
                                                                    const double* __restrict a, double hh, double h,
                                                                    int n) {
  for (int i = 0; i < n; ++i) {
    v[i] += hh * a[i];
    x[i] += h * v[i];
  }
}

__attribute__((target_clones("avx2", "default"))) void kickAndDriftBy(double* __restrict x, double* __restrict v,
                                                                      const double* __restrict a,
                                                                      const double* __restrict factor, double h, int n) {
  for (int i = 0; i < n; ++i) {
    v[i] += factor[i] * a[i];
    x[i] += h * v[i];
  }
}

__attribute__((target_clones("avx2", "default"))) void addScaledBy(double* __restrict y, const double* __restrict x,
                                                                   const double* __restrict factor, int n) {
  for (int i = 0; i < n; ++i) y[i] += factor[i] * x[i];
}

}  // namespace chaindrive
