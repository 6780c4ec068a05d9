#include "span/span_calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <stdexcept>

#include <Eigen/Dense>

#include "dynamics/body_forces.h"
#include "dynamics/dynamics.h"
#include "dynamics/joint_forces.h"
#include "statics/preload.h"
#include "span/span_dynamics.h"
#include "span/span_system.h"

namespace chaindrive::span {

namespace {

constexpr double kMinTension = 30.0;  // [N] a nearly slack span sags: its stretch is no law's
// load torques on every loaded sprocket [N m] and supply pressures of a hydraulic chamber [Pa]
constexpr double kLoads[] = {-5.0, 0.0, 5.0, 10.0, 20.0, 40.0};
constexpr int kLevels = static_cast<int>(sizeof kLoads / sizeof kLoads[0]);
constexpr int kReference = 3;         // the others' level (10 N m) while one sprocket takes its levels
constexpr double kSupplies[] = {1e5, 3e5, 10e5, 20e5, 35e5};
// The largest full grid taken whole, in poses times the chain's links cubed (each Newton
// iteration of a pose factors the link model's dense stiffness, three coordinates a link): the
// default drive's, 36 rows at 5 supply pressures with 120 links, about 20 s of CPU.
constexpr double kFullGridWork = 180.0 * 120.0 * 120.0 * 120.0;
constexpr int kNodes = 6;             // law nodes

// The link model's span tensions at its state y: the mean joint tension over the links on each
// span's free parts and guides (what the span's spring holds), located by their path positions
// at the start (statics move the chain along the path by far less than a pitch).
std::vector<double> linkSpanTensions(const SpanModel& sm, const std::vector<double>& yLink, const InputValues& in) {
  const Model& m = *sm.links;
  Data d(m);
  HeldInputs held(m);
  held.values = in;
  generalizedForces(m, d, held, 0.0, yLink.data());
  measureJoints(m, d);
  std::vector<double> sum(sm.spans.size(), 0.0), count(sm.spans.size(), 0.0);
  for (int j = 0; j < m.chain.links; ++j) {
    const PathPart& part = sm.pathParts[m.path.segmentAt(sm.monitoredStart[j])];
    if (part.kind == PathPart::Kind::Sprocket) continue;
    sum[part.span] += d.joints.tension[j];
    count[part.span] += 1.0;
  }
  for (std::size_t i = 0; i < sum.size(); ++i) sum[i] = count[i] > 0.0 ? sum[i] / count[i] : 0.0;
  return sum;
}

// The span model at a static pose of the link model with the link model's span tensions: the
// spans' stretches there and, per pivoting guide, the ratio of the chain torque the link model's
// equilibrium needs to the one the span model's table gives.
void spanAtPose(const SpanModel& sm, const std::vector<double>& yLink, const InputValues& in,
                const std::vector<double>& tension, std::vector<double>& stretch, std::vector<double>& leverRatio) {
  const Model& m = *sm.links;
  std::vector<double> y = nominalSpanState(sm, in.crankSpeed);
  for (std::size_t r = 0; r < m.rotors.size(); ++r) y[sm.stateAngle[r]] = yLink[m.rotors[r].stateAngle];
  SpanData d(sm);
  d.quasiStatic = true;
  if (sm.stateChamberOil >= 0) holdChamberAtRest(m.tensioner, in.supplyPressure, d.chamber);  // as the link model's statics
  d.prescribedTension = tension;
  HeldInputs held(m);
  held.values = in;
  evaluateSpanForces(sm, d, held, 0.0, y.data());
  stretch.resize(sm.spans.size());
  for (std::size_t i = 0; i < sm.spans.size(); ++i) stretch[i] = d.spans[i].stretch;
  leverRatio.clear();
  for (const GuideTable& t : sm.tables)  // rotorGen = chain + the rest: 0 with the chain's torque scaled
    leverRatio.push_back(1.0 - d.rotorGen[t.rotor] / d.chainTorque[t.rotor]);
}

// The law through the poses' (tension, stretch) of one span: the stretch a piecewise-linear
// function of the tension, by least squares, with knots equally spaced from the smallest to the
// largest tension (at most kNodes; a knot whose segment would hold fewer than three poses is
// dropped); its nodes are the stretches at the knots. The residuals go into rms and largest.
EngagementLaw fitLaw(const std::vector<double>& T, const std::vector<double>& e, double& rms, double& largest) {
  const double lo = *std::min_element(T.begin(), T.end()), hi = *std::max_element(T.begin(), T.end());
  std::vector<double> knots = {lo};
  for (int k = 1; k < kNodes; ++k) {
    const double next = lo + (hi - lo) * k / (kNodes - 1);
    const auto held = std::count_if(T.begin(), T.end(), [&](double t) { return t > knots.back() && t <= next; });
    if (held >= 3 || k == kNodes - 1) knots.push_back(next);
  }
  const int nk = static_cast<int>(knots.size()), np = static_cast<int>(T.size());
  // columns: 1, T, and a ramp max(T - knot, 0) per inner knot; tensions in kN keep it well scaled
  auto basis = [&](double t, int c) {
    return c == 0 ? 1.0 : c == 1 ? t * 1e-3 : std::max(t - knots[c - 1], 0.0) * 1e-3;
  };
  Eigen::MatrixXd A(np, nk);
  Eigen::VectorXd b(np);
  for (int p = 0; p < np; ++p) {
    for (int c = 0; c < nk; ++c) A(p, c) = basis(T[p], c);
    b[p] = e[p];
  }
  // a ridge on the slope changes: the stretch depends a little on the neighbouring spans' tensions
  // too, and the fit shall not turn that scatter into wiggles of the stiffness (a change of
  // 100 um/kN costs as much as 10 um off the law at every pose)
  Eigen::MatrixXd ridge = Eigen::MatrixXd::Zero(nk, nk);
  for (int c = 2; c < nk; ++c) ridge(c, c) = 0.01 * np;
  const Eigen::VectorXd x = (A.transpose() * A + ridge).ldlt().solve(A.transpose() * b);
  const Eigen::VectorXd r = A * x - b;
  rms = std::sqrt(r.squaredNorm() / np);
  largest = r.cwiseAbs().maxCoeff();
  EngagementLaw law;
  for (double t : knots) {
    double s = 0.0;
    for (int c = 0; c < nk; ++c) s += x[c] * basis(t, c);
    law.stretch.push_back(s);
    law.tension.push_back(t);
  }
  for (std::size_t k = 1; k < law.stretch.size(); ++k)
    if (!(law.stretch[k] > law.stretch[k - 1]))
      throw std::runtime_error("span calibration: the stretch does not grow with the tension between " +
                               std::to_string(law.tension[k - 1]) + " and " + std::to_string(law.tension[k]) + " N");
  law.energy.assign(law.stretch.size(), 0.0);
  for (std::size_t k = 1; k < law.stretch.size(); ++k)
    law.energy[k] = law.energy[k - 1] +
                    0.5 * (law.tension[k] + law.tension[k - 1]) * (law.stretch[k] - law.stretch[k - 1]);
  return law;
}

// The loads of a pose: its row of load torques on the loaded sprockets, and a supply pressure.
InputValues poseInputs(const Model& m, const std::vector<int>& loaded, const std::vector<double>& loads,
                       double supply) {
  InputValues in;
  in.loadTorque.assign(m.rotors.size(), 0.0);
  for (std::size_t k = 0; k < loaded.size(); ++k) in.loadTorque[loaded[k]] = loads[k];
  in.supplyPressure = supply;
  return in;
}

}  // namespace

std::vector<std::vector<double>> fullLoadGrid(int loadedSprockets) {
  int combos = 1;
  for (int k = 0; k < loadedSprockets; ++k) combos *= kLevels;
  std::vector<std::vector<double>> rows;
  for (int code = 0; code < combos; ++code) {
    std::vector<double> row;
    for (int k = 0, c = code; k < loadedSprockets; ++k, c /= kLevels) row.push_back(kLoads[c % kLevels]);
    rows.push_back(row);
  }
  return rows;
}

// Why these poses: a span's tension is the slack span's (the tensioner's, set by the supply
// pressure) plus the loads of the sprockets before it over their radii, and each span's law is
// fitted over its own tension. The diagonal takes every partial sum of the loads, so every
// span's tension, from its smallest to its largest (the full grid's extremes are diagonal
// poses); one sprocket at a time moves the tensions of the spans after it against those before
// it, so that a span's tension is not tied to its neighbours' (with the diagonal alone the fit
// would give a span the part of its stretch that follows its neighbours). A random design (a
// Latin hypercube) would take each sprocket's levels equally often but not the partial sums:
// their extremes, where the laws' stiffness at the top is fitted, would come rarely.
std::vector<std::vector<double>> linearLoadDesign(int loadedSprockets) {
  std::vector<std::vector<double>> rows;
  for (int level = 0; level < kLevels; ++level) rows.emplace_back(loadedSprockets, kLoads[level]);
  for (int k = 0; k < loadedSprockets; ++k)
    for (int level = 0; level < kLevels; ++level) {
      if (level == kReference) continue;  // (on the diagonal)
      std::vector<double> row(loadedSprockets, kLoads[kReference]);
      row[k] = kLoads[level];
      rows.push_back(row);
    }
  return rows;
}

// The full grid where it is no larger than the linear design (up to one loaded sprocket), and for
// two loaded sprockets where it costs no more than the default drive's (kFullGridWork: the
// default drive keeps the calibration its figures were made with); the linear design otherwise
// (from three loaded sprockets always: 6^n rows).
std::vector<std::vector<double>> calibrationLoads(int loadedSprockets, int supplyPressures, int links) {
  if (loadedSprockets <= 1) return fullLoadGrid(loadedSprockets);
  const double side = links;  // (products of integers: exact, whatever the C library's pow)
  const double work = kLevels * kLevels * supplyPressures * side * side * side;
  return loadedSprockets == 2 && work <= kFullGridWork ? fullLoadGrid(loadedSprockets) : linearLoadDesign(loadedSprockets);
}

std::vector<double> calibrationSupplies(const Model& m) {
  if (!m.tensioner.hydraulicChamber()) return {m.tensioner.hydraulic.supplyPressure};
  return std::vector<double>(std::begin(kSupplies), std::end(kSupplies));
}

std::vector<int> loadedSprockets(const Model& m) {
  std::vector<int> loaded;
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    if (!m.rotors[r].isSprocket || m.rotors[r].prescribed) continue;
    const int s = m.description.sprocketIndex(m.rotors[r].name);
    if (s >= 0 && m.description.sprockets[s].loaded) loaded.push_back(static_cast<int>(r));
  }
  return loaded;
}

SpanCalibration identifySpanLaws(const SpanModel& sm) {
  const Model& m = *sm.links;
  return identifySpanLaws(sm, calibrationLoads(static_cast<int>(loadedSprockets(m).size()),
                                               static_cast<int>(calibrationSupplies(m).size()), m.chain.links));
}

SpanCalibration identifySpanLaws(const SpanModel& sm, const std::vector<std::vector<double>>& loads) {
  const std::clock_t t0 = std::clock();
  const Model& m = *sm.links;
  const std::vector<int> loaded = loadedSprockets(m);
  for (const std::vector<double>& row : loads)
    if (row.size() != loaded.size())
      throw std::invalid_argument("span calibration: a pose with " + std::to_string(row.size()) + " loads for " +
                                  std::to_string(loaded.size()) + " loaded sprockets");
  const std::vector<double> supplies = calibrationSupplies(m);
  const std::size_t ns = sm.spans.size();
  std::vector<std::vector<double>> T(ns), e(ns);
  SpanCalibration c;
  c.leverRatioMin.assign(sm.tables.size(), 1e300);
  c.leverRatioMax.assign(sm.tables.size(), -1e300);
  std::vector<double> previous;  // the last pose solved: the next solve starts there
  for (double supply : supplies)
    for (const std::vector<double>& row : loads) {
      const InputValues in = poseInputs(m, loaded, row, supply);
      PreloadReport report;
      std::vector<double> yLink;
      try {
        yLink = initialState(m, in, PreloadOptions{}, report, previous.empty() ? nullptr : &previous);
      } catch (const std::runtime_error&) {
        report.converged = false;
      }
      if (report.converged) previous = yLink;
      const std::vector<double> tension = report.converged ? linkSpanTensions(sm, yLink, in) : std::vector<double>{};
      if (tension.empty() || *std::min_element(tension.begin(), tension.end()) < kMinTension) {
        ++c.posesRejected;
        continue;
      }
      std::vector<double> stretch, ratio;
      spanAtPose(sm, yLink, in, tension, stretch, ratio);
      for (std::size_t i = 0; i < ns; ++i) {
        T[i].push_back(tension[i]);
        e[i].push_back(stretch[i]);
      }
      for (std::size_t g = 0; g < ratio.size(); ++g) {
        c.leverRatioMin[g] = std::min(c.leverRatioMin[g], ratio[g]);
        c.leverRatioMax[g] = std::max(c.leverRatioMax[g], ratio[g]);
      }
      ++c.poses;
    }
  if (c.poses < 2 * kNodes)
    throw std::runtime_error("span calibration: " + std::to_string(c.poses) + " static poses of the link model " +
                             "converged with every span in tension; the fit needs " + std::to_string(2 * kNodes));
  c.residualRms.resize(ns);
  c.residualMax.resize(ns);
  for (std::size_t i = 0; i < ns; ++i) c.laws.push_back(fitLaw(T[i], e[i], c.residualRms[i], c.residualMax[i]));
  SpanModel withLaws = sm;  // the seats stand in series with the spans' laws
  applyCalibration(withLaws, c);
  c.seats = identifyGuideSeats(withLaws);
  c.cpuSeconds = static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
  return c;
}

void applyCalibration(SpanModel& sm, const SpanCalibration& c) {
  for (std::size_t i = 0; i < sm.spans.size(); ++i) sm.spans[i].engagement = c.laws[i];
  // the seats where the drive asks for them (description: spanModel.guideSeat)
  const SpanModelDesc& want = sm.links->description.spanModel;
  sm.seats.assign(sm.tables.size(), GuideSeat{});
  if (want.guideSeat == SpanModelDesc::Source::Off) return;
  for (std::size_t t = 0; t < c.seats.size() && t < sm.tables.size(); ++t) {
    sm.seats[t] = c.seats[t].seat;
    if (want.guideSeat == SpanModelDesc::Source::Given) sm.seats[t].stiffness = want.guideSeatStiffness;
  }
}

std::vector<std::string> describeCalibration(const SpanModel& sm, const SpanCalibration& c) {
  std::vector<std::string> lines;
  char line[400];
  std::snprintf(line, sizeof line, "engagement laws from %d static poses of the link model (%d rejected) in %.2f s CPU",
                c.poses, c.posesRejected, c.cpuSeconds);
  lines.push_back(line);
  for (std::size_t i = 0; i < sm.spans.size(); ++i) {
    const EngagementLaw& law = c.laws[i];
    std::string nodes;
    for (std::size_t k = 0; k < law.stretch.size(); ++k) {
      char node[64];
      std::snprintf(node, sizeof node, "%s%.0f N at %.4f mm", k ? ", " : "", law.tension[k], law.stretch[k] * 1e3);
      nodes += node;
    }
    const std::size_t n = law.stretch.size();
    const double top = (law.stretch[n - 1] - law.stretch[n - 2]) / (law.tension[n - 1] - law.tension[n - 2]);
    std::snprintf(line, sizeof line, "span %s: %s; compliance at the top %.0f um/kN (joints in series %.0f); "
                  "stretch off the law %.1f um rms, %.1f um largest", sm.spans[i].name.c_str(), nodes.c_str(),
                  top * 1e9, 1e9 / sm.spans[i].stiffness, c.residualRms[i] * 1e6, c.residualMax[i] * 1e6);
    lines.push_back(line);
  }
  for (std::size_t g = 0; g < sm.tables.size(); ++g) {
    std::snprintf(line, sizeof line, "guide '%s': the link model's chain torque over the span model's %.4f to %.4f",
                  sm.links->rotors[sm.tables[g].rotor].name.c_str(), c.leverRatioMin[g], c.leverRatioMax[g]);
    lines.push_back(line);
  }
  for (std::size_t t = 0; t < c.seats.size(); ++t) lines.push_back(describeSeat(sm, static_cast<int>(t), c.seats[t]));
  return lines;
}

}  // namespace chaindrive::span
