// The suppliers' bench for a hydraulic tensioner: the device alone (dynamics/hydraulic_tensioner.h)
// on a rig, in one of two tests:
// - loop: the plunger driven on a prescribed sinusoid x(t) = mean + amplitude sin(2 pi f t), the
//   supply open; the force over the displacement gives the loops the suppliers measure at
//   20-200 Hz. The motion is given, so the state is the chamber pressure alone (and the volumes
//   that flowed): integrating a plunger mass under a prescribed motion would only add the
//   integrator's drift to a motion that is known exactly.
// - leak-down: a constant force pushes the plunger in, the supply closed (check valve absent);
//   the state is the plunger's stroke and rate (its mass) and the pressure.
// No plunger spring: the rig measures the hydraulic force alone (the spring adds its preload
// and rate, known exactly). Besides the pressure, the state accumulates the volumes that flowed
// through the check valve, the leak gap and the relief valve, for the oil's volume balance.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "choice.h"
#include "description/hydraulic_tensioner.h"
#include "dynamics/hydraulic_tensioner.h"
#include "integrators/ode_system.h"

namespace chaindrive {

enum class RigTest { Loop, LeakDown };
template <>
struct ChoiceNames<RigTest> {
  static constexpr ChoiceName<RigTest> table[] = {{RigTest::Loop, "loop"}, {RigTest::LeakDown, "leak-down"}};
};

struct RigSetup {
  RigTest test = RigTest::Loop;
  HydraulicTensionerDesc tensioner;  // its oilTemperature and supplyPressure are the rig's oil and supply
  // loop: x(t) = mean + amplitude sin(2 pi frequency t) [m, m, Hz]
  double mean = 0.0, amplitude = 0.1e-3, frequency = 100.0;
  // leak-down: the force pushing the plunger in [N]
  double force = 300.0;
  // the chamber's gauge pressure at t = 0 [Pa]; NaN: loop: the supply less the check valve's
  // cracking pressure (the chamber filled through it at rest); leak-down: force / area (at rest
  // in balance)
  double initialPressure = std::numeric_limits<double>::quiet_NaN();
};

/// The rig's state and derivatives at one time.
struct RigSample {
  double time = 0.0, stroke = 0.0, rate = 0.0;
  double pressure = 0.0;   // [Pa] gauge, the chamber's (at least the floor while it cavitates)
  HydraulicResult device;  // force, pressure rate, flows, vapour volume, powers
  // the volumes [m3] that flowed since t = 0: in through the check valve, out through the leak
  // gap and the relief valve; the vapour's volume (the chamber starts filled)
  double volumeCheck = 0.0, volumeLeak = 0.0, volumeRelief = 0.0, volumeVapour = 0.0;
};

class TensionerRig : public OdeSystem {
 public:
  explicit TensionerRig(const RigSetup& setup);

  int size() const override { return first_ + 4; }
  int rhs(double t, const double* y, double* ydot) noexcept override;
  void toleranceScales(double* scale) const override;
  int velocityOf(int i) const override { return first_ == 2 && i == 0 ? 1 : -1; }
  bool isVelocity(int i) const override { return first_ == 2 && i == 1; }
  bool healthy(double t, const double* y, Failure& why) noexcept override;
  const Failure& lastError() const override { return error_; }

  /// The state at t = 0.
  std::vector<double> initialState() const;
  /// The sample of state y at time t.
  RigSample sample(double t, const double* y) const;
  const HydraulicTensionerDesc& tensioner() const { return device_; }
  double viscosity() const { return viscosity_; }

 private:
  /// The plunger's stroke and rate at t (prescribed, or the state's).
  void motion(double t, const double* y, double& stroke, double& rate) const;

  RigSetup setup_;
  HydraulicTensionerDesc device_;  // the setup's, the check valve removed for a leak-down
  double viscosity_ = 0.0;         // [Pa s] at the rig's oil temperature
  int first_ = 0;                  // index of the pressure: 0 (loop) or 2 (leak-down: stroke, rate first)
  Failure error_;
};

/// Runs the rig from t = 0 to `duration` with the integrator of `settings`; a sample every
/// `outputStep` (a multiple of a fixed-step method's step), the first at t = 0.
std::vector<RigSample> runRig(const RigSetup& setup, const IntegratorSettings& settings, double duration,
                              double outputStep);

}  // namespace chaindrive
