#include "linear/cyclic_block_tridiagonal.h"

#include <cmath>
#include <stdexcept>

namespace chaindrive {

CyclicBlockTridiagonal3::CyclicBlockTridiagonal3(int n)
    : n_(n), diag_(n), upper_(n), lower_(n), pivotInverse_(n), border_(n), borderRow_(n) {
  if (n < 3) throw std::invalid_argument("a cyclic block-tridiagonal ring needs at least 3 block rows");
  setZero();
}

void CyclicBlockTridiagonal3::setZero() {
  for (int i = 0; i < n_; ++i) diag_[i].setZero(), upper_[i].setZero(), lower_[i].setZero();
}

namespace {
bool invert(const Eigen::Matrix3d& a, Eigen::Matrix3d& inverse) {
  bool invertible = false;
  double determinant = 0.0;
  a.computeInverseAndDetWithCheck(inverse, determinant, invertible, 1e-300);
  return invertible && std::isfinite(determinant);
}
}  // namespace

// Rows 0..n-2 form an open block-tridiagonal band; row n-1 and column n-1 (the ring's closure)
// are a border. Block Thomas elimination of the band carries the border column along
// (border_), and eliminates the border row's entries one column at a time (borderRow_ keeps the
// multipliers); what is left of the corner is inverted last.
bool CyclicBlockTridiagonal3::factor() {
  const int last = n_ - 1;
  Block rowCoupling = upper_[last];  // the border row's entry in the current column (row n-1, col i)
  Block corner = diag_[last];
  for (int i = 0; i < last; ++i) {
    Block pivot = diag_[i];
    Block column = i == 0 ? lower_[0] : Block::Zero();  // row i's entry in column n-1
    if (i > 0) {
      const Block multiplier = lower_[i] * pivotInverse_[i - 1];
      pivot.noalias() -= multiplier * upper_[i - 1];
      column.noalias() -= multiplier * border_[i - 1];
      lower_[i] = multiplier;  // kept for the forward substitution
    }
    if (i == last - 1) column += upper_[i];  // row n-2's upper neighbour is the border column
    border_[i] = column;
    if (!invert(pivot, pivotInverse_[i])) return false;
    if (i == last - 1) rowCoupling += lower_[last];  // row n-1's lower neighbour is column n-2
    const Block rowMultiplier = rowCoupling * pivotInverse_[i];
    borderRow_[i] = rowMultiplier;
    corner.noalias() -= rowMultiplier * column;
    if (i + 1 < last) rowCoupling.noalias() = -rowMultiplier * upper_[i];
  }
  return invert(corner, cornerInverse_);
}

void CyclicBlockTridiagonal3::solve(double* b) const {
  const int last = n_ - 1;
  auto part = [b](int i) { return Eigen::Map<Part>(b + 3 * i); };
  // forward: the band's multipliers, then the border row's
  for (int i = 1; i < last; ++i) part(i).noalias() -= lower_[i] * part(i - 1);
  Part tail = part(last);
  for (int i = 0; i < last; ++i) tail.noalias() -= borderRow_[i] * part(i);
  part(last) = cornerInverse_ * tail;
  // backward
  const Part xLast = part(last);
  for (int i = last - 1; i >= 0; --i) {
    Part r = part(i);
    r.noalias() -= border_[i] * xLast;
    if (i + 1 < last) r.noalias() -= upper_[i] * part(i + 1);
    part(i) = pivotInverse_[i] * r;
  }
}

}  // namespace chaindrive
