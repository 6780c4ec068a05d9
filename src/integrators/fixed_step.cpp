#include "integrators/fixed_step.h"

namespace chaindrive {

__attribute__((target_clones("avx2", "default"))) void addScaled(double* __restrict y, const double* __restrict x,
                                                                 double a, int n) {
  for (int i = 0; i < n; ++i) y[i] += a * x[i];
}

}  // namespace chaindrive
