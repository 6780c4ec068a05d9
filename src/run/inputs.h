// Input signals for runs outside co-simulation: a crankshaft speed with rotational vibration
// (engine orders) and constant load torques, or time series read from CSV.
#pragma once

#include <string>
#include <vector>

#include "dynamics/data.h"
#include "assembly/model.h"

namespace chaindrive {

/// Crankshaft: phi(t) = w0 t + sum_k A_k sin(k w0 t + p_k), so w(t) = w0 + sum_k k w0 A_k cos(k w0 t + p_k)
/// (orders k per crankshaft revolution, angle amplitudes A_k in rad). Load torques constant.
class HarmonicInputs : public InputSignal {
 public:
  struct Order {
    double order = 2.0, amplitude = 0.0, phase = 0.0;
  };
  HarmonicInputs(const Model& m, double meanSpeed)
      : mean_(meanSpeed), supplyPressure_(m.tensioner.hydraulic.supplyPressure), loads_(m.rotors.size(), 0.0) {}
  void addOrder(const Order& o) { orders_.push_back(o); }
  void setLoad(int rotor, double torque) { loads_[rotor] = torque; }
  void evaluate(double t, InputValues& v) const override;

 private:
  double mean_;
  double supplyPressure_;  // [Pa] a hydraulic tensioner's oil supply: the drive's
  std::vector<Order> orders_;
  std::vector<double> loads_;
};

/// Time series: linear interpolation, held constant outside the table.
/// CSV: a header `time,<driven sprocket>.w,<sprocket>.tau,...` (SI units), '#' comment lines;
/// besides, `<pivoting guide>.tau` (a torque on the guide, positive in its output sense: the
/// tension guide's towards the chain) and `tensioner.supplyPressure` (a hydraulic tensioner's
/// gauge supply [Pa]; the drive's without the column): the excitations of the modes study.
class TableInputs : public InputSignal {
 public:
  /// Throws std::invalid_argument naming the file, line and column on bad input.
  TableInputs(const Model& m, const std::string& csvPath);
  void evaluate(double t, InputValues& v) const override;
  double endTime() const { return time_.empty() ? 0.0 : time_.back(); }

 private:
  double supplyPressure_;                     // [Pa] a hydraulic tensioner's oil supply: the drive's
  std::vector<double> time_;
  std::vector<double> crank_;                 // empty if not given
  std::vector<std::vector<double>> loads_;    // per rotor, empty if not given
  std::vector<double> supply_;                // empty if not given
};

}  // namespace chaindrive
