// What both rigid-contact methods (Moreau-Jean time stepping, event-driven integration) keep and
// offer: the state, the contact and bilateral forces of the last step or state, the counters and
// the energy accounts.
#pragma once

#include <vector>

#include "nonsmooth/system.h"

namespace chaindrive::ns {

/// A contact force by the system's contact tag (time stepping: the last step's impulse / h).
struct ContactForce {
  int tag = -1;
  long long id = 0;
  double fN = 0.0, fT = 0.0;
  double fT2 = 0.0;  // a compliant normal's second friction direction (Contact::wT2)
};

class NonsmoothMethod {
 public:
  virtual ~NonsmoothMethod() = default;
  /// Starts at (t, q, v) (penetrations projected out; event-driven: an impact first if contacts
  /// are approaching). The energy accounts are kept (set them before with setEnergy).
  virtual void reset(double t, const double* q, const double* v) = 0;
  /// Integrates to tout; throws IntegrationError with the time and the reason on failure.
  virtual void advance(double tout) = 0;

  double time() const { return t_; }
  const std::vector<double>& q() const { return q_; }
  const std::vector<double>& v() const { return v_; }
  const NsStats& stats() const { return stats_; }
  const std::vector<ContactForce>& contactForces() const { return forces_; }
  /// Bilateral constraint forces, in the system's order.
  const std::vector<double>& bilateralForces() const { return bilateralForces_; }
  /// Work put in by the prescribed motion and the loads, and energy dissipated (damping,
  /// friction, impacts) since the accounts were set.
  double inputWork() const { return inputWork_; }
  double dissipated() const { return dissipated_; }
  void setEnergy(double input, double dissipated) {
    inputWork_ = input;
    dissipated_ = dissipated;
  }

 protected:
  explicit NonsmoothMethod(int n) : q_(n, 0.0), v_(n, 0.0) {}

  double t_ = 0.0;
  std::vector<double> q_, v_;
  std::vector<ContactForce> forces_;
  std::vector<double> bilateralForces_;
  NsStats stats_;
  double inputWork_ = 0.0, dissipated_ = 0.0;
};

}  // namespace chaindrive::ns
