#include "linear/array_loops.h"

namespace chaindrive {

__attribute__((target_clones("avx2", "default"))) void scaleInto(double* __restrict out, const double* __restrict x,
                                                                 double factor, int n) {
  for (int i = 0; i < n; ++i) out[i] = x[i] * factor;
}

__attribute__((target_clones("avx2", "default"))) void addConstant(double* __restrict y, double c, int n) {
  for (int i = 0; i < n; ++i) y[i] += c;
}

}  // namespace chaindrive
