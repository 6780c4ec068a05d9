// Lemke's complementary pivoting method for the linear complementarity problem
//
//   find z >= 0 with w = M z + q >= 0 and w'z = 0                        (LCP(M, q))
//
// Pure numerics on (M, q): nothing here knows about chains, contacts or time stepping.
//
// Method. The augmented system w = M z + q + d z0 with the covering vector d = (1, ..., 1) is
// solved by complementary pivoting from the almost-complementary basis {w} (Lemke's scheme 1):
// the artificial variable z0 enters first, the most negative q_i leaves; after that the
// complement of the variable that left enters, until z0 leaves (a solution) or the entering
// column has no positive entry (ray termination: Lemke cannot solve this LCP; for P-matrices and
// for positive semidefinite M with a feasible LCP this does not happen).
//
// Degeneracy. The minimum ratio test is lexicographic: among the rows with a positive entry of
// the entering column a = B^-1 A_e, the pivot row minimises (b_i, (B^-1)_i.) / a_i
// lexicographically, b = B^-1 q the basic values. This is the symbolic perturbation
// q + (eps, eps^2, ..., eps^n) and rules out cycling. If z0 is among the rows that tie in the first
// component, z0 leaves (that ends the method with a solution). Comparisons use tolerances
// relative to the data: an entry of a counts as positive only above 1e-11 times the bound
// |B^-1 row|_1 |A_e|_inf of its rounding error; first components tie within 1e-11 times
// |B^-1 row|_1 |q|_inf / a_i (the rounding bound of b_i / a_i).
//
// Numerics. The inverse basis B^-1 is kept explicitly and updated by the rank-one (product form,
// Gauss-Jordan) update at every pivot; every 50 pivots, and once more at the end, it is
// recomputed from the basis by Gauss-Jordan elimination with partial pivoting, the basic values
// are recomputed and improved by one step of iterative refinement. The final solution is the
// better (by the error below) of the updated and the recomputed one; tiny negative z from
// rounding are set to zero. A final error above 1e-8 (a numerically singular basis: the pivots
// followed rounding noise) turns Solved into NumericalFailure; conversely, a ray termination or
// iteration limit at a point whose error is below 1e-8 (z0 zero to rounding, the last degenerate
// pivot lost in rounding) is a solution.
//
// Pivot counting convention. `pivots` counts the pivots AFTER the initial one that brings z0
// into the basis (the convention of Siconos' lcp_lexicolemke and of the classical statement
// that Murty's example of size n takes 2^n - 1 pivots). A problem with q >= 0 takes 0 pivots
// (z = 0); every other solved problem takes at least 1. `maxPivots` caps the same count: a
// problem solved in exactly maxPivots pivots is Solved.
//
// Pivot cap. In exact arithmetic the lexicographic rule never returns to a basis, so the method
// ends within n 2^(n-1) pivots (the number of almost-complementary bases), and Murty's example
// shows that 2^n - 1 can be needed: no polynomial cap covers every problem. The cap is a guard
// against cycling in floating point (ties that rounding resolves inconsistently), not a bound of
// the method. The default, max(10000, 100 n^2), never goes below Siconos' default for
// lcp_lexicolemke (10000) and grows with n so that a capped run costs O(n^4): a pivot costs
// O(n^2) (the entering column, the ratio test and the rank-one update; the refactorization every
// 50 pivots, O(n^3), adds O(n^2) per pivot). Measured (Release build, AMD EPYC): a run stopped
// by the default cap at n = 100 (Murty's example, 10^6 pivots) takes 10 s of CPU, 10 us per
// pivot as on the drive's LCPs of that size, which end in about 100 pivots; Murty n = 14 takes
// 4.4 ms. The default solves Murty's example up to n = 14 (16383 pivots, cap 19600); n = 15
// (32767 pivots, cap 22500) needs an explicit cap.
//
// Error. error = ||z - max(0, z - (M z + q))||_2 / ||q||_2 (the natural-map residual used by
// Siconos; the plain norm if ||q||_2 is below machine epsilon).
//
// Allocation. A LemkeSolver sized once (constructor capacity or reserve(n)) performs no heap
// allocation in solve() for problems with n <= capacity, provided M, q and z are passed as
// objects with contiguous column storage (an Eigen::MatrixXd / VectorXd or blocks of them: an
// expression would make Eigen::Ref build a temporary) and, for the VectorXd& overload, z
// already has size n. A larger problem grows the work arrays (allocating once).
//
// Determinism. The method is a fixed sequence of floating-point operations: identical inputs
// give bit-identical outputs (on the same build).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace chaindrive::lcp {

enum class Status {
  Solved,            ///< z solves the LCP (z0 left the basis); see Result::error
  RayTermination,    ///< the entering column has no positive entry: Lemke finds no solution
  IterationLimit,    ///< maxPivots pivots done without a solution (see iterationLimitMessage)
  NumericalFailure,  ///< non-finite data or values, a numerically singular basis, or an end basis
                     ///< whose error exceeds 1e-8
};

/// "Solved", "RayTermination", "IterationLimit", "NumericalFailure".
const char* statusName(Status s) noexcept;

struct Result {
  Status status = Status::NumericalFailure;
  int pivots = 0;      ///< pivots after the initial one (see the convention above)
  double error = 0.0;  ///< the natural-map error of the returned z (NaN for non-finite data)
  int maxPivots = 0;   ///< the cap in force: maxPivots, or defaultMaxPivots(n) if maxPivots < 0
};

/// The report of a capped run of size n, for IterationLimit: "LCP iteration limit: P pivots
/// without a solution (cap C for n = N; <howToRaise>)", e.g. howToRaise "raise it with
/// --max-pivots" (the part after the semicolon is left out if howToRaise is empty).
std::string iterationLimitMessage(const Result& r, int n, const std::string& howToRaise);

/// Lemke's method with lexicographic degeneracy resolution; an object holds the work arrays so
/// that repeated solves (one per time step) allocate nothing.
///
/// On return z holds: the solution (Solved); the z part of the last almost-complementary basic
/// solution (RayTermination, IterationLimit; it is not a solution); zeros (non-finite data).
class LemkeSolver {
 public:
  explicit LemkeSolver(int capacity = 0);

  /// Makes room for problems up to size n (allocates only if n exceeds the capacity).
  void reserve(int n);
  int capacity() const noexcept { return capacity_; }

  /// The pivot cap used when maxPivots < 0: max(10000, 100 n^2), at most INT_MAX (see "Pivot
  /// cap" above). Murty's example needs 2^n - 1 pivots: pass maxPivots for it beyond n = 14.
  static int defaultMaxPivots(int n) noexcept;

  /// Solves LCP(M, q). M must be n x n and q of size n (else std::invalid_argument); z is
  /// resized to n only if its size differs.
  Result solve(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
               Eigen::VectorXd& z, int maxPivots = -1);
  /// The same with z a view (a segment of a larger vector); z must have size n.
  Result solve(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
               Eigen::Ref<Eigen::VectorXd> z, int maxPivots = -1);

 private:
  Result run(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
             Eigen::Ref<Eigen::VectorXd> z, int maxPivots);
  static bool finiteData(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q, int n);
  Status pivotFrom(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q, int n, int r,
                   int maxPivots, int& pivots);
  void acceptAndPolish(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
                       Eigen::Ref<Eigen::VectorXd> z, int n, Result& res);
  void column(const Eigen::Ref<const Eigen::MatrixXd>& M, int n, int var, double* a, double& colNorm) const;
  int ratioTest(int n, double qNorm, double colNorm);
  void pivot(int n, int r);
  bool refactor(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q, int n);
  void basisMatrix(const Eigen::Ref<const Eigen::MatrixXd>& M, int n);
  bool invertBasis(int n);
  void basicValues(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q, int n);
  void extractZ(int n, Eigen::Ref<Eigen::VectorXd> z) const;

  int capacity_ = 0;
  Eigen::MatrixXd binv_;    // (cap x cap) inverse basis B^-1; row i belongs to the variable basis_[i]
  Eigen::MatrixXd work_;    // (cap x cap) the basis matrix during a refactorization
  Eigen::VectorXd b_;       // (cap) basic values B^-1 q
  Eigen::VectorXd a_;       // (cap) entering column B^-1 A_e
  Eigen::VectorXd rowr_;    // (cap) the pivot row of B^-1 before the update
  Eigen::VectorXd rowNorm_; // (cap) |B^-1 row|_1 for the rows tested in the ratio test
  Eigen::VectorXd tmp_;     // (cap) residuals, w = M z + q
  Eigen::VectorXd zBest_;   // (cap) the better of the updated and the refactorized solution
  std::vector<int> basis_;  // (cap) variable basic in each row: w_k = k, z_k = n + k, z0 = 2n
  std::vector<int> cand_;   // (cap) candidate rows of the ratio test
};

/// ||z - max(0, z - (M z + q))||_2 / ||q||_2 (plain norm if ||q||_2 < machine epsilon).
/// Allocates nothing.
double lcpError(const Eigen::Ref<const Eigen::MatrixXd>& M, const Eigen::Ref<const Eigen::VectorXd>& q,
                const Eigen::Ref<const Eigen::VectorXd>& z);

/// A problem of the Siconos numerics test collection (dense storage).
struct Problem {
  Eigen::MatrixXd M;
  Eigen::VectorXd q;
  std::string comment;  ///< whatever follows q in the file, trimmed
};

/// Reads the Siconos dense LCP format: n, 0 (dense), n, n, "n n", the n*n entries of M
/// column-major, the n entries of q, then a free comment. Throws std::runtime_error naming the
/// file and what is wrong (missing file, bad header, too few numbers, a token that is no number).
Problem readLcpFile(const std::string& path);

/// A planar (2D) friction-contact problem: u = W r + q with, per contact i, u = (u_N, u_T) at
/// (2i, 2i + 1) and r = (r_N, r_T) likewise; 0 <= u_N _|_ r_N >= 0 and Coulomb's law
/// |r_T| <= mu_i r_N with maximal dissipation.
struct FrictionProblem {
  Eigen::MatrixXd W;   ///< (2 nc x 2 nc)
  Eigen::VectorXd q;   ///< (2 nc)
  Eigen::VectorXd mu;  ///< (nc) friction coefficients
  int contacts() const noexcept { return static_cast<int>(mu.size()); }
};

/// Reads the Siconos fc2d format: 2 (dimension), nc, then the matrix as in readLcpFile without
/// the leading size (0, 2nc, 2nc, "2nc 2nc", 4 nc^2 entries column-major), q (2 nc), mu (nc);
/// anything after is ignored. Throws std::runtime_error naming the file and what is wrong.
FrictionProblem readFc2dFile(const std::string& path);

/// The LCP form of a planar friction-contact problem (size 3 nc). Per contact i the LCP variables
/// are z = (r_N, r'_T, lambda) at (3i, 3i+1, 3i+2) with r_T = r'_T - mu_i r_N, and
///   w_3i   = u_N                     _|_ r_N
///   w_3i+1 = u_T + lambda            _|_ r'_T      (r'_T in (0, 2 mu r_N) forces u_T = 0)
///   w_3i+2 = 2 mu_i r_N - r'_T       _|_ lambda    (|r_T| <= mu r_N; lambda = -u_T when sliding)
/// with u = W r + q written in z: the column of r_N^j is W_.Nj - mu_j W_.Tj, that of r'_T^j is
/// W_.Tj. M and q are resized.
void frictionToLcp(const FrictionProblem& p, Eigen::MatrixXd& M, Eigen::VectorXd& q);

/// The contact forces r = (r_N, r_T) per contact (size 2 nc) from an LCP solution z. r is resized.
void lcpToForces(const FrictionProblem& p, const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::VectorXd& r);

}  // namespace chaindrive::lcp
