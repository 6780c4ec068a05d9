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
#include <vector>
#include <limits>
#include <string>

#include "lcp/lemke.h"

using namespace chaindrive::lcp;

static void usage(std::FILE* out) {
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

static bool parseInt(const std::string& s, int& v) {
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

int main(int argc, char** argv) {
  std::string file;
  int maxPivots = -1;
  bool fc2d = false;
  int repeat = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      usage(stdout);
      return 0;
    } else if (a == "--fc2d") {
      fc2d = true;
    } else if (a == "--max-pivots") {
      if (i + 1 >= argc || !parseInt(argv[i + 1], maxPivots)) {
        std::fprintf(stderr, "chaindrive-lcp: --max-pivots needs a non-negative integer\n");
        usage(stderr);
        return 2;
      }
      ++i;
    } else if (a == "--repeat") {
      if (i + 1 >= argc || !parseInt(argv[i + 1], repeat) || repeat < 1) {
        std::fprintf(stderr, "chaindrive-lcp: --repeat needs a positive integer\n");
        usage(stderr);
        return 2;
      }
      ++i;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "chaindrive-lcp: unknown argument '%s'\n", a.c_str());
      usage(stderr);
      return 2;
    } else if (file.empty()) {
      file = a;
    } else {
      std::fprintf(stderr, "chaindrive-lcp: more than one file given ('%s', '%s')\n", file.c_str(), a.c_str());
      usage(stderr);
      return 2;
    }
  }
  if (file.empty()) {
    std::fprintf(stderr, "chaindrive-lcp: no problem file given\n");
    usage(stderr);
    return 2;
  }

  Eigen::MatrixXd M;
  Eigen::VectorXd q;
  FrictionProblem fp;
  try {
    if (fc2d) {
      fp = readFc2dFile(file);
      frictionToLcp(fp, M, q);
    } else {
      Problem p = readLcpFile(file);
      M = std::move(p.M);
      q = std::move(p.q);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "chaindrive-lcp: %s\n", e.what());
    return 2;
  }

  LemkeSolver solver(static_cast<int>(q.size()));
  Eigen::VectorXd z(q.size());
  const Result r = solver.solve(M, q, z, maxPivots);
  std::printf("status: %s\n", statusName(r.status));
  if (repeat > 0) {
    // median CPU time per solve (the solver is sized once; no allocation per solve)
    std::vector<double> times;
    for (int k = 0; k < repeat; ++k) {
      timespec a{}, b{};
      clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &a);
      solver.solve(M, q, z, maxPivots);
      clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &b);
      times.push_back(static_cast<double>(b.tv_sec - a.tv_sec) + 1e-9 * static_cast<double>(b.tv_nsec - a.tv_nsec));
    }
    std::sort(times.begin(), times.end());
    std::printf("time per solve: %.9g s (median of %d)\n", times[times.size() / 2], repeat);
  }
  std::printf("pivots: %d\n", r.pivots);
  std::printf("error: %.17g\n", r.error);
  std::printf("z:\n");
  for (Eigen::Index i = 0; i < z.size(); ++i) std::printf("%.17g\n", z(i));
  if (fc2d) {
    Eigen::VectorXd forces;
    lcpToForces(fp, z, forces);
    std::printf("r (r_N r_T per contact):\n");
    for (int c = 0; c < fp.contacts(); ++c) std::printf("%.17g %.17g\n", forces(2 * c), forces(2 * c + 1));
  }
  if (r.status == Status::IterationLimit) {
    // on stderr, so that the result format on stdout stays the same; after it in a shared log
    std::fflush(stdout);
    std::fprintf(stderr, "chaindrive-lcp: %s\n",
                 iterationLimitMessage(r, static_cast<int>(q.size()), "raise it with --max-pivots").c_str());
  }
  return r.status == Status::Solved ? 0 : 1;
}
