#include "linear/array_loops.h"

#include "simd.h"

namespace chaindrive {

namespace {

CHAINDRIVE_ALWAYS_INLINE void scaleIntoBody(double* __restrict out, const double* __restrict x, double factor,
                                            int n) {
  for (int i = 0; i < n; ++i) out[i] = x[i] * factor;
}

CHAINDRIVE_ALWAYS_INLINE void addConstantBody(double* __restrict y, double c, int n) {
  for (int i = 0; i < n; ++i) y[i] += c;
}

}  // namespace

CHAINDRIVE_DISPATCH_BY_CPU(void, scaleInto, (double* __restrict out, const double* __restrict x, double factor, int n),
                           (out, x, factor, n))
CHAINDRIVE_DISPATCH_BY_CPU(void, addConstant, (double* __restrict y, double c, int n), (y, c, n))

}  // namespace chaindrive
