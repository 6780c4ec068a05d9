// Lemke's method (src/lcp/lemke.*): Murty's exponential example, caps and failures, random
// P-matrix and positive semidefinite problems against a brute-force enumeration of all
// complementary bases, a single friction contact through the LCP form, determinism, no heap
// allocation per solve and the readers. The problem files of tests/data are checked one by one
// in collection_test.cpp; the command-line tool in tests/cpp/cli/chaindrive_lcp_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "lcp/lemke.h"
#include "lcp/lcp_test_util.h"

#include "allocation_counter.h"

using namespace chaindrive::lcp;
using namespace chaindrive::lcp::test;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Brute force over all 2^n complementary bases: z_S = -M_SS^-1 q_S, z = 0 elsewhere; a basis
// solves the LCP if z >= 0 and w = M z + q >= 0 up to `tol` (absolute). Bases with a numerically
// singular M_SS (relative pivot threshold 1e-10) are skipped; a solvable LCP always has a
// solution in a nonsingular complementary basis (the one Lemke ends in).
struct Enumeration {
  int solutions = 0;  // bases that solve the LCP (several if degenerate)
  VectorXd z;         // the one with the smallest violation
  double violation = std::numeric_limits<double>::infinity();
};

Enumeration enumerate(const MatrixXd& M, const VectorXd& q, double tol) {
  const int n = static_cast<int>(q.size());
  Enumeration e;
  std::vector<int> S;
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    S.clear();
    for (int i = 0; i < n; ++i)
      if (mask & (1u << i)) S.push_back(i);
    const int s = static_cast<int>(S.size());
    VectorXd z = VectorXd::Zero(n);
    if (s > 0) {
      MatrixXd A(s, s);
      VectorXd b(s);
      for (int a = 0; a < s; ++a) {
        b(a) = -q(S[a]);
        for (int c = 0; c < s; ++c) A(a, c) = M(S[a], S[c]);
      }
      Eigen::FullPivLU<MatrixXd> lu(A);
      lu.setThreshold(1e-10);
      if (!lu.isInvertible()) continue;
      const VectorXd zS = lu.solve(b);
      for (int a = 0; a < s; ++a) z(S[a]) = zS(a);
    }
    const VectorXd w = M * z + q;
    double v = 0.0;
    for (int i = 0; i < n; ++i) v = std::max({v, -z(i), -w(i)});
    if (v <= tol) {
      ++e.solutions;
      if (v < e.violation) {
        e.violation = v;
        e.z = z;
      }
    }
  }
  return e;
}

}  // namespace

// =============================================================================================
// Murty's exponential example

// n = 4..14: exactly 2^n - 1 pivots (the pivot convention of lemke.h: the initial pivot of z0 is
// not counted) and z = 2^n e_n. The data are small integers and the pivots are +-1 and +-2, so
// the arithmetic is exact: z is compared exactly. The cap is set to exactly 2^n - 1: a problem
// solved in exactly maxPivots pivots is Solved.
TEST(LcpMurty, ExponentialPivotCountAndSolution) {
  LemkeSolver solver(14);
  for (int n = 4; n <= 14; ++n) {
    MatrixXd M;
    VectorXd q, z;
    murty(n, M, q);
    const int expected = (1 << n) - 1;
    const Result r = solver.solve(M, q, z, expected);
    ASSERT_EQ(r.status, Status::Solved) << "n = " << n;
    EXPECT_EQ(r.pivots, expected) << "n = " << n;
    VectorXd zExact = VectorXd::Zero(n);
    zExact(n - 1) = std::ldexp(1.0, n);
    EXPECT_EQ(z, zExact) << "n = " << n;
    EXPECT_EQ(r.error, 0.0) << "n = " << n;
  }
}

// The default cap, max(10000, 100 n^2), solves Murty's example for n = 12 and 14 (4095 and 16383
// pivots under caps of 14400 and 19600) with the exact solution; n = 15 (32767 pivots) exceeds
// its cap of 22500 and stops after exactly that many. No maxPivots is passed anywhere here.
TEST(LcpMurty, DefaultCapSolvesSizes12And14) {
  LemkeSolver solver(15);
  MatrixXd M;
  VectorXd q, z;
  for (int n : {12, 14}) {
    murty(n, M, q);
    const Result r = solver.solve(M, q, z);
    ASSERT_EQ(r.status, Status::Solved) << "n = " << n;
    EXPECT_EQ(r.pivots, (1 << n) - 1) << "n = " << n;
    EXPECT_EQ(r.maxPivots, LemkeSolver::defaultMaxPivots(n)) << "n = " << n;
    VectorXd zExact = VectorXd::Zero(n);
    zExact(n - 1) = std::ldexp(1.0, n);
    EXPECT_EQ(z, zExact) << "n = " << n;
    EXPECT_EQ(r.error, 0.0) << "n = " << n;
  }
  murty(15, M, q);
  const Result r = solver.solve(M, q, z);
  EXPECT_EQ(r.status, Status::IterationLimit);
  EXPECT_EQ(r.pivots, 22500);
  EXPECT_EQ(r.maxPivots, 22500);
}

// The generator reproduces lcp_exp_murty2.dat (n = 6) exactly.
TEST(LcpMurty, GeneratorMatchesTheCollectionFile) {
  const Problem p = readLcpFile(dataPath("lcp_exp_murty2.dat"));
  MatrixXd M;
  VectorXd q;
  murty(6, M, q);
  EXPECT_EQ(p.M, M);
  EXPECT_EQ(p.q, q);
}

// =============================================================================================
// Limits and failures

// Murty n = 10 needs 1023 pivots: a cap of 100 stops after exactly 100 (and one below the count
// for n = 6 stops too), reporting IterationLimit with the last iterate, which is no solution, the
// cap in force and a message with both.
TEST(LcpLimits, IterationLimitIsHonoured) {
  MatrixXd M;
  VectorXd q, z;
  murty(10, M, q);
  LemkeSolver solver(10);
  Result r = solver.solve(M, q, z, 100);
  EXPECT_EQ(r.status, Status::IterationLimit);
  EXPECT_EQ(r.pivots, 100);
  EXPECT_EQ(r.maxPivots, 100);
  EXPECT_GT(r.error, 0.0);
  EXPECT_EQ(iterationLimitMessage(r, 10, "raise it with --max-pivots"),
            "LCP iteration limit: 100 pivots without a solution (cap 100 for n = 10; raise it with --max-pivots)");
  EXPECT_EQ(iterationLimitMessage(r, 10, ""), "LCP iteration limit: 100 pivots without a solution (cap 100 for n = 10)");
  murty(6, M, q);
  r = solver.solve(M, q, z, 62);
  EXPECT_EQ(r.status, Status::IterationLimit);
  EXPECT_EQ(r.pivots, 62);
  r = solver.solve(M, q, z, 0);
  EXPECT_EQ(r.status, Status::IterationLimit);
  EXPECT_EQ(r.pivots, 0);
  // the default cap is enough for n = 6 (63 pivots)
  r = solver.solve(M, q, z);
  EXPECT_EQ(r.status, Status::Solved);
  EXPECT_EQ(r.maxPivots, 10000);
}

// The default cap: max(10000, 100 n^2) (Siconos' 10000 up to n = 10), at most INT_MAX.
TEST(LcpLimits, DefaultCapGrowsWithTheSquaredSize) {
  EXPECT_EQ(LemkeSolver::defaultMaxPivots(0), 10000);
  EXPECT_EQ(LemkeSolver::defaultMaxPivots(1), 10000);
  EXPECT_EQ(LemkeSolver::defaultMaxPivots(6), 10000);
  EXPECT_EQ(LemkeSolver::defaultMaxPivots(10), 10000);
  EXPECT_EQ(LemkeSolver::defaultMaxPivots(11), 12100);
  EXPECT_EQ(LemkeSolver::defaultMaxPivots(12), 14400);
  EXPECT_EQ(LemkeSolver::defaultMaxPivots(14), 19600);
  EXPECT_EQ(LemkeSolver::defaultMaxPivots(100), 1000000);
  EXPECT_EQ(LemkeSolver::defaultMaxPivots(4634), 2147395600);
  EXPECT_EQ(LemkeSolver::defaultMaxPivots(4635), std::numeric_limits<int>::max());
  EXPECT_EQ(LemkeSolver::defaultMaxPivots(std::numeric_limits<int>::max()), std::numeric_limits<int>::max());
}

// NaN or infinite data: NumericalFailure, z = 0, NaN error; never a "solution".
TEST(LcpLimits, NonFiniteDataIsANumericalFailure) {
  const Problem p = readLcpFile(dataPath("lcp_deudeu.dat"));
  LemkeSolver solver(2);
  VectorXd z(2);
  for (int k = 0; k < 4; ++k) {
    MatrixXd M = p.M;
    VectorXd q = p.q;
    if (k == 0) M(1, 0) = std::numeric_limits<double>::quiet_NaN();
    if (k == 1) q(1) = std::numeric_limits<double>::quiet_NaN();
    if (k == 2) M(0, 0) = std::numeric_limits<double>::infinity();
    if (k == 3) q(0) = -std::numeric_limits<double>::infinity();
    const Result r = solver.solve(M, q, z);
    EXPECT_EQ(r.status, Status::NumericalFailure) << "case " << k;
    EXPECT_EQ(r.pivots, 0);
    EXPECT_TRUE(std::isnan(r.error));
    EXPECT_EQ(z, VectorXd::Zero(2));
  }
}

// q >= 0: z = 0 with 0 pivots and error exactly 0 (also q = 0 and the empty problem).
TEST(LcpLimits, NonNegativeQIsTrivial) {
  MatrixXd M(3, 3);
  M << 1, -2, 3, 4, -5, 6, 7, 8, -9;  // any M
  VectorXd q(3);
  q << 0.5, 0.0, 2.0;
  VectorXd z = VectorXd::Constant(3, 7.0);
  LemkeSolver solver;
  Result r = solver.solve(M, q, z);
  EXPECT_EQ(r.status, Status::Solved);
  EXPECT_EQ(r.pivots, 0);
  EXPECT_EQ(r.error, 0.0);
  EXPECT_EQ(z, VectorXd::Zero(3));
  r = solver.solve(M, VectorXd::Zero(3), z);
  EXPECT_EQ(r.status, Status::Solved);
  EXPECT_EQ(r.pivots, 0);
  VectorXd z0;
  r = solver.solve(MatrixXd(0, 0), VectorXd(0), z0);
  EXPECT_EQ(r.status, Status::Solved);
  EXPECT_EQ(z0.size(), 0);
}

// Sizes: z is resized when it has the wrong size; a view must have the right size; M and q must
// agree (std::invalid_argument, a programming error).
TEST(LcpLimits, SizesAreChecked) {
  const Problem p = readLcpFile(dataPath("lcp_deudeu.dat"));
  LemkeSolver solver;
  VectorXd z(5);
  EXPECT_EQ(solver.solve(p.M, p.q, z).status, Status::Solved);
  EXPECT_EQ(z.size(), 2);
  VectorXd big = VectorXd::Constant(4, -1.0);
  EXPECT_EQ(solver.solve(p.M, p.q, big.segment(1, 2)).status, Status::Solved);
  EXPECT_EQ(big(0), -1.0);
  EXPECT_EQ(big(3), -1.0);
  EXPECT_NEAR(big(1), 4.0 / 3.0, 1e-14);
  EXPECT_THROW(solver.solve(p.M, p.q, big.segment(0, 3)), std::invalid_argument);
  EXPECT_THROW(solver.solve(p.M, VectorXd::Zero(3), z), std::invalid_argument);
  EXPECT_THROW(lcpError(p.M, p.q, VectorXd::Zero(3)), std::invalid_argument);
  EXPECT_STREQ(statusName(Status::Solved), "Solved");
  EXPECT_STREQ(statusName(Status::RayTermination), "RayTermination");
  EXPECT_STREQ(statusName(Status::IterationLimit), "IterationLimit");
  EXPECT_STREQ(statusName(Status::NumericalFailure), "NumericalFailure");
}

// =============================================================================================
// Random problems against brute-force enumeration (fixed seed)

// P-matrices (unique solution for every q): 25 per size n = 1..10 and kind, 750 problems:
//  - symmetric positive definite A A' + I (A n x n uniform in [-1, 1]),
//  - nonsymmetric strictly row diagonally dominant with positive diagonal,
//  - small-integer diagonally dominant M with integer q in [-3, 3] (exact ties: degenerate).
// For the first two, q = w0 - M z0 with complementary z0, w0 >= 0 and, for about a quarter of
// the indices, z0_i = w0_i = 0 (degenerate: the lexicographic rule matters).
// Tolerance: z to 1e-9 relative to max(1, |z|_inf) (the matrices have condition numbers below
// about 1e3 here, so the rounding error is below 1e-12; 1e-9 leaves room and still catches any
// wrong basis, whose z differs in O(1)); the enumeration accepts violations below 1e-9.
TEST(LcpRandom, PMatricesMatchEnumeration) {
  Rng rng(20240611);
  LemkeSolver solver(10);
  int problems = 0, degenerateTies = 0;
  double worstError = 0.0, worstDiff = 0.0;
  for (int n = 1; n <= 10; ++n) {
    for (int kind = 0; kind < 3; ++kind) {
      for (int rep = 0; rep < 25; ++rep) {
        MatrixXd M(n, n);
        VectorXd q(n);
        if (kind == 0) {
          MatrixXd A(n, n);
          for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) A(i, j) = rng.uniform(-1.0, 1.0);
          M = A * A.transpose() + MatrixXd::Identity(n, n);
        } else if (kind == 1) {
          for (int i = 0; i < n; ++i) {
            double off = 0.0;
            for (int j = 0; j < n; ++j)
              if (j != i) off += std::abs(M(i, j) = rng.uniform(-1.0, 1.0));
            M(i, i) = off + rng.uniform(0.1, 1.0);
          }
        } else {
          for (int i = 0; i < n; ++i) {
            int off = 0;
            for (int j = 0; j < n; ++j)
              if (j != i) {
                const int v = rng.integer(-1, 1);
                M(i, j) = v;
                off += std::abs(v);
              }
            M(i, i) = off + rng.integer(1, 2);
            q(i) = rng.integer(-3, 3);
          }
        }
        if (kind < 2) {
          VectorXd z0 = VectorXd::Zero(n), w0 = VectorXd::Zero(n);
          for (int i = 0; i < n; ++i) {
            const int pick = rng.integer(0, 3);  // 0, 1: z0_i > 0; 2: w0_i > 0; 3: both zero
            if (pick <= 1) z0(i) = rng.uniform(0.1, 2.0);
            else if (pick == 2) w0(i) = rng.uniform(0.1, 2.0);
          }
          q = w0 - M * z0;
        }
        const Enumeration e = enumerate(M, q, 1e-9);
        ASSERT_GE(e.solutions, 1) << "n " << n << " kind " << kind << " rep " << rep;
        if (e.solutions > 1) ++degenerateTies;
        VectorXd z;
        const Result r = solver.solve(M, q, z);
        ASSERT_EQ(r.status, Status::Solved) << "n " << n << " kind " << kind << " rep " << rep;
        const double diff = (z - e.z).lpNorm<Eigen::Infinity>() / std::max(1.0, e.z.lpNorm<Eigen::Infinity>());
        EXPECT_LE(diff, 1e-9) << "n " << n << " kind " << kind << " rep " << rep;
        EXPECT_LE(r.error, 1e-12) << "n " << n << " kind " << kind << " rep " << rep;
        worstError = std::max(worstError, r.error);
        worstDiff = std::max(worstDiff, diff);
        ++problems;
      }
    }
  }
  EXPECT_EQ(problems, 750);
  EXPECT_GT(degenerateTies, 50);  // the degenerate construction did produce degenerate problems
  std::printf("  P-matrices: %d problems (%d degenerate), worst error %.3g, worst |z - z_enum| %.3g\n", problems,
              degenerateTies, worstError, worstDiff);
}

// Positive semidefinite M = B B' (B n x k, k < n: singular), and the nonsymmetric PSD
// B B' + (C - C'), n = 1..10, 25 of each per size (500 problems); q = w0 - M z0 with
// complementary z0, w0 >= 0 (some indices with both zero), so a solution exists and Lemke must
// find one (PSD matrices are copositive-plus). z need not be unique; what is unique
// (Cottle-Pang-Stone, Thm 3.1.7): w = M z + q for symmetric PSD M, and q'z for every PSD M.
// These are compared with the enumeration's solution to 1e-9 relative to max(1, the values'
// scale) (rounding in rank-deficient bases stays near 1e-13; a wrong solution differs in O(1));
// complementarity through the error, <= 1e-10.
TEST(LcpRandom, SemidefiniteMatricesMatchEnumeration) {
  Rng rng(777);
  LemkeSolver solver(10);
  int problems = 0;
  double worstError = 0.0;
  for (int n = 1; n <= 10; ++n) {
    for (int kind = 0; kind < 2; ++kind) {
      for (int rep = 0; rep < 25; ++rep) {
        const int k = n == 1 ? 0 : rng.integer(1, n - 1);
        MatrixXd B(n, k);
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < k; ++j) B(i, j) = rng.uniform(-1.0, 1.0);
        MatrixXd M = B * B.transpose();
        if (kind == 1) {
          MatrixXd C(n, n);
          for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) C(i, j) = rng.uniform(-1.0, 1.0);
          M += C - C.transpose();
        }
        VectorXd z0 = VectorXd::Zero(n), w0 = VectorXd::Zero(n);
        for (int i = 0; i < n; ++i) {
          const int pick = rng.integer(0, 3);
          if (pick <= 1) z0(i) = rng.uniform(0.1, 2.0);
          else if (pick == 2) w0(i) = rng.uniform(0.1, 2.0);
        }
        const VectorXd q = w0 - M * z0;
        const Enumeration e = enumerate(M, q, 1e-9);
        ASSERT_GE(e.solutions, 1) << "n " << n << " kind " << kind << " rep " << rep;
        VectorXd z;
        const Result r = solver.solve(M, q, z);
        ASSERT_EQ(r.status, Status::Solved) << "n " << n << " kind " << kind << " rep " << rep;
        EXPECT_LE(r.error, 1e-10) << "n " << n << " kind " << kind << " rep " << rep;
        EXPECT_GE(z.minCoeff(), 0.0);
        const VectorXd w = M * z + q, wE = M * e.z + q;
        if (kind == 0) {
          const double scale = std::max(1.0, wE.lpNorm<Eigen::Infinity>());
          EXPECT_LE((w - wE).lpNorm<Eigen::Infinity>(), 1e-9 * scale) << "n " << n << " rep " << rep;
        }
        const double qz = q.dot(z), qzE = q.dot(e.z);
        EXPECT_LE(std::abs(qz - qzE), 1e-9 * std::max(1.0, std::abs(qzE))) << "n " << n << " kind " << kind;
        worstError = std::max(worstError, r.error);
        ++problems;
      }
    }
  }
  EXPECT_EQ(problems, 500);
  std::printf("  PSD: %d problems, worst error %.3g\n", problems, worstError);
}

// =============================================================================================
// Planar friction contact through the LCP form (the fc2d files: collection_test.cpp)

// One contact with W = I, q = (-1, v), mu = 0.3: u = r + q, so r_N = 1 (u_N = 0); for |v| > mu
// the contact slides against u_T = v + r_T with r_T = -mu sign(v); for |v| <= mu it sticks with
// r_T = -v (u_T = 0). Exact data and a few operations: 1e-14.
TEST(LcpFrictionContact, SingleContactSlidesAndSticks) {
  FrictionProblem p;
  p.W = MatrixXd::Identity(2, 2);
  p.mu = VectorXd::Constant(1, 0.3);
  for (double v : {2.0, -2.0, 0.1, -0.25, 0.0}) {
    p.q = Eigen::Vector2d(-1.0, v);
    const ContactSolution s = solveFriction(p);
    ASSERT_EQ(s.result.status, Status::Solved) << "v = " << v;
    EXPECT_NEAR(s.r(0), 1.0, 1e-14);
    const double rT = std::abs(v) > 0.3 ? (v > 0 ? -0.3 : 0.3) : -v;
    EXPECT_NEAR(s.r(1), rT, 1e-14) << "v = " << v;
    expectCoulomb(p, s.r, s.u, 1e-14);
  }
}

// The slider-crank problems: forces against the README's reference values, listed to 5 decimal
// places, so the tolerance is half a unit in the fifth decimal, 5e-6 (+1e-12 for our rounding).
// The LCP error is at rounding level on 00000 (<= 1e-12); 00001 has a rank-deficient W (its two
// tangent columns are nearly equal), where the README accepts Siconos' 1e-5: we require that

// =============================================================================================
// Determinism and allocation

// Identical inputs give bit-identical outputs: the same solver object twice, after other solves
// in between (no state leaks), and a fresh solver.
TEST(LcpDeterminism, RepeatedSolvesAreBitIdentical) {
  for (const char* f : {"lcp_tobenna.dat", "lcp_mmc.dat", "lcp_enum_fails.dat"}) {
    const Problem p = readLcpFile(dataPath(f));
    const Problem other = readLcpFile(dataPath("lcp_CPS_4.dat"));
    LemkeSolver a(40);
    VectorXd z1, z2, z3, zo;
    const Result r1 = a.solve(p.M, p.q, z1);
    a.solve(other.M, other.q, zo);
    const Result r2 = a.solve(p.M, p.q, z2);
    LemkeSolver b;
    const Result r3 = b.solve(p.M, p.q, z3);
    ASSERT_EQ(z1.size(), z2.size());
    EXPECT_EQ(std::memcmp(z1.data(), z2.data(), sizeof(double) * static_cast<std::size_t>(z1.size())), 0) << f;
    EXPECT_EQ(std::memcmp(z1.data(), z3.data(), sizeof(double) * static_cast<std::size_t>(z1.size())), 0) << f;
    EXPECT_EQ(r1.pivots, r2.pivots);
    EXPECT_EQ(r1.pivots, r3.pivots);
    EXPECT_EQ(std::memcmp(&r1.error, &r2.error, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&r1.error, &r3.error, sizeof(double)), 0);
  }
}

// A solver sized once allocates nothing per solve for problems up to its capacity (solution
// vectors of the right size passed in): counted through malloc/calloc/realloc while solving the
// problems of tests/data/lcp, of sizes up to 40 (including ray terminations, an iteration limit and the
// periodic refactorizations of tobenna's 126 pivots). The counter is shown to work: a
// std::vector and an Eigen vector allocated in the counted region and a problem beyond the
// capacity are all counted.
TEST(LcpAllocation, NoHeapAllocationPerSolve) {
  if (!chaindrive::test::allocationCountingAvailable()) GTEST_SKIP() << "allocation counting needs glibc and no sanitizer";
  using chaindrive::test::countAllocations;
  std::vector<Problem> problems;
  for (const auto& f : datFiles(dataPath(""))) problems.push_back(readLcpFile(dataPath(f)));
  MatrixXd murtyM;
  VectorXd murtyQ;
  murty(10, murtyM, murtyQ);
  std::vector<VectorXd> zs;
  for (const auto& p : problems) zs.emplace_back(p.q.size());
  VectorXd zMurty(10);
  std::vector<Result> results(problems.size() + 1);
  LemkeSolver solver(40);

  const long duringSolves = countAllocations([&] {
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t i = 0; i < problems.size(); ++i) results[i] = solver.solve(problems[i].M, problems[i].q, zs[i]);
      results.back() = solver.solve(murtyM, murtyQ, zMurty, 100);
    }
  });
  const long probeCount = countAllocations([] {
    std::vector<double> probe(100);
    probe[0] = 1.0;
  });
  const long eigenProbeCount = countAllocations([] {
    VectorXd probe(100);
    probe(0) = 1.0;
  });
  MatrixXd bigM = MatrixXd::Identity(41, 41);
  VectorXd bigQ = VectorXd::Constant(41, -1.0), bigZ(41);
  Result big{};
  const long growCount = countAllocations([&] { big = solver.solve(bigM, bigQ, bigZ); });

  EXPECT_EQ(duringSolves, 0);
  EXPECT_GE(probeCount, 1);       // operator new is counted
  EXPECT_GE(eigenProbeCount, 1);  // Eigen's aligned malloc is counted
  EXPECT_GE(growCount, 1);        // the work arrays grow to 41 once
  EXPECT_EQ(big.status, Status::Solved);
  EXPECT_EQ(results.back().status, Status::IterationLimit);
  int solved = 0;
  for (std::size_t i = 0; i + 1 < results.size(); ++i) solved += results[i].status == Status::Solved;
  EXPECT_EQ(solved, 15);
}

// =============================================================================================
// Readers

namespace {
std::string readError(const std::string& path, bool fc2d = false) {
  try {
    if (fc2d) readFc2dFile(path);
    else readLcpFile(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

// The format: column-major matrix (each printed line is a column), q, then the comment.
TEST(LcpReader, ReadsColumnMajorMatrixQAndComment) {
  const Problem p = readLcpFile(dataPath("lcp_CPS_2.dat"));
  ASSERT_EQ(p.M.rows(), 3);
  MatrixXd M(3, 3);
  M << 0, -1, 2, 2, 0, -2, -1, 1, 0;  // the file's lines "0 2 -1", "-1 0 1", "2 -2 0" are columns
  EXPECT_EQ(p.M, M);
  EXPECT_EQ(p.q, Eigen::Vector3d(-3, 6, -1));
  EXPECT_EQ(p.comment, "Example 4.4.7 CPS 2009");
  const FrictionProblem f = readFc2dFile(dataPath("fc2d/FC2D_SliderCrankLagrangian00000.dat"));
  EXPECT_EQ(f.W.rows(), 4);
  EXPECT_EQ(f.mu, Eigen::Vector2d(0.01, 0.01));
  EXPECT_DOUBLE_EQ(f.W(1, 0), -4.642665883420582986218506e+02);
  EXPECT_DOUBLE_EQ(f.W(0, 1), -4.642662921766745967033785e+02);
}

// Every error names the file and what is wrong.
TEST(LcpReader, ErrorsNameTheFileAndTheProblem) {
  const std::string missing = ::testing::TempDir() + "no_such_lcp_file.dat";
  EXPECT_NE(readError(missing).find(missing), std::string::npos);
  EXPECT_NE(readError(missing).find("cannot open"), std::string::npos);

  struct Bad {
    const char* name;
    const char* text;
    const char* message;
    bool fc2d;
  };
  const Bad bad[] = {
      {"empty.dat", "", "expected the problem size n (an integer), found the end of the file", false},
      {"size.dat", "x\n", "expected the problem size n (an integer), found 'x'", false},
      {"zero.dat", "0\n0\n0\n0\n0 0\n", "problem size 0 is out of range", false},
      {"sparse.dat", "2\n1\n2\n2\n2 2\n", "storage type 1 of M is not supported", false},
      {"rows.dat", "2\n0\n3\n2\n2 2\n", "the number of rows of M is 3, expected 2", false},
      {"short.dat", "2\n0\n2\n2\n2 2\n1 0\n0 1\n-1\n", "expected entry 2 of the 2 of q, found the end of the file", false},
      {"word.dat", "2\n0\n2\n2\n2 2\n1 0\nzero 1\n-1 -1\n", "expected entry 3 of the 4 of M (a number), found 'zero'", false},
      {"dim.dat", "3\n1\n", "dimension 3 is not supported", true},
      {"mu.dat", "2\n1\n0\n2\n2\n2 2\n1 0 0 1\n-1 0\n-0.5\n", "friction coefficient 1 is -0.5", true},
  };
  for (const Bad& b : bad) {
    const std::string path = writeTemp(b.name, b.text);
    const std::string msg = readError(path, b.fc2d);
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find(b.message), std::string::npos) << b.name << ": " << msg;
  }
}

