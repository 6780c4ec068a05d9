#include "integrators/fixed_step.h"

#include "simd.h"

namespace chaindrive {

namespace {

CHAINDRIVE_ALWAYS_INLINE void addScaledBody(double* __restrict y, const double* __restrict x, double a, int n) {
  for (int i = 0; i < n; ++i) y[i] += a * x[i];
}

CHAINDRIVE_ALWAYS_INLINE void kickAndDriftBody(double* __restrict x, double* __restrict v,
                                               const double* __restrict a, double hh, double h, int n) {
  for (int i = 0; i < n; ++i) {
    v[i] += hh * a[i];
    x[i] += h * v[i];
  }
}

CHAINDRIVE_ALWAYS_INLINE void kickAndDriftByBody(double* __restrict x, double* __restrict v,
                                                 const double* __restrict a, const double* __restrict factor,
                                                 double h, int n) {
  for (int i = 0; i < n; ++i) {
    v[i] += factor[i] * a[i];
    x[i] += h * v[i];
  }
}

CHAINDRIVE_ALWAYS_INLINE void addScaledByBody(double* __restrict y, const double* __restrict x,
                                              const double* __restrict factor, int n) {
  for (int i = 0; i < n; ++i) y[i] += factor[i] * x[i];
}

}  // namespace

CHAINDRIVE_DISPATCH_BY_CPU(void, addScaled, (double* __restrict y, const double* __restrict x, double a, int n),
                           (y, x, a, n))
CHAINDRIVE_DISPATCH_BY_CPU(void, kickAndDrift,
                           (double* __restrict x, double* __restrict v, const double* __restrict a, double hh,
                            double h, int n),
                           (x, v, a, hh, h, n))
CHAINDRIVE_DISPATCH_BY_CPU(void, kickAndDriftBy,
                           (double* __restrict x, double* __restrict v, const double* __restrict a,
                            const double* __restrict factor, double h, int n),
                           (x, v, a, factor, h, n))
CHAINDRIVE_DISPATCH_BY_CPU(void, addScaledBy,
                           (double* __restrict y, const double* __restrict x, const double* __restrict factor,
                            int n),
                           (y, x, factor, n))

}  // namespace chaindrive
