// The command-line tool chaindrive-lcp (src/cli/chaindrive_lcp.cpp), run as a separate process
// (build/chaindrive-lcp next to build/tests/cpp/chaindrive_tests): the printed result, the exit
// codes, the pivot cap on the command line and friction-contact files.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <system_error>

#include <sys/wait.h>

#include <Eigen/Dense>

#include "lcp/lcp_test_util.h"

using namespace chaindrive::lcp::test;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {
struct CliRun {
  int code;
  std::string out;
};

std::filesystem::path cliPath() {
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  return self.parent_path().parent_path().parent_path() / "chaindrive-lcp";
}

CliRun runCli(const std::string& args) {
  const std::string cmd = "'" + cliPath().string() + "' " + args + " 2>&1";
  CliRun r{-1, ""};
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  std::size_t got = 0;
  while ((got = std::fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, got);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// A run of a problem of size n stopped by a cap of `cap` pivots: exit code 1, the status and the
// pivots on stdout, and on stderr "chaindrive-lcp: LCP iteration limit: <cap> pivots without a
// solution (cap <cap> for n = <n>; raise it with --max-pivots)".
void expectStoppedAtTheCap(const CliRun& r, int cap, int n) {
  const std::string c = std::to_string(cap);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("status: IterationLimit\npivots: " + c + "\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("chaindrive-lcp: LCP iteration limit: " + c + " pivots without a solution (cap " + c +
                       " for n = " + std::to_string(n) + "; raise it with --max-pivots)\n"),
            std::string::npos)
      << r.out;
}
}  // namespace

// Exit codes 0 (solved), 1 (ray, limit), 2 (bad arguments, unreadable file naming it); output:
// status, pivots, error, z at full precision (17 significant digits).
TEST(LcpCli, PrintsTheResultAndUsesTheExitCodes) {
  if (!std::filesystem::exists(cliPath())) GTEST_SKIP() << "chaindrive-lcp not found at " << cliPath();
  CliRun r = runCli("'" + dataPath("lcp_deudeu.dat") + "'");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("status: Solved\npivots: 2\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n1.3333333333333333\n2.3333333333333335\n"), std::string::npos) << r.out;

  r = runCli("'" + dataPath("lcp_CPS_3.dat") + "'");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("status: RayTermination"), std::string::npos) << r.out;

  r = runCli("'" + dataPath("lcp_exp_murty2.dat") + "' --max-pivots 10");
  expectStoppedAtTheCap(r, 10, 6);

  r = runCli("--fc2d '" + dataPath("fc2d/FC2D_SliderCrankLagrangian00000.dat") + "'");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("r (r_N r_T per contact):\n0.0557794"), std::string::npos) << r.out;

  r = runCli("/nonexistent/problem.dat");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("/nonexistent/problem.dat"), std::string::npos) << r.out;

  r = runCli("'" + dataPath("lcp_deudeu.dat") + "' --max-pivots many");
  EXPECT_EQ(r.code, 2) << r.out;
  r = runCli("");
  EXPECT_EQ(r.code, 2) << r.out;
  r = runCli("'" + dataPath("lcp_deudeu.dat") + "' --frobnicate");
  EXPECT_EQ(r.code, 2) << r.out;
}

namespace {
// Murty's example of size n as a file of the Siconos dense format (integers: exact in text).
std::string writeMurtyFile(int n) {
  MatrixXd M;
  VectorXd q;
  murty(n, M, q);
  std::ostringstream text;
  text.precision(17);
  text << n << "\n0\n" << n << "\n" << n << "\n" << n << " " << n << "\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) text << M(i, j) << (i + 1 == n ? "\n" : " ");
  for (int i = 0; i < n; ++i) text << q(i) << (i + 1 == n ? "\n" : " ");
  text << "Murty's exponential example, n = " << n << "\n";
  return writeTemp("murty" + std::to_string(n) + ".dat", text.str());
}
}  // namespace

// The default cap on the command line: Murty n = 12 (4095 pivots) is solved; n = 15 (32767
// pivots) stops at its cap of 22500 with exit code 1, the status and pivots on stdout and the
// pivots and the cap on stderr.
TEST(LcpCli, DefaultCapSolvesMurty12AndReportsACappedRun) {
  if (!std::filesystem::exists(cliPath())) GTEST_SKIP() << "chaindrive-lcp not found at " << cliPath();
  CliRun r = runCli("'" + writeMurtyFile(12) + "'");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("status: Solved\npivots: 4095\nerror: 0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n4096\n"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("iteration limit"), std::string::npos) << r.out;

  r = runCli("'" + writeMurtyFile(15) + "'");
  expectStoppedAtTheCap(r, 22500, 15);
}
