#include "dynamics/dynamics.h"

#include <algorithm>
#include <cmath>

#include "dynamics/body_forces.h"
#include "dynamics/contact_compliant.h"
#include "dynamics/contact_kinematics.h"
#include "dynamics/joint_forces.h"

namespace chaindrive {

// Every work array sized once here: the contacts for every link against every sprocket and
// guide face (the most detectContacts can find), so that no evaluation allocates.
Data::Data(const Model& m) {
  inputs.loadTorque.assign(m.rotors.size(), 0.0);
  links.resize(m.chain.links);
  rotorAngle.assign(m.rotors.size(), 0.0);
  rotorRate.assign(m.rotors.size(), 0.0);
  rotorCos.assign(m.rotors.size(), 1.0);
  rotorSin.assign(m.rotors.size(), 0.0);
  joints.resize(m.chain.links);
  std::size_t faces = 0, mostFaces = 0;
  for (const auto& g : m.guides) {
    faces += g.faces.size();
    mostFaces = std::max(mostFaces, g.faces.size());
  }
  placedFaces.resize(mostFaces);
  contacts.resize(static_cast<std::size_t>(m.chain.links) * (m.sprockets.size() + faces));
  gen.assign(m.nGen, 0.0);
  gapHints.assign((m.chain.links + 1) * m.sprockets.size(), -1);
}

// Stages 1-5 of dynamics.h, the generalized forces summed into d.gen and the powers kept.
void generalizedForces(const Model& m, Data& d, const InputSignal& in, double t, const double* y) {
  ++d.rhsEvaluations;
  in.evaluate(t, d.inputs);
  evaluateKinematics(m, d, y);
  std::fill(d.gen.begin(), d.gen.end(), 0.0);
  double pIn = 0.0, pDiss = 0.0;
  if (d.jointForces) pDiss += evaluateJoints(m, d);
  if (d.compliantContacts) {
    detectContacts(m, d, 0.0);
    pDiss += evaluateCompliantContacts(m, d);
  } else {
    d.nContacts = 0;
  }
  evaluateBodyForces(m, d, pIn, pDiss);
  d.powerInput = pIn;
  d.powerDissipated = pDiss;
}

void forwardCompliant(const Model& m, Data& d, const InputSignal& in, double t, const double* y, double* ydot) {
  generalizedForces(m, d, in, t, y);
  // links: positions move with their velocities, velocities with force over mass (diagonal)
  const int n = m.chain.links;
  const double invM = 1.0 / m.chain.mass, invJ = 1.0 / m.chain.inertia;
  for (int i = 0; i < n; ++i) {
    const double* s = y + 6 * i;
    double* o = ydot + 6 * i;
    const double* g = &d.gen[3 * i];
    o[0] = s[3];
    o[1] = s[4];
    o[2] = s[5];
    o[3] = g[0] * invM;
    o[4] = g[1] * invM;
    o[5] = g[2] * invJ;
  }
  // rotors: the driven one follows the crankshaft input, the free ones their torque over inertia
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    const RotorModel& ro = m.rotors[r];
    if (ro.prescribed) {
      ydot[ro.stateAngle] = d.rotorRate[r];
    } else {
      ydot[ro.stateAngle] = y[ro.stateRate];
      ydot[ro.stateRate] = d.gen[m.rotorGen(static_cast<int>(r))] / ro.inertia;
    }
  }
  // the energy accumulators integrate the powers of this evaluation
  ydot[m.stateInputWork] = d.powerInput;
  ydot[m.stateDissipated] = d.powerDissipated;
}

EnergyTerms energyTerms(const Model& m, const Data& d, const double* y) {
  EnergyTerms e;
  const int n = m.chain.links;
  for (int i = 0; i < n; ++i) {
    const double* s = y + 6 * i;
    e.kinetic += 0.5 * m.chain.mass * (s[3] * s[3] + s[4] * s[4]) + 0.5 * m.chain.inertia * s[5] * s[5];
  }
  for (const RotorModel& r : m.rotors)
    if (!r.prescribed) e.kinetic += 0.5 * r.inertia * y[r.stateRate] * y[r.stateRate];
  // elastic: joints, contact penetrations (the Hertz-type law integrated), tensioner and gravity
  e.elastic = d.jointForces ? jointEnergy(m, d) : 0.0;
  for (int i = 0; i < d.nContacts; ++i) {
    const ContactPoint& c = d.contacts[i];
    if (c.gap >= 0.0) continue;
    const ContactLaw& law = c.kind == ContactPoint::Kind::RollerSprocket ? m.rollerSprocket : m.plateGuide;
    e.elastic += law.stiffness * std::pow(-c.gap, law.exponent + 1.0) / (law.exponent + 1.0);
  }
  double grav = 0.0;
  e.elastic += bodyPotentialEnergy(m, d, grav);
  e.gravity = grav;
  e.inputWork = y[m.stateInputWork];
  e.dissipated = y[m.stateDissipated];
  return e;
}

}  // namespace chaindrive
