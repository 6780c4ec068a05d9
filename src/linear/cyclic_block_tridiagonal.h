// Linear systems whose matrix is block tridiagonal with 3 x 3 blocks and closed into a ring
// (block row i couples to rows i - 1 and i + 1 modulo n): the structure of any ring of bodies
// with 3 coordinates each coupled to their neighbours. Factored by block elimination without
// pivoting between blocks (meant for matrices that are symmetric positive definite or close to
// it), with the ring's closing blocks carried as a border: O(n) time, storage sized once.
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace chaindrive {

class CyclicBlockTridiagonal3 {
 public:
  using Block = Eigen::Matrix3d;
  using Part = Eigen::Vector3d;

  /// A ring of n >= 3 block rows.
  explicit CyclicBlockTridiagonal3(int n);
  int size() const { return n_; }

  /// The blocks to fill before factor(): row i's diagonal, its coupling to row i + 1 (upper) and
  /// to row i - 1 (lower), indices modulo n. setZero() clears all of them.
  Block& diagonal(int i) { return diag_[i]; }
  Block& upper(int i) { return upper_[i]; }
  Block& lower(int i) { return lower_[i]; }
  void setZero();

  /// Factors the matrix; the lower blocks are overwritten (fill all blocks again before the next
  /// factor()). False when a pivot block is singular or its inverse not finite; the factors are
  /// then unusable.
  bool factor();
  /// Solves A x = b for the factored matrix; x overwrites b (3 n values, block row by row).
  void solve(double* b) const;

 private:
  int n_;
  std::vector<Block> diag_, upper_, lower_;
  // factors: inverse pivots of the interior rows 0..n-2, the border column (couplings to row
  // n-1), the multipliers of the border row, and the inverse of the reduced corner
  std::vector<Block> pivotInverse_, border_, borderRow_;
  Block cornerInverse_;
};

}  // namespace chaindrive
