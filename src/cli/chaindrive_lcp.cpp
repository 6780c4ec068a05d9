// chaindrive-lcp: solves a linear complementarity problem from a file (Siconos dense format) or a
// planar friction-contact problem (Siconos fc2d format, solved through its LCP form) with Lemke's
// method and prints the status, the number of pivots, the error and z.
//
// Exit codes: 0 solved; 1 ray termination, iteration limit or numerical failure (the status is
// still printed; an iteration limit also gets a line on stderr with the pivots and the cap);
// 2 bad arguments or an unreadable file.
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/arguments.h"
#include "lcp/lemke.h"

using namespace chaindrive::lcp;
namespace cli = chaindrive::cli;

namespace {

constexpr const char* kTool = "chaindrive-lcp";

void usage(std::FILE* out) {
  std::fputs(
      "usage: chaindrive-lcp FILE [--max-pivots N] [--fc2d] [--repeat N]\n"
      "  Solves the LCP w = M z + q >= 0, z >= 0, w'z = 0 read from FILE (Siconos dense format)\n"
      "  with Lemke's method (lexicographic). With --fc2d, FILE is a planar friction-contact\n"
      "  problem (Siconos fc2d format), solved through its LCP form; the contact forces\n"
      "  (r_N, r_T per contact) are printed after z.\n"
      "  Prints: status, pivots, error, then z one value per line (full precision). With --repeat N\n"
      "  the problem is solved N times and the median CPU time per solve is printed as well.\n"
      "  --max-pivots N caps the pivots (default max(10000, 100 n^2) for a problem of size n).\n"
      "  Exit code: 0 solved; 1 ray termination, iteration limit (also reported on stderr with\n"
      "  the pivots and the cap), numerical failure; 2 bad arguments or unreadable file.\n",
      out);
}

bool parseInt(const std::string& s, int& v) {
  if (s.empty()) return false;
  std::size_t used = 0;
  try {
    const long long x = std::stoll(s, &used);
    if (used != s.size() || x < 0 || x > std::numeric_limits<int>::max()) return false;
    v = static_cast<int>(x);
  } catch (const std::exception&) {
    return false;
  }
  return true;
}

struct LcpArguments {
  std::string file;
  int maxPivots = -1;
  bool fc2d = false;
  int repeat = 0;
};

// One problem file and the options in any order; -h/--help ends the reading. Throws
// std::invalid_argument for a bad argument.
LcpArguments parseArguments(cli::Arguments& args) {
  LcpArguments r;
  while (args.next()) {
    const std::string& a = args.current();
    if (a == "--fc2d") {
      r.fc2d = true;
    } else if (a == "--max-pivots") {
      if (!args.hasValue() || !parseInt(args.value(), r.maxPivots))
        throw std::invalid_argument("--max-pivots needs a non-negative integer");
    } else if (a == "--repeat") {
      if (!args.hasValue() || !parseInt(args.value(), r.repeat) || r.repeat < 1)
        throw std::invalid_argument("--repeat needs a positive integer");
    } else if (!a.empty() && a[0] == '-') {
      throw std::invalid_argument("unknown argument '" + a + "'");
    } else if (r.file.empty()) {
      r.file = a;
    } else {
      throw std::invalid_argument("more than one file given ('" + r.file + "', '" + a + "')");
    }
  }
  if (!args.help() && r.file.empty()) throw std::invalid_argument("no problem file given");
  return r;
}

// The problem in its LCP form (M, q); an fc2d problem keeps its friction form for the forces.
struct LcpProblem {
  Eigen::MatrixXd M;
  Eigen::VectorXd q;
  FrictionProblem fp;
};

LcpProblem readProblem(const LcpArguments& r) {
  LcpProblem p;
  if (r.fc2d) {
    p.fp = readFc2dFile(r.file);
    frictionToLcp(p.fp, p.M, p.q);
  } else {
    Problem lp = readLcpFile(r.file);
    p.M = std::move(lp.M);
    p.q = std::move(lp.q);
  }
  return p;
}

// The median CPU time per solve of `repeat` more solves (the solver is sized once; no allocation
// per solve); z holds the last one's solution.
void printMedianTime(LemkeSolver& solver, const LcpProblem& p, Eigen::VectorXd& z, const LcpArguments& r) {
  std::vector<double> times;
  for (int k = 0; k < r.repeat; ++k) {
    timespec a{}, b{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &a);
    solver.solve(p.M, p.q, z, r.maxPivots);
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &b);
    times.push_back(static_cast<double>(b.tv_sec - a.tv_sec) + 1e-9 * static_cast<double>(b.tv_nsec - a.tv_nsec));
  }
  std::sort(times.begin(), times.end());
  std::printf("time per solve: %.9g s (median of %d)\n", times[times.size() / 2], r.repeat);
}

// Solves and prints status, pivots, error, z (and the contact forces of an fc2d problem); returns
// the exit code.
int solve(const LcpProblem& p, const LcpArguments& r) {
  LemkeSolver solver(static_cast<int>(p.q.size()));
  Eigen::VectorXd z(p.q.size());
  const Result res = solver.solve(p.M, p.q, z, r.maxPivots);
  std::printf("status: %s\n", statusName(res.status));
  if (r.repeat > 0) printMedianTime(solver, p, z, r);
  // the solution, then the contact forces of a friction problem
  std::printf("pivots: %d\n", res.pivots);
  std::printf("error: %.17g\n", res.error);
  std::printf("z:\n");
  for (Eigen::Index i = 0; i < z.size(); ++i) std::printf("%.17g\n", z(i));
  if (r.fc2d) {
    Eigen::VectorXd forces;
    lcpToForces(p.fp, z, forces);
    std::printf("r (r_N r_T per contact):\n");
    for (int c = 0; c < p.fp.contacts(); ++c) std::printf("%.17g %.17g\n", forces(2 * c), forces(2 * c + 1));
  }
  if (res.status == Status::IterationLimit) {
    // on stderr, so that the result format on stdout stays the same; after it in a shared log
    std::fflush(stdout);
    std::fprintf(stderr, "chaindrive-lcp: %s\n",
                 iterationLimitMessage(res, static_cast<int>(p.q.size()), "raise it with --max-pivots").c_str());
  }
  return res.status == Status::Solved ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  // the command line: a bad one is reported in one line on stderr
  cli::Arguments args(argc, argv);
  LcpArguments parsed;
  try {
    parsed = parseArguments(args);
  } catch (const std::exception& e) {
    return cli::argumentError(kTool, e.what());
  }
  if (args.help()) {
    usage(stdout);
    return 0;
  }
  // the problem (an unreadable file counts as a bad argument), its solution
  LcpProblem problem;
  try {
    problem = readProblem(parsed);
  } catch (const std::exception& e) {
    return cli::userError(kTool, e.what());
  }
  return solve(problem, parsed);
}
