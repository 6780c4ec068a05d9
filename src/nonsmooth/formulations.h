// The complementarity problems of the paper in standard LCP form, for a diagonal mass matrix:
// for the active contacts and bilateral constraints, relative velocities (or accelerations)
// u = G F + b with the Delassus matrix G = W^T M^-1 W, bilateral rows u_B = 0 eliminated by
// their Schur complement, and per contact one of
//   NormalOnly     0 <= u_N  _|_  F_N >= 0                              (frictionless; impacts)
//   Friction       planar Coulomb with maximal dissipation in the cone |F_T| <= mu F_N, as the
//                  LCP of NUMERICS.md: z = (F_N, F'_T, xi), F_T = F'_T - mu F_N,
//                  w = (u_N, u_T + xi, 2 mu F_N - F'_T)   (the decomposition of eq. 7 into eq. 8)
//   SlidingFolded  a sliding contact with known direction s: F_T = -mu s F_N folded into the
//                  normal column (the W_G mu_G term of eq. 1); 0 <= u_N _|_ F_N >= 0
//   PolygonFriction  a compliant normal (Contact::compliantNormal): friction only, in the plane
//                  of its two directions, the friction cone (a disc of radius `bound`, the
//                  normal force being known) linearized by a polygon of d facets inscribed in
//                  it, Stewart and Trinkle's LCP with the normal force given:
//                  z = (beta_1..beta_d, lambda), F = sum_j e_j beta_j (e_j at the angles
//                  2 pi j / d, so the radial and circumferential bounds are exact),
//                  w = (e_j . u + lambda, bound - sum_j beta_j): lambda is the sliding speed
//                  along the facet most opposed to u (maximal dissipation), 0 when sticking
// The same assembly serves the impact law (eq. 10-12, b = (1 + e) gdot_A), the acceleration
// level (eq. 5-8, b = W^T M^-1 h + wbar) and the velocity level of time stepping.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "lcp/lemke.h"
#include "nonsmooth/system.h"

namespace chaindrive::ns {

enum class RowKind { NormalOnly, Friction, SlidingFolded, PolygonFriction };

struct ContactRow {
  const Contact* contact = nullptr;
  RowKind kind = RowKind::NormalOnly;
  double mu = 0.0;         // friction coefficient used (Friction, SlidingFolded)
  double slideSign = 0.0;  // SlidingFolded: sign of the sliding velocity
  double bN = 0.0, bT = 0.0;
  double bT2 = 0.0;        // PolygonFriction: the offset along the second direction
  double bound = 0.0;      // PolygonFriction: the friction's bound (force or impulse)
  int facets = 0;          // PolygonFriction: the polygon's number of facets (>= 3)
};

struct ConstraintSolution {
  lcp::Status status = lcp::Status::Solved;
  int size = 0;      // LCP size
  int pivots = 0;
  double error = 0.0;
  std::vector<double> fN, fT;   // per contact row: force (or impulse) along normal and tangent
  std::vector<double> fT2;      // per contact row: along the second friction direction
  std::vector<double> fB;       // per bilateral constraint
  std::vector<char> sticking;   // Friction and PolygonFriction rows: inside the cone
  bool regularized = false;     // solved only after the regularization (see ConstraintSolver)
  lcp::Result last;             // Lemke's result of the last attempt (its pivots and cap)
  bool solved() const { return status == lcp::Status::Solved; }
};

/// The kind of failure of a constraint problem that Lemke did not solve.
inline FailureKind lcpFailureKind(lcp::Status status) {
  switch (status) {
    case lcp::Status::RayTermination: return FailureKind::LcpRayTermination;
    case lcp::Status::IterationLimit: return FailureKind::LcpIterationLimit;
    case lcp::Status::NumericalFailure: return FailureKind::LcpNumericalFailure;
    case lcp::Status::Solved: break;
  }
  return FailureKind::Other;
}

/// The status of a solution for failure messages: the Lemke status name, and for an iteration
/// limit the pivots and the cap of the last attempt.
inline std::string statusText(const ConstraintSolution& s) {
  std::string text = lcp::statusName(s.status);
  if (s.status == lcp::Status::IterationLimit)
    text += " (" + lcp::iterationLimitMessage(s.last, s.size, "raise it with maxPivots in the method's settings") + ")";
  return text;
}

/// Adds one solve to the counters.
inline void countSolve(NsStats& st, const ConstraintSolution& s) {
  ++st.lcpSolves;
  st.lcpSizeSum += s.size;
  st.lcpSizeMax = std::max<long long>(st.lcpSizeMax, s.size);
  st.pivots += s.pivots;
  if (s.regularized) ++st.regularizedLcps;
}

/// Regularization: if Lemke's method fails on an LCP (ray termination or a numerically singular
/// basis), it is solved once more with delta * max(diag G) added to the diagonal of G (default
/// delta = 1e-8), and if that fails too, with 100 delta: a contact compliance so small that the
/// velocity it admits, delta * max(diag G) * impulse, stays far below any velocity of interest
/// (1e-9 m/s for the chain's impulses per 2.5 us step at delta = 1e-8), but that makes the
/// normal block positive definite where contacts outnumber
/// the degrees of freedom they act on (an inner link seated on a sprocket with both rollers has
/// four contact directions on its three coordinates), which can leave Lemke's method with a
/// numerically singular basis.
class ConstraintSolver {
 public:
  void setRegularization(double delta) { regularization_ = delta; }
  double regularization() const { return regularization_; }
  /// Solves for the forces; bB are the bilateral offsets (u_B = G_B F + bB must vanish).
  const ConstraintSolution& solve(const std::vector<ContactRow>& rows, const std::vector<const Bilateral*>& bilateral,
                                  const std::vector<double>& bB, const double* minv, int maxPivots = -1);
  const ConstraintSolution& solution() const { return sol_; }
  /// Writes the next `count` LCPs solved into `directory` (Siconos dense format, lcp_<k>.dat),
  /// and every LCP that is not solved (lcp_failed_<k>.dat).
  void record(const std::string& directory, int count) {
    recordDir_ = directory;
    recordLeft_ = count;
  }

 private:
  void clearSolution(int nc, int nb);
  void assembleDelassus(const std::vector<ContactRow>& rows, const double* minv);
  bool condenseBilateral(const std::vector<ContactRow>& rows, const std::vector<const Bilateral*>& bilateral,
                         const std::vector<double>& bB, const double* minv);
  void buildForceMap(const std::vector<ContactRow>& rows);
  void solveContactLcp(const std::vector<ContactRow>& rows, int nb, int maxPivots);
  void assembleLcp(const std::vector<ContactRow>& rows);
  void polygonRows(const ContactRow& r, int c, int o);
  void contactForces(const std::vector<ContactRow>& rows);
  void bilateralForces(int nc, int nb);
  void writeLcp(const std::string& path, int nc, int nb) const;

  lcp::LemkeSolver lemke_;
  Eigen::LDLT<Eigen::MatrixXd> bilateralLdlt_;  // G_BB of the last problem with bilateral constraints
  ConstraintSolution sol_;
  Eigen::MatrixXd D_, DUB_, DBB_, X_, T_, M_, DT_;
  Eigen::VectorXd b_, bBv_, y_, q_, z_, F_;
  std::string recordDir_;
  int recordLeft_ = 0, recorded_ = 0, failed_ = 0;
  double regularization_ = 1e-8;
};

/// Moves q onto the constraints: penetrating contacts (gap < 0) back to the surface,
/// 0 <= g + G P _|_ P >= 0, and bilateral constraints to g_B = 0, by q += M^-1 W P (a position
/// impulse; a few passes for the nonlinear constraints). Returns the largest remaining
/// violation [m].
double projectPositions(NonsmoothSystem& sys, double t, double* q, const double* v, ConstraintSolver& solver,
                        int passes = 3);

/// v += M^-1 col * s
inline void addImpulse(const SparseColumn& col, double s, const double* minv, double* v) {
  for (int k = 0; k < col.n; ++k) v[col.idx[k]] += minv[col.idx[k]] * col.val[k] * s;
}

}  // namespace chaindrive::ns
