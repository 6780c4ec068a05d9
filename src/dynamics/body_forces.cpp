#include "dynamics/body_forces.h"

#include <algorithm>
#include <cmath>

#include "linear/array_loops.h"

namespace chaindrive {

TensionerResult tensionerForce(const TensionerModel& t, Vec2 pivot, double cosA, double sinA, double rate) {
  TensionerResult r;
  const Vec2 arm = rotate(t.pad - pivot, cosA, sinA);
  const Vec2 pad = pivot + arm;
  const double s = dot(pad - t.housing, t.direction);
  const double sDot = dot(crossWz(rate, arm), t.direction);
  const double spring = t.preload + t.stiffness * (t.nominalStroke - s);
  const double c = sDot < 0.0 ? t.dampingRetract : t.dampingExtend;
  const double f = std::max(0.0, spring - c * sDot);
  r.force = f;
  r.stroke = s - t.nominalStroke;
  r.rate = sDot;
  r.torque = cross(arm, f * t.direction);
  r.power = (std::max(0.0, spring) - f) * sDot;
  if (t.stiffness > 0.0) r.energy = spring > 0.0 ? spring * spring / (2.0 * t.stiffness) : 0.0;
  else r.energy = -t.preload * (s - t.nominalStroke);
  return r;
}

void evaluateBodyForces(const Model& m, Data& d, double& powerInput, double& powerDissipated) {
  const int n = m.chain.links;
  // link weight
  const Vec2 w = m.chain.mass * m.gravity;
  if (w.x != 0.0) addConstant(&d.gen[m.linkGen(0, Model::kX)], w.x, n);  // (component by component)
  if (w.y != 0.0) addConstant(&d.gen[m.linkGen(0, Model::kY)], w.y, n);
  TensionerResult t;
  evaluateRotorForces(m, d.inputs, d.rotorCos.data(), d.rotorSin.data(), d.rotorRate.data(), d.gen.data() + m.rotorGen(0), t,
                      powerInput, powerDissipated);
  if (m.tensioner.present) {
    d.tensionerForce = t.force;
    d.tensionerStroke = t.stroke;
    d.tensionerRate = t.rate;
  }
}

void evaluateRotorForces(const Model& m, const InputValues& in, const double* cosA, const double* sinA,
                         const double* rate, double* rotorGen, TensionerResult& tensioner, double& powerInput,
                         double& powerDissipated) {
  // guides: pivot friction and weight
  for (const GuideModel& g : m.guides) {
    if (g.rotor < 0) continue;
    const double w = rate[g.rotor];
    rotorGen[g.rotor] -= g.pivotDamping * w;
    powerDissipated += g.pivotDamping * w * w;
    if (g.mass > 0.0) {
      const Vec2 arm = rotate(g.centerOfMass - g.pivot, cosA[g.rotor], sinA[g.rotor]);
      rotorGen[g.rotor] += cross(arm, g.mass * m.gravity);
    }
  }
  // tensioner
  if (m.tensioner.present) {
    const int r = m.tensioner.rotor;
    tensioner = tensionerForce(m.tensioner, m.rotors[r].axis, cosA[r], sinA[r], rate[r]);
    rotorGen[r] += tensioner.torque;
    powerDissipated += tensioner.power;
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
    e += tensionerForce(m.tensioner, m.rotors[r].axis, d.rotorCos[r], d.rotorSin[r], d.rotorRate[r]).energy;
  }
  return e;
}

}  // namespace chaindrive
