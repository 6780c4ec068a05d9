// Moreau-Jean time stepping at velocity level (one LCP per step, normal contacts with Newton's
// restitution and planar Coulomb friction):
//   q_m = q + h/2 v,   v_free = v + h M^-1 h(t + h/2, q_m, v),
//   M (v+ - v_free) = W P,   q+ = q_m + h/2 v+,
// contacts active when their gap at q_m, extrapolated by half a step, is not positive (up to a
// tolerance):
//   0 <= u_N+ + e u_N-  _|_  P_N >= 0,   |P_T| <= mu P_N (maximal dissipation),
// bilateral constraints W_B^T v+ = -2 g_B(q_m) / h (they close at the end of the step).
// Accumulating impacts (Zeno) pass naturally; the velocity LCP always has a solution for
// positive definite Delassus matrices (Stewart-Trinkle, Anitescu-Potra); a failed LCP is
// reported as an error with the time and the Lemke status.
#pragma once

#include <string>
#include <vector>

#include "nonsmooth/formulations.h"
#include "nonsmooth/system.h"

namespace chaindrive::ns {

struct MoreauJeanSettings {
  double step = 1e-5;          // [s] longest step; each advance() interval is divided equally
  bool staticFriction = true;  // use muStatic for contacts that stuck in the previous step
  double gapTolerance = 1e-10; // [m] a contact is active when its predicted gap is below this
                               // (keeps resting contacts active against rounding)
  int maxPivots = -1;
  std::string recordLcpDirectory;  // write the first recordLcpCount LCPs there (Siconos format)
  int recordLcpCount = 0;
};

/// Last step's contact forces (impulse / h) by the system's contact tag.
struct ContactForce {
  int tag = -1;
  long long id = 0;
  double fN = 0.0, fT = 0.0;
};

class MoreauJean {
 public:
  MoreauJean(NonsmoothSystem& sys, const MoreauJeanSettings& s);
  void reset(double t, const double* q, const double* v);
  /// Steps to tout; throws IntegrationError with the time and the reason on failure.
  void advance(double tout);

  double time() const { return t_; }
  const std::vector<double>& q() const { return q_; }
  const std::vector<double>& v() const { return v_; }
  const NsStats& stats() const { return stats_; }
  const std::vector<ContactForce>& contactForces() const { return forces_; }
  /// Last step's bilateral constraint forces (impulse / h), in the system's order.
  const std::vector<double>& bilateralForces() const { return bilateralForces_; }
  double inputWork() const { return inputWork_; }
  double dissipated() const { return dissipated_; }
  void setEnergy(double input, double dissipated) { inputWork_ = input; dissipated_ = dissipated; }

 private:
  void step(double h);

  NonsmoothSystem& sys_;
  MoreauJeanSettings settings_;
  const std::vector<double>& minv_;
  int n_;
  double t_ = 0.0;
  std::vector<double> q_, v_, qm_, h_, vfree_, vnew_, presc_, prescAcc_;
  ConstraintSet cs_;
  ConstraintSolver solver_;
  std::vector<ContactRow> rows_;
  std::vector<const Bilateral*> bil_;
  std::vector<double> bB_;
  std::vector<long long> stuck_;      // ids of contacts that stuck in the last step (sorted)
  std::vector<ContactForce> forces_;
  std::vector<double> bilateralForces_;
  NsStats stats_;
  double inputWork_ = 0.0, dissipated_ = 0.0;
};

}  // namespace chaindrive::ns
