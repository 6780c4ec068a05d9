#include "span/seat_calibration.h"

#include <cstdio>
#include <stdexcept>

#include <Eigen/Dense>

#include "dynamics/body_forces.h"
#include "dynamics/dynamics.h"
#include "dynamics/jacobian.h"
#include "statics/preload.h"
#include "span/span_calibration.h"
#include "span/span_dynamics.h"
#include "span/span_system.h"

namespace chaindrive::span {

namespace {

// A link model (below 2 % softer than the spans) keeps the guide on its spans: no seat.
constexpr double kSofterBy = 0.02;

// The link model against the guide's turn with the sprockets held, at its static pose y: the
// stiffness condensed onto the guide's angle (links free) and the damping on that motion (the
// links following as in statics) at the nominal motion of the reference speed.
struct LinkGuideResponse {
  double stiffness = 0.0, damping = 0.0;
};

LinkGuideResponse linkGuideResponse(const Model& m, const InputValues& in, const std::vector<double>& y, int guide) {
  const int nLinks = 3 * m.chain.links;
  std::vector<int> freeIndex(m.nGen, -1);
  for (int g = 0; g < nLinks; ++g) freeIndex[g] = g;
  freeIndex[m.rotorGen(guide)] = nLinks;
  Data d(m);
  HeldInputs held(m);
  held.values = in;
  held.values.crankSpeed = 0.0;
  if (m.stateChamberOil >= 0) holdChamberAtRest(m.tensioner, in.supplyPressure, d.chamber);
  JacobianAssembler jac(m);
  Eigen::MatrixXd K(nLinks + 1, nLinks + 1);
  jac.stiffness(m, d, held, 0.0, y.data(), freeIndex, K);
  const Eigen::MatrixXd S = -0.5 * (K + K.transpose());  // (friction's small asymmetry)
  const Eigen::VectorXd coupling = S.col(nLinks).head(nLinks);
  Eigen::VectorXd shape(nLinks + 1);
  shape.head(nLinks) = -S.topLeftCorner(nLinks, nLinks).ldlt().solve(coupling);
  shape[nLinks] = 1.0;
  LinkGuideResponse r;
  r.stiffness = S(nLinks, nLinks) + coupling.dot(shape.head(nLinks));
  // damping: the generalized forces' change when the shape's velocities are added to the nominal
  // motion's, projected on the shape
  std::vector<double> yv = y;
  const std::vector<double> nominal = nominalState(m, kSeatReferenceSpeed);
  for (int g = 0; g < nLinks; ++g) yv[g + nLinks] = nominal[g + nLinks];
  for (const RotorModel& rotor : m.rotors)
    if (rotor.stateRate >= 0) yv[rotor.stateRate] = nominal[rotor.stateRate];
  held.values.crankSpeed = kSeatReferenceSpeed;
  generalizedForces(m, d, held, 0.0, yv.data());
  const std::vector<double> q0 = d.gen;
  constexpr double kRate = 1e-4;  // [rad/s] of the guide
  for (int g = 0; g < nLinks; ++g) yv[g + nLinks] += kRate * shape[g];
  yv[m.rotors[guide].stateRate] += kRate;
  generalizedForces(m, d, held, 0.0, yv.data());
  for (int g = 0; g <= nLinks; ++g) {
    const int gen = g < nLinks ? g : m.rotorGen(guide);
    r.damping -= shape[g] * (d.gen[gen] - q0[gen]) / kRate;
  }
  return r;
}

// The span model at the link model's rotor angles: the guide's stiffness and damping, in all and
// of the spans alone (central differences of the guide's torques), and the spans' torque there.
struct SpanGuideResponse {
  double stiffness = 0.0, spansStiffness = 0.0, damping = 0.0, spansDamping = 0.0, faceTorque = 0.0;
};

SpanGuideResponse spanGuideResponse(const SpanModel& sm, const InputValues& in, const std::vector<double>& yLink,
                                    int table) {
  const Model& m = *sm.links;
  const int guide = sm.tables[table].rotor;
  std::vector<double> y = nominalSpanState(sm, kSeatReferenceSpeed);
  for (std::size_t r = 0; r < m.rotors.size(); ++r) y[sm.stateAngle[r]] = yLink[m.rotors[r].stateAngle];
  SpanData d(sm);
  if (sm.stateChamberOil >= 0) holdChamberAtRest(m.tensioner, in.supplyPressure, d.chamber);
  HeldInputs held(m);
  held.values = in;
  held.values.crankSpeed = kSeatReferenceSpeed;
  // the torques at the guide's angle (or rate) moved by dx: all, and the spans' alone
  auto torques = [&](int state, double dx, double& spans) {
    std::vector<double> yy = y;
    yy[state] += dx;
    evaluateSpanForces(sm, d, held, 0.0, yy.data());
    spans = 0.0;
    for (std::size_t i = 0; i < sm.spans.size(); ++i)
      if (sm.spans[i].table == table) spans += d.spans[i].faceTorque;
    return d.rotorGen[guide];
  };
  SpanGuideResponse r;
  double below = 0.0, above = 0.0;
  constexpr double kAngle = 1e-6, kRate = 1e-4;
  const int angle = sm.stateAngle[guide], rate = sm.stateRate[guide];
  r.stiffness = -(torques(angle, kAngle, above) - torques(angle, -kAngle, below)) / (2.0 * kAngle);
  r.spansStiffness = -(above - below) / (2.0 * kAngle);
  r.damping = -(torques(rate, kRate, above) - torques(rate, -kRate, below)) / (2.0 * kRate);
  r.spansDamping = -(above - below) / (2.0 * kRate);
  torques(angle, 0.0, r.faceTorque);
  return r;
}

}  // namespace

InputValues seatReferenceInputs(const Model& m) {
  InputValues in;
  in.loadTorque.assign(m.rotors.size(), 0.0);
  for (int r : loadedSprockets(m)) in.loadTorque[r] = kSeatReferenceLoad;
  in.supplyPressure = m.tensioner.hydraulic.supplyPressure;
  return in;
}

std::vector<SeatIdentification> identifyGuideSeats(const SpanModel& sm) {
  const Model& m = *sm.links;
  std::vector<SeatIdentification> seats(sm.tables.size());
  if (sm.tables.empty()) return seats;
  const InputValues in = seatReferenceInputs(m);
  PreloadReport report;
  const std::vector<double> yLink = initialState(m, in, PreloadOptions{}, report);
  if (!report.converged)
    throw std::runtime_error("guide seats: the link model's statics at the reference pose: " + report.message);
  for (std::size_t t = 0; t < sm.tables.size(); ++t) {
    const int guide = sm.tables[t].rotor;
    const LinkGuideResponse link = linkGuideResponse(m, in, yLink, guide);
    const SpanGuideResponse span = spanGuideResponse(sm, in, yLink, static_cast<int>(t));
    SeatIdentification& s = seats[t];
    s.tensionerStiffness = span.stiffness - span.spansStiffness;
    s.linkStiffness = link.stiffness - s.tensionerStiffness;
    s.spanDamping = span.spansDamping;
    s.linkDamping = link.damping - (span.damping - span.spansDamping);
    s.seat.torque0 = span.faceTorque;
    s.seat.spanStiffness = span.spansStiffness;
    if (s.linkStiffness > 0.0 && s.linkStiffness <= (1.0 - kSofterBy) * span.spansStiffness)
      s.seat.stiffness = 1.0 / (1.0 / s.linkStiffness - 1.0 / span.spansStiffness);
  }
  return seats;
}

std::string describeSeat(const SpanModel& sm, int table, const SeatIdentification& s) {
  char line[400];
  const std::string name = sm.links->rotors[sm.tables[table].rotor].name;
  if (!s.seat.present()) {
    std::snprintf(line, sizeof line, "guide '%s': no seat (the link model's chain %.4g N m/rad against the spans' "
                  "%.4g: not softer)", name.c_str(), s.linkStiffness, s.seat.spanStiffness);
    return line;
  }
  std::snprintf(line, sizeof line, "guide '%s': seat %.4g N m/rad at %.4g N m (the link model's chain %.4g N m/rad "
                "against the spans' %.4g, the tensioner %.4g; on that motion the link model's damping %.4g N m s/rad, "
                "the spans' %.4g)", name.c_str(), s.seat.stiffness, s.seat.torque0, s.linkStiffness, s.seat.spanStiffness,
                s.tensionerStiffness, s.linkDamping, s.spanDamping);
  return line;
}

}  // namespace chaindrive::span
