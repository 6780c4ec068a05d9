#include "dynamics/body_forces.h"

#include <algorithm>
#include <cmath>

#include "linear/array_loops.h"
#include "math/elementary.h"

namespace chaindrive {

namespace {

// The spring's energy: its force's integral from zero force (or, without a rate, the preload's work).
double springEnergy(const TensionerModel& t, double spring, double stroke) {
  if (t.stiffness > 0.0) return spring > 0.0 ? spring * spring / (2.0 * t.stiffness) : 0.0;
  return -t.preload * stroke;
}

// The hydraulic tensioner's chamber on the plunger beside its spring: its force, flows and powers
// into r (dynamics/hydraulic_tensioner.h).
double addChamber(const TensionerModel& t, double stroke, const ChamberState& chamber, TensionerResult& r) {
  const HydraulicResult h =
      hydraulicChamber(t.hydraulic, stroke, chamber.pressure, chamber.supplyPressure, chamber.viscosity);
  r.chamberPressure = h.pressure;
  r.flows = h.flows;
  r.supplyPower = h.supplyPower;
  r.power += h.dissipatedPower;
  return h.force;
}

// The compressed oil's energy, p^2 V / (2 K) at the chamber's volume: exact for a constant bulk
// modulus, what the energy balance over a run needs (the oil stores little beside what it passes).
double oilEnergy(const TensionerModel& t, const TensionerResult& r) {
  const double volume = t.hydraulic.chamberVolume + plungerArea(t.hydraulic) * r.stroke;
  const double p = r.chamberPressure;
  return p * p * volume / (2.0 * effectiveBulkModulus(t.hydraulic.oil, p));
}

}  // namespace

double tensionerEnergy(const TensionerModel& t, const TensionerResult& r) {
  return r.energy + (t.kind == TensionerKind::Hydraulic ? oilEnergy(t, r) : 0.0);
}

double heldChamberPotential(const TensionerModel& t, const TensionerResult& r) {
  if (t.kind != TensionerKind::Hydraulic) return 0.0;
  const double s = r.stroke;
  const double beyond = std::max(t.hydraulic.strokeMin - s, s - t.hydraulic.strokeMax);
  const double stops = beyond > 0.0 ? 0.5 * t.hydraulic.endStopStiffness * beyond * beyond : 0.0;
  return -r.chamberPressure * plungerArea(t.hydraulic) * s + stops - oilEnergy(t, r);
}

double tensionerOilViscosity(const TensionerModel& t) {
  return t.hydraulicChamber() ? oilViscosity(t.hydraulic.oil, t.hydraulic.oilTemperature) : 0.0;
}

namespace {

// The pad's position along the plunger's direction from the housing [m].
double padExtension(const TensionerModel& t, Vec2 pivot, Vec2 arm) { return dot(pivot + arm - t.housing, t.direction); }

}  // namespace

double tensionerStroke(const TensionerModel& t, Vec2 pivot, double cosA, double sinA) {
  return padExtension(t, pivot, rotate(t.pad - pivot, cosA, sinA)) - t.nominalStroke;
}

void fillChamber(const TensionerModel& t, Vec2 pivot, double cosA, double sinA, double content,
                 ChamberState& chamber) {
  chamber.ratio = chamberVolume(t.hydraulic, tensionerStroke(t, pivot, cosA, sinA)) / content;
  if (!chamber.held) chamber.pressure = t.chamberOil.pressureAt(chamber.ratio);
}

double chamberOilAt(const TensionerModel& t, Vec2 pivot, double cosA, double sinA, double pressure) {
  return chamberVolume(t.hydraulic, tensionerStroke(t, pivot, cosA, sinA)) / t.chamberOil.volumeRatio(pressure);
}

double chamberOilAtRest(const Model& m, double guideAngle, double supplyPressure) {
  const TensionerModel& t = m.tensioner;
  return chamberOilAt(t, m.rotors[t.rotor].axis, math::cos(guideAngle), math::sin(guideAngle),
                      chamberRestPressure(t.hydraulic, supplyPressure));
}

void holdChamberAtRest(const TensionerModel& t, double supplyPressure, ChamberState& chamber) {
  chamber.held = true;
  chamber.pressure = chamberRestPressure(t.hydraulic, supplyPressure);
}

double chamberOilRate(const TensionerModel& t, const ChamberState& chamber, const HydraulicFlows& flows) {
  return t.chamberOil.contentRate(flows.check - flows.leak - flows.relief, chamber.ratio);
}

TensionerResult tensionerForce(const TensionerModel& t, Vec2 pivot, double cosA, double sinA, double rate,
                               const ChamberState& chamber) {
  TensionerResult r;
  const Vec2 arm = rotate(t.pad - pivot, cosA, sinA);
  const double s = padExtension(t, pivot, arm);
  const double sDot = dot(crossWz(rate, arm), t.direction);
  const double spring = t.preload + t.stiffness * (t.nominalStroke - s);
  r.stroke = s - t.nominalStroke;
  r.rate = sDot;
  r.energy = springEnergy(t, spring, r.stroke);
  double f;
  if (t.kind == TensionerKind::Hydraulic) {
    // the plunger does not pull the guide: the chamber's force (>= 0) and the spring's push it
    f = std::max(0.0, spring + addChamber(t, r.stroke, chamber, r));
  } else {
    const double c = sDot < 0.0 ? t.dampingRetract : t.dampingExtend;
    f = std::max(0.0, spring - c * sDot);
    r.power = (std::max(0.0, spring) - f) * sDot;
  }
  r.force = f;
  r.torque = cross(arm, f * t.direction);
  return r;
}

void addLinkWeight(const Model& m, Data& d, LinkRange r) {
  const Vec2 w = m.chain.mass * m.gravity;
  const int n = r.last - r.first;
  if (w.x != 0.0) addConstant(&d.gen[m.linkGen(r.first, Model::kX)], w.x, n);  // (component by component)
  if (w.y != 0.0) addConstant(&d.gen[m.linkGen(r.first, Model::kY)], w.y, n);
}

void evaluateBodyForces(const Model& m, Data& d, double& powerInput, double& powerDissipated) {
  addLinkWeight(m, d, {0, m.chain.links});
  evaluateRotorBodyForces(m, d, powerInput, powerDissipated);
}

void evaluateRotorBodyForces(const Model& m, Data& d, double& powerInput, double& powerDissipated) {
  TensionerResult t;
  evaluateRotorForces(m, d.inputs, d.rotorCos.data(), d.rotorSin.data(), d.rotorRate.data(), d.chamber,
                      d.gen.data() + m.rotorGen(0), t, powerInput, powerDissipated);
  if (m.tensioner.present) {
    d.tensionerForce = t.force;
    d.tensionerStroke = t.stroke;
    d.tensionerRate = t.rate;
    d.chamberPressure = t.chamberPressure;
    d.tensionerFlows = t.flows;
    if (m.stateChamberOil >= 0) d.chamberOilRate = chamberOilRate(m.tensioner, d.chamber, t.flows);
  }
}

void evaluateRotorForces(const Model& m, const InputValues& in, const double* cosA, const double* sinA,
                         const double* rate, const ChamberState& chamber, double* rotorGen, TensionerResult& tensioner,
                         double& powerInput, double& powerDissipated) {
  // guides: pivot friction, weight and an applied torque (in the guide's output sense)
  for (const GuideModel& g : m.guides) {
    if (g.rotor < 0) continue;
    const double w = rate[g.rotor];
    rotorGen[g.rotor] -= g.pivotDamping * w;
    powerDissipated += g.pivotDamping * w * w;
    const double applied = m.rotorOutputSign[g.rotor] * in.loadTorque[g.rotor];
    rotorGen[g.rotor] += applied;
    powerInput += applied * w;
    if (g.mass > 0.0) {
      const Vec2 arm = rotate(g.centerOfMass - g.pivot, cosA[g.rotor], sinA[g.rotor]);
      rotorGen[g.rotor] += cross(arm, g.mass * m.gravity);
    }
  }
  // tensioner
  if (m.tensioner.present) {
    const int r = m.tensioner.rotor;
    ChamberState oil = chamber;
    oil.supplyPressure = in.supplyPressure;
    tensioner = tensionerForce(m.tensioner, m.rotors[r].axis, cosA[r], sinA[r], rate[r], oil);
    rotorGen[r] += tensioner.torque;
    powerDissipated += tensioner.power;
    powerInput += tensioner.supplyPower;
  }
  // load torques on free sprockets (positive opposes the running direction), drive power
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    const RotorModel& ro = m.rotors[r];
    if (!ro.isSprocket) continue;
    if (ro.prescribed) {
      // the drive holds the prescribed motion against everything acting on the sprocket
      powerInput += -rotorGen[r] * rate[r];
    } else {
      const double tau = -m.sense * in.loadTorque[r];
      rotorGen[r] += tau;
      powerInput += tau * rate[r];
    }
  }
}

double bodyPotentialEnergy(const Model& m, const Data& d, double& gravityEnergy) {
  double e = 0.0;
  gravityEnergy = 0.0;
  for (int i = 0; i < m.chain.links; ++i) gravityEnergy -= m.chain.mass * dot(m.gravity, d.links[i].c);
  for (const GuideModel& g : m.guides) {
    if (g.rotor < 0 || g.mass <= 0.0) continue;
    const Vec2 com = g.pivot + rotate(g.centerOfMass - g.pivot, d.rotorCos[g.rotor], d.rotorSin[g.rotor]);
    gravityEnergy -= g.mass * dot(m.gravity, com);
  }
  if (m.tensioner.present) {
    const int r = m.tensioner.rotor;
    ChamberState oil = d.chamber;
    oil.supplyPressure = d.inputs.supplyPressure;
    e += tensionerEnergy(m.tensioner, tensionerForce(m.tensioner, m.rotors[r].axis, d.rotorCos[r], d.rotorSin[r],
                                                     d.rotorRate[r], oil));
  }
  return e;
}

}  // namespace chaindrive
