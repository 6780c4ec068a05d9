#include "nonsmooth/rigid_drive.h"

#include <cmath>

#include "dynamics/pin_sheave.h"
#include "dynamics/contact_kinematics.h"
#include "dynamics/dynamics.h"
#include "dynamics/health.h"

namespace chaindrive {

namespace {

long long contactId(const ContactPoint& c) {
  const long long kind = static_cast<long long>(c.kind);
  return ((((kind * 16384 + c.link) * 2 + c.end) * 256 + c.element) * 256) + (c.face < 0 ? 255 : c.face);
}

// the same contact pair re-evaluated at another state (for the acceleration terms)
bool sameContact(const Model& m, const ContactPoint& id, const Data& d, double margin, ContactPoint& out) {
  const LinkKin& lk = d.links[id.link];
  const int r = id.rotor;
  const double cosA = r >= 0 ? d.rotorCos[r] : 1.0, sinA = r >= 0 ? d.rotorSin[r] : 0.0;
  const double rate = r >= 0 ? d.rotorRate[r] : 0.0, angle = r >= 0 ? d.rotorAngle[r] : 0.0;
  if (id.kind == ContactPoint::Kind::PinSheave) return false;  // (no acceleration terms: time stepping only)
  if (id.kind == ContactPoint::Kind::RollerSprocket)
    return rollerSprocketKinematics(m, id.element, id.link, id.end, lk, angle, cosA, sinA, rate, margin, out);
  return plateGuideKinematics(m, id.element, id.face, id.link, lk, cosA, sinA, rate, margin, out);
}

}  // namespace

RigidContactDrive::RigidContactDrive(std::shared_ptr<const Model> m, const InputSignal& in, bool idealJoints,
                                     const HealthLimits& health, bool rigidPins)
    : model_(std::move(m)), in_(in), ideal_(idealJoints), rigidPins_(rigidPins), health_(health), d_(*model_),
      dp_(*model_) {
  const Model& md = *model_;
  n_ = 3 * md.chain.links + static_cast<int>(md.rotors.size());
  minv_.assign(n_, 0.0);
  for (int i = 0; i < md.chain.links; ++i) {
    minv_[md.linkGen(i, Model::kX)] = minv_[md.linkGen(i, Model::kY)] = 1.0 / md.chain.mass;
    minv_[md.linkGen(i, Model::kGamma)] = 1.0 / md.chain.inertia;
  }
  for (std::size_t r = 0; r < md.rotors.size(); ++r)
    minv_[md.rotorGen(static_cast<int>(r))] = md.rotors[r].prescribed ? 0.0 : 1.0 / md.rotors[r].inertia;
  y_.assign(md.nStates, 0.0);
  yp_.assign(md.nStates, 0.0);
  // a CVT's compliant pins keep the normal force of their axial compliance among the smooth
  // forces, their friction is the constraint (compliant normals, system.h)
  for (Data* d : {&d_, &dp_}) {
    d->compliantContacts = !md.pulleys.empty() && !rigidPins_;
    d->pinFriction = false;
    d->jointForces = !ideal_;
  }
  inputs_.loadTorque.assign(md.rotors.size(), 0.0);
}

void RigidContactDrive::unpack(const double* y, double* q, double* v) const {
  const Model& m = *model_;
  for (int i = 0; i < m.chain.links; ++i)
    for (int k = 0; k < 3; ++k) {
      q[m.linkGen(i, k)] = y[m.linkState(i, k)];
      v[m.linkGen(i, k)] = y[m.linkState(i, 3 + k)];
    }
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    const int g = m.rotorGen(static_cast<int>(r));
    q[g] = y[m.rotors[r].stateAngle];
    if (m.rotors[r].stateRate >= 0) v[g] = y[m.rotors[r].stateRate];
  }
}

void RigidContactDrive::pack(const double* q, const double* v, double* y) const {
  const Model& m = *model_;
  for (int i = 0; i < m.chain.links; ++i)
    for (int k = 0; k < 3; ++k) {
      y[m.linkState(i, k)] = q[m.linkGen(i, k)];
      y[m.linkState(i, 3 + k)] = v[m.linkGen(i, k)];
    }
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    const int g = m.rotorGen(static_cast<int>(r));
    y[m.rotors[r].stateAngle] = q[g];
    if (m.rotors[r].stateRate >= 0) y[m.rotors[r].stateRate] = v[g];
  }
}

void RigidContactDrive::setSmoothStates(const double* y) {
  const int c = model_->stateChamberOil;
  if (c >= 0) y_[c] = y[c];  // (pack leaves it: evaluate() reads it from y_)
}

void RigidContactDrive::smoothStates(double* y) const {
  const int c = model_->stateChamberOil;
  if (c >= 0) y[c] = y_[c];
}

void RigidContactDrive::advanceSmoothStates(double h) {
  const int c = model_->stateChamberOil;
  if (c >= 0) y_[c] += h * d_.chamberOilRate;
}

void RigidContactDrive::prescribed(double t, double* v, double* a) const {
  const Model& m = *model_;
  if (m.drivenRotor < 0) return;
  in_.evaluate(t, inputs_);
  const int g = m.rotorGen(m.drivenRotor);
  v[g] = m.sense * inputs_.crankSpeed;
  a[g] = m.sense * inputs_.crankAcceleration;
}

void RigidContactDrive::evaluate(double t, const double* q, const double* v) {
  pack(q, v, y_.data());
  generalizedForces(*model_, d_, in_, t, y_.data());
}

void RigidContactDrive::forces(double t, const double* q, const double* v, double* h) {
  evaluate(t, q, v);
  for (int i = 0; i < n_; ++i) h[i] = d_.gen[i];
}

double RigidContactDrive::dissipatedPower(double t, const double* q, const double* v) {
  evaluate(t, q, v);
  return d_.powerDissipated;
}

double RigidContactDrive::inputPower(double t, const double* q, const double* v) {
  evaluate(t, q, v);
  return d_.powerInput;
}

void RigidContactDrive::constraints(double t, const double* q, const double* v, double margin, bool accelerations,
                                    ns::ConstraintSet& out) {
  const Model& m = *model_;
  out.clear();
  pack(q, v, y_.data());
  in_.evaluate(t, d_.inputs);
  evaluateKinematics(m, d_, y_.data());
  detectContacts(m, d_, margin);
  last_.assign(d_.contacts.begin(), d_.contacts.begin() + d_.nContacts);
  if (accelerations)
    for (int side = 0; side < 2; ++side) contactsAlongTheMotion(side == 0 ? 1 : -1, probes_[side]);
  for (std::size_t k = 0; k < last_.size(); ++k) {
    ContactPoint& c = last_[k];
    if (c.kind == ContactPoint::Kind::PinSheave)
      out.contacts.push_back(pinContact(c, static_cast<int>(k)));
    else
      out.contacts.push_back(rigidContact(c, static_cast<int>(k), accelerations));
  }
  if (ideal_) idealJointConstraints(accelerations, out);
}

// The contacts of last_ re-evaluated at the state moved by sgn kProbeStep along the motion
// (q +- eps v, t +- eps, at fixed v and prescribed velocities): their relative velocities there
// give the acceleration terms by central differences, gddot = W qddot + wbar.
void RigidContactDrive::contactsAlongTheMotion(int sgn, std::vector<ContactPoint>& dst) {
  const Model& m = *model_;
  const double eps = kProbeStep;
  for (int i = 0; i < m.nStates; ++i) yp_[i] = y_[i];
  for (int i = 0; i < m.chain.links; ++i)
    for (int k = 0; k < 3; ++k) yp_[m.linkState(i, k)] += sgn * eps * y_[m.linkState(i, 3 + k)];
  // prescribed rotors turn on at their rate at t (their acceleration is in W qddot)
  dp_.inputs = d_.inputs;
  for (const RotorModel& r : m.rotors)
    yp_[r.stateAngle] += sgn * eps * (r.prescribed ? m.sense * d_.inputs.crankSpeed : y_[r.stateRate]);
  evaluateKinematics(m, dp_, yp_.data());
  dst.resize(last_.size());
  for (std::size_t k = 0; k < last_.size(); ++k)
    if (!sameContact(m, last_[k], dp_, 1.0, dst[k])) dst[k] = last_[k];
}

// A roller-sprocket or plate-guide contact (tag k) with Newton's impact law and Coulomb friction;
// with the acceleration terms from the probes along the motion.
ns::Contact RigidContactDrive::rigidContact(const ContactPoint& c, int k, bool accelerations) const {
  const Model& m = *model_;
  const ContactLaw& law = c.kind == ContactPoint::Kind::RollerSprocket ? m.rollerSprocket : m.plateGuide;
  ns::Contact out;
  out.id = contactId(c);
  out.gap = c.gap;
  out.tag = k;
  double wl[3], wr;
  wColumn(c, c.normal, wl, wr);
  for (int j = 0; j < 3; ++j) out.wN.add(m.linkGen(c.link, j), wl[j]);
  if (c.rotor >= 0) out.wN.add(m.rotorGen(c.rotor), wr);
  wColumn(c, c.tangent, wl, wr);
  for (int j = 0; j < 3; ++j) out.wT.add(m.linkGen(c.link, j), wl[j]);
  if (c.rotor >= 0) out.wT.add(m.rotorGen(c.rotor), wr);
  out.mu = out.muStatic = law.friction;
  out.restitution = law.restitution;
  if (accelerations) {
    // wbar = d/dt (W(q)^T v) at fixed v: the relative velocities of the same contact pair at
    // the states moved forward and backward along the motion
    const ContactPoint& a = probes_[0][k];
    const ContactPoint& b = probes_[1][k];
    out.wbarN = (a.vN - b.vN) / (2.0 * kProbeStep);
    out.wbarT = (a.vT - b.vT) / (2.0 * kProbeStep);
  }
  return out;
}

// Journal bearings replaced by ideal joints: the front pin of link j is the rear pin of link j+1,
// two bilateral constraints per joint.
void RigidContactDrive::idealJointConstraints(bool accelerations, ns::ConstraintSet& out) const {
  const Model& m = *model_;
  const int n = m.chain.links;
  const double hp = 0.5 * m.chain.pitch;
  for (int j = 0; j < n; ++j) {
    const int k = j + 1 == n ? 0 : j + 1;
    const LinkKin& a = d_.links[j];
    const LinkKin& b = d_.links[k];
    const Vec2 dpos = a.front - b.rear;
    const Vec2 pa = hp * perp(a.e), pb = hp * perp(b.e);
    const Vec2 wbar = -hp * (a.w * a.w * a.e + b.w * b.w * b.e);
    for (int axis = 0; axis < 2; ++axis) {
      ns::Bilateral bl;
      bl.g = axis == 0 ? dpos.x : dpos.y;
      bl.w.add(m.linkGen(j, axis), 1.0);
      bl.w.add(m.linkGen(j, Model::kGamma), axis == 0 ? pa.x : pa.y);
      bl.w.add(m.linkGen(k, axis), -1.0);
      bl.w.add(m.linkGen(k, Model::kGamma), axis == 0 ? pb.x : pb.y);
      bl.wbar = accelerations ? (axis == 0 ? wbar.x : wbar.y) : 0.0;
      out.bilateral.push_back(bl);
    }
  }
}

// A CVT pin in the sheaves (contact tag k). Compliant pins: a compliant normal whose friction
// acts in the sheave plane, radially (along the contact normal) and circumferentially, bounded by
// the pin's axial force at this state. Rigid pins: a
// contact on the running circle (c's gap moved there) with Newton's law and the wedge's friction.
ns::Contact RigidContactDrive::pinContact(ContactPoint& c, int k) {
  const Model& m = *model_;
  const PinSheaveLaw& law = m.pinSheave;
  ns::Contact p;
  p.id = contactId(c);
  p.tag = k;
  if (rigidPins_) {
    c.gap += d_.pulleyFreeRadius[c.element] - d_.pulleyRunningRadius[c.element];
    p.mu = p.muStatic = law.friction / (law.tanWedge * law.cosWedge);
    p.restitution = law.restitution;
  } else {
    p.frictionBound = 0.0;
    if (c.gap < 0.0)
      p.frictionBound = pinFrictionLimit(law, pinSheaveForce(law, m.frictionRegularization, -c.gap, c.vN, c.vT).axial);
  }
  p.gap = c.gap;
  ns::SparseColumn& radial = rigidPins_ ? p.wN : p.wT;
  ns::SparseColumn& circumferential = rigidPins_ ? p.wT : p.wT2;
  for (auto [dir, col] : {std::pair{c.normal, &radial}, std::pair{c.tangent, &circumferential}}) {
    double wl[3], wr;
    wColumn(c, dir, wl, wr);
    for (int j = 0; j < 3; ++j) col->add(m.linkGen(c.link, j), wl[j]);
    col->add(m.rotorGen(c.rotor), wr);
  }
  return p;
}

void RigidContactDrive::contactPoints(const std::vector<ns::ContactForce>& f, std::vector<ContactPoint>& out) const {
  out.clear();
  for (const ns::ContactForce& cf : f) {
    if (cf.tag < 0 || cf.tag >= static_cast<int>(last_.size())) continue;
    ContactPoint c = last_[cf.tag];
    c.fN = cf.fN;
    c.fT = cf.fT;
    if (c.kind == ContactPoint::Kind::PinSheave && !rigidPins_) {  // the law's normal force, two friction directions
      const Model& m = *model_;
      c.fN = c.gap < 0.0 ? pinSheaveForce(m.pinSheave, m.frictionRegularization, -c.gap, c.vN, c.vT).normal : 0.0;
      c.fNFriction = cf.fT;
      c.fT = cf.fT2;
    }
    out.push_back(c);
  }
}

bool RigidContactDrive::healthy(double t, const double* q, const double* v, Failure& why) {
  if (!finiteState(q, n_, why) || !finiteState(v, n_, why)) return false;
  const Model& m = *model_;
  if (m.stateChamberOil >= 0 && !chamberFilled(y_[m.stateChamberOil], t, why)) return false;
  pack(q, v, y_.data());
  evaluateKinematics(m, d_, y_.data());
  // the contacts of the last constraint evaluation (within the step)
  return chainHealthy(
      m, health_, [&](int j) { return norm(d_.links[j].front - d_.links[(j + 1) % m.chain.links].rear); },
      last_.data(), static_cast<int>(last_.size()), t, why);
}

RigidIntegrator::RigidIntegrator(std::shared_ptr<RigidContactDrive> sys, ContactMethod method,
                                 const IntegratorSettings& s)
    : sys_(std::move(sys)), method_(method) {
  q_.assign(sys_->size(), 0.0);
  v_.assign(sys_->size(), 0.0);
  if (method == ContactMethod::TimeStepping) {
    ns::MoreauJeanSettings ms;
    ms.step = s.fixed.step;
    fixedStep_ = s.fixed.step;
    ms.gapTolerance = s.rigid.gapTolerance;
    ms.recordLcpDirectory = s.rigid.recordLcpDirectory;
    ms.recordLcpCount = s.rigid.recordLcpCount;
    ms.frictionFacets = s.rigid.frictionFacets;
    ns_ = std::make_unique<ns::MoreauJean>(*sys_, ms);
  } else if (method == ContactMethod::EventDriven) {
    ns::EventDrivenSettings es;
    es.rtol = s.adaptive.rtol;
    es.atolPosition = s.adaptive.rtol * 1e-3;
    es.atolVelocity = s.adaptive.rtol;
    es.maxStep = s.adaptive.maxStep;
    es.stabilization = 2e4;
    es.reboundThreshold = s.eventDriven.reboundThreshold;
    es.maxEventsPerSecond = s.eventDriven.maxEventsPerSecond;
    es.gapTolerance = s.rigid.gapTolerance;
    es.recordLcpDirectory = s.rigid.recordLcpDirectory;
    es.recordLcpCount = s.rigid.recordLcpCount;
    ns_ = std::make_unique<ns::EventDriven>(*sys_, es);
  } else {
    throw std::invalid_argument("contact method 'compliant' is not a rigid-contact method; allowed: event-driven, "
                                "time-stepping");
  }
}

void RigidIntegrator::reset(double t0, const double* y0) {
  sys_->unpack(y0, q_.data(), v_.data());
  sys_->setSmoothStates(y0);
  const Model& m = sys_->model();
  ns_->setEnergy(y0[m.stateInputWork], y0[m.stateDissipated]);
  ns_->reset(t0, q_.data(), v_.data());
}

void RigidIntegrator::advance(double tout, double* y) {
  const Model& m = sys_->model();
  ns_->advance(tout);
  sys_->pack(ns_->q().data(), ns_->v().data(), y);
  sys_->smoothStates(y);
  y[m.stateInputWork] = ns_->inputWork();
  y[m.stateDissipated] = ns_->dissipated();
}

IntegratorStats RigidIntegrator::stats() const {
  const ns::NsStats& n = contactStats();
  IntegratorStats s;
  s.steps = n.steps;
  s.rhsEvaluations = n.rhsEvaluations;
  return s;
}

const std::vector<double>& RigidIntegrator::jointForces() const {
  return ns_->bilateralForces();
}

const ns::NsStats& RigidIntegrator::contactStats() const { return ns_->stats(); }

void RigidIntegrator::contactPoints(std::vector<ContactPoint>& out) const {
  sys_->contactPoints(ns_->contactForces(), out);
}

}  // namespace chaindrive
