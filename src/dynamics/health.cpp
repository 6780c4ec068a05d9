#include "dynamics/health.h"

#include "simd.h"

namespace chaindrive {

namespace {

CHAINDRIVE_ALWAYS_INLINE bool allFiniteBody(const double* x, int n) {
  typedef double Quad __attribute__((vector_size(32)));
  Quad s0 = {}, s1 = {};
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    Quad a, b;
    std::memcpy(&a, x + i, sizeof a);
    std::memcpy(&b, x + i + 4, sizeof b);
    s0 += a * 0.0;
    s1 += b * 0.0;
  }
  double rest = 0.0;
  for (; i < n; ++i) rest += x[i] * 0.0;
  const Quad s = s0 + s1;
  return s[0] + s[1] + s[2] + s[3] + rest == 0.0;
}

}  // namespace

CHAINDRIVE_DISPATCH_BY_CPU(bool, allFinite, (const double* x, int n), (x, n))

}  // namespace chaindrive
