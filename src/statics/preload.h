// The start state: the nominal polygonal pose with the nominal motion at the initial crankshaft
// speed, pre-loaded by a kinetostatic solve: the static equilibrium of all forces (joints,
// contacts, tensioner, gravity, load torques and friction at the nominal sliding velocities)
// with the d'Alembert forces of the nominal motion (centripetal accelerations on sprockets and
// guides), the driven sprocket held. A run at constant speed then starts near its steady state.
#pragma once

#include <string>
#include <vector>

#include "dynamics/data.h"
#include "assembly/model.h"

namespace chaindrive {

struct PreloadOptions {
  bool enabled = true;
  int maxIterations = 200;
  double forceTolerance = 1e-6;  // [N] on link forces; torques scaled by the pitch
};

struct PreloadReport {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;     // [N] largest scaled residual at the end
  double cpuSeconds = 0.0;
  std::string message;
};

/// Rotor rates of the nominal motion at the crankshaft speed (math sense): sprockets in the ratio
/// of their teeth to the driven one's, guides at rest.
std::vector<double> nominalRotorRates(const Model& m, double crankSpeed);

/// The nominal (rigid, unstretched) pose with nominal velocities; energy accumulators zero.
std::vector<double> nominalState(const Model& m, double crankSpeed);
/// The same at the given rotor rates (math sense) and chain speed [m/s] (pins on the spans move
/// at it along the path, pins on a wheel with the wheel).
std::vector<double> nominalState(const Model& m, const std::vector<double>& rates, double chainSpeed);

/// A hydraulic tensioner's chamber at rest in state y: the oil content that fills it, at the
/// guide's angle in y, to the supply's gauge pressure [Pa] less the check valve's cracking
/// pressure (the valve just closed). Nothing without a chamber.
void setChamberAtRest(const Model& m, double supplyPressure, std::vector<double>& y);

/// Nominal state, pre-loaded. Throws std::runtime_error if the solve diverges (with the reason).
/// `guess`: the solve starts from its positions instead of the nominal pose (a nearby solution).
std::vector<double> initialState(const Model& m, const InputValues& inputs, const PreloadOptions& opt,
                                 PreloadReport& report, const std::vector<double>* guess = nullptr);

}  // namespace chaindrive
