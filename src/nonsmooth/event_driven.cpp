#include "nonsmooth/event_driven.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <arkode/arkode_erkstep.h>

#include "integrators/ode_system.h"
#include "integrators/sundials_common.h"

namespace chaindrive::ns {

struct EventDriven::Sundials {
  SundialsContext ctx;
  std::unique_ptr<SerialVector> y, atol;
  void* mem = nullptr;
  CallbackState cb;
  ~Sundials() {
    if (mem) ERKStepFree(&mem);
  }
};

namespace {

extern "C" int edRhs(double t, N_Vector y, N_Vector ydot, void* user) noexcept {
  return static_cast<EventDriven*>(user)->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
}
extern "C" int edRoots(double t, N_Vector y, double* g, void* user) noexcept {
  return static_cast<EventDriven*>(user)->roots(t, N_VGetArrayPointer(y), g);
}
extern "C" void edErr(int code, const char* module, const char* function, char* msg, void* user) noexcept {
  try {
    static_cast<std::string*>(user)->assign(std::string(module ? module : "") + "/" + (function ? function : "") + " (" +
                                            std::to_string(code) + "): " + (msg ? msg : ""));
  } catch (...) {
  }
}

constexpr double kRootMargin = 1e-3;  // [m] contacts farther than this are not watched
constexpr long long kEventBatch = 100;  // the event rate is checked over batches of this many events

}  // namespace

EventDriven::EventDriven(NonsmoothSystem& sys, const EventDrivenSettings& s)
    : NonsmoothMethod(sys.size()),
      sys_(sys),
      settings_(s),
      minv_(sys.inverseMass()),
      n_(sys.size()),
      sun_(std::make_unique<Sundials>()) {
  h_.assign(n_, 0.0);
  afree_.assign(n_, 0.0);
  acc_.assign(n_, 0.0);
  presc_.assign(n_, 0.0);
  prescAcc_.assign(n_, 0.0);
  if (!s.recordLcpDirectory.empty()) solver_.record(s.recordLcpDirectory, s.recordLcpCount);
  sun_->y = std::make_unique<SerialVector>(2 * n_ + 2, sun_->ctx.ctx);
  sun_->atol = std::make_unique<SerialVector>(2 * n_ + 2, sun_->ctx.ctx);
}

EventDriven::~EventDriven() = default;

const EventDriven::Closed* EventDriven::findClosed(long long id) const {
  auto it = std::lower_bound(closed_.begin(), closed_.end(), id, [](const Closed& c, long long k) { return c.id < k; });
  return it != closed_.end() && it->id == id ? &*it : nullptr;
}

double EventDriven::kineticEnergy(const double* v) const {
  double e = 0.0;
  for (int i = 0; i < n_; ++i)
    if (minv_[i] > 0.0) e += 0.5 * v[i] * v[i] / minv_[i];
  return e;
}

bool EventDriven::accelerations(double t, const double* q, const double* v, bool record) {
  sys_.forces(t, q, v, h_.data());
  std::copy(v, v + n_, presc_.begin());
  sys_.prescribed(t, presc_.data(), prescAcc_.data());
  for (int i = 0; i < n_; ++i) afree_[i] = minv_[i] > 0.0 ? minv_[i] * h_[i] : prescAcc_[i];
  sys_.constraints(t, q, v, std::max(10.0 * settings_.gapTolerance, 1e-9), true, cs_);
  const double a = settings_.stabilization;
  rows_.clear();
  for (const Contact& c : cs_.contacts) {
    const Closed* cl = findClosed(c.id);
    if (!cl) continue;
    ContactRow r;
    r.contact = &c;
    const double gdN = c.wN.dot(v), gdT = c.wT.dot(v);
    r.bN = c.wN.dot(afree_.data()) + c.wbarN + 2.0 * a * gdN + a * a * c.gap;
    r.bT = c.wT.dot(afree_.data()) + c.wbarT + 2.0 * a * gdT;
    if (c.mu <= 0.0 && c.muStatic <= 0.0) {
      r.kind = RowKind::NormalOnly;
    } else if (cl->mode == Mode::Stick) {
      r.kind = RowKind::Friction;
      r.mu = c.muStatic;
    } else {
      r.kind = RowKind::SlidingFolded;
      r.mu = c.mu;
      r.slideSign = cl->sign;
    }
    rows_.push_back(r);
  }
  bil_.clear();
  bB_.clear();
  for (const Bilateral& b : cs_.bilateral) {
    bil_.push_back(&b);
    bB_.push_back(b.w.dot(afree_.data()) + b.wbar + 2.0 * a * b.w.dot(v) + a * a * b.g);
  }
  std::copy(afree_.begin(), afree_.end(), acc_.begin());
  if (record) forces_.clear();
  if (rows_.empty() && bil_.empty()) return true;
  const ConstraintSolution& s = solver_.solve(rows_, bil_, bB_, minv_.data(), settings_.maxPivots);
  countSolve(stats_, s);
  if (!s.solved()) {
    std::string ids;
    for (const ContactRow& r : rows_)
      ids += (ids.empty() ? "" : ", ") + std::to_string(r.contact->id) +
             (r.kind == RowKind::SlidingFolded ? " (sliding)" : r.kind == RowKind::Friction ? " (sticking)" : "");
    lastFailure_.kind = lcpFailureKind(s.status);
    lastFailure_.reason = std::string("acceleration LCP of size ") + std::to_string(s.size) +
                          " has no solution found by Lemke (" + statusText(s) + ") for the closed contacts " + ids +
                          (s.status == lcp::Status::RayTermination
                               ? ": the contact problem is inconsistent (no or several solutions, as in the Painleve paradox)"
                               : "");
    return false;
  }
  for (std::size_t k = 0; k < rows_.size(); ++k) {
    addImpulse(rows_[k].contact->wN, s.fN[k], minv_.data(), acc_.data());
    addImpulse(rows_[k].contact->wT, s.fT[k], minv_.data(), acc_.data());
    if (record) forces_.push_back(ContactForce{rows_[k].contact->tag, rows_[k].contact->id, s.fN[k], s.fT[k]});
  }
  for (std::size_t k = 0; k < bil_.size(); ++k) addImpulse(bil_[k]->w, s.fB[k], minv_.data(), acc_.data());
  if (record) bilateralForces_.assign(s.fB.begin(), s.fB.end());
  return true;
}

int EventDriven::rhs(double t, const double* y, double* ydot) noexcept {
  try {
    ++stats_.rhsEvaluations;
    const double* q = y;
    const double* v = y + n_;
    if (!accelerations(t, q, v, false)) return -1;
    std::copy(v, v + n_, ydot);
    std::copy(acc_.begin(), acc_.end(), ydot + n_);
    // powers: smooth input, the drive's work through constraint forces on prescribed DOFs,
    // damping and sliding friction
    double drive = 0.0, friction = 0.0;
    const ConstraintSolution& s = solver_.solution();
    if (!rows_.empty())
      for (std::size_t k = 0; k < rows_.size(); ++k) {
        const Contact& c = *rows_[k].contact;
        friction -= s.fT[k] * c.wT.dot(v);
        for (const SparseColumn* col : {&c.wN, &c.wT}) {
          const double f = col == &c.wN ? s.fN[k] : s.fT[k];
          for (int j = 0; j < col->n; ++j)
            if (minv_[col->idx[j]] == 0.0) drive -= f * col->val[j] * v[col->idx[j]];
        }
      }
    ydot[2 * n_] = sys_.inputPower(t, q, v) + drive;
    ydot[2 * n_ + 1] = sys_.dissipatedPower(t, q, v) + std::max(0.0, friction);
    for (int i = 0; i < 2 * n_ + 2; ++i)
      if (!std::isfinite(ydot[i])) return 1;
    return 0;
  } catch (const std::exception& e) {
    lastFailure_ = {FailureKind::Other, e.what()};
    return -1;
  }
}

int EventDriven::roots(double t, const double* y, double* g) noexcept {
  try {
    const double* q = y;
    const double* v = y + n_;
    // closing: the smallest gap of the open contacts, shifted by half the gap tolerance so that
    // a contact that just rebounded from gap ~ 0 starts positive and its next landing is seen
    // even when the whole flight fits into one step
    sys_.constraints(t, q, v, kRootMargin, false, cs_);
    double gmin = kRootMargin;
    for (const Contact& c : cs_.contacts)
      if (!findClosed(c.id)) gmin = std::min(gmin, c.gap + 0.5 * settings_.gapTolerance);
    g[0] = gmin;
    // slip to stick: the sliding velocity, in its sliding direction, offset by half the stick
    // speed so that it is positive when the contact starts sliding from rest
    for (std::size_t k = 0; k < sliding_.size(); ++k) {
      const Closed* cl = findClosed(sliding_[k]);
      const double sign = cl ? cl->sign : 1.0;
      double val = 1.0;
      for (const Contact& c : cs_.contacts)
        if (c.id == sliding_[k]) val = sign * c.wT.dot(v) + 0.5 * settings_.stickSpeed;
      g[1 + k] = val;
    }
    if (!sticking_.empty()) {
      // stick to slip: the friction force reaches the static cone, mu_s F_N - |F_T| = 0
      for (std::size_t k = 0; k < sticking_.size(); ++k) g[1 + sliding_.size() + k] = 1.0;
      if (!accelerations(t, q, v, true)) return 1;
      for (std::size_t k = 0; k < sticking_.size(); ++k)
        for (const ContactForce& f : forces_)
          if (f.id == sticking_[k]) {
            const Closed* cl = findClosed(f.id);
            (void)cl;
            double muS = 0.0;
            for (const ContactRow& r : rows_)
              if (r.contact->id == f.id) muS = r.mu;
            // the reserve, less a relative 1e-9 so that it is not exactly zero where a contact
            // sticks on the cone's boundary (a missed transition is caught by the stick speed)
            g[1 + sliding_.size() + k] = muS * f.fN * (1.0 - 1e-9) - std::fabs(f.fT);
          }
    }
    return 0;
  } catch (...) {
    return -1;
  }
}

void EventDriven::setupRoots() {
  sliding_.clear();
  sticking_.clear();
  sys_.constraints(t_, q_.data(), v_.data(), std::max(10.0 * settings_.gapTolerance, 1e-9), false, cs_);
  for (const Closed& c : closed_) {
    if (c.mode == Mode::Slide) {
      sliding_.push_back(c.id);
      continue;
    }
    for (const Contact& k : cs_.contacts)
      if (k.id == c.id && k.muStatic > 0.0) sticking_.push_back(c.id);
  }
  const int nr = 1 + static_cast<int>(sliding_.size() + sticking_.size());
  if (ERKStepRootInit(sun_->mem, nr, edRoots) < 0) throw std::runtime_error("ERKStepRootInit failed");
  std::vector<int> dir(nr, -1);  // gaps closing; sliding velocities reversing; friction reaching the cone
  ERKStepSetRootDirection(sun_->mem, dir.data());
  ERKStepSetNoInactiveRootWarn(sun_->mem);
}

void EventDriven::restartIntegrator() {
  double* y = sun_->y->data();
  std::copy(q_.begin(), q_.end(), y);
  std::copy(v_.begin(), v_.end(), y + n_);
  y[2 * n_] = inputWork_;
  y[2 * n_ + 1] = dissipated_;
  if (!sun_->mem) {
    sun_->mem = ERKStepCreate(edRhs, t_, sun_->y->v, sun_->ctx.ctx);
    if (!sun_->mem) throw std::runtime_error("ERKStepCreate failed");
    ERKStepSetUserData(sun_->mem, this);
    ERKStepSetErrHandlerFn(sun_->mem, edErr, &solverMessage_);
    if (ERKStepSetTableName(sun_->mem, settings_.erkTable.c_str()) != 0)
      throw std::invalid_argument("unknown ARKODE ERK table '" + settings_.erkTable + "'");
    double* at = sun_->atol->data();
    for (int i = 0; i < n_; ++i) {
      at[i] = settings_.atolPosition;
      at[n_ + i] = settings_.atolVelocity;
    }
    at[2 * n_] = at[2 * n_ + 1] = 1e-6;
    ERKStepSVtolerances(sun_->mem, settings_.rtol, sun_->atol->v);
    ERKStepSetMaxNumSteps(sun_->mem, 10000000);
    if (settings_.maxStep > 0.0) ERKStepSetMaxStep(sun_->mem, settings_.maxStep);
  } else {
    ERKStepReset(sun_->mem, t_, sun_->y->v);
  }
  setupRoots();
}

// The impact at the current state (where a contact at the surface approaches), the slow
// rebounds closed, the dissipated energy booked; then the positions projected onto the surface
// and the contacts classified for the next smooth phase.
void EventDriven::impact(double t) {
  const double tol = settings_.gapTolerance;
  sys_.constraints(t, q_.data(), v_.data(), tol, false, cs_);
  collectImpactRows();
  if (anyApproaching()) {
    vBefore_.assign(v_.begin(), v_.end());
    applyNewtonImpact(t);
    closeSlowRebounds(t);
    // energy: the drive's work on prescribed DOFs does not change them; the loss is the rest
    const double lost = kineticEnergy(vBefore_.data()) - kineticEnergy(v_.data());
    dissipated_ += lost;
  }
  // position projection: contacts found below the surface (events are located at a gap of
  // minus half the tolerance) are moved back onto it, with the bilateral constraints, so that
  // every flight starts from a non-negative gap and its landing changes the sign of the root
  // function
  projectPositions(sys_, t, q_.data(), v_.data(), solver_);
  sys_.constraints(t, q_.data(), v_.data(), tol, false, cs_);
  classifyContacts();
}

// Newton's law for every contact at the surface (closed and closing), frictionless: the
// post-impact normal velocity is at least -e times the one before; the bilateral constraints
// keep zero velocity.
void EventDriven::collectImpactRows() {
  const double tol = settings_.gapTolerance;
  rows_.clear();
  for (const Contact& c : cs_.contacts) {
    if (c.gap > tol) continue;
    ContactRow r;
    r.contact = &c;
    r.kind = RowKind::NormalOnly;
    r.bN = (1.0 + c.restitution) * c.wN.dot(v_.data());
    rows_.push_back(r);
  }
  bil_.clear();
  bB_.clear();
  for (const Bilateral& b : cs_.bilateral) {
    bil_.push_back(&b);
    bB_.push_back(b.w.dot(v_.data()));
  }
}

// An impact only where a contact at the surface approaches: otherwise its impulses are zero.
bool EventDriven::anyApproaching() const {
  bool any = false;
  for (const ContactRow& r : rows_) any = any || r.bN < 0.0;
  return any;
}

// The impact LCP (eq. 10-12) and its impulses on v_.
void EventDriven::applyNewtonImpact(double t) {
  const ConstraintSolution& s = solver_.solve(rows_, bil_, bB_, minv_.data(), settings_.maxPivots);
  countSolve(stats_, s);
  if (!s.solved())
    throw IntegrationError(t, lcpFailureKind(s.status),
                           std::string("impact LCP of size ") + std::to_string(s.size) + " not solved: " + statusText(s));
  for (std::size_t k = 0; k < rows_.size(); ++k) addImpulse(rows_[k].contact->wN, s.fN[k], minv_.data(), v_.data());
  for (std::size_t k = 0; k < bil_.size(); ++k) addImpulse(bil_[k]->w, s.fB[k], minv_.data(), v_.data());
  ++stats_.impacts;
}

// A rebound slower than the threshold (and not exactly zero: a contact that stays closed).
bool EventDriven::reboundsSlowly(double uN) const {
  return uN < settings_.reboundThreshold && std::fabs(uN) > 0.0;
}

// Slow rebounds close their contact, so that accumulating impacts (Zeno) end instead of
// tunnelling: a plastic impact for them, the other contacts and the bilateral constraints kept.
void EventDriven::closeSlowRebounds(double t) {
  closing_.clear();
  for (const ContactRow& r : rows_)
    if (reboundsSlowly(r.contact->wN.dot(v_.data()))) {
      Bilateral b;
      b.w = r.contact->wN;
      closing_.push_back(b);
    }
  if (closing_.empty()) return;
  collectPlasticImpactRows();
  applyPlasticImpact(t);
}

// The plastic impact's problem: the other contacts' rows at their velocity after the impact
// (inelastic now), equality rows for the bilateral constraints and the closing contacts.
void EventDriven::collectPlasticImpactRows() {
  others_.clear();
  for (const ContactRow& r : rows_) {
    const double u = r.contact->wN.dot(v_.data());
    if (!reboundsSlowly(u)) {
      ContactRow o = r;
      o.bN = u;
      others_.push_back(o);
    }
  }
  eq_.assign(bil_.begin(), bil_.end());
  beq_.clear();
  for (std::size_t k = 0; k < bil_.size(); ++k) beq_.push_back(bil_[k]->w.dot(v_.data()));
  for (const Bilateral& b : closing_) {  // (closing_ is complete: the pointers stay valid)
    eq_.push_back(&b);
    beq_.push_back(b.w.dot(v_.data()));
  }
}

// The plastic impact LCP and its impulses on v_.
void EventDriven::applyPlasticImpact(double t) {
  const ConstraintSolution& s = solver_.solve(others_, eq_, beq_, minv_.data(), settings_.maxPivots);
  countSolve(stats_, s);
  if (!s.solved())
    throw IntegrationError(t, lcpFailureKind(s.status),
                           std::string("closing (plastic) impact LCP not solved: ") + statusText(s));
  for (std::size_t k = 0; k < others_.size(); ++k) addImpulse(others_[k].contact->wN, s.fN[k], minv_.data(), v_.data());
  for (std::size_t k = 0; k < eq_.size(); ++k) addImpulse(eq_[k]->w, s.fB[k], minv_.data(), v_.data());
}

// The closed contacts after an impact: at the surface and not separating; sticking where the
// tangential speed is below the stick speed, else sliding in its direction.
void EventDriven::classifyContacts() {
  closed_.clear();
  for (const Contact& c : cs_.contacts) {
    if (c.gap > settings_.gapTolerance) continue;
    const double uN = c.wN.dot(v_.data());
    if (uN >= settings_.reboundThreshold) continue;  // separating
    const double uT = c.wT.dot(v_.data());
    Closed cl{c.id, std::fabs(uT) < settings_.stickSpeed ? Mode::Stick : Mode::Slide, uT >= 0.0 ? 1.0 : -1.0};
    closed_.push_back(cl);
  }
  std::sort(closed_.begin(), closed_.end(), [](const Closed& a, const Closed& b) { return a.id < b.id; });
}

bool EventDriven::reclassify(double t) {
  sys_.constraints(t, q_.data(), v_.data(), kRootMargin, false, cs_);
  bool changed = false, needImpact = false;
  std::vector<Closed> next;
  for (const Closed& cl : closed_) {
    const Contact* c = nullptr;
    for (const Contact& k : cs_.contacts)
      if (k.id == cl.id) c = &k;
    if (!c || c->gap > settings_.gapTolerance) {
      changed = true;  // opened
      continue;
    }
    Closed n = cl;
    const double uT = c->wT.dot(v_.data());
    if (n.mode == Mode::Stick && std::fabs(uT) > settings_.stickSpeed) {
      n.mode = Mode::Slide;
      n.sign = uT >= 0.0 ? 1.0 : -1.0;
      changed = true;
    } else if (n.mode == Mode::Slide && uT * n.sign < -settings_.stickSpeed) {  // reversal the root missed
      n.mode = Mode::Stick;
      changed = true;
    }
    next.push_back(n);
  }
  for (const Contact& c : cs_.contacts)
    if (!findClosed(c.id) && c.gap < -settings_.gapTolerance) needImpact = true;  // missed closing
  closed_ = next;
  if (needImpact) {
    impact(t);
    return true;
  }
  return changed;
}

void EventDriven::reset(double t, const double* q, const double* v) {
  t_ = t;
  std::copy(q, q + n_, q_.begin());
  std::copy(v, v + n_, v_.begin());
  eventWindowStart_ = t;
  eventWindowCount_ = 0;
  impact(t);
  restartIntegrator();
  accelerations(t_, q_.data(), v_.data(), true);
}

void EventDriven::advance(double tout) {
  if (tout <= t_) return;
  ERKStepSetStopTime(sun_->mem, tout);
  while (t_ < tout) {
    const int flag = takeStep(tout);
    bool restart = false;
    if (flag == ARK_ROOT_RETURN) {
      handleRoots();
      countEvent();
      restart = true;
    }
    if (reclassify(t_)) {
      countEvent();
      restart = true;
    }
    Failure why;
    if (!sys_.healthy(t_, q_.data(), v_.data(), why)) throw IntegrationError(t_, why);
    checkEventRate();
    // a new contact configuration is a new smooth phase: the integrator starts afresh from the
    // state after the event, with the root functions of the new configuration
    if (restart) {
      restartIntegrator();
      ERKStepSetStopTime(sun_->mem, tout);
    }
  }
  if (!accelerations(t_, q_.data(), v_.data(), true)) throw IntegrationError(t_, lastFailure_);
}

// One step of the integrator towards tout (to a root where one is found); the state after it in
// t_, q_, v_ and the energy accumulators. Returns the solver's flag (ARK_ROOT_RETURN at a root).
int EventDriven::takeStep(double tout) {
  double t = t_;
  // cleared, so that a failure the right-hand side reports during this step is told from the
  // solver's own
  lastFailure_.kind = FailureKind::Other;
  lastFailure_.reason.clear();  // keeps its capacity
  const int flag = ERKStepEvolve(sun_->mem, tout, sun_->y->v, &t, ARK_ONE_STEP);
  if (flag < 0) throwStepFailure(flag);
  ++stats_.steps;
  t_ = t;
  const double* y = sun_->y->data();
  std::copy(y, y + n_, q_.begin());
  std::copy(y + n_, y + 2 * n_, v_.begin());
  inputWork_ = y[2 * n_];
  dissipated_ = y[2 * n_ + 1];
  return flag;
}

// A failed step: the right-hand side's own failure (its constraint problem) where it reported
// one, else the solver's flag and message; at the solver's current time.
void EventDriven::throwStepFailure(int flag) {
  const Failure why = lastFailure_.reason.empty()
                          ? Failure{sundialsFailureKind(flag),
                                    std::string("ARKODE flag ") + std::to_string(flag) + ": " + solverMessage_}
                          : lastFailure_;
  double tcur = t_;
  ERKStepGetCurrentTime(sun_->mem, &tcur);
  throw IntegrationError(tcur, why);
}

// The events at a root (root functions in setupRoots' order: the closing gap, the sliding
// contacts, the sticking ones): mode changes first, then the impact, which classifies the
// contacts anew.
void EventDriven::handleRoots() {
  rootInfo_.assign(1 + sliding_.size() + sticking_.size(), 0);
  ERKStepGetRootInfo(sun_->mem, rootInfo_.data());
  stickWhereSlidingStopped();
  if (!sticking_.empty()) slideWhereFrictionSaturated();
  if (rootInfo_[0] != 0) impact(t_);
}

// Sliding contacts whose sliding velocity reached zero stick.
void EventDriven::stickWhereSlidingStopped() {
  for (std::size_t k = 0; k < sliding_.size(); ++k)
    if (rootInfo_[1 + k] != 0)
      for (Closed& c : closed_)
        if (c.id == sliding_[k]) c.mode = Mode::Stick;
}

// The friction force of sticking contacts reached the static cone: they slide against it, with
// kinetic friction (the forces at the current state tell the direction).
void EventDriven::slideWhereFrictionSaturated() {
  accelerations(t_, q_.data(), v_.data(), true);
  for (std::size_t k = 0; k < sticking_.size(); ++k) {
    if (rootInfo_[1 + sliding_.size() + k] == 0) continue;
    for (const ContactForce& f : forces_)
      if (f.id == sticking_[k])
        for (Closed& c : closed_)
          if (c.id == f.id) {
            c.mode = Mode::Slide;
            c.sign = f.fT > 0.0 ? -1.0 : 1.0;
          }
  }
}

void EventDriven::countEvent() {
  ++stats_.events;
  ++eventWindowCount_;
}

// The event rate over the last batch of events: above the limit, the events run away (an
// accumulation the safeguards do not end) and the run fails instead of crawling on.
void EventDriven::checkEventRate() {
  if (eventWindowCount_ < kEventBatch) return;
  const double span = t_ - eventWindowStart_;
  if (static_cast<double>(eventWindowCount_) > settings_.maxEventsPerSecond * span) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "runaway events: %lld events in %.3g s (%.3g per s; limit %.3g per s)",
                  eventWindowCount_, span, span > 0.0 ? static_cast<double>(eventWindowCount_) / span : HUGE_VAL,
                  settings_.maxEventsPerSecond);
    throw IntegrationError(t_, FailureKind::RunawayEvents, buf);
  }
  eventWindowStart_ = t_;
  eventWindowCount_ = 0;
}

}  // namespace chaindrive::ns
