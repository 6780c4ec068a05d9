// Rigid-contact mechanics (the paper's section 2): the interface a mechanical system offers the
// complementarity methods, and the constraint data they work on.
//
// Generalized coordinates q and velocities v have the same size n; the mass matrix is diagonal
// (true for the chain in absolute coordinates and for the classic test problems). A degree of
// freedom with inverse mass 0 is prescribed: its velocity and acceleration come from
// prescribed(t) (the driven crankshaft sprocket), so contacts on it see its motion through the
// W columns and no impulse changes it.
#pragma once

#include <string>
#include <vector>

#include "failure.h"

namespace chaindrive::ns {

/// A column of a constraint Jacobian in generalized-velocity space (few non-zeros).
struct SparseColumn {
  static constexpr int kMax = 8;
  int n = 0;
  int idx[kMax] = {};
  double val[kMax] = {};
  void add(int i, double v) {
    for (int k = 0; k < n; ++k)
      if (idx[k] == i) {
        val[k] += v;
        return;
      }
    idx[n] = i;
    val[n] = v;
    ++n;
  }
  double dot(const double* x) const {
    double s = 0.0;
    for (int k = 0; k < n; ++k) s += val[k] * x[idx[k]];
    return s;
  }
};

/// a^T diag(w) b for two sparse columns.
inline double weightedDot(const SparseColumn& a, const SparseColumn& b, const double* w) {
  double s = 0.0;
  for (int i = 0; i < a.n; ++i)
    for (int j = 0; j < b.n; ++j)
      if (a.idx[i] == b.idx[j]) s += a.val[i] * b.val[j] * w[a.idx[i]];
  return s;
}

/// One unilateral contact: g_N >= 0 with Coulomb friction. Relative velocities are
/// gdot_N = wN . v, gdot_T = wT . v (prescribed DOFs included in v); accelerations
/// gddot = w . qddot + wbar.
///
/// A contact with a compliant normal (frictionBound >= 0) is not a normal constraint: its normal
/// force is one of the system's smooth forces (a CVT pin pressed between elastic sheaves), and
/// only its friction is, in the plane of the two directions wT and wT2 (sheave plane: radial and
/// circumferential), bounded by |F_T| <= frictionBound [N] (Coulomb's mu times that normal force).
struct Contact {
  long long id = 0;        // stable identity over time
  double gap = 0.0;        // g_N [m]
  SparseColumn wN, wT;     // columns of W_N and W_T
  SparseColumn wT2;        // compliant normal: the second friction direction (else empty)
  double frictionBound = -1.0;  // >= 0: a compliant normal, the friction's bound [N]
  bool compliantNormal() const { return frictionBound >= 0.0; }
  double wbarN = 0.0, wbarT = 0.0;  // acceleration terms (only when requested)
  double mu = 0.0;         // kinetic (sliding) friction coefficient
  double muStatic = 0.0;   // static friction coefficient (>= mu)
  double restitution = 0.0;
  int tag = -1;            // the system's own index (e.g. into its contact list)
};

/// A bilateral constraint g_B(q) = 0 (ideal joints).
struct Bilateral {
  SparseColumn w;
  double g = 0.0;
  double wbar = 0.0;
};

struct ConstraintSet {
  std::vector<Contact> contacts;
  std::vector<Bilateral> bilateral;
  void clear() {
    contacts.clear();
    bilateral.clear();
  }
};

class NonsmoothSystem {
 public:
  virtual ~NonsmoothSystem() = default;
  virtual int size() const = 0;
  /// Diagonal of M^-1; 0 marks a prescribed degree of freedom.
  virtual const std::vector<double>& inverseMass() const = 0;
  /// Velocities and accelerations of the prescribed degrees of freedom at t (others untouched).
  virtual void prescribed(double /*t*/, double* /*v*/, double* /*a*/) const {}
  /// Smooth generalized forces (everything but the rigid constraints).
  virtual void forces(double t, const double* q, const double* v, double* h) = 0;
  /// Contacts with gap below `margin` and all bilateral constraints at (t, q, v); with
  /// acceleration terms (wbar) when `accelerations` is set.
  virtual void constraints(double t, const double* q, const double* v, double margin, bool accelerations,
                           ConstraintSet& out) = 0;
  /// Power of the smooth dissipative forces (damping) at (t, q, v), for the energy balance.
  virtual double dissipatedPower(double /*t*/, const double* /*q*/, const double* /*v*/) { return 0.0; }
  /// Power put in by prescribed motion and loads at (t, q, v) through the smooth forces.
  virtual double inputPower(double /*t*/, const double* /*q*/, const double* /*v*/) { return 0.0; }
  /// Advances the system's first-order smooth states beside q and v (a hydraulic tensioner's
  /// chamber) over a step h, with their rates at the last evaluation of the smooth forces (the
  /// step's midpoint: time stepping calls it after its energy account).
  virtual void advanceSmoothStates(double /*h*/) {}
  /// Physical sanity of a state; false with the reason on blow-up.
  virtual bool healthy(double /*t*/, const double* /*q*/, const double* /*v*/, Failure& /*why*/) { return true; }
};

/// Counters of a complementarity method.
struct NsStats {
  long long steps = 0;          // time steps (time-stepping) or integrator steps (event-driven)
  long long events = 0;         // event-driven: root events handled
  long long impacts = 0;        // impact LCPs with at least one closing contact (time stepping:
                                // steps in which a contact closes approaching)
  long long lcpSolves = 0;
  long long lcpSizeSum = 0;
  long long lcpSizeMax = 0;
  long long pivots = 0;
  long long regularizedLcps = 0;  // LCPs solved only after the regularization (formulations.h)
  long long rhsEvaluations = 0;
};

}  // namespace chaindrive::ns
