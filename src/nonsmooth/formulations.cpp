#include "nonsmooth/formulations.h"
#include "math/elementary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace chaindrive::ns {

namespace {

// The two directions of a row in the Delassus block and their offsets: normal and tangent, or a
// compliant normal's two friction directions.
const SparseColumn& column(const ContactRow& r, int s) {
  if (r.kind == RowKind::PolygonFriction) return s == 0 ? r.contact->wT : r.contact->wT2;
  return s == 0 ? r.contact->wN : r.contact->wT;
}
double offset(const ContactRow& r, int s) {
  if (r.kind == RowKind::PolygonFriction) return s == 0 ? r.bT : r.bT2;
  return s == 0 ? r.bN : r.bT;
}
int variables(const ContactRow& r) {
  if (r.kind == RowKind::Friction) return 3;
  return r.kind == RowKind::PolygonFriction ? r.facets + 1 : 1;
}
// the polygon's facet direction j of d, in the row's two directions
double facetCos(int j, int d) { return math::cos(2.0 * 3.14159265358979323846 * j / d); }
double facetSin(int j, int d) { return math::sin(2.0 * 3.14159265358979323846 * j / d); }

}  // namespace

// The contact forces F_U (normal and tangential per contact row) and the bilateral forces F_B
// of one constraint problem: the Delassus operator G = W' M^-1 W, the bilateral block condensed
// out, the LCP in the variables z with F_U = T z, solved by Lemke (regularized on failure), then
// F_B from the condensed equations.
const ConstraintSolution& ConstraintSolver::solve(const std::vector<ContactRow>& rows,
                                                  const std::vector<const Bilateral*>& bilateral,
                                                  const std::vector<double>& bB, const double* minv, int maxPivots) {
  const int nc = static_cast<int>(rows.size());
  const int nb = static_cast<int>(bilateral.size());
  clearSolution(nc, nb);
  assembleDelassus(rows, minv);
  if (nb > 0 && !condenseBilateral(rows, bilateral, bB, minv)) {
    sol_.status = lcp::Status::NumericalFailure;
    return sol_;
  }
  if (nc > 0) {
    buildForceMap(rows);
    solveContactLcp(rows, nb, maxPivots);
    if (sol_.status != lcp::Status::Solved) return sol_;
    contactForces(rows);
  } else {
    F_.resize(0);
  }
  if (nb > 0) bilateralForces(nc, nb);
  return sol_;
}

void ConstraintSolver::clearSolution(int nc, int nb) {
  sol_.fN.assign(nc, 0.0);
  sol_.fT.assign(nc, 0.0);
  sol_.fT2.assign(nc, 0.0);
  sol_.fB.assign(nb, 0.0);
  sol_.sticking.assign(nc, 0);
  sol_.status = lcp::Status::Solved;
  sol_.size = sol_.pivots = 0;
  sol_.error = 0.0;
  sol_.regularized = false;
}

// The unilateral block D = G_UU (normal and tangential direction of each row) and its offsets b.
void ConstraintSolver::assembleDelassus(const std::vector<ContactRow>& rows, const double* minv) {
  const int nu = 2 * static_cast<int>(rows.size());
  D_.resize(nu, nu);
  b_.resize(nu);
  for (int a = 0; a < nu; ++a) {
    const SparseColumn& ca = column(rows[a / 2], a % 2);
    b_[a] = offset(rows[a / 2], a % 2);
    for (int c = a; c < nu; ++c) D_(a, c) = D_(c, a) = weightedDot(ca, column(rows[c / 2], c % 2), minv);
  }
}

// The bilateral forces eliminated: D -= G_UB G_BB^-1 G_BU, b -= G_UB G_BB^-1 bB (the
// factorization kept for bilateralForces). False if G_BB cannot be factorized.
bool ConstraintSolver::condenseBilateral(const std::vector<ContactRow>& rows,
                                         const std::vector<const Bilateral*>& bilateral,
                                         const std::vector<double>& bB, const double* minv) {
  const int nb = static_cast<int>(bilateral.size());
  const int nu = 2 * static_cast<int>(rows.size());
  DBB_.resize(nb, nb);
  DUB_.resize(nu, nb);
  bBv_.resize(nb);
  for (int i = 0; i < nb; ++i) {
    bBv_[i] = bB[i];
    for (int j = i; j < nb; ++j) DBB_(i, j) = DBB_(j, i) = weightedDot(bilateral[i]->w, bilateral[j]->w, minv);
    for (int a = 0; a < nu; ++a) DUB_(a, i) = weightedDot(column(rows[a / 2], a % 2), bilateral[i]->w, minv);
  }
  // a tiny relative regularisation keeps redundant constraints (if any) solvable
  const double reg = 1e-13 * (DBB_.diagonal().cwiseAbs().maxCoeff() + 1e-300);
  for (int i = 0; i < nb; ++i) DBB_(i, i) += reg;
  bilateralLdlt_.compute(DBB_);
  if (bilateralLdlt_.info() != Eigen::Success) return false;
  if (nu > 0) {
    X_ = bilateralLdlt_.solve(DUB_.transpose());  // nb x nu
    D_.noalias() -= DUB_ * X_;
    b_.noalias() -= X_.transpose() * bBv_;
  }
  return true;
}

// The forces from the LCP variables, F = T z: one variable (F_N) per NormalOnly or SlidingFolded
// row (F_T = -mu s F_N folded in), three per Friction row, z = (F_N, F'_T, xi) with
// F_T = F'_T - mu F_N, d + 1 per PolygonFriction row (the header's table).
void ConstraintSolver::buildForceMap(const std::vector<ContactRow>& rows) {
  const int nc = static_cast<int>(rows.size());
  int nz = 0;
  for (const ContactRow& r : rows) nz += variables(r);
  T_.setZero(2 * nc, nz);
  for (int c = 0, o = 0; c < nc; o += variables(rows[c]), ++c) {
    const ContactRow& r = rows[c];
    if (r.kind == RowKind::PolygonFriction) {
      for (int j = 0; j < r.facets; ++j) {
        T_(2 * c, o + j) = facetCos(j, r.facets);
        T_(2 * c + 1, o + j) = facetSin(j, r.facets);
      }
      continue;
    }
    T_(2 * c, o) = 1.0;
    if (r.kind == RowKind::Friction) {
      T_(2 * c + 1, o) = -r.mu;
      T_(2 * c + 1, o + 1) = 1.0;
    } else if (r.kind == RowKind::SlidingFolded) {
      T_(2 * c + 1, o) = -r.mu * r.slideSign;
    }
  }
  z_.resize(nz);
  sol_.size = nz;
}

// Lemke on the LCP, first as posed; if it fails, with the regularization, then with 100 times
// it (see the class comment). Recorded LCPs are written before each solve.
void ConstraintSolver::solveContactLcp(const std::vector<ContactRow>& rows, int nb, int maxPivots) {
  const int nc = static_cast<int>(rows.size());
  const int nu = 2 * nc;
  double dmax = 0.0;
  for (int a = 0; a < nu; ++a) dmax = std::max(dmax, D_(a, a));
  double added = 0.0;
  for (int attempt = 0; attempt < 3; ++attempt) {
    if (attempt > 0) {
      if (!(regularization_ > 0.0)) break;
      const double target = (attempt == 1 ? 1.0 : 100.0) * regularization_ * dmax;
      for (int a = 0; a < nu; ++a) D_(a, a) += target - added;
      added = target;
      sol_.regularized = true;
    }
    assembleLcp(rows);
    if (recordLeft_ > 0) {
      --recordLeft_;
      writeLcp(recordDir_ + "/lcp_" + std::to_string(recorded_++) + ".dat", nc, nb);
    }
    const lcp::Result res = lemke_.solve(M_, q_, z_, maxPivots);
    sol_.status = res.status;
    sol_.pivots += res.pivots;
    sol_.error = res.error;
    sol_.last = res;
    if (res.status == lcp::Status::Solved) break;
    // a failed LCP is always kept when recording is on, for offline study
    if (!recordDir_.empty()) writeLcp(recordDir_ + "/lcp_failed_" + std::to_string(failed_++) + ".dat", nc, nb);
  }
}

// (M, q) of the LCP w = M z + q: the rows of D T for u_N (and for Friction rows u_T + xi), and
// for Friction rows the cone row 2 mu F_N - F'_T; PolygonFriction rows: polygonRows.
void ConstraintSolver::assembleLcp(const std::vector<ContactRow>& rows) {
  const int nc = static_cast<int>(rows.size());
  const Eigen::Index nz = z_.size();
  M_.setZero(nz, nz);
  q_.setZero(nz);
  DT_.noalias() = D_ * T_;
  for (int c = 0, o = 0; c < nc; o += variables(rows[c]), ++c) {
    const ContactRow& r = rows[c];
    if (r.kind == RowKind::PolygonFriction) {
      polygonRows(r, c, o);
      continue;
    }
    M_.row(o) = DT_.row(2 * c);
    q_[o] = b_[2 * c];
    if (r.kind == RowKind::Friction) {
      M_.row(o + 1) = DT_.row(2 * c + 1);
      M_(o + 1, o + 2) += 1.0;
      q_[o + 1] = b_[2 * c + 1];
      M_(o + 2, o) = 2.0 * r.mu;
      M_(o + 2, o + 1) = -1.0;
    }
  }
}

// A PolygonFriction row c with variables from o: per facet j, e_j . (D T z + b) + lambda, and
// the bound row bound - sum_j beta_j.
void ConstraintSolver::polygonRows(const ContactRow& r, int c, int o) {
  const int d = r.facets;
  for (int j = 0; j < d; ++j) {
    const double ex = facetCos(j, d), ey = facetSin(j, d);
    M_.row(o + j) = ex * DT_.row(2 * c) + ey * DT_.row(2 * c + 1);
    M_(o + j, o + d) += 1.0;
    q_[o + j] = ex * b_[2 * c] + ey * b_[2 * c + 1];
    M_(o + d, o + j) = -1.0;
  }
  q_[o + d] = r.bound;
}

// F_U = T z per row; a friction row sticks when its force lies strictly inside the cone (for a
// polygon: the sum of its facet forces below the bound).
void ConstraintSolver::contactForces(const std::vector<ContactRow>& rows) {
  const int nc = static_cast<int>(rows.size());
  F_ = T_ * z_;
  for (int c = 0, o = 0; c < nc; o += variables(rows[c]), ++c) {
    const ContactRow& r = rows[c];
    if (r.kind == RowKind::PolygonFriction) {
      sol_.fT[c] = F_[2 * c];
      sol_.fT2[c] = F_[2 * c + 1];
      sol_.sticking[c] = z_.segment(o, r.facets).sum() < r.bound * (1.0 - 1e-9) ? 1 : 0;
    } else {
      sol_.fN[c] = F_[2 * c];
      sol_.fT[c] = F_[2 * c + 1];
      // strictly inside the friction cone: sticking; on its boundary: sliding (or about to)
      if (r.kind == RowKind::Friction)
        sol_.sticking[c] = std::fabs(sol_.fT[c]) < r.mu * sol_.fN[c] * (1.0 - 1e-9) ? 1 : 0;
    }
  }
}

// F_B = -G_BB^-1 (bB + G_BU F_U)
void ConstraintSolver::bilateralForces(int nc, int nb) {
  Eigen::VectorXd rhs = bBv_;
  if (nc > 0) rhs.noalias() += DUB_.transpose() * F_;
  const Eigen::VectorXd fb = -bilateralLdlt_.solve(rhs);
  for (int i = 0; i < nb; ++i) sol_.fB[i] = fb[i];
}

void ConstraintSolver::writeLcp(const std::string& path, int nc, int nb) const {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) return;
  const int nz = static_cast<int>(q_.size());
  std::fprintf(f, "%d\n0\n%d\n%d\n%d\t%d\n", nz, nz, nz, nz, nz);
  for (int c = 0; c < nz; ++c)
    for (int r = 0; r < nz; ++r) std::fprintf(f, "%.17g%s", M_(r, c), r + 1 == nz ? "\n" : " ");
  for (int r = 0; r < nz; ++r) std::fprintf(f, "%.17g%s", q_[r], r + 1 == nz ? "\n" : " ");
  std::fprintf(f, "chain drive contact LCP (%d contacts, %d bilateral constraints eliminated)\n", nc, nb);
  std::fclose(f);
}

double projectPositions(NonsmoothSystem& sys, double t, double* q, const double* v, ConstraintSolver& solver,
                        int passes) {
  const std::vector<double>& minv = sys.inverseMass();
  ConstraintSet cs;
  std::vector<ContactRow> rows;
  std::vector<const Bilateral*> bil;
  std::vector<double> bB;
  double worst = 0.0;
  for (int pass = 0; pass <= passes; ++pass) {
    sys.constraints(t, q, v, 0.0, false, cs);
    rows.clear();
    bil.clear();
    bB.clear();
    worst = 0.0;
    for (const Contact& c : cs.contacts) {
      if (c.gap >= 0.0 || c.compliantNormal()) continue;  // (a compliant normal may penetrate)
      worst = std::max(worst, -c.gap);
      ContactRow r;
      r.contact = &c;
      r.kind = RowKind::NormalOnly;
      r.bN = c.gap;
      rows.push_back(r);
    }
    for (const Bilateral& b : cs.bilateral) {
      worst = std::max(worst, std::fabs(b.g));
      bil.push_back(&b);
      bB.push_back(b.g);
    }
    if (pass == passes || worst == 0.0 || (rows.empty() && bil.empty())) break;
    const ConstraintSolution& s = solver.solve(rows, bil, bB, minv.data());
    if (!s.solved()) break;
    for (std::size_t k = 0; k < rows.size(); ++k) addImpulse(rows[k].contact->wN, s.fN[k], minv.data(), q);
    for (std::size_t k = 0; k < bil.size(); ++k) addImpulse(bil[k]->w, s.fB[k], minv.data(), q);
  }
  return worst;
}

}  // namespace chaindrive::ns
