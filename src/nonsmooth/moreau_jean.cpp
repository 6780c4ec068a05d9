#include "nonsmooth/moreau_jean.h"

#include <algorithm>
#include <cmath>

#include "integrators/ode_system.h"

namespace chaindrive::ns {

MoreauJean::MoreauJean(NonsmoothSystem& sys, const MoreauJeanSettings& s)
    : NonsmoothMethod(sys.size()), sys_(sys), settings_(s), minv_(sys.inverseMass()), n_(sys.size()) {
  if (!(s.step > 0.0)) throw std::invalid_argument("time-stepping needs a positive step");
  if (s.frictionFacets < 3)
    throw std::invalid_argument("frictionFacets " + std::to_string(s.frictionFacets) +
                                ": the friction polygon needs at least 3 facets");
  grid_.unit = s.step;
  if (!s.recordLcpDirectory.empty()) solver_.record(s.recordLcpDirectory, s.recordLcpCount);
  qm_.assign(n_, 0.0);
  h_.assign(n_, 0.0);
  vfree_.assign(n_, 0.0);
  vnew_.assign(n_, 0.0);
  presc_.assign(n_, 0.0);
  prescAcc_.assign(n_, 0.0);
}

void MoreauJean::reset(double t, const double* q, const double* v) {
  t_ = t;
  grid_.start = t;
  k_ = 0;
  std::copy(q, q + n_, q_.begin());
  std::copy(v, v + n_, v_.begin());
  forces_.clear();
  stuck_.clear();
  active_.clear();
  // start on the constraints (a pre-loaded compliant state penetrates by micrometres)
  projectPositions(sys_, t_, q_.data(), v_.data(), solver_);
}

void MoreauJean::advance(double tout) {
  // whole steps of exactly h on the grid from the last reset (step times t0 + k h)
  const long long target = grid_.indexOf(tout);
  for (; k_ < target; ++k_) {
    step(grid_.unit);
    t_ = grid_.time(k_ + 1);
  }
}

// One step of length h from t_ (the header's scheme):
//   q_m = q + h/2 v,   v_free = v + h M^-1 h(t + h/2, q_m, v),
//   M (v+ - v_free) = W P  with the velocity LCP on the active contacts,   q+ = q_m + h/2 v+
void MoreauJean::step(double h) {
  const double tm = t_ + 0.5 * h;
  freeMotion(h, tm);
  activeConstraints(h, tm);
  const double contactWork = applyImpulses(h);
  accountEnergy(h, tm, contactWork);
  sys_.advanceSmoothStates(h);  // (at the midpoint with the mean velocity: accountEnergy's evaluation)
  for (int i = 0; i < n_; ++i) q_[i] = qm_[i] + 0.5 * h * vnew_[i];
  v_.swap(vnew_);
  ++stats_.steps;
  Failure why;
  if (!sys_.healthy(t_ + h, q_.data(), v_.data(), why)) throw IntegrationError(t_ + h, why);
}

// q_m and v_free; prescribed degrees of freedom follow their motion.
void MoreauJean::freeMotion(double h, double tm) {
  for (int i = 0; i < n_; ++i) qm_[i] = q_[i] + 0.5 * h * v_[i];
  sys_.forces(tm, qm_.data(), v_.data(), h_.data());
  for (int i = 0; i < n_; ++i) vfree_[i] = v_[i] + h * minv_[i] * h_[i];
  std::copy(vfree_.begin(), vfree_.end(), presc_.begin());
  sys_.prescribed(t_ + h, presc_.data(), prescAcc_.data());
  for (int i = 0; i < n_; ++i)
    if (minv_[i] == 0.0) vfree_[i] = presc_[i];
}

// The rows of the velocity LCP: constraints at the midpoint, contacts predicted closed by the
// end of the step (Newton restitution in bN; static friction for those that stuck), and the
// bilateral constraints closing at the end of the step.
void MoreauJean::activeConstraints(double h, double tm) {
  double vmax = 0.0;
  for (int i = 0; i < n_; ++i) vmax = std::max(vmax, std::fabs(v_[i]));
  sys_.constraints(tm, qm_.data(), v_.data(), std::max(settings_.gapTolerance, 2.0 * h * vmax), false, cs_);
  rows_.clear();
  bool impact = false;
  for (const Contact& c : cs_.contacts) {
    if (c.compliantNormal()) {
      if (c.frictionBound > 0.0) rows_.push_back(polygonRow(c, h));
      continue;
    }
    const double gdot = c.wN.dot(v_.data());
    if (c.gap + 0.5 * h * gdot > settings_.gapTolerance) continue;
    ContactRow r;
    r.contact = &c;
    const bool stuck = std::binary_search(stuck_.begin(), stuck_.end(), c.id);
    r.mu = settings_.staticFriction && stuck ? c.muStatic : c.mu;
    r.kind = r.mu > 0.0 ? RowKind::Friction : RowKind::NormalOnly;
    r.bN = c.wN.dot(vfree_.data()) + c.restitution * std::min(0.0, gdot);
    r.bT = c.wT.dot(vfree_.data());
    rows_.push_back(r);
    // an impact: a contact that closes approaching (it was not active in the last step)
    impact = impact || (gdot < 0.0 && !std::binary_search(active_.begin(), active_.end(), c.id));
  }
  if (impact) ++stats_.impacts;
  active_.clear();
  for (const ContactRow& r : rows_) active_.push_back(r.contact->id);
  std::sort(active_.begin(), active_.end());
  bil_.clear();
  bB_.clear();
  for (const Bilateral& b : cs_.bilateral) {
    bil_.push_back(&b);
    bB_.push_back(b.w.dot(vfree_.data()) + 2.0 * b.g / h);
  }
}

// A compliant normal's friction: the impulse bound of the step, the free relative velocities.
ContactRow MoreauJean::polygonRow(const Contact& c, double h) const {
  ContactRow r;
  r.contact = &c;
  r.kind = RowKind::PolygonFriction;
  r.facets = settings_.frictionFacets;
  r.bound = h * c.frictionBound;
  r.bT = c.wT.dot(vfree_.data());
  r.bT2 = c.wT2.dot(vfree_.data());
  return r;
}

// v+ = v_free + M^-1 W P from the LCP's impulses; the forces (P / h) and the contacts that stick
// are kept. Returns the impulses' work on the relative motion (mean of the velocities).
double MoreauJean::applyImpulses(double h) {
  vnew_ = vfree_;
  forces_.clear();
  double contactWork = 0.0;
  if (rows_.empty() && bil_.empty()) {
    stuck_.clear();
    return contactWork;
  }
  const ConstraintSolution& s = solver_.solve(rows_, bil_, bB_, minv_.data(), settings_.maxPivots);
  countSolve(stats_, s);
  if (!s.solved())
    throw IntegrationError(t_, lcpFailureKind(s.status),
                           std::string("velocity LCP of size ") + std::to_string(s.size) + " not solved: " + statusText(s));
  for (std::size_t k = 0; k < rows_.size(); ++k) {
    addImpulse(rows_[k].contact->wN, s.fN[k], minv_.data(), vnew_.data());
    addImpulse(rows_[k].contact->wT, s.fT[k], minv_.data(), vnew_.data());
    addImpulse(rows_[k].contact->wT2, s.fT2[k], minv_.data(), vnew_.data());
  }
  for (std::size_t k = 0; k < bil_.size(); ++k) addImpulse(bil_[k]->w, s.fB[k], minv_.data(), vnew_.data());
  bilateralForces_.resize(bil_.size());
  for (std::size_t k = 0; k < bil_.size(); ++k) bilateralForces_[k] = s.fB[k] / h;
  // prescribed degrees of freedom are not moved by impulses (minv = 0)
  stuck_.clear();
  for (std::size_t k = 0; k < rows_.size(); ++k) {
    const Contact& c = *rows_[k].contact;
    const double uN = 0.5 * (c.wN.dot(v_.data()) + c.wN.dot(vnew_.data()));
    const double uT = 0.5 * (c.wT.dot(v_.data()) + c.wT.dot(vnew_.data()));
    const double uT2 = 0.5 * (c.wT2.dot(v_.data()) + c.wT2.dot(vnew_.data()));
    contactWork += s.fN[k] * uN + s.fT[k] * uT + s.fT2[k] * uT2;
    if (s.sticking[k]) stuck_.push_back(c.id);
    forces_.push_back(ContactForce{c.tag, c.id, s.fN[k] / h, s.fT[k] / h, s.fT2[k] / h});
  }
  for (std::size_t k = 0; k < bil_.size(); ++k)
    contactWork += s.fB[k] * 0.5 * (bil_[k]->w.dot(v_.data()) + bil_[k]->w.dot(vnew_.data()));
  std::sort(stuck_.begin(), stuck_.end());
  return contactWork;
}

// Energy: smooth input and damping at the midpoint; impulses: their work on the relative motion
// is dissipated, except what they do on prescribed degrees of freedom (the drive's work).
void MoreauJean::accountEnergy(double h, double tm, double contactWork) {
  double drive = 0.0;
  for (std::size_t k = 0; k < rows_.size(); ++k) {
    const Contact& c = *rows_[k].contact;
    const ConstraintSolution& s = solver_.solution();
    for (const SparseColumn* col : {&c.wN, &c.wT, &c.wT2}) {
      const double f = col == &c.wN ? s.fN[k] : col == &c.wT ? s.fT[k] : s.fT2[k];
      for (int j = 0; j < col->n; ++j)
        if (minv_[col->idx[j]] == 0.0) drive -= f * col->val[j] * 0.5 * (v_[col->idx[j]] + vnew_[col->idx[j]]);
    }
  }
  for (int i = 0; i < n_; ++i) h_[i] = 0.5 * (v_[i] + vnew_[i]);  // mean velocity (reuse h_)
  inputWork_ += h * sys_.inputPower(tm, qm_.data(), h_.data()) + drive;
  dissipated_ += h * sys_.dissipatedPower(tm, qm_.data(), h_.data()) - contactWork;
}

}  // namespace chaindrive::ns
