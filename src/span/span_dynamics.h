// The span model's forward dynamics and its work area: rotor kinematics, span stretches and
// tensions (spring-damper, centrifugal part, capstan over guides), the torques on sprockets and
// pivoting guides, then the body forces shared with the link model (tensioner, guide pivots, load
// torques: dynamics/body_forces.h) and the rotor accelerations over the lumped inertias.
#pragma once

#include <vector>

#include "dynamics/data.h"
#include "dynamics/dynamics.h"
#include "span/span_model.h"

namespace chaindrive::span {

/// One span at one instant.
struct SpanState {
  double stretch = 0.0, stretchRate = 0.0;  // [m], [m/s]
  double tension = 0.0;        // [N] spring-damper force (the span's mean tension)
  double speed = 0.0;          // [m/s] chain speed, mean of the two ends' R cos(theta_rel) omega
  double centrifugal = 0.0;    // [N] rho v^2
  double passed = 0.0;         // [m] chain passed over its leaving end less over its arriving end
  double speedFrom = 0.0, speedTo = 0.0;  // [m/s] chain speed at the leaving and arriving ends
  double radiusFrom = 0.0, radiusTo = 0.0;  // [m] effective radii R cos(theta_rel) of the ends
  double guideTorqueIn = 0.0, guideTorqueOut = 0.0;  // [m] its pivoting guide's table coefficients
  double slope = 0.0;          // [m/rad] its length's by its guide's face angle (0 without one)
  double faceTorque = 0.0;     // [N m] on its pivoting guide's face, math sense (0 without one)
  std::vector<double> factor;  // (free parts) capstan factor of (T - rho v^2) relative to the first part
  double weighted = 0.0;       // [m] the free parts' lengths weighted by their factors
  double tensionFrom = 0.0, tensionTo = 0.0;  // [N] where the chain leaves A / arrives on B
  double partTension(int part) const { return centrifugal + (tensionFrom - centrifugal) * factor[part]; }
};

struct SpanData {
  explicit SpanData(const SpanModel& m);
  // statics (the preload, the identification): springs without damping (and there the chamber
  // held: chamber.held, as the link model's statics hold it)
  bool quasiStatic = false;
  std::vector<double> prescribedTension;  // (spans) spring tensions instead of the laws' (identification); empty
  InputValues inputs;
  std::vector<double> rotorAngle, rotorRate, rotorCos, rotorSin;  // (rotors) math sense
  std::vector<double> chainTorque;     // (rotors) [N m] of the chain on the rotor, math sense
  std::vector<double> faceAngle, faceRate;  // (guide tables) the angle and rate the spans' path
                                            // follows: a seat's face (GuideSeat), else the guide's
  std::vector<double> rotorGen;        // (rotors) all torques, math sense
  std::vector<SpanState> spans;
  double tensionerForce = 0.0, tensionerStroke = 0.0, tensionerRate = 0.0;
  ChamberState chamber;               // a hydraulic tensioner's (as the link model's Data)
  double chamberOilRate = 0.0;        // [m3/s] of the content
  double chamberPressure = 0.0;       // [Pa] gauge, the chamber's
  HydraulicFlows tensionerFlows;      // [m3/s]
  double powerInput = 0.0, powerDissipated = 0.0;
  bool seatUnsolved = false;           // a guide seat's balance not found at the last evaluation
  long long rhsEvaluations = 0;
};

/// Torques at (t, y) into d.chainTorque and d.rotorGen; spans, tensioner and powers into d.
void evaluateSpanForces(const SpanModel& m, SpanData& d, const InputSignal& in, double t, const double* y);

/// ydot = f(t, y). Never allocates.
void spanForward(const SpanModel& m, SpanData& d, const InputSignal& in, double t, const double* y, double* ydot);

/// Energy terms at y after an evaluation at y: rotor kinetic energy (with the lumped chain),
/// span springs and tensioner, the accumulators.
EnergyTerms spanEnergy(const SpanModel& m, const SpanData& d, const double* y);

}  // namespace chaindrive::span
