// Lemke's method with lexicographic degeneracy resolution; readers of the Siconos test formats;
// the LCP form of planar friction-contact problems. See lemke.h for the method and conventions.
#include "lcp/lemke.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace chaindrive::lcp {

namespace {

// An entry a_i of the entering column counts as positive only above this factor times the bound
// |B^-1 row i|_1 |A_e|_inf of its rounding error: smaller ones are rounding noise of zeros.
constexpr double kPivotTolerance = 1e-13;
// A basic value b_i (or an entry of B^-1) counts as zero within this many units of roundoff
// times its rounding bound |B^-1 row i|_1 |q|_inf (|B^-1 row i|_1).
constexpr double kZeroTolerance = 16.0;
// Two nonzero ratios (or lexicographic components) tie within this relative difference.
constexpr double kTieTolerance = 1e-12;
// The inverse basis is recomputed from scratch every this many pivots.
constexpr int kRefactorInterval = 50;
// A basis that Lemke's method ends with is accepted as a solution only if its error (see
// lemke.h) is below this; above it the basis was numerically singular (NumericalFailure).
constexpr double kAcceptedError = 1e-8;
// The default pivot cap (lemke.h, "Pivot cap"): never below Siconos' default for
// lcp_lexicolemke, growing as this factor times n^2 so that a capped run costs O(n^4).
constexpr long long kSiconosMaxPivots = 10000;
constexpr long long kPivotsPerSquaredSize = 100;

double naturalMapError(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
                       const Eigen::Ref<const Eigen::VectorXd>& z) {
  const Eigen::Index n = q.size();
  double sum = 0.0, qsum = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    double w = q(i);
    for (Eigen::Index j = 0; j < n; ++j) w += M(i, j) * z(j);
    const double e = z(i) - std::max(0.0, z(i) - w);
    sum += e * e;
    qsum += q(i) * q(i);
  }
  const double err = std::sqrt(sum), qn = std::sqrt(qsum);
  return qn > std::numeric_limits<double>::epsilon() ? err / qn : err;
}

}  // namespace

const char* statusName(Status s) noexcept {
  switch (s) {
    case Status::Solved: return "Solved";
    case Status::RayTermination: return "RayTermination";
    case Status::IterationLimit: return "IterationLimit";
    case Status::NumericalFailure: return "NumericalFailure";
  }
  return "Unknown";
}

double lcpError(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
                const Eigen::Ref<const Eigen::VectorXd>& z) {
  if (M.rows() != q.size() || M.cols() != q.size() || z.size() != q.size())
    throw std::invalid_argument("lcpError: M, q and z sizes differ");
  return naturalMapError(M, q, z);
}

// ---------------------------------------------------------------------------------------------
// LemkeSolver

LemkeSolver::LemkeSolver(int capacity) { reserve(capacity); }

void LemkeSolver::reserve(int n) {
  if (n <= capacity_) return;
  capacity_ = n;
  binv_.resize(n, n);
  work_.resize(n, n);
  b_.resize(n);
  a_.resize(n);
  rowr_.resize(n);
  rowNorm_.resize(n);
  tmp_.resize(n);
  zBest_.resize(n);
  basis_.assign(static_cast<std::size_t>(n), 0);
  cand_.assign(static_cast<std::size_t>(n), 0);
}

int LemkeSolver::defaultMaxPivots(int n) noexcept {
  constexpr long long intMax = std::numeric_limits<int>::max();
  const long long size = std::max(n, 0);
  // n^2 clamped first so that the product cannot overflow for any int n
  const long long squaredSize = std::min(size * size, intMax);
  const long long cap = std::max(kSiconosMaxPivots, kPivotsPerSquaredSize * squaredSize);
  return static_cast<int>(std::min(cap, intMax));
}

std::string iterationLimitMessage(const Result& r, int n, const std::string& howToRaise) {
  return "LCP iteration limit: " + std::to_string(r.pivots) + " pivots without a solution (cap " +
         std::to_string(r.maxPivots) + " for n = " + std::to_string(n) +
         (howToRaise.empty() ? std::string() : "; " + howToRaise) + ")";
}

Result LemkeSolver::solve(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
                          Eigen::VectorXd& z, int maxPivots) {
  if (M.rows() != q.size() || M.cols() != q.size())
    throw std::invalid_argument("LemkeSolver::solve: M is " + std::to_string(M.rows()) + "x" +
                                std::to_string(M.cols()) + " but q has size " + std::to_string(q.size()));
  if (z.size() != q.size()) z.resize(q.size());
  return run(M, q, z, maxPivots);
}

Result LemkeSolver::solve(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
                          Eigen::Ref<Eigen::VectorXd> z, int maxPivots) {
  if (M.rows() != q.size() || M.cols() != q.size() || z.size() != q.size())
    throw std::invalid_argument("LemkeSolver::solve: M is " + std::to_string(M.rows()) + "x" +
                                std::to_string(M.cols()) + ", q has size " + std::to_string(q.size()) +
                                ", z has size " + std::to_string(z.size()));
  return run(M, q, z, maxPivots);
}

// The column B^-1 A_e of variable var into a; colNorm = |A_e|_inf. The columns of the augmented
// system w - M z - d z0 = q: w_k -> e_k, z_k -> -M_.k, z0 -> -d = -(1, ..., 1).
void LemkeSolver::column(const Eigen::Ref<const Eigen::MatrixXd>& M, int n, int var, double* a,
                         double& colNorm) const {
  Eigen::Map<Eigen::VectorXd> av(a, n);
  if (var < n) {
    av = binv_.col(var).head(n);
    colNorm = 1.0;
  } else if (var < 2 * n) {
    const int k = var - n;
    av.setZero();
    colNorm = 0.0;
    for (int j = 0; j < n; ++j) {
      const double m = M(j, k);
      if (m == 0.0) continue;
      av.noalias() -= m * binv_.col(j).head(n);
      colNorm = std::max(colNorm, std::abs(m));
    }
  } else {
    av.setZero();
    for (int j = 0; j < n; ++j) av.noalias() -= binv_.col(j).head(n);
    colNorm = 1.0;
  }
}

// Lexicographic minimum ratio test on the entering column a_; returns the pivot row or -1 (no
// positive entry: ray termination).
int LemkeSolver::ratioTest(int n, double qNorm, double colNorm) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  // the 1-norms of the rows of B^-1, summed column by column (contiguous; each row's sum in the
  // order of its columns all the same)
  auto norms = rowNorm_.head(n);
  norms.setZero();
  for (int c = 0; c < n; ++c) norms += binv_.col(c).head(n).cwiseAbs();
  int nc = 0;
  for (int i = 0; i < n; ++i) {
    const double ai = a_(i);
    if (ai > 0.0 && ai > kPivotTolerance * norms(i) * colNorm) cand_[static_cast<std::size_t>(nc++)] = i;
  }
  if (nc == 0) return -1;

  // Keeps the candidates whose value is the minimum within kTieTolerance (relative).
  auto keepMinimisers = [&](auto value) {
    double vmin = value(cand_[0]);
    for (int c = 1; c < nc; ++c) vmin = std::min(vmin, value(cand_[static_cast<std::size_t>(c)]));
    int kept = 0;
    for (int c = 0; c < nc; ++c) {
      const int i = cand_[static_cast<std::size_t>(c)];
      if (value(i) - vmin <= kTieTolerance * std::abs(vmin)) cand_[static_cast<std::size_t>(kept++)] = i;
    }
    nc = kept;
  };

  // First component: the ratio b_i / a_i. A basic value within its rounding bound of zero counts
  // as zero (the degenerate rows that the lexicographic rule is for); other ratios tie only if
  // they agree to a few units in the last place.
  keepMinimisers([&](int i) {
    const double bi = b_(i);
    return bi <= kZeroTolerance * eps * rowNorm_(i) * qNorm ? 0.0 : bi / a_(i);
  });
  if (nc == 1) return cand_[0];
  // z0 among the minimisers: let it leave (that ends the method with a solution).
  for (int c = 0; c < nc; ++c)
    if (basis_[static_cast<std::size_t>(cand_[static_cast<std::size_t>(c)])] == 2 * n)
      return cand_[static_cast<std::size_t>(c)];

  // Further components: the columns of B^-1, divided by a_i, in order; entries within their
  // rounding bound of zero count as zero.
  for (int k = 0; k < n && nc > 1; ++k)
    keepMinimisers([&](int i) {
      const double v = binv_(i, k);
      return std::abs(v) <= kZeroTolerance * eps * rowNorm_(i) ? 0.0 : v / a_(i);
    });
  // Still tied (only for a numerically singular basis): the largest pivot, then the first row.
  int best = cand_[0];
  for (int c = 1; c < nc; ++c) {
    const int i = cand_[static_cast<std::size_t>(c)];
    if (a_(i) > a_(best)) best = i;
  }
  return best;
}

// Pivot on row r with the entering column a_: the rank-one update of B^-1 and b.
void LemkeSolver::pivot(int n, int r) {
  const double ar = a_(r);
  rowr_.head(n) = binv_.row(r).head(n).transpose() / ar;
  for (int j = 0; j < n; ++j) {
    const double t = rowr_(j);
    if (t != 0.0) binv_.col(j).head(n).noalias() -= t * a_.head(n);
    binv_(r, j) = t;
  }
  const double br = b_(r) / ar;
  b_.head(n).noalias() -= br * a_.head(n);
  b_(r) = br;
}

// Recomputes B^-1 from the basis (Gauss-Jordan with partial pivoting) and b = B^-1 q with one
// step of iterative refinement. Returns false if the basis is numerically singular.
bool LemkeSolver::refactor(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
                           int n) {
  basisMatrix(M, n);
  if (!invertBasis(n)) return false;
  basicValues(M, q, n);
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(b_(i))) return false;
  return true;
}

// The basis matrix B into work_: the column of each basic variable (w_i: e_i, z_j: -M_.j,
// z0: -1).
void LemkeSolver::basisMatrix(const Eigen::Ref<const Eigen::MatrixXd>& M, int n) {
  auto W = work_.topLeftCorner(n, n);
  for (int j = 0; j < n; ++j) {
    const int var = basis_[static_cast<std::size_t>(j)];
    if (var < n) {
      W.col(j).setZero();
      W(var, j) = 1.0;
    } else if (var < 2 * n) {
      W.col(j) = -M.col(var - n);
    } else {
      W.col(j).setConstant(-1.0);
    }
  }
}

// B^-1 into binv_ by Gauss-Jordan with partial pivoting on work_ (overwritten); false if a pivot
// is within rounding of zero (or NaN).
bool LemkeSolver::invertBasis(int n) {
  auto W = work_.topLeftCorner(n, n);
  auto Bi = binv_.topLeftCorner(n, n);
  const double scale = W.cwiseAbs().maxCoeff();
  const double tiny = static_cast<double>(n) * std::numeric_limits<double>::epsilon() * scale;
  Bi.setIdentity();
  for (int j = 0; j < n; ++j) {
    int p = j;
    for (int i = j + 1; i < n; ++i)
      if (std::abs(W(i, j)) > std::abs(W(p, j))) p = i;
    const double piv = W(p, j);
    if (!(std::abs(piv) > tiny)) return false;  // also catches NaN
    if (p != j) {
      W.row(j).swap(W.row(p));
      Bi.row(j).swap(Bi.row(p));
    }
    W.row(j) /= piv;
    Bi.row(j) /= piv;
    // Eliminate column j from the other rows: a rank-one update with f = W_.j (f_j = 0).
    tmp_.head(n) = W.col(j);
    tmp_(j) = 0.0;
    for (int c = 0; c < n; ++c) {
      const double t = W(j, c);
      if (t != 0.0) W.col(c).noalias() -= t * tmp_.head(n);
      const double s = Bi(j, c);
      if (s != 0.0) Bi.col(c).noalias() -= s * tmp_.head(n);
    }
  }
  return true;
}

// b = B^-1 q, then b += B^-1 (q - B b): one step of iterative refinement.
void LemkeSolver::basicValues(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
                              int n) {
  auto Bi = binv_.topLeftCorner(n, n);
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 0) {
      tmp_.head(n) = q;
      b_.head(n).setZero();
    } else {
      tmp_.head(n) = q;
      for (int j = 0; j < n; ++j) {
        const int var = basis_[static_cast<std::size_t>(j)];
        const double x = b_(j);
        if (var < n) tmp_(var) -= x;
        else if (var < 2 * n) tmp_.head(n).noalias() += x * M.col(var - n);
        else tmp_.head(n).array() += x;
      }
    }
    for (int j = 0; j < n; ++j) {
      const double t = tmp_(j);
      if (t != 0.0) b_.head(n).noalias() += t * Bi.col(j);
    }
  }
}

void LemkeSolver::extractZ(int n, Eigen::Ref<Eigen::VectorXd> z) const {
  z.setZero();
  for (int i = 0; i < n; ++i) {
    const int var = basis_[static_cast<std::size_t>(i)];
    if (var >= n && var < 2 * n) z(var - n) = std::max(b_(i), 0.0);
  }
}

// Lemke's method as a table of contents: the cheap exits (no variables, non-finite data, q >= 0),
// the complementary pivoting from the most negative q_i, then the end point judged by its
// natural-map error and polished.
Result LemkeSolver::run(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
                        Eigen::Ref<Eigen::VectorXd> z, int maxPivots) {
  const int n = static_cast<int>(q.size());
  Result res;
  if (maxPivots < 0) maxPivots = defaultMaxPivots(n);
  res.maxPivots = maxPivots;
  if (n == 0) {
    res.status = Status::Solved;
    return res;
  }
  reserve(n);
  if (!finiteData(M, q, n)) {
    z.setZero();
    res.status = Status::NumericalFailure;
    res.error = std::numeric_limits<double>::quiet_NaN();
    return res;
  }
  // q >= 0: z = 0. Otherwise the row of the most negative q_i leaves when z0 enters; among
  // equal q_i the last row is the lexicographic minimum of the rows (q_i, e_i').
  int r = 0;
  for (int i = 1; i < n; ++i)
    if (q(i) <= q(r)) r = i;
  if (q(r) >= 0.0) {
    z.setZero();
    res.status = Status::Solved;
    res.error = naturalMapError(M, q, z);
    return res;
  }
  res.status = pivotFrom(M, q, n, r, maxPivots, res.pivots);
  extractZ(n, z);
  res.error = naturalMapError(M, q, z);
  acceptAndPolish(M, q, z, n, res);
  return res;
}

bool LemkeSolver::finiteData(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
                             int n) {
  bool finite = true;
  for (int j = 0; j < n && finite; ++j) {
    finite = std::isfinite(q(j));
    for (int i = 0; i < n && finite; ++i) finite = std::isfinite(M(i, j));
  }
  return finite;
}

// Complementary pivoting from the basis of all w with z0 entering for w_r, until z0 leaves
// (solved), no row limits the entering column (ray termination), the cap is reached or the
// basis loses its accuracy. Counts the pivots in `pivots`.
Status LemkeSolver::pivotFrom(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
                              int n, int r, int maxPivots, int& pivots) {
  binv_.topLeftCorner(n, n).setIdentity();
  b_.head(n) = q;
  for (int i = 0; i < n; ++i) basis_[static_cast<std::size_t>(i)] = i;
  const double qNorm = q.lpNorm<Eigen::Infinity>();

  // The initial pivot: z0 enters (column -d), w_r leaves. Not counted (see lemke.h).
  a_.head(n).setConstant(-1.0);
  pivot(n, r);
  basis_[static_cast<std::size_t>(r)] = 2 * n;
  int entering = n + r;  // the complement of w_r

  pivots = 0;
  for (;;) {
    if (pivots >= maxPivots) return Status::IterationLimit;
    double colNorm = 0.0;
    column(M, n, entering, a_.data(), colNorm);
    const int row = ratioTest(n, qNorm, colNorm);
    if (row < 0) return Status::RayTermination;
    pivot(n, row);
    ++pivots;
    const int leaving = basis_[static_cast<std::size_t>(row)];
    basis_[static_cast<std::size_t>(row)] = entering;
    if (leaving == 2 * n) return Status::Solved;
    entering = leaving < n ? leaving + n : leaving - n;
    bool ok = true;
    for (int i = 0; i < n && ok; ++i) ok = std::isfinite(b_(i));
    if (ok && pivots % kRefactorInterval == 0) ok = refactor(M, q, n);
    if (!ok) return Status::NumericalFailure;
  }
}

// An end point whose error is within kAcceptedError is a solution even after a ray termination
// or the cap; a solution is polished from a fresh factorization of its basis (the better of the
// two kept) and must meet kAcceptedError.
void LemkeSolver::acceptAndPolish(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                  const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Ref<Eigen::VectorXd> z, int n,
                                  Result& res) {
  if ((res.status == Status::RayTermination || res.status == Status::IterationLimit) && res.error <= kAcceptedError) {
    // z0 is zero to rounding: the almost-complementary point is a solution (the degenerate last
    // pivot that would take z0 out was lost in rounding)
    res.status = Status::Solved;
  }
  if (res.status != Status::Solved) return;
  zBest_.head(n) = z;
  if (refactor(M, q, n)) {
    extractZ(n, z);
    const double e = naturalMapError(M, q, z);
    if (e < res.error) res.error = e;
    else z = zBest_.head(n);
  }
  if (!(res.error <= kAcceptedError)) res.status = Status::NumericalFailure;  // also NaN
}

// ---------------------------------------------------------------------------------------------
// Readers

namespace {

class TokenReader {
 public:
  explicit TokenReader(const std::string& path) : path_(path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open the file");
    std::ostringstream ss;
    ss << in.rdbuf();
    text_ = ss.str();
  }

  [[noreturn]] void fail(const std::string& what) const { throw std::runtime_error(path_ + ": " + what); }

  std::string_view next() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    return std::string_view(text_).substr(start, pos_ - start);
  }

  long long integer(const std::string& what) {
    const std::string_view t = next();
    if (t.empty()) fail("expected " + what + " (an integer), found the end of the file");
    long long v = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || p != t.data() + t.size())
      fail("expected " + what + " (an integer), found '" + std::string(t) + "'");
    return v;
  }

  double number(const std::string& what) {
    std::string_view t = next();
    if (t.empty()) fail("expected " + what + ", found the end of the file");
    std::string_view u = t;
    if (u.size() > 1 && u[0] == '+') u.remove_prefix(1);
    double v = 0.0;
    const auto [p, ec] = std::from_chars(u.data(), u.data() + u.size(), v);
    if (ec != std::errc() || p != u.data() + u.size())
      fail("expected " + what + " (a number), found '" + std::string(t) + "'");
    return v;
  }

  std::string rest() const {
    std::size_t a = pos_, b = text_.size();
    while (a < b && std::isspace(static_cast<unsigned char>(text_[a]))) ++a;
    while (b > a && std::isspace(static_cast<unsigned char>(text_[b - 1]))) --b;
    return text_.substr(a, b - a);
  }

 private:
  std::string path_, text_;
  std::size_t pos_ = 0;
};

constexpr long long kMaxSize = 20000;

// The matrix block after its size: 0 (dense), rows, cols, rows, cols, entries column-major.
Eigen::MatrixXd readDenseMatrix(TokenReader& in, long long n, const std::string& name) {
  const long long storage = in.integer("the storage type of " + name);
  if (storage != 0)
    in.fail("storage type " + std::to_string(storage) + " of " + name + " is not supported (only 0 = dense)");
  const char* labels[4] = {"the number of rows", "the number of columns", "the number of rows (repeated)",
                           "the number of columns (repeated)"};
  for (const char* label : labels) {
    const long long v = in.integer(std::string(label) + " of " + name);
    if (v != n)
      in.fail(std::string(label) + " of " + name + " is " + std::to_string(v) + ", expected " + std::to_string(n));
  }
  const Eigen::Index m = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd A(m, m);
  for (Eigen::Index k = 0; k < m * m; ++k)
    A(k % m, k / m) = in.number("entry " + std::to_string(k + 1) + " of the " + std::to_string(m * m) + " of " + name);
  return A;
}

}  // namespace

Problem readLcpFile(const std::string& path) {
  TokenReader in(path);
  const long long n = in.integer("the problem size n");
  if (n < 1 || n > kMaxSize)
    in.fail("problem size " + std::to_string(n) + " is out of range; allowed 1.." + std::to_string(kMaxSize));
  Problem p;
  p.M = readDenseMatrix(in, n, "M");
  p.q.resize(static_cast<Eigen::Index>(n));
  for (Eigen::Index i = 0; i < p.q.size(); ++i)
    p.q(i) = in.number("entry " + std::to_string(i + 1) + " of the " + std::to_string(n) + " of q");
  p.comment = in.rest();
  return p;
}

FrictionProblem readFc2dFile(const std::string& path) {
  TokenReader in(path);
  const long long dim = in.integer("the dimension");
  if (dim != 2) in.fail("dimension " + std::to_string(dim) + " is not supported (only 2 = planar friction contact)");
  const long long nc = in.integer("the number of contacts");
  if (nc < 1 || 2 * nc > kMaxSize)
    in.fail("number of contacts " + std::to_string(nc) + " is out of range; allowed 1.." + std::to_string(kMaxSize / 2));
  FrictionProblem p;
  p.W = readDenseMatrix(in, 2 * nc, "W");
  p.q.resize(static_cast<Eigen::Index>(2 * nc));
  for (Eigen::Index i = 0; i < p.q.size(); ++i)
    p.q(i) = in.number("entry " + std::to_string(i + 1) + " of the " + std::to_string(2 * nc) + " of q");
  p.mu.resize(static_cast<Eigen::Index>(nc));
  for (Eigen::Index i = 0; i < p.mu.size(); ++i) {
    p.mu(i) = in.number("friction coefficient " + std::to_string(i + 1) + " of " + std::to_string(nc));
    if (!(std::isfinite(p.mu(i)) && p.mu(i) >= 0.0))
      in.fail("friction coefficient " + std::to_string(i + 1) + " is " + std::to_string(p.mu(i)) +
              "; it must be finite and >= 0");
  }
  return p;
}

// ---------------------------------------------------------------------------------------------
// Planar friction contact as an LCP

void frictionToLcp(const FrictionProblem& p, Eigen::MatrixXd& M, Eigen::VectorXd& q) {
  const Eigen::Index nc = p.mu.size();
  if (p.W.rows() != 2 * nc || p.W.cols() != 2 * nc || p.q.size() != 2 * nc)
    throw std::invalid_argument("frictionToLcp: W must be 2nc x 2nc and q of size 2nc for nc = mu.size()");
  M.setZero(3 * nc, 3 * nc);
  q.resize(3 * nc);
  for (Eigen::Index i = 0; i < nc; ++i) {
    for (Eigen::Index j = 0; j < nc; ++j) {
      // u_N^i and u_T^i in terms of r_N^j and r'_T^j (r_T^j = r'_T^j - mu_j r_N^j).
      for (Eigen::Index s = 0; s < 2; ++s) {
        const double wN = p.W(2 * i + s, 2 * j), wT = p.W(2 * i + s, 2 * j + 1);
        M(3 * i + s, 3 * j) = wN - p.mu(j) * wT;
        M(3 * i + s, 3 * j + 1) = wT;
      }
    }
    M(3 * i + 1, 3 * i + 2) = 1.0;          // u_T + lambda
    M(3 * i + 2, 3 * i) = 2.0 * p.mu(i);    // 2 mu r_N - r'_T
    M(3 * i + 2, 3 * i + 1) = -1.0;
    q(3 * i) = p.q(2 * i);
    q(3 * i + 1) = p.q(2 * i + 1);
    q(3 * i + 2) = 0.0;
  }
}

void lcpToForces(const FrictionProblem& p, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::VectorXd& r) {
  const Eigen::Index nc = p.mu.size();
  if (z.size() != 3 * nc) throw std::invalid_argument("lcpToForces: z must have size 3 nc");
  r.resize(2 * nc);
  for (Eigen::Index i = 0; i < nc; ++i) {
    r(2 * i) = z(3 * i);
    r(2 * i + 1) = z(3 * i + 1) - p.mu(i) * z(3 * i);
  }
}

}  // namespace chaindrive::lcp
