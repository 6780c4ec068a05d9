#include "run/mode_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "math/elementary.h"

namespace chaindrive {

namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr double kMinRatio = 1e-4, kMaxRatio = 0.5;

// The channels' residual sum of squares after the linear least squares of each on the columns of
// A (one row per sample).
double leastSquaresResidual(const Eigen::MatrixXd& A, const std::vector<std::vector<double>>& channels) {
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  double sum = 0.0;
  for (const std::vector<double>& c : channels) {
    const Eigen::Map<const Eigen::VectorXd> y(c.data(), A.rows());
    sum += (A * qr.solve(y) - y).squaredNorm();
  }
  return sum;
}

// The basis at the samples: with a mode (omega, sigma) [1/s] its cosine and sine, then each
// channel's drift (a quadratic over the window); without one (omega = 0), the drift alone.
Eigen::MatrixXd basis(const std::vector<double>& t, double omega, double sigma) {
  const Eigen::Index n = static_cast<Eigen::Index>(t.size()), mode = omega > 0.0 ? 2 : 0;
  Eigen::MatrixXd A(n, mode + 3);
  const double t0 = t.front(), span = t.back() - t.front();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double s = t[static_cast<std::size_t>(i)] - t0, u = s / span;
    if (mode) {
      const double e = math::exp(-sigma * s);
      A(i, 0) = e * math::cos(omega * s);
      A(i, 1) = e * math::sin(omega * s);
    }
    A(i, mode) = 1.0;
    A(i, mode + 1) = u;
    A(i, mode + 2) = u * u;
  }
  return A;
}

// The channels' residual at (f, zeta) after each channel's amplitude, phase and drift.
double residualAt(const std::vector<double>& t, const std::vector<std::vector<double>>& channels, double f,
                  double zeta) {
  const double omega = kTwoPi * f;
  return leastSquaresResidual(basis(t, omega, zeta * omega / std::sqrt(1.0 - zeta * zeta)), channels);
}

using Point = std::array<double, 2>;

// Nelder-Mead's simplex from `start` with the given steps, until its extent is within `tolerance`
// in each coordinate (or 200 iterations); the best point, its cost in `value`.
template <class Cost>
Point nelderMead(const Cost& cost, const Point& start, const Point& step, const Point& tolerance, double& value) {
  std::array<Point, 3> simplex = {{start, {start[0] + step[0], start[1]}, {start[0], start[1] + step[1]}}};
  std::array<double, 3> f{};
  for (int i = 0; i < 3; ++i) f[i] = cost(simplex[i]);
  for (int it = 0; it < 200; ++it) {
    std::array<int, 3> order = {0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return f[a] < f[b]; });
    const int lo = order[0], mid = order[1], hi = order[2];
    if (std::fabs(simplex[hi][0] - simplex[lo][0]) < tolerance[0] &&
        std::fabs(simplex[hi][1] - simplex[lo][1]) < tolerance[1])
      break;
    const Point centre = {0.5 * (simplex[lo][0] + simplex[mid][0]), 0.5 * (simplex[lo][1] + simplex[mid][1])};
    auto along = [&](double s) {
      return Point{centre[0] + s * (simplex[hi][0] - centre[0]), centre[1] + s * (simplex[hi][1] - centre[1])};
    };
    const Point reflected = along(-1.0);
    const double fr = cost(reflected);
    if (fr < f[lo]) {
      const Point expanded = along(-2.0);
      const double fe = cost(expanded);
      simplex[hi] = fe < fr ? expanded : reflected;
      f[hi] = std::min(fe, fr);
    } else if (fr < f[mid]) {
      simplex[hi] = reflected, f[hi] = fr;
    } else if (const Point contracted = along(0.5); cost(contracted) < f[hi]) {
      simplex[hi] = contracted, f[hi] = cost(contracted);
    } else {  // shrink towards the best
      for (int i : {mid, hi}) {
        simplex[i] = {0.5 * (simplex[i][0] + simplex[lo][0]), 0.5 * (simplex[i][1] + simplex[lo][1])};
        f[i] = cost(simplex[i]);
      }
    }
  }
  const int best = static_cast<int>(std::min_element(f.begin(), f.end()) - f.begin());
  value = f[best];
  return simplex[best];
}

}  // namespace

FittedMode fitDampedMode(const std::vector<double>& t, const std::vector<std::vector<double>>& channels, double fMin,
                         double fMax) {
  if (t.size() < 8 || channels.empty() || !(fMax > fMin) || !(fMin > 0.0))
    throw std::invalid_argument("fitDampedMode: at least 8 samples, one channel and 0 < fMin < fMax");
  for (const std::vector<double>& c : channels)
    if (c.size() != t.size()) throw std::invalid_argument("fitDampedMode: a channel of another length than t");
  // grid: frequencies a tenth of the window's bin apart, damping ratios log-spaced
  const double bin = 1.0 / (t.back() - t.front());
  const double df = 0.1 * bin;
  constexpr int kRatios = 24;
  double bestF = fMin, bestZ = 0.01, best = std::numeric_limits<double>::infinity();
  for (double f = fMin; f <= fMax; f += df)
    for (int k = 0; k < kRatios; ++k) {
      const double z = kMinRatio * math::pow(kMaxRatio / kMinRatio, k / (kRatios - 1.0));
      const double r = residualAt(t, channels, f, z);
      if (r < best) best = r, bestF = f, bestZ = z;
    }
  // Nelder-Mead on (f, ln zeta) inside the bounds
  auto cost = [&](const Point& p) -> double {
    if (p[0] < fMin || p[0] > fMax || p[1] < math::log(kMinRatio) || p[1] > math::log(kMaxRatio)) return std::numeric_limits<double>::infinity();
    return residualAt(t, channels, p[0], math::exp(p[1]));
  };
  double value = 0.0;
  const Point p = nelderMead(cost, {bestF, math::log(bestZ)}, {df, 0.2}, {1e-6 * bin, 1e-7}, value);
  FittedMode m;
  m.frequency = p[0];
  m.dampingRatio = math::exp(p[1]);
  const double reference = leastSquaresResidual(basis(t, 0.0, 0.0), channels);  // the drift alone
  m.residual = reference > 0.0 ? std::sqrt(value / reference) : 0.0;
  m.atBound = m.frequency < fMin + 1e-3 * bin || m.frequency > fMax - 1e-3 * bin;
  return m;
}

}  // namespace chaindrive
