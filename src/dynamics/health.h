// Health of a running drive state, shared by the compliant drive (DriveSystem) and the
// rigid-contact drive: a finite state, no joint opened beyond HealthLimits::blowUpDeformation
// times the pitch, no contact deeper than HealthLimits::tunnellingDepth times the roller radius.
// Each check returns false with the failure (its kind and reason) in `why`.
#pragma once

#include <cmath>
#include <cstring>
#include <string>

#include "dynamics/contact_kinematics.h"
#include "integrators/ode_system.h"
#include "assembly/model.h"

namespace chaindrive {

/// True if every x[0..n) is finite: x * 0 is 0 for a finite x and NaN otherwise, summed in two
/// independent sums of pairs (the check of every step and every derivative: no branch per
/// component; GCC's and Clang's vector extensions keep each pair in one SSE2 register).
inline bool allFinite(const double* x, int n) {
  typedef double Pair __attribute__((vector_size(16)));
  Pair s0 = {0.0, 0.0}, s1 = {0.0, 0.0};
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    Pair a, b;
    std::memcpy(&a, x + i, sizeof a);
    std::memcpy(&b, x + i + 2, sizeof b);
    s0 += a * 0.0;
    s1 += b * 0.0;
  }
  double rest = 0.0;
  for (; i < n; ++i) rest += x[i] * 0.0;
  const Pair s = s0 + s1;
  return s[0] + s[1] + rest == 0.0;
}

/// False if some of x[0..n) is not finite.
inline bool finiteState(const double* x, int n, Failure& why) {
  if (allFinite(x, n)) return true;
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(x[i])) {
      why = {FailureKind::NonFinite, "non-finite state (component " + std::to_string(i) + ")"};
      return false;
    }
  return true;
}

/// The joint and contact checks; opening(j) is the distance [m] by which joint j is opened.
template <class Opening>
bool chainHealthy(const Model& m, const HealthLimits& limits, Opening opening, const ContactPoint* contacts,
                  int nContacts, double t, Failure& why) {
  const double limit = limits.blowUpDeformation * m.chain.pitch;
  for (int j = 0; j < m.chain.links; ++j) {
    const double dist = opening(j);
    if (!(dist <= limit)) {
      why = {FailureKind::BlowUp, "blow-up: joint " + std::to_string(j) + " stretched by " + std::to_string(dist * 1e3) +
                                      " mm (limit " + std::to_string(limit * 1e3) + " mm) at t = " + std::to_string(t) + " s"};
      return false;
    }
  }
  return !deepPenetration(contacts, nContacts, limits.tunnellingDepth * m.chain.rollerRadius, t, why);
}

}  // namespace chaindrive
