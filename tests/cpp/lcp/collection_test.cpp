// The LCP test collection against Lemke's method (src/lcp/lemke.*): every problem file of
// tests/data/lcp (the Siconos collection), tests/data/lcp_chain (LCPs recorded from the drive)
// and tests/data/lcp/fc2d (planar friction contact) with the expected result of each listed in
// one table, expected failures (ray termination) included, and a check that the table covers
// every file.
//
// Solver configurations. There is one solver for plain LCP files: LemkeSolver (lexicographic
// Lemke) with its default pivot cap; src/lcp has no other pivoting rule or LCP method, so each
// .dat file of lcp/ and lcp_chain/ is solved once. The fc2d files are friction-contact problems,
// not LCPs: they are solved by the same Lemke through the friction-contact LCP form
// (frictionToLcp, forces by lcpToForces), the only way the project solves them. The table names
// the configuration of each row.
//
// Where the table cannot hold the expected result (a solution set, a solution Lemke does not
// find, the data proof that none exists, forces in closed form from the data), a detail test
// below checks it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "lcp/lemke.h"
#include "lcp/lcp_test_util.h"

using namespace chaindrive::lcp;
using namespace chaindrive::lcp::test;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

enum class Solver {
  Lemke,          // LemkeSolver on (M, q) of the file, default pivot cap
  LemkeFriction,  // LemkeSolver, default pivot cap, on frictionToLcp of an fc2d file
};

const char* solverName(Solver s) { return s == Solver::Lemke ? "Lemke" : "Lemke (friction LCP form)"; }

struct CollectionCase {
  const char* file;       // relative to tests/data
  Solver solver;
  Status status;          // the expected status
  int pivots;             // expected pivot count, -1: not checked
  double errorTol;        // bound on Result::error (checked only where the status is Solved)
  std::vector<double> x;  // expected leading entries of z (Lemke) or of the forces r (friction); empty: not checked
  double xTol;            // absolute tolerance on those entries
  int contacts;           // friction: the number of contacts in the file (0 for plain LCPs)
};

// Tolerances. Lcp files: exact listed values (fractions, integers) are compared to 1e-13
// absolute (a few hundred rounding units of O(1) data after a handful of pivots; the final basis
// is refactorized and refined); values listed to k decimal digits are compared to half a unit in
// the last listed digit (the rounding of the table itself). Pivot counts are those of Siconos'
// lexicographic Lemke where the README gives them: the same pivoting rule gives the same path.
// Error where solved: <= 1e-12 (the exact solution's error is 0; the computed one carries only
// rounding: seen up to 6e-14 on tobenna).
// lcp_chain files (tests/data/lcp_chain/README.md): singular Delassus matrices; solved with
// Siconos' pivot counts and an error at rounding level (Siconos: 2e-15 and 6e-16), <= 1e-12.
// fc2d slider-crank: forces against the README's reference values, listed to 5 decimal places,
// so the tolerance is half a unit in the fifth decimal, 5e-6 (+1e-12 for our rounding). The LCP
// error is at rounding level on 00000 (<= 1e-12); 00001 has a rank-deficient W (its two tangent
// columns are nearly equal), where the README accepts Siconos' 1e-5: we require that (seen:
// about 3e-16).
// fc2d 00394: q is rounding noise (|q| < 2e-15): all 12 forces zero, to 1e-12 (W ~ 0.4, so
// forces of the size of q / W would be ~1e-15). fc2d 00374: the README's "all zero" is wrong;
// its forces follow in closed form from the data (detail test below).
// Every fc2d row also checks the contact laws, to 1e-12 of the data scale max(1, |q|_inf) (|q|
// ~ 10 on the slider-crank and 37 on 00374; on 00394, whose q is rounding noise, 1e-12 absolute).
const std::vector<CollectionCase>& collection() {
  static const std::vector<CollectionCase> cases = {
      {"lcp/lcp_deudeu.dat", Solver::Lemke, Status::Solved, 2, 1e-12, {4.0 / 3.0, 7.0 / 3.0}, 1e-13, 0},
      {"lcp/lcp_trivial.dat", Solver::Lemke, Status::Solved, -1, 1e-12, {1.0, 1.0 / 2, 1.0 / 3, 1.0 / 4, 1.0 / 5, 1.0 / 6, 1.0 / 7, 1.0 / 8, 1.0 / 9}, 1e-13, 0},
      {"lcp/lcp_ortiz.dat", Solver::Lemke, Status::Solved, -1, 1e-12, {2.0 / 3.0, 0.0, 1.0 / 3.0, 0.0}, 1e-13, 0},
      {"lcp/lcp_CPS_1.dat", Solver::Lemke, Status::Solved, -1, 1e-12, {}, 0.0, 0},  // z1 + z2 = 1: detail test
      {"lcp/lcp_CPS_2.dat", Solver::Lemke, Status::Solved, -1, 1e-12, {0.0, 1.0, 3.0}, 1e-13, 0},
      {"lcp/lcp_CPS_3.dat", Solver::Lemke, Status::RayTermination, -1, 0.0, {}, 0.0, 0},  // a solution exists: detail test
      {"lcp/lcp_CPS_4.dat", Solver::Lemke, Status::Solved, -1, 1e-12, {2.0, 2.0, 2.0, 92.0}, 1e-12, 0},  // 92: 1e-13 of its size
      {"lcp/lcp_CPS_4bis.dat", Solver::Lemke, Status::Solved, -1, 1e-12, {3.0, 3.0, 0.0, 83.0}, 1e-12, 0},
      {"lcp/lcp_CPS_5.dat", Solver::Lemke, Status::Solved, -1, 1e-12, {0.0, 1.0}, 1e-13, 0},
      {"lcp/lcp_mmc.dat", Solver::Lemke, Status::Solved, 22, 1e-12, {1.4914e-4, 1.4102e-4}, 0.5e-8, 0},  // 5 significant digits
      {"lcp/lcp_exp_murty.dat", Solver::Lemke, Status::Solved, -1, 1e-12, {0, 0, 0, 0, 0, 1}, 1e-13, 0},
      {"lcp/lcp_Pang_isolated_sol.dat", Solver::Lemke, Status::Solved, -1, 1e-12, {1.0, 0.0, 0.0}, 1e-13, 0},
      {"lcp/lcp_inf_sol_perturbed.dat", Solver::Lemke, Status::Solved, -1, 1e-12, {1.0, 0.0, 1e-4}, 1e-13, 0},
      {"lcp/lcp_enum_fails.dat", Solver::Lemke, Status::Solved, 7, 1e-12, {6.4499e-5, 3.7109e-6, 0.0, 8.0163e-5}, 0.5e-9, 0},  // 5 digits of the largest
      {"lcp/lcp_tobenna.dat", Solver::Lemke, Status::Solved, 126, 1e-12, {0.5422, 0.4578}, 0.5e-4, 0},  // 4 decimals
      {"lcp/lcp_exp_murty2.dat", Solver::Lemke, Status::Solved, 63, 1e-12, {0, 0, 0, 0, 0, 64.0}, 1e-12, 0},
      {"lcp/lcp_Pang_isolated_sol_perturbed.dat", Solver::Lemke, Status::RayTermination, -1, 0.0, {}, 0.0, 0},  // no solution: detail test
      {"lcp_chain/chain_ts_singular_1.dat", Solver::Lemke, Status::Solved, 91, 1e-12, {}, 0.0, 0},
      {"lcp_chain/chain_ts_singular_2.dat", Solver::Lemke, Status::Solved, 75, 1e-12, {}, 0.0, 0},
      {"lcp/fc2d/FC2D_SliderCrankLagrangian00000.dat", Solver::LemkeFriction, Status::Solved, -1, 1e-12, {0.05578, 0.00056, 0.05522, 0.00055}, 5e-6 + 1e-12, 2},
      {"lcp/fc2d/FC2D_SliderCrankLagrangian00001.dat", Solver::LemkeFriction, Status::Solved, -1, 1e-5, {0.04453, 0.00045, 0.04408, 0.00044}, 5e-6 + 1e-12, 2},
      {"lcp/fc2d/FrictionContactProblem00374.dat", Solver::LemkeFriction, Status::Solved, -1, 1e-12, {}, 0.0, 28},  // forces: detail test
      {"lcp/fc2d/FrictionContactProblem00394.dat", Solver::LemkeFriction, Status::Solved, -1, 1e-12, std::vector<double>(12, 0.0), 1e-12, 6},
  };
  return cases;
}

// gtest prints the parameter by its file name
void PrintTo(const CollectionCase& c, std::ostream* os) { *os << c.file << " (" << solverName(c.solver) << ")"; }

// (the fixture and its test in the unnamed namespace too: a class of external linkage derived
// from one with internal linkage is an error when the file is compiled in a batch with others)
class LcpCollection : public ::testing::TestWithParam<CollectionCase> {};

// Status, pivots and solution (or forces) as in the table; where solved, the error within the
// row's bound and equal to lcpError of the returned z, z >= 0, and for friction the contact laws.
TEST_P(LcpCollection, MatchesTheExpectedResult) {
  const CollectionCase& c = GetParam();
  const std::string path = testDataPath(c.file);
  Problem p;          // the LCP solved: the file's, or the friction-contact LCP form
  FrictionProblem f;  // friction only
  Outcome o;
  VectorXd x, u;  // the checked solution: z, or the forces r with the velocities u
  if (c.solver == Solver::Lemke) {
    p = readLcpFile(path);
    o = solveProblem(p.M, p.q);
    x = o.z;
  } else {
    f = readFc2dFile(path);
    ASSERT_EQ(f.contacts(), c.contacts);
    ContactSolution s = solveFriction(f);
    p.M = std::move(s.M);
    p.q = std::move(s.q);
    o.result = s.result;
    o.z = std::move(s.z);
    x = std::move(s.r);
    u = std::move(s.u);
  }
  ASSERT_EQ(statusName(o.result.status), std::string(statusName(c.status)));
  if (c.pivots >= 0) {
    EXPECT_EQ(o.result.pivots, c.pivots);
  }
  if (c.status == Status::Solved) {
    EXPECT_LE(o.result.error, c.errorTol);
    EXPECT_DOUBLE_EQ(o.result.error, lcpError(p.M, p.q, o.z));
    EXPECT_GE(o.z.minCoeff(), 0.0);
    if (c.solver == Solver::LemkeFriction) expectCoulomb(f, x, u, 1e-12 * std::max(1.0, f.q.lpNorm<Eigen::Infinity>()));
  }
  const char* name = c.solver == Solver::Lemke ? "z_" : "r_";
  ASSERT_LE(c.x.size(), static_cast<std::size_t>(x.size()));
  for (std::size_t i = 0; i < c.x.size(); ++i)
    EXPECT_NEAR(x(static_cast<Eigen::Index>(i)), c.x[i], c.xTol) << name << i + 1;
  RecordProperty("pivots", o.result.pivots);
  std::printf("  %-45s %-15s pivots %4d  error %.3g\n", c.file, statusName(o.result.status), o.result.pivots,
              o.result.error);
}

INSTANTIATE_TEST_SUITE_P(LcpSiconos, LcpCollection, ::testing::ValuesIn(collection()),
                         [](const ::testing::TestParamInfo<CollectionCase>& param) {
                           std::string s = std::filesystem::path(param.param.file).stem().string();
                           for (char& ch : s)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return s;
                         });

}  // namespace

// The table covers every problem file of the three folders, each once with its solver
// configuration, and nothing else (a new file must be added).
TEST(LcpCollectionFiles, TableCoversEveryFile) {
  std::vector<std::pair<std::string, Solver>> files;
  for (const auto& [folder, solver] : {std::pair<std::string, Solver>{"lcp/", Solver::Lemke},
                                       {"lcp_chain/", Solver::Lemke},
                                       {"lcp/fc2d/", Solver::LemkeFriction}})
    for (const auto& f : datFiles(testDataPath(folder))) files.emplace_back(folder + f, solver);
  EXPECT_EQ(files.size(), collection().size());
  for (const auto& [f, solver] : files) {
    int rows = 0;
    for (const auto& c : collection()) rows += f == c.file && solver == c.solver;
    EXPECT_EQ(rows, 1) << f << " with " << solverName(solver) << " is not in the test table once";
  }
}

// CPS_1: M = [[1, 1], [1, 1]], q = (-1, -1): every z >= 0 with z1 + z2 = 1 solves it (singular
// M); the sum is exact up to rounding (1e-14).
TEST(LcpCollectionDetails, Cps1SolutionOnTheSegment) {
  const Problem p = readLcpFile(dataPath("lcp_CPS_1.dat"));
  const Outcome o = solveProblem(p.M, p.q);
  ASSERT_EQ(o.result.status, Status::Solved);
  EXPECT_NEAR(o.z(0) + o.z(1), 1.0, 1e-14);
  EXPECT_GE(o.z.minCoeff(), 0.0);
  EXPECT_NE(p.comment.find("z_1 + z_2 = 1"), std::string::npos) << p.comment;
}

// CPS_3 (a bimatrix game): Lemke stops on a ray although a solution exists; the README's
// enumerated solution (1/90, 2/45, 1/90, 2/45) does solve it (error at rounding level, 1e-15).
TEST(LcpCollectionDetails, Cps3RayTerminationThoughASolutionExists) {
  const Problem p = readLcpFile(dataPath("lcp_CPS_3.dat"));
  EXPECT_EQ(solveProblem(p.M, p.q).result.status, Status::RayTermination);
  VectorXd z(4);
  z << 1.0 / 90, 2.0 / 45, 1.0 / 90, 2.0 / 45;
  EXPECT_LE(lcpError(p.M, p.q, z), 1e-15);
}

// Pang perturbed: row 1 of M is (0, -1, -1) and q_1 = -1e-4, so w_1 < 0 for every z >= 0: there is
// no solution, and the solver must not claim one (exact data check, then the status).
TEST(LcpCollectionDetails, PangPerturbedHasNoSolutionAndIsNotSolved) {
  const Problem p = readLcpFile(dataPath("lcp_Pang_isolated_sol_perturbed.dat"));
  EXPECT_EQ(p.M(0, 0), 0.0);
  EXPECT_EQ(p.M(0, 1), -1.0);
  EXPECT_EQ(p.M(0, 2), -1.0);
  EXPECT_EQ(p.q(0), -1e-4);
  const Outcome o = solveProblem(p.M, p.q);
  EXPECT_NE(o.result.status, Status::Solved);
  EXPECT_EQ(o.result.status, Status::RayTermination);
}

// FrictionContactProblem00374: the README lists "all zero", but the file does not allow that:
// contacts 12..21 (1-based) have q_N = -36.7875 with W rows and columns that are diagonal
// (decoupled from everything else), so u_N = W_NN r_N + q_N >= 0 forces r_N = 36.7875 / W_NN
// (147..178) there; q_T = 0 gives r_T = 0. All other contacts have q_N >= -2e-15 and zero
// forces. Checked against this closed form to 1e-12 relative to the largest force (rounding),
// and against the contact laws directly.
TEST(LcpFrictionContact, Problem00374MatchesTheDecoupledClosedForm) {
  const FrictionProblem p = readFc2dFile(dataPath("fc2d/FrictionContactProblem00374.dat"));
  ASSERT_EQ(p.contacts(), 28);
  VectorXd rExact = VectorXd::Zero(56);
  int loaded = 0;
  for (int i = 0; i < 28; ++i) {
    if (p.q(2 * i) < -1.0) {
      // the closed form needs the contact to be decoupled: check that
      for (int j = 0; j < 56; ++j) {
        if (j == 2 * i || j == 2 * i + 1) continue;
        ASSERT_EQ(p.W(2 * i, j), 0.0);
        ASSERT_EQ(p.W(2 * i + 1, j), 0.0);
        ASSERT_EQ(p.W(j, 2 * i), 0.0);
        ASSERT_EQ(p.W(j, 2 * i + 1), 0.0);
      }
      ASSERT_EQ(p.W(2 * i, 2 * i + 1), 0.0);
      ASSERT_EQ(p.W(2 * i + 1, 2 * i), 0.0);
      ASSERT_EQ(p.q(2 * i + 1), 0.0);
      rExact(2 * i) = -p.q(2 * i) / p.W(2 * i, 2 * i);
      ++loaded;
    }
  }
  EXPECT_EQ(loaded, 10);
  const ContactSolution s = solveFriction(p);
  ASSERT_EQ(s.result.status, Status::Solved);
  EXPECT_LE(s.result.error, 1e-12);
  EXPECT_LE((s.r - rExact).lpNorm<Eigen::Infinity>(), 1e-12 * rExact.lpNorm<Eigen::Infinity>());
  expectCoulomb(p, s.r, s.u, 1e-12 * p.q.lpNorm<Eigen::Infinity>());
  std::printf("  00374: pivots %d  error %.3g  max |r - r_exact| %.3g (max r %.6g)\n", s.result.pivots,
              s.result.error, (s.r - rExact).lpNorm<Eigen::Infinity>(), rExact.maxCoeff());
}
