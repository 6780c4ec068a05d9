// The ring solver against a dense LU of the same matrix, on rings from the smallest (3 rows, where
// the closing blocks meet the band) to the drive's size.
#include <gtest/gtest.h>

#include <random>

#include "linear/cyclic_block_tridiagonal.h"

using namespace chaindrive;

namespace {

// A symmetric positive definite ring like a chain's iteration matrix (masses plus spring
// couplings), with a nonsymmetric part of the size friction adds; the same blocks in dense form.
Eigen::MatrixXd fillRing(CyclicBlockTridiagonal3& w, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = w.size();
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (int i = 0; i < n; ++i) {
    const int k = (i + 1) % n;
    Eigen::Matrix3d c;
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) c(r, s) = u(rng);
    dense.block<3, 3>(3 * i, 3 * k) += -c;
    dense.block<3, 3>(3 * k, 3 * i) += -c.transpose();
    dense.block<3, 3>(3 * i, 3 * i) += c * c.transpose() + 2.0 * Eigen::Matrix3d::Identity();
    dense.block<3, 3>(3 * k, 3 * k) += c.transpose() * c;
    dense(3 * i, 3 * i + 1) += 0.1 * u(rng);
  }
  for (int i = 0; i < n; ++i) {
    const int k = (i + 1) % n, j = (i + n - 1) % n;
    w.diagonal(i) = dense.block<3, 3>(3 * i, 3 * i);
    w.upper(i) = dense.block<3, 3>(3 * i, 3 * k);
    w.lower(i) = dense.block<3, 3>(3 * i, 3 * j);
  }
  return dense;
}

}  // namespace

TEST(CyclicBlockTridiagonal, SolvesLikeADenseLu) {
  std::mt19937 rng(7);
  for (int n : {3, 4, 5, 17, 120}) {
    CyclicBlockTridiagonal3 w(n);
    const Eigen::MatrixXd dense = fillRing(w, rng);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(3 * n, -1.0, 2.0);
    const Eigen::VectorXd expected = dense.partialPivLu().solve(b);
    ASSERT_TRUE(w.factor()) << n;
    Eigen::VectorXd x = b;
    w.solve(x.data());
    EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm()) << "ring of " << n;
    EXPECT_LT((dense * x - b).norm(), 1e-12 * b.norm()) << "ring of " << n;
  }
}

TEST(CyclicBlockTridiagonal, ASingularPivotIsReported) {
  CyclicBlockTridiagonal3 w(4);
  for (int i = 0; i < 4; ++i) w.diagonal(i) = Eigen::Matrix3d::Identity();
  w.diagonal(1)(2, 2) = 0.0;  // row 1 decoupled and singular
  EXPECT_FALSE(w.factor());
  EXPECT_THROW(CyclicBlockTridiagonal3(2), std::invalid_argument);
}
