#include "span/span_dynamics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dynamics/body_forces.h"
#include "math/elementary.h"

namespace chaindrive::span {

SpanData::SpanData(const SpanModel& m) {
  const std::size_t nr = m.links->rotors.size();
  inputs.loadTorque.assign(nr, 0.0);
  chamber.viscosity = tensionerOilViscosity(m.links->tensioner);
  rotorAngle.assign(nr, 0.0);
  rotorRate.assign(nr, 0.0);
  rotorCos.assign(nr, 1.0);
  rotorSin.assign(nr, 0.0);
  chainTorque.assign(nr, 0.0);
  rotorGen.assign(nr, 0.0);
  faceAngle.assign(m.tables.size(), 0.0);
  faceRate.assign(m.tables.size(), 0.0);
  spans.resize(m.spans.size());
  for (std::size_t i = 0; i < m.spans.size(); ++i) spans[i].factor.assign(m.spans[i].parts.size(), 1.0);
}

namespace {

// Cubic Hermite interpolation of the span length and its slope; linear for the torque
// coefficients. Angles outside the table take its end values (the health check stops such runs).
struct TableValue {
  double length, slope, torqueIn, torqueOut;
};

TableValue lookUp(const GuideTable& t, double psi) {
  const int last = static_cast<int>(t.length.size()) - 1;
  double u = (psi - t.angle0) / t.dAngle;
  u = std::min(std::max(u, 0.0), static_cast<double>(last));
  const int i = std::min(static_cast<int>(u), last - 1);
  const double f = u - i, h = t.dAngle;
  const double h00 = (1.0 + 2.0 * f) * (1.0 - f) * (1.0 - f), h10 = f * (1.0 - f) * (1.0 - f);
  const double h01 = f * f * (3.0 - 2.0 * f), h11 = f * f * (f - 1.0);
  TableValue v;
  v.length = h00 * t.length[i] + h10 * h * t.slope[i] + h01 * t.length[i + 1] + h11 * h * t.slope[i + 1];
  const double dh00 = 6.0 * f * (f - 1.0), dh10 = (1.0 - f) * (1.0 - 3.0 * f);
  const double dh01 = 6.0 * f * (1.0 - f), dh11 = f * (3.0 * f - 2.0);
  v.slope = (dh00 * t.length[i] + dh01 * t.length[i + 1]) / h + dh10 * t.slope[i] + dh11 * t.slope[i + 1];
  v.torqueIn = (1.0 - f) * t.torqueIn[i] + f * t.torqueIn[i + 1];
  v.torqueOut = (1.0 - f) * t.torqueOut[i] + f * t.torqueOut[i + 1];
  return v;
}

void rotorKinematics(const SpanModel& m, SpanData& d, const double* y) {
  const Model& lm = *m.links;
  for (std::size_t r = 0; r < lm.rotors.size(); ++r) {
    const double a = y[m.stateAngle[r]];
    d.rotorAngle[r] = a;
    if (!lm.rotors[r].isSprocket) {  // only guides need them (tensioner, weight)
      d.rotorCos[r] = math::cos(a);
      d.rotorSin[r] = math::sin(a);
    }
    d.rotorRate[r] = lm.rotors[r].prescribed ? lm.sense * d.inputs.crankSpeed : y[m.stateRate[r]];
  }
}

// Span i's ends: the chain passed over its end sprockets (st.passed), their effective radii and
// speeds, and the capstan factors its guides give (they hang on the chain's speed alone). Nothing
// here hangs on the guide's face angle, so a seat's solve (seatFace) does it once.
void spanEnds(const SpanModel& m, SpanData& d, int i) {
  const Model& lm = *m.links;
  const Span& sp = m.spans[i];
  SpanState& st = d.spans[i];
  const double sense = lm.sense;
  const double thA = sense * (d.rotorAngle[sp.from.rotor] - lm.rotors[sp.from.rotor].initialAngle);
  const double thB = sense * (d.rotorAngle[sp.to.rotor] - lm.rotors[sp.to.rotor].initialAngle);
  const double sA = chainPassed(sp.from, thA, st.radiusFrom), sB = chainPassed(sp.to, thB, st.radiusTo);
  st.passed = sA - sB;
  st.speedFrom = st.radiusFrom * sense * d.rotorRate[sp.from.rotor];
  st.speedTo = st.radiusTo * sense * d.rotorRate[sp.to.rotor];
  st.speed = 0.5 * (st.speedFrom + st.speedTo);
  st.centrifugal = m.chainDensity * st.speed * st.speed;
  const double mu = m.guideFriction * st.speed / std::sqrt(st.speed * st.speed +
                                                           m.frictionRegularization * m.frictionRegularization);
  st.weighted = sp.parts[0];
  for (std::size_t k = 1; k < sp.parts.size(); ++k) {
    st.factor[k] = st.factor[k - 1] * math::exp(mu * sp.wraps[k - 1]);
    st.weighted += sp.parts[k] * st.factor[k];
  }
}

// Stretch of span i and its rate at its pivoting guide's face angle and rate (d.faceAngle,
// d.faceRate), after spanEnds; the guide table's torque coefficients for its loads.
void spanAtFaceAngle(const SpanModel& m, SpanData& d, int i) {
  const Span& sp = m.spans[i];
  SpanState& st = d.spans[i];
  TableValue g{sp.length0, 0.0, 0.0, 0.0};
  if (sp.table >= 0) g = lookUp(m.tables[sp.table], d.faceAngle[sp.table]);
  st.guideTorqueIn = g.torqueIn;
  st.guideTorqueOut = g.torqueOut;
  st.slope = g.slope;
  st.stretch = g.length - sp.length0 - st.passed;
  st.stretchRate = (sp.table >= 0 ? g.slope * d.faceRate[sp.table] : 0.0) - (st.speedFrom - st.speedTo);
}

// Span i's spring tension: its engagement law (span_calibration.h), the joints' in series
// without one, or prescribed (identification); its slope by the stretch into `slope` [N/m].
double springTension(const SpanModel& m, const SpanData& d, int i, double& slope) {
  const Span& sp = m.spans[i];
  const double e = d.spans[i].stretch;
  if (!d.prescribedTension.empty()) {
    slope = 0.0;
    return d.prescribedTension[i];
  }
  if (sp.engagement.empty()) {
    slope = sp.stiffness;
    return sp.stiffness * e;
  }
  return sp.engagement.tensionAt(e, &slope);
}

// The tension's distribution over the guides of span i (the tension above the centrifugal part
// grows over each guide by its capstan factor, spanEnds; the spring holds the length-weighted
// mean) and the spans' torque on its pivoting guide's face.
void distributeTension(const SpanModel& m, SpanData& d, int i) {
  const Span& sp = m.spans[i];
  SpanState& st = d.spans[i];
  st.tensionFrom = st.centrifugal + (st.tension - st.centrifugal) * sp.partsLength / st.weighted;
  st.tensionTo = st.partTension(static_cast<int>(sp.parts.size()) - 1);
  st.faceTorque = 0.0;
  if (sp.table >= 0) {
    const int k = sp.tableGuide;
    const double over = st.tensionFrom - st.centrifugal;
    st.faceTorque = st.guideTorqueIn * over * st.factor[k] + st.guideTorqueOut * over * st.factor[k + 1];
  }
}

// Span i at its face's angle and rate: kinematics, tension (spring and damper), distribution.
void spanAtFace(const SpanModel& m, SpanData& d, int i) {
  spanEnds(m, d, i);
  spanAtFaceAngle(m, d, i);
  double slope = 0.0;
  SpanState& st = d.spans[i];
  st.tension = springTension(m, d, i, slope) + (d.quasiStatic ? 0.0 : m.spans[i].damping * st.stretchRate);
  distributeTension(m, d, i);
}

// Span i whose guide sits on a seat (GuideSeat): the face angle chi where the spans' torque on
// the face equals the seat's, torque0 + k (chi - psi), by the secant method from chi = psi (the
// same start every time: the same bits whatever came before), its first step, and every step once
// the secant stalls, on the slope -(k + the spans' identified stiffness). The face's rate is the one that keeps that balance in
// the linear spring's terms, chi' = (k psi' + k_e l' dv) / (k + k_e l'^2): the guide's rate and
// the chain's speed difference dv over the span shared between the seat and the span's stretch
// (k_e the law's slope, l' the table's).
void seatFace(const SpanModel& m, SpanData& d, int i) {
  constexpr int kMaxIterations = 100, kSecantIterations = 8;
  constexpr double kTolerance = 1e-13;  // [rad]
  const int t = m.spans[i].table;
  const GuideSeat& seat = m.seats[t];
  const int r = m.tables[t].rotor;
  SpanState& st = d.spans[i];
  const double psi = d.rotorAngle[r];
  double chi = psi, chiBefore = psi, imbalanceBefore = 0.0;
  double below = -std::numeric_limits<double>::infinity(), above = std::numeric_limits<double>::infinity();
  spanEnds(m, d, i);
  for (int it = 0;; ++it) {
    d.faceAngle[t] = chi;
    d.faceRate[t] = d.rotorRate[r];
    spanAtFaceAngle(m, d, i);
    double ke = 0.0;
    const double spring = springTension(m, d, i, ke);
    const double dv = st.speedFrom - st.speedTo;
    d.faceRate[t] = (seat.stiffness * d.rotorRate[r] + ke * st.slope * dv) / (seat.stiffness + ke * st.slope * st.slope);
    st.stretchRate = st.slope * d.faceRate[t] - dv;
    st.tension = spring + (d.quasiStatic ? 0.0 : m.spans[i].damping * st.stretchRate);
    distributeTension(m, d, i);
    const double imbalance = st.faceTorque - seat.torque0 - seat.stiffness * (chi - psi);
    // the secant's slope while it falls (the balance falls with chi) and for the first
    // kSecantIterations, else the identified one; a step out of the bracket the iterates have
    // found (a law's kink or the face's end can throw either) bisects it
    const double secant = it > 0 && chi != chiBefore ? (imbalance - imbalanceBefore) / (chi - chiBefore) : 0.0;
    const double slope = it < kSecantIterations && secant < 0.0 ? secant : -(seat.stiffness + seat.spanStiffness);
    (imbalance > 0.0 ? below : above) = chi;
    double next = chi - imbalance / slope;
    if (std::isfinite(below) && std::isfinite(above) && (next <= below || next >= above)) next = 0.5 * (below + above);
    const double step = next - chi;
    if (std::fabs(step) <= kTolerance) break;
    if (it == kMaxIterations) {  // (SpanSystem::rhs stops the run naming the seat)
      d.seatUnsolved = true;
      break;
    }
    chiBefore = chi, imbalanceBefore = imbalance;
    chi += step;
  }
}

// The torques of span i on its end sprockets and on its pivoting guide (through the face); the
// power its damper and guide friction dissipate.
void spanLoads(const SpanModel& m, SpanData& d, int i) {
  const Model& lm = *m.links;
  const Span& sp = m.spans[i];
  const SpanState& st = d.spans[i];
  const double sense = lm.sense;
  // sprockets: the chain pulls the leaving end forwards, the arriving end backwards
  d.chainTorque[sp.from.rotor] += sense * st.tensionFrom * st.radiusFrom;
  d.chainTorque[sp.to.rotor] -= sense * st.tensionTo * st.radiusTo;
  d.powerDissipated += d.quasiStatic ? 0.0 : sp.damping * st.stretchRate * st.stretchRate;
  for (std::size_t k = 0; k + 1 < sp.parts.size(); ++k)
    d.powerDissipated += (st.partTension(static_cast<int>(k) + 1) - st.partTension(static_cast<int>(k))) * st.speed;
  if (sp.table >= 0) d.chainTorque[m.tables[sp.table].rotor] += st.faceTorque;
}

}  // namespace

void evaluateSpanForces(const SpanModel& m, SpanData& d, const InputSignal& in, double t, const double* y) {
  ++d.rhsEvaluations;
  d.seatUnsolved = false;
  in.evaluate(t, d.inputs);
  rotorKinematics(m, d, y);
  std::fill(d.chainTorque.begin(), d.chainTorque.end(), 0.0);
  d.powerInput = d.powerDissipated = 0.0;
  const int n = static_cast<int>(m.spans.size());
  for (int i = 0; i < n; ++i) {
    const int table = m.spans[i].table;
    if (table >= 0 && m.seats[table].present()) {
      seatFace(m, d, i);
      continue;
    }
    if (table >= 0) {
      d.faceAngle[table] = d.rotorAngle[m.tables[table].rotor];
      d.faceRate[table] = d.rotorRate[m.tables[table].rotor];
    }
    spanAtFace(m, d, i);
  }
  for (int i = 0; i < n; ++i) spanLoads(m, d, i);
  d.rotorGen = d.chainTorque;  // same size: no allocation
  TensionerResult t0;
  const TensionerModel& tm = m.links->tensioner;
  if (m.stateChamberOil >= 0)
    fillChamber(tm, m.links->rotors[tm.rotor].axis, d.rotorCos[tm.rotor], d.rotorSin[tm.rotor], y[m.stateChamberOil],
                d.chamber);
  evaluateRotorForces(*m.links, d.inputs, d.rotorCos.data(), d.rotorSin.data(), d.rotorRate.data(), d.chamber,
                      d.rotorGen.data(), t0, d.powerInput, d.powerDissipated);
  d.tensionerForce = t0.force;
  d.tensionerStroke = t0.stroke;
  d.tensionerRate = t0.rate;
  d.chamberPressure = t0.chamberPressure;
  d.tensionerFlows = t0.flows;
  if (m.stateChamberOil >= 0) d.chamberOilRate = chamberOilRate(tm, d.chamber, t0.flows);
}

void spanForward(const SpanModel& m, SpanData& d, const InputSignal& in, double t, const double* y, double* ydot) {
  evaluateSpanForces(m, d, in, t, y);
  const Model& lm = *m.links;
  for (std::size_t r = 0; r < lm.rotors.size(); ++r) {
    ydot[m.stateAngle[r]] = d.rotorRate[r];
    if (m.stateRate[r] >= 0) ydot[m.stateRate[r]] = d.rotorGen[r] / m.rotorInertia[r];
  }
  ydot[m.stateInputWork] = d.powerInput;
  ydot[m.stateDissipated] = d.powerDissipated;
  if (m.stateChamberOil >= 0) ydot[m.stateChamberOil] = d.chamberOilRate;
  accumulateImpulses(m.chainImpulse, d.chainTorque, ydot);
}

EnergyTerms spanEnergy(const SpanModel& m, const SpanData& d, const double* y) {
  EnergyTerms e;
  const Model& lm = *m.links;
  for (std::size_t r = 0; r < lm.rotors.size(); ++r)
    if (m.stateRate[r] >= 0) e.kinetic += 0.5 * m.rotorInertia[r] * d.rotorRate[r] * d.rotorRate[r];
  for (std::size_t i = 0; i < m.spans.size(); ++i) {
    const Span& sp = m.spans[i];
    const double stretch = d.spans[i].stretch;
    e.elastic += sp.engagement.empty() ? 0.5 * sp.stiffness * stretch * stretch : sp.engagement.energyAt(stretch);
  }
  for (std::size_t t = 0; t < m.tables.size(); ++t) {  // the seats' springs (their preloads' work too)
    const double slip = d.faceAngle[t] - d.rotorAngle[m.tables[t].rotor];
    e.elastic += m.seats[t].torque0 * slip + 0.5 * m.seats[t].stiffness * slip * slip;
  }
  if (lm.tensioner.present) {
    const int r = lm.tensioner.rotor;
    ChamberState oil = d.chamber;
    oil.supplyPressure = d.inputs.supplyPressure;
    e.elastic += tensionerEnergy(lm.tensioner, tensionerForce(lm.tensioner, lm.rotors[r].axis, d.rotorCos[r],
                                                              d.rotorSin[r], d.rotorRate[r], oil));
  }
  e.inputWork = y[m.stateInputWork];
  e.dissipated = y[m.stateDissipated];
  return e;
}

}  // namespace chaindrive::span
