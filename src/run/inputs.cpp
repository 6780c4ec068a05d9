#include "run/inputs.h"
#include "math/elementary.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace chaindrive {

void HarmonicInputs::evaluate(double t, InputValues& v) const {
  double w = mean_, a = 0.0;
  for (const Order& o : orders_) {
    const double arg = o.order * mean_ * t + o.phase;
    w += o.order * mean_ * o.amplitude * math::cos(arg);
    a -= o.order * o.order * mean_ * mean_ * o.amplitude * math::sin(arg);
  }
  v.crankSpeed = w;
  v.crankAcceleration = a;
  v.supplyPressure = supplyPressure_;
  for (std::size_t r = 0; r < loads_.size() && r < v.loadTorque.size(); ++r) v.loadTorque[r] = loads_[r];
}

namespace {
std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream ss(line);
  while (std::getline(ss, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  return out;
}
constexpr int kCrankColumn = -1, kSupplyColumn = -3;  // (>= 0: the rotor whose torque the column holds)

// What each column of the header sets: the crankshaft's speed, a free sprocket's load, a pivoting
// guide's torque, a hydraulic tensioner's supply pressure; anything else is refused naming what is.
std::vector<int> columnRoles(const Model& m, const std::string& path, const std::vector<std::string>& header) {
  const std::string crankName = m.drivenRotor >= 0 ? m.rotors[m.drivenRotor].name + ".w" : "";
  const bool chamber = m.tensioner.hydraulicChamber();
  std::vector<int> role(header.size(), -2);
  for (std::size_t c = 1; c < header.size(); ++c) {
    if (!crankName.empty() && header[c] == crankName) role[c] = kCrankColumn;
    if (chamber && header[c] == "tensioner.supplyPressure") role[c] = kSupplyColumn;
    for (std::size_t r = 0; r < m.rotors.size(); ++r)
      if (!m.rotors[r].prescribed && header[c] == m.rotors[r].name + ".tau") role[c] = static_cast<int>(r);
    if (role[c] == -2)
      throw std::invalid_argument(path + ": column '" + header[c] + "' is unknown; allowed: " + crankName +
                                  ", <free sprocket>.tau, <pivoting guide>.tau" +
                                  (chamber ? ", tensioner.supplyPressure" : " (tensioner.supplyPressure: a hydraulic "
                                                                            "tensioner's only)"));
  }
  return role;
}

}  // namespace

TableInputs::TableInputs(const Model& m, const std::string& path) : supplyPressure_(m.tensioner.hydraulic.supplyPressure) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot be opened");
  std::string line;
  std::vector<std::string> header;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty() || line[0] == '#') continue;
    header = splitCsv(line);
    break;
  }
  if (header.empty() || header[0] != "time")
    throw std::invalid_argument(path + ": the first non-comment line must be a header starting with 'time'");
  const std::vector<int> role = columnRoles(m, path, header);
  loads_.assign(m.rotors.size(), {});
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty() || line[0] == '#') continue;
    const auto cells = splitCsv(line);
    if (cells.size() != header.size())
      throw std::invalid_argument(path + ":" + std::to_string(lineNo) + ": expected " + std::to_string(header.size()) +
                                  " values, got " + std::to_string(cells.size()));
    std::vector<double> vals(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) {
      char* end = nullptr;
      vals[c] = std::strtod(cells[c].c_str(), &end);
      if (end == cells[c].c_str() || *end != '\0' || !std::isfinite(vals[c]))
        throw std::invalid_argument(path + ":" + std::to_string(lineNo) + ": column '" + header[c] + "': '" + cells[c] +
                                    "' is not a finite number");
    }
    if (!time_.empty() && vals[0] < time_.back())
      throw std::invalid_argument(path + ":" + std::to_string(lineNo) + ": time decreases");
    time_.push_back(vals[0]);
    for (std::size_t c = 1; c < cells.size(); ++c)
      (role[c] == kCrankColumn ? crank_ : role[c] == kSupplyColumn ? supply_ : loads_[role[c]]).push_back(vals[c]);
  }
  if (time_.size() < 1) throw std::invalid_argument(path + ": no data rows");
  if (m.drivenRotor >= 0 && crank_.empty())
    throw std::invalid_argument(path + ": column '" + m.rotors[m.drivenRotor].name + ".w' is missing");
}

void TableInputs::evaluate(double t, InputValues& v) const {
  // index of the last sample at or before t
  std::size_t k = 0;
  double w = 0.0;
  if (t <= time_.front()) {
    k = 0;
  } else if (t >= time_.back()) {
    k = time_.size() - 1;
  } else {
    k = static_cast<std::size_t>(std::upper_bound(time_.begin(), time_.end(), t) - time_.begin()) - 1;
    const double dt = time_[k + 1] - time_[k];
    w = dt > 0.0 ? (t - time_[k]) / dt : 1.0;
  }
  auto interp = [&](const std::vector<double>& s) { return w > 0.0 ? (1.0 - w) * s[k] + w * s[k + 1] : s[k]; };
  v.supplyPressure = supply_.empty() ? supplyPressure_ : interp(supply_);
  if (!crank_.empty()) {
    v.crankSpeed = interp(crank_);
    v.crankAcceleration = (w > 0.0 && time_[k + 1] > time_[k]) ? (crank_[k + 1] - crank_[k]) / (time_[k + 1] - time_[k]) : 0.0;
  }
  for (std::size_t r = 0; r < loads_.size() && r < v.loadTorque.size(); ++r)
    if (!loads_[r].empty()) v.loadTorque[r] = interp(loads_[r]);
}

}  // namespace chaindrive
