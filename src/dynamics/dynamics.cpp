#include "dynamics/dynamics.h"

#include <algorithm>
#include <cmath>

#include "dynamics/pin_sheave.h"
#include "dynamics/body_forces.h"
#include "dynamics/contact_compliant.h"
#include "dynamics/contact_kinematics.h"
#include "dynamics/joint_forces.h"
#include "dynamics/link_loops.h"
#include "linear/array_loops.h"
#include "math/elementary.h"

namespace chaindrive {

// Every work array sized once here: the contacts for every link against every sprocket and
// guide face (the most detectContacts can find), so that no evaluation allocates.
LinkArrays::LinkArrays(int n) : links(n) {
  for (std::vector<double>* a : {&cx, &cy, &vx, &vy, &w, &ex, &ey, &rearX, &rearY, &frontX, &frontY, &vRearX, &vRearY,
                                 &vFrontX, &vFrontY})
    a->assign(static_cast<std::size_t>(n + kPadding), 0.0);
}

JointArrays::JointArrays(int joints)
    : tension(joints, 0.0),
      deformation(joints, 0.0),
      joints_(joints),
      fx_(static_cast<std::size_t>(joints + 1 + LinkArrays::kPadding), 0.0),
      fy_(static_cast<std::size_t>(joints + 1 + LinkArrays::kPadding), 0.0) {}

void JointArrays::setForce(int j, Vec2 f) {
  fx_[j + 1] = f.x;
  fy_[j + 1] = f.y;
  if (j == joints_ - 1) {  // (its copy in front of the first joint)
    fx_[0] = f.x;
    fy_[0] = f.y;
  }
}

RollerHints::RollerHints(int sprockets, int pins)
    : stride(pins + LinkArrays::kPadding),
      gap(static_cast<std::size_t>(sprockets * stride), -1),
      gapX(gap.size(), std::nan("")),
      gapY(gap.size(), std::nan("")),
      fromX(gap.size(), std::nan("")),
      fromY(gap.size(), std::nan("")),
      toX(gap.size(), std::nan("")),
      toY(gap.size(), std::nan("")),
      bodyX(gap.size(), 0.0),
      bodyY(gap.size(), 0.0),
      clearance(gap.size(), -1.0) {}

void RollerHints::setGap(int h, const SprocketModel& s, int gapIndex) {
  gap[h] = gapIndex;
  const int z = static_cast<int>(s.gapDirs.size());
  const bool known = gapIndex >= 0 && gapIndex < z;
  const Vec2 none{std::nan(""), std::nan("")};
  const Vec2 axis = known ? s.gapDirs[gapIndex] : none;
  const Vec2 from = known ? s.toothDirs[gapIndex] : none;
  const Vec2 to = known ? s.toothDirs[gapIndex + 1 == z ? 0 : gapIndex + 1] : none;
  gapX[h] = axis.x, gapY[h] = axis.y;
  fromX[h] = from.x, fromY[h] = from.y;
  toX[h] = to.x, toY[h] = to.y;
}

SearchWindows::SearchWindows(int links, int sprockets, int guides)
    : blocks((links + kBlock - 1) / kBlock),
      words((blocks + 63) / 64),
      centerX(static_cast<std::size_t>(links + LinkArrays::kPadding), 0.0),
      centerY(centerX.size(), 0.0),
      axisX(centerX.size(), 0.0),
      axisY(centerX.size(), 0.0),
      boundX(static_cast<std::size_t>(guides), 0.0),
      boundY(static_cast<std::size_t>(guides), 0.0),
      windows(static_cast<std::size_t>((sprockets + guides) * words), 0) {}

Data::Data(const Model& m)
    : links(m.chain.links),
      joints(m.chain.links),
      vectorLanes(supportedVectorLanes()),
      windows(m.chain.links, static_cast<int>(m.sprockets.size()), static_cast<int>(m.guides.size())),
      rollerHints(static_cast<int>(m.sprockets.size()), m.chain.links) {
  inputs.loadTorque.assign(m.rotors.size(), 0.0);
  chamber.viscosity = tensionerOilViscosity(m.tensioner);
  for (const PulleyModel& p : m.pulleys) {
    pulleyFreeRadius.push_back(p.freeRadius);
    pulleyRunningRadius.push_back(p.runningRadius);
  }
  rotorAngle.assign(m.rotors.size(), 0.0);
  rotorChainTorque.assign(m.rotors.size(), 0.0);
  rotorRate.assign(m.rotors.size(), 0.0);
  rotorCos.assign(m.rotors.size(), 1.0);
  rotorSin.assign(m.rotors.size(), 0.0);
  std::size_t faces = 0;
  for (const auto& g : m.guides) faces += g.faces.size();
  placedFaces.resize(faces);
  guideBoundX.assign(m.guides.size(), 0.0);
  guideBoundY.assign(m.guides.size(), 0.0);
  guideReach2.assign(m.guides.size(), 0.0);
  contacts.resize(static_cast<std::size_t>(m.chain.links) * (m.sprockets.size() + faces + m.pulleys.size()));
  gen.assign(m.nGen, 0.0);
  contactDamping.assign(3 * static_cast<std::size_t>(m.chain.links), 0.0);
  dampingWork.assign(5 * static_cast<std::size_t>(m.chain.links + 1 + LinkArrays::kPadding), 0.0);
}

void Data::useThreads(const Model& m, StagePool* pool) {
  threads = ThreadedWork{};
  if (!pool || pool->size() == 1) return;
  const int n = m.chain.links, count = pool->size();
  threads.pool = pool;
  threads.parts.resize(static_cast<std::size_t>(count));
  for (ThreadPart& part : threads.parts) {
    part.blocks.assign(static_cast<std::size_t>(windows.words), 0);
    part.plates.resize(placedFaces.size() * static_cast<std::size_t>(n));
    part.plateCount.assign(placedFaces.size(), 0);
  }
  // (contiguous parts: fewer cache lines that two threads write than parts dealt round the threads,
  // which ran slower; each part ends on whole vectors and search blocks)
  const int share = ((n + count - 1) / count + 3) / 4 * 4;
  for (int t = 0; t < count && t * share < n; ++t) {
    ThreadPart& part = threads.parts[static_cast<std::size_t>(t)];
    const LinkRange r{t * share, std::min(n, (t + 1) * share)};
    part.ranges.push_back(r);
    for (int b = r.first / SearchWindows::kBlock; b * SearchWindows::kBlock < r.last; ++b)
      part.blocks[static_cast<std::size_t>(b / 64)] |= std::uint64_t{1} << (b % 64);
  }
  threads.jointPower.assign(static_cast<std::size_t>(n + LinkArrays::kPadding), 0.0);
  threads.pinTorque.assign(rollerHints.gap.size(), 0.0);
  threads.pinPower.assign(rollerHints.gap.size(), 0.0);
}

// Stages 1-5 of dynamics.h, the generalized forces summed into d.gen and the powers kept.
void generalizedForces(const Model& m, Data& d, const InputSignal& in, double t, const double* y) {
  ++d.rhsEvaluations;
  in.evaluate(t, d.inputs);
  evaluateKinematics(m, d, y);
  // the joints write the links' generalized forces, the later stages add to them
  const auto rotorGen = d.gen.begin() + m.rotorGen(0);
  std::fill(rotorGen, d.gen.end(), 0.0);
  double pIn = 0.0, pDiss = 0.0;
  if (d.jointForces) pDiss += evaluateJoints(m, d);
  else std::fill(d.gen.begin(), rotorGen, 0.0);
  if (d.compliantContacts) {
    pDiss += detectContacts(m, d, 0.0, true);
  } else {
    d.nContacts = 0;
  }
  addLinkWeight(m, d, {0, m.chain.links});
  rotorStage(m, d, y, pIn, pDiss);
}

void rotorStage(const Model& m, Data& d, const double* y, double powerInput, double powerDissipated) {
  // the chain's torques on the rotors before the bodies' own forces join them (the joints and the
  // links' weight touch the links' entries only)
  std::copy(d.gen.begin() + m.rotorGen(0), d.gen.end(), d.rotorChainTorque.begin());
  if (m.stateChamberOil >= 0) {
    const int r = m.tensioner.rotor;
    fillChamber(m.tensioner, m.rotors[r].axis, d.rotorCos[r], d.rotorSin[r], y[m.stateChamberOil], d.chamber);
  }
  evaluateRotorBodyForces(m, d, powerInput, powerDissipated);
  d.powerInput = powerInput;
  d.powerDissipated = powerDissipated;
}

void forwardCompliant(const Model& m, Data& d, const InputSignal& in, double t, const double* y, double* ydot) {
  generalizedForces(m, d, in, t, y);
  linkDerivatives(m, d, y, ydot, {0, m.chain.links});
  otherDerivatives(m, d, y, ydot);
}

void linkDerivatives(const Model& m, const Data& d, const double* y, double* ydot, LinkRange r) {
  // positions move with their velocities, velocities with force over mass (diagonal)
  const int n = m.chain.links, count = r.last - r.first;
  const double invM = 1.0 / m.chain.mass, invJ = 1.0 / m.chain.inertia;
  for (int k = 0; k < 3; ++k) std::copy(y + (3 + k) * n + r.first, y + (3 + k) * n + r.last, ydot + k * n + r.first);
  const double* g = d.gen.data();
  double* a = ydot + 3 * n;
  for (int k = 0; k < 3; ++k) scaleInto(a + k * n + r.first, g + k * n + r.first, k < 2 ? invM : invJ, count);
}

void otherDerivatives(const Model& m, const Data& d, const double* y, double* ydot) {
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
  if (m.stateChamberOil >= 0) ydot[m.stateChamberOil] = d.chamberOilRate;
  accumulateImpulses(m.chainImpulse, d.rotorChainTorque, ydot);
}

EnergyTerms energyTerms(const Model& m, const Data& d, const double* y) {
  EnergyTerms e;
  const int n = m.chain.links;
  for (int i = 0; i < n; ++i) {
    const double vx = y[m.linkState(i, Model::kVx)], vy = y[m.linkState(i, Model::kVy)];
    const double w = y[m.linkState(i, Model::kOmega)];
    e.kinetic += 0.5 * m.chain.mass * (vx * vx + vy * vy) + 0.5 * m.chain.inertia * w * w;
  }
  for (const RotorModel& r : m.rotors)
    if (!r.prescribed) e.kinetic += 0.5 * r.inertia * y[r.stateRate] * y[r.stateRate];
  // elastic: joints, contact penetrations (the Hertz-type law integrated), tensioner and gravity
  e.elastic = d.jointForces ? jointEnergy(m, d) : 0.0;
  for (int i = 0; i < d.nContacts; ++i) {
    const ContactPoint& c = d.contacts[i];
    if (c.gap >= 0.0) continue;
    if (c.kind == ContactPoint::Kind::PinSheave) {
      e.elastic += pinSheaveForce(m.pinSheave, m.frictionRegularization, -c.gap, 0.0, 0.0).energy;
      continue;
    }
    const ContactLaw& law = c.kind == ContactPoint::Kind::RollerSprocket ? m.rollerSprocket : m.plateGuide;
    const double depth = -c.gap;  // (a linear law's integral without pow: the outputs at every 0.1 ms)
    e.elastic += law.exponent == 1.0 ? law.stiffness * (depth * depth) / 2.0
                                     : law.stiffness * math::pow(depth, law.exponent + 1.0) / (law.exponent + 1.0);
  }
  double grav = 0.0;
  e.elastic += bodyPotentialEnergy(m, d, grav);
  e.gravity = grav;
  e.inputWork = y[m.stateInputWork];
  e.dissipated = y[m.stateDissipated];
  return e;
}

}  // namespace chaindrive
