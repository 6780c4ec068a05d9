#include "nonsmooth/formulations.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace chaindrive::ns {

namespace {
const SparseColumn& column(const ContactRow& r, int s) { return s == 0 ? r.contact->wN : r.contact->wT; }
}  // namespace

const ConstraintSolution& ConstraintSolver::solve(const std::vector<ContactRow>& rows,
                                                  const std::vector<const Bilateral*>& bilateral,
                                                  const std::vector<double>& bB, const double* minv, int maxPivots) {
  const int nc = static_cast<int>(rows.size());
  const int nb = static_cast<int>(bilateral.size());
  const int nu = 2 * nc;
  sol_.fN.assign(nc, 0.0);
  sol_.fT.assign(nc, 0.0);
  sol_.fB.assign(nb, 0.0);
  sol_.sticking.assign(nc, 0);
  sol_.status = lcp::Status::Solved;
  sol_.size = sol_.pivots = 0;
  sol_.error = 0.0;
  sol_.regularized = false;

  // Delassus blocks
  D_.resize(nu, nu);
  b_.resize(nu);
  for (int a = 0; a < nu; ++a) {
    const SparseColumn& ca = column(rows[a / 2], a % 2);
    b_[a] = a % 2 == 0 ? rows[a / 2].bN : rows[a / 2].bT;
    for (int c = a; c < nu; ++c) D_(a, c) = D_(c, a) = weightedDot(ca, column(rows[c / 2], c % 2), minv);
  }
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  if (nb > 0) {
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
    ldlt.compute(DBB_);
    if (ldlt.info() != Eigen::Success) {
      sol_.status = lcp::Status::NumericalFailure;
      return sol_;
    }
    if (nu > 0) {
      X_ = ldlt.solve(DUB_.transpose());  // nb x nu
      D_.noalias() -= DUB_ * X_;
      b_.noalias() -= X_.transpose() * bBv_;
    }
  }
  if (nc > 0) {
    // forces from LCP variables: F = T z
    int nz = 0;
    for (const ContactRow& r : rows) nz += r.kind == RowKind::Friction ? 3 : 1;
    T_.setZero(nu, nz);
    int o = 0;
    for (int c = 0; c < nc; ++c) {
      const ContactRow& r = rows[c];
      T_(2 * c, o) = 1.0;
      if (r.kind == RowKind::Friction) {
        T_(2 * c + 1, o) = -r.mu;
        T_(2 * c + 1, o + 1) = 1.0;
        o += 3;
      } else {
        if (r.kind == RowKind::SlidingFolded) T_(2 * c + 1, o) = -r.mu * r.slideSign;
        o += 1;
      }
    }
    z_.resize(nz);
    sol_.size = nz;
    // first as posed; if Lemke fails, with the regularization, then with 100 times it (see the
    // class comment)
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
      M_.setZero(nz, nz);
      q_.setZero(nz);
      DT_.noalias() = D_ * T_;
      o = 0;
      for (int c = 0; c < nc; ++c) {
        const ContactRow& r = rows[c];
        M_.row(o) = DT_.row(2 * c);
        q_[o] = b_[2 * c];
        if (r.kind == RowKind::Friction) {
          M_.row(o + 1) = DT_.row(2 * c + 1);
          M_(o + 1, o + 2) += 1.0;
          q_[o + 1] = b_[2 * c + 1];
          M_(o + 2, o) = 2.0 * r.mu;
          M_(o + 2, o + 1) = -1.0;
          o += 3;
        } else {
          o += 1;
        }
      }
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
    if (sol_.status != lcp::Status::Solved) return sol_;
    F_ = T_ * z_;
    o = 0;
    for (int c = 0; c < nc; ++c) {
      sol_.fN[c] = F_[2 * c];
      sol_.fT[c] = F_[2 * c + 1];
      if (rows[c].kind == RowKind::Friction) {
        // strictly inside the friction cone: sticking; on its boundary: sliding (or about to)
        sol_.sticking[c] = std::fabs(sol_.fT[c]) < rows[c].mu * sol_.fN[c] * (1.0 - 1e-9) ? 1 : 0;
        o += 3;
      } else {
        o += 1;
      }
    }
  } else {
    F_.resize(0);
  }
  if (nb > 0) {
    // F_B = -DBB^-1 (bB + DBU F_U)
    Eigen::VectorXd rhs = bBv_;
    if (nc > 0) rhs.noalias() += DUB_.transpose() * F_;
    const Eigen::VectorXd fb = -ldlt.solve(rhs);
    for (int i = 0; i < nb; ++i) sol_.fB[i] = fb[i];
  }
  return sol_;
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
      if (c.gap >= 0.0) continue;
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
