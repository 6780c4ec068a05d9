// Health of a running drive state, shared by the compliant drive (DriveSystem) and the
// rigid-contact drive: a finite state, no joint opened beyond HealthLimits::blowUpDeformation
// times the pitch, no contact deeper than HealthLimits::tunnellingDepth times the roller radius.
// Each check returns false with the failure (its kind and reason) in `why`.
#pragma once

#include <cmath>
#include <cstring>
#include <string>

#include "dynamics/contact_kinematics.h"
#include "failure.h"
#include "assembly/model.h"

namespace chaindrive {

/// What counts as a physically failed state (checked after steps, reported as IntegrationError).
struct HealthLimits {
  double blowUpDeformation = 0.25;  // a joint stretched beyond this fraction of the pitch: blow-up
  double tunnellingDepth = 0.5;     // a contact deeper than this fraction of the roller radius: tunnelling
};

/// True if every x[0..n) is finite: x * 0 is 0 for a finite x and NaN otherwise, summed in
/// vectors (the check of every step and every derivative: no branch per component; AVX2 where the
/// CPU has it).
bool allFinite(const double* x, int n);

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

/// False once a hydraulic chamber's oil content [m3] is no longer positive (it emptied).
inline bool chamberFilled(double content, double t, Failure& why) {
  if (content > 0.0) return true;
  why = {FailureKind::BlowUp, "blow-up at t = " + std::to_string(t) + " s: the tensioner's chamber emptied"};
  return false;
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
  return !deepPenetration(contacts, nContacts, limits.tunnellingDepth * m.chain.depthScale, t, why);
}

}  // namespace chaindrive
