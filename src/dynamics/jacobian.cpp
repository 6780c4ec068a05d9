#include "dynamics/jacobian.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "dynamics/body_forces.h"
#include "dynamics/contact_compliant.h"
#include "dynamics/contact_kinematics.h"
#include "dynamics/dynamics.h"
#include "dynamics/joint_forces.h"
#include "math/elementary.h"

namespace chaindrive {

namespace {

// absolute perturbations per kind of state
constexpr double kDxPosition = 1e-9;   // m
constexpr double kDxAngle = 1e-8;      // rad
constexpr double kDxVelocity = 1e-6;   // m/s
constexpr double kDxRate = 1e-5;       // rad/s
constexpr double kDxOil = 1e-9;       // of the chamber's volume (about 1 Pa at the oil's modulus)

double perturbation(const Model& m, int state) {
  if (state < 6 * m.chain.links) {
    const int k = state / m.chain.links;  // the link component (model.h)
    return k < 2 ? kDxPosition : k == 2 ? kDxAngle : k < 5 ? kDxVelocity : kDxRate;
  }
  for (const auto& r : m.rotors) {
    if (state == r.stateAngle) return kDxAngle;
    if (state == r.stateRate) return kDxRate;
  }
  if (state == m.stateChamberOil) return kDxOil * m.tensioner.hydraulic.chamberVolume;
  return 1e-6;
}

// A hydraulic tensioner's chamber at state y with its guide at angle (cos, sin): filled from its
// content (held as d's in statics); the supply and viscosity of d.
ChamberState chamberAt(const Model& m, const Data& d, const double* y, double cosA, double sinA) {
  ChamberState c = d.chamber;
  if (m.stateChamberOil >= 0)
    fillChamber(m.tensioner, m.rotors[m.tensioner.rotor].axis, cosA, sinA, y[m.stateChamberOil], c);
  c.supplyPressure = d.inputs.supplyPressure;
  return c;
}

// Angle, its cosine and sine, and rate of rotor r in state y (the driven rotor's rate is the
// crankshaft input).
void rotorState(const Model& m, const Data& d, const double* y, int r, double& angle, double& c, double& s,
                double& rate) {
  const RotorModel& ro = m.rotors[r];
  angle = y[ro.stateAngle];
  c = math::cos(angle);
  s = math::sin(angle);
  rate = ro.prescribed ? m.sense * d.inputs.crankSpeed : y[ro.stateRate];
}

}  // namespace

JacobianAssembler::JacobianAssembler(const Model& m) {
  const int n = m.chain.links;
  const int ns = m.nStates;
  std::vector<std::set<int64_t>> colRows(ns);
  auto add = [&](int row, int col) { colRows[col].insert(row); };
  for (int i = 0; i < ns; ++i) add(i, i);
  std::vector<int> rotorStates;
  for (const auto& r : m.rotors) {
    rotorStates.push_back(r.stateAngle);
    if (r.stateRate >= 0) rotorStates.push_back(r.stateRate);
  }
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) add(m.linkState(i, k), m.linkState(i, 3 + k));
    for (int nb : {(i + n - 1) % n, i, (i + 1) % n})
      for (int k = 0; k < 6; ++k)
        for (int r = 3; r < 6; ++r) add(m.linkState(i, r), m.linkState(nb, k));
    for (int s : rotorStates)
      for (int r = 3; r < 6; ++r) add(m.linkState(i, r), s);
  }
  for (const auto& r : m.rotors) {
    if (r.prescribed) continue;
    add(r.stateAngle, r.stateRate);
    for (int c = 0; c < 6 * n; ++c) add(r.stateRate, c);
    for (int s : rotorStates) add(r.stateRate, s);
  }
  // a hydraulic tensioner's chamber and its guide: the guide's torque over the oil content, the
  // content's rate over the guide's angle (and the content: the diagonal)
  if (m.stateChamberOil >= 0) {
    const RotorModel& guide = m.rotors[m.tensioner.rotor];
    add(guide.stateRate, m.stateChamberOil);
    add(m.stateChamberOil, guide.stateAngle);
  }
  colPtr_.assign(ns + 1, 0);
  for (int c = 0; c < ns; ++c) {
    colPtr_[c + 1] = colPtr_[c] + static_cast<int64_t>(colRows[c].size());
    for (int64_t r : colRows[c]) rows_.push_back(r);
  }
  yWork_.assign(ns, 0.0);
}

int JacobianAssembler::find(int64_t row, int64_t col) const {
  const auto b = rows_.begin() + colPtr_[col], e = rows_.begin() + colPtr_[col + 1];
  const auto it = std::lower_bound(b, e, row);
  return (it != e && *it == row) ? static_cast<int>(it - rows_.begin()) : -1;
}

int JacobianAssembler::genRow(const Model& m, int gen) const {
  const int n3 = 3 * m.chain.links;
  if (gen < n3) return n3 + gen;  // the velocity of a link coordinate (model.h)
  return m.rotors[gen - n3].stateRate;  // -1 for the driven rotor
}

// Calls sink(gen, col, dQ/dy) for every element derivative at the state in yWork_: each
// element's generalized forces, differenced over the few states it depends on.
template <class Sink>
void JacobianAssembler::differentiate(const Model& m, Data& d, double /*t*/, Sink&& sink) {
  differentiateJoints(m, sink);
  differentiateContacts(m, d, sink);
  differentiateRotorElements(m, d, sink);
}

// Joint j couples link j and its successor: 6 forces over their 12 states.
template <class Sink>
void JacobianAssembler::differentiateJoints(const Model& m, Sink& sink) {
  const int n = m.chain.links;
  double* y = yWork_.data();
  for (int j = 0; j < n; ++j) {
    const int k = j + 1 == n ? 0 : j + 1;
    auto eval = [&](double out[6]) {
      const LinkKin a = linkKinematics(m, y, j), b = linkKinematics(m, y, k);
      const JointResult r = jointForce(m.chain, a, b);
      std::fill(out, out + 6, 0.0);
      addJointGen(a, b, r.force, out, out + 3);
    };
    double base[6], pert[6];
    eval(base);
    for (int side = 0; side < 2; ++side) {
      const int link = side == 0 ? j : k;
      for (int q = 0; q < 6; ++q) {
        const int col = m.linkState(link, q);
        const double h = perturbation(m, col), keep = y[col];
        y[col] = keep + h;
        eval(pert);
        y[col] = keep;
        for (int g = 0; g < 6; ++g) {
          const double dq = (pert[g] - base[g]) / h;
          if (dq != 0.0) sink(m.linkGen(g < 3 ? j : k, g % 3), col, dq);
        }
      }
    }
  }
}

// The contacts closed at the current state: the link's force and torque and the reaction torque
// on the contact's rotor, over the link's 6 states and the rotor's angle and rate.
template <class Sink>
void JacobianAssembler::differentiateContacts(const Model& m, const Data& d, Sink& sink) {
  double* y = yWork_.data();
  for (int ci = 0; ci < d.nContacts; ++ci) {
    const ContactPoint id = d.contacts[ci];
    const int r = id.rotor;
    auto eval = [&](double out[4]) {
      ContactPoint c;
      const LinkKin lk = linkKinematics(m, y, id.link);
      double angle = 0, cs = 1, sn = 0, rate = 0;
      if (r >= 0) rotorState(m, d, y, r, angle, cs, sn, rate);
      bool ok;
      if (id.kind == ContactPoint::Kind::RollerSprocket)
        ok = rollerSprocketKinematics(m, id.element, id.link, id.end, lk, angle, cs, sn, rate, 0.0, c);
      else
        ok = plateGuideKinematics(m, id.element, id.face, id.link, lk, cs, sn, rate, 0.0, c);
      std::fill(out, out + 4, 0.0);
      if (!ok) return;
      const ContactLaw& law = c.kind == ContactPoint::Kind::RollerSprocket ? m.rollerSprocket : m.plateGuide;
      compliantContactForce(law, m.frictionRegularization, c);
      const Vec2 f = c.fN * c.normal + c.fT * c.tangent;
      out[0] = f.x;
      out[1] = f.y;
      out[2] = cross(c.rLink, f);
      out[3] = c.rotor >= 0 ? -cross(c.rRotor, f) : 0.0;
    };
    int cols[8];
    int nc = 0;
    for (int q = 0; q < 6; ++q) cols[nc++] = m.linkState(id.link, q);
    if (r >= 0) {
      cols[nc++] = m.rotors[r].stateAngle;
      if (m.rotors[r].stateRate >= 0) cols[nc++] = m.rotors[r].stateRate;
    }
    double base[4], pert[4];
    eval(base);
    for (int q = 0; q < nc; ++q) {
      const int col = cols[q];
      const double h = perturbation(m, col), keep = y[col];
      y[col] = keep + h;
      eval(pert);
      y[col] = keep;
      for (int g = 0; g < 4; ++g) {
        if (g == 3 && r < 0) continue;
        const double dq = (pert[g] - base[g]) / h;
        if (dq != 0.0) sink(g < 3 ? m.linkGen(id.link, g) : m.rotorGen(r), col, dq);
      }
    }
  }
}

// The guides' own torques (tensioner, pivot damping and weight) over their angle and rate.
template <class Sink>
void JacobianAssembler::differentiateRotorElements(const Model& m, const Data& d, Sink& sink) {
  double* y = yWork_.data();
  for (const GuideModel& g : m.guides) {
    if (g.rotor < 0) continue;
    const RotorModel& ro = m.rotors[g.rotor];
    auto eval = [&]() {
      double angle, cs, sn, rate;
      rotorState(m, d, y, g.rotor, angle, cs, sn, rate);
      double tq = -g.pivotDamping * rate;
      if (g.mass > 0.0) tq += cross(rotate(g.centerOfMass - g.pivot, cs, sn), g.mass * m.gravity);
      if (m.tensioner.present && m.tensioner.rotor == g.rotor)
        tq += tensionerForce(m.tensioner, ro.axis, cs, sn, rate, chamberAt(m, d, y, cs, sn)).torque;
      return tq;
    };
    const double base = eval();
    const bool chamber = m.stateChamberOil >= 0 && m.tensioner.rotor == g.rotor;
    for (int col : {ro.stateAngle, ro.stateRate, chamber ? m.stateChamberOil : -1}) {
      if (col < 0) continue;
      const double h = perturbation(m, col), keep = y[col];
      y[col] = keep + h;
      const double dq = (eval() - base) / h;
      y[col] = keep;
      if (dq != 0.0) sink(m.rotorGen(g.rotor), col, dq);
    }
  }
}

// A hydraulic tensioner's chamber: its content's rate over the guide's angle and the content,
// into the chamber's row of values.
void JacobianAssembler::differentiateChamber(const Model& m, const Data& d, double* values) {
  if (m.stateChamberOil < 0) return;
  double* y = yWork_.data();
  const int r = m.tensioner.rotor;
  const RotorModel& ro = m.rotors[r];
  auto rate = [&]() {
    double angle, cs, sn, w;
    rotorState(m, d, y, r, angle, cs, sn, w);
    const ChamberState c = chamberAt(m, d, y, cs, sn);
    return chamberOilRate(m.tensioner, c, tensionerForce(m.tensioner, ro.axis, cs, sn, w, c).flows);
  };
  const double base = rate();
  for (int col : {ro.stateAngle, m.stateChamberOil}) {
    const double h = perturbation(m, col), keep = y[col];
    y[col] = keep + h;
    const double dc = (rate() - base) / h;
    y[col] = keep;
    values[find(m.stateChamberOil, col)] += dc;
  }
}

void JacobianAssembler::assemble(const Model& m, Data& d, const InputSignal& in, double t, const double* y,
                                 double* values) {
  generalizedForces(m, d, in, t, y);  // contacts and inputs at this state
  std::copy(y, y + m.nStates, yWork_.begin());
  std::fill(values, values + nnz(), 0.0);
  const int n = m.chain.links;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) values[find(m.linkState(i, k), m.linkState(i, 3 + k))] = 1.0;
  for (const auto& r : m.rotors)
    if (!r.prescribed) values[find(r.stateAngle, r.stateRate)] = 1.0;
  const double invM = 1.0 / m.chain.mass, invJ = 1.0 / m.chain.inertia;
  differentiateChamber(m, d, values);
  differentiate(m, d, t, [&](int gen, int col, double dq) {
    const int row = genRow(m, gen);
    if (row < 0) return;
    double scale;
    if (gen < 3 * n) scale = gen >= m.linkGen(0, Model::kGamma) ? invJ : invM;
    else scale = 1.0 / m.rotors[gen - 3 * n].inertia;
    const int idx = find(row, col);
    if (idx >= 0) values[idx] += dq * scale;
  });
}

void JacobianAssembler::stiffness(const Model& m, Data& d, const InputSignal& in, double t, const double* y,
                                  const std::vector<int>& freeIndex, Eigen::MatrixXd& K) {
  generalizedForces(m, d, in, t, y);
  std::copy(y, y + m.nStates, yWork_.begin());
  K.setZero();
  const int n = m.chain.links;
  // state column -> generalized coordinate (positions only)
  auto genOfState = [&](int col) -> int {
    if (col < 6 * n) return col < 3 * n ? col : -1;  // link positions: the generalized order (model.h)
    for (std::size_t r = 0; r < m.rotors.size(); ++r)
      if (m.rotors[r].stateAngle == col) return m.rotorGen(static_cast<int>(r));
    return -1;
  };
  differentiate(m, d, t, [&](int gen, int col, double dq) {
    const int gc = genOfState(col);
    if (gc < 0) return;
    const int r = freeIndex[gen], c = freeIndex[gc];
    if (r >= 0 && c >= 0) K(r, c) += dq;
  });
}

}  // namespace chaindrive
