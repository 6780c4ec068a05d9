// Helpers for the tests of Lemke's method (src/lcp/lemke.*) and of the command-line tool
// chaindrive-lcp: the test data, one solve, Murty's exponential example, a portable random
// generator, planar friction contact through the LCP form and the contact laws, temporary files.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "lcp/lemke.h"

namespace chaindrive::lcp::test {

/// A file of tests/data, named relative to it ("lcp/lcp_deudeu.dat", "lcp_chain/...").
inline std::string testDataPath(const std::string& relative) {
  return std::string(CHAINDRIVE_SOURCE_DIR) + "/tests/data/" + relative;
}

/// A file of the Siconos collection, tests/data/lcp ("" gives the folder).
inline std::string dataPath(const std::string& name) { return testDataPath("lcp/" + name); }

/// The names of the problem files (*.dat) directly in a folder, sorted.
inline std::vector<std::string> datFiles(const std::string& folder) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.path().extension() == ".dat") files.push_back(entry.path().filename().string());
  std::sort(files.begin(), files.end());
  return files;
}

struct Outcome {
  Result result;
  Eigen::VectorXd z;
};

/// LCP(M, q) by a fresh LemkeSolver (maxPivots < 0: the default cap).
inline Outcome solveProblem(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, int maxPivots = -1) {
  LemkeSolver solver;
  Outcome o;
  o.result = solver.solve(M, q, o.z, maxPivots);
  return o;
}

/// Murty's exponential example: M_ii = 1, M_ij = 2 (j > i), 0 below; q_i = -sum_{j=i..n} 2^j
/// (1-based). Solution 2^n e_n after 2^n - 1 pivots.
inline void murty(int n, Eigen::MatrixXd& M, Eigen::VectorXd& q) {
  M = Eigen::MatrixXd::Zero(n, n);
  q.resize(n);
  for (int i = 0; i < n; ++i) {
    M(i, i) = 1.0;
    for (int j = i + 1; j < n; ++j) M(i, j) = 2.0;
    double s = 0.0;
    for (int j = i + 1; j <= n; ++j) s += std::ldexp(1.0, j);
    q(i) = -s;
  }
}

/// A portable uniform generator (the same numbers with every standard library).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : g_(seed) {}
  double uniform(double a, double b) { return a + (b - a) * static_cast<double>(g_() >> 11) * 0x1.0p-53; }
  int integer(int a, int b) { return a + static_cast<int>(g_() % static_cast<std::uint64_t>(b - a + 1)); }

 private:
  std::mt19937_64 g_;
};

/// A planar friction-contact problem solved through its LCP form (M, q) by a fresh LemkeSolver
/// with the default cap: the result and z of the LCP, the forces r and the velocities
/// u = W r + q.
struct ContactSolution {
  Eigen::MatrixXd M;
  Eigen::VectorXd q;
  Result result;
  Eigen::VectorXd z, r, u;
};

inline ContactSolution solveFriction(const FrictionProblem& p) {
  ContactSolution s;
  frictionToLcp(p, s.M, s.q);
  LemkeSolver solver;
  s.result = solver.solve(s.M, s.q, s.z);
  lcpToForces(p, s.z, s.r);
  s.u = p.W * s.r + p.q;
  return s;
}

/// The contact laws in terms of (u, r) with absolute tolerance tol: 0 <= u_N _|_ r_N >= 0,
/// |r_T| <= mu r_N, u_T = 0 when sticking, r_T = -mu r_N sign(u_T) when sliding.
inline void expectCoulomb(const FrictionProblem& p, const Eigen::VectorXd& r, const Eigen::VectorXd& u, double tol) {
  for (int i = 0; i < p.contacts(); ++i) {
    const double rN = r(2 * i), rT = r(2 * i + 1), uN = u(2 * i), uT = u(2 * i + 1), mu = p.mu(i);
    EXPECT_GE(rN, -tol) << "contact " << i;
    EXPECT_GE(uN, -tol) << "contact " << i;
    EXPECT_LE(std::min(std::abs(rN), std::abs(uN)), tol) << "contact " << i;
    EXPECT_LE(std::abs(rT), mu * rN + tol) << "contact " << i;
    if (uT > tol) {
      EXPECT_NEAR(rT, -mu * rN, tol) << "contact " << i;
    }
    if (uT < -tol) {
      EXPECT_NEAR(rT, mu * rN, tol) << "contact " << i;
    }
    if (std::abs(rT) < mu * rN - tol) {
      EXPECT_NEAR(uT, 0.0, tol) << "contact " << i;
    }
  }
}

/// Writes text to a file in gtest's temporary folder and returns its path.
inline std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "lcp_test_" + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace chaindrive::lcp::test
