// Moreau-Jean time stepping at velocity level (one LCP per step, normal contacts with Newton's
// restitution and planar Coulomb friction):
//   q_m = q + h/2 v,   v_free = v + h M^-1 h(t + h/2, q_m, v),
//   M (v+ - v_free) = W P,   q+ = q_m + h/2 v+,
// contacts active when their gap at q_m, extrapolated by half a step, is not positive (up to a
// tolerance):
//   0 <= u_N+ + e u_N-  _|_  P_N >= 0,   |P_T| <= mu P_N (maximal dissipation),
// bilateral constraints W_B^T v+ = -2 g_B(q_m) / h (they close at the end of the step).
// Contacts with a compliant normal (system.h) enter with their friction only, bounded by the
// normal force of the midpoint, |P_T| <= h F_bound, in a polygon of frictionFacets facets: their
// closure is the smooth force's, so they see no impact.
// Accumulating impacts (Zeno) pass naturally; the velocity LCP always has a solution for
// positive definite Delassus matrices (Stewart-Trinkle, Anitescu-Potra); a failed LCP is
// reported as an error with the time and the Lemke status.
#pragma once

#include <string>
#include <vector>

#include "nonsmooth/formulations.h"
#include "nonsmooth/method.h"
#include "nonsmooth/system.h"
#include "integrators/time_grid.h"

namespace chaindrive::ns {

struct MoreauJeanSettings {
  double step = 1e-5;          // [s] the step, exactly: advance() steps on the grid t0 + k step
  bool staticFriction = true;  // use muStatic for contacts that stuck in the previous step
  double gapTolerance = 1e-10; // [m] a contact is active when its predicted gap is below this
                               // (keeps resting contacts active against rounding)
  int maxPivots = -1;
  int frictionFacets = 8;      // facets of the polygon that linearizes a compliant normal's
                               // friction disc (formulations.h, PolygonFriction)
  std::string recordLcpDirectory;  // write the first recordLcpCount LCPs there (Siconos format)
  int recordLcpCount = 0;
};

/// Forces (contactForces, bilateralForces) are the last step's impulses divided by its length.
class MoreauJean : public NonsmoothMethod {
 public:
  MoreauJean(NonsmoothSystem& sys, const MoreauJeanSettings& s);
  void reset(double t, const double* q, const double* v) override;
  /// Steps to the point of the grid t0 + k step (t0: the last reset) that time_grid.h's rule
  /// assigns to tout.
  void advance(double tout) override;
  double stepSize() const { return grid_.unit; }

 private:
  void step(double h);
  void freeMotion(double h, double tm);
  void activeConstraints(double h, double tm);
  ContactRow polygonRow(const Contact& c, double h) const;
  double applyImpulses(double h);
  void accountEnergy(double h, double tm, double contactWork);

  NonsmoothSystem& sys_;
  MoreauJeanSettings settings_;
  const std::vector<double>& minv_;
  int n_;
  std::vector<double> qm_, h_, vfree_, vnew_, presc_, prescAcc_;
  ConstraintSet cs_;
  ConstraintSolver solver_;
  std::vector<ContactRow> rows_;
  std::vector<const Bilateral*> bil_;
  std::vector<double> bB_;
  std::vector<long long> stuck_;      // ids of contacts that stuck in the last step (sorted)
  std::vector<long long> active_;     // ids of the contacts active in the last step (sorted)
  TimeGrid grid_;                     // t0 (the last reset) + k step
  long long k_ = 0;                   // grid index of the state
};

}  // namespace chaindrive::ns
