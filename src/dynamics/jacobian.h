// Jacobian df/dy of the compliant forward dynamics, assembled element by element (joints,
// contacts, tensioner, guide pivots) from forward differences of each element's generalized
// forces with respect to the few states it depends on. The sparse pattern is a fixed superset
// (every link may touch every rotor), so a sparse direct solver can analyse it once.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "dynamics/data.h"
#include "assembly/model.h"

namespace chaindrive {

class JacobianAssembler {
 public:
  explicit JacobianAssembler(const Model& m);

  int64_t nnz() const { return static_cast<int64_t>(rows_.size()); }
  const std::vector<int64_t>& columnPointers() const { return colPtr_; }
  const std::vector<int64_t>& rowIndices() const { return rows_; }

  /// CSC values of df/dy at (t, y). Evaluates the dynamics at y into d first.
  void assemble(const Model& m, Data& d, const InputSignal& in, double t, const double* y, double* values);

  /// Dense dQ/dq restricted to the free generalized coordinates (links and free rotors, in
  /// generalized-force order without the driven rotor), at velocities as in y. Used by the
  /// static preload. `freeIndex` maps a generalized index to its row (-1 if fixed).
  void stiffness(const Model& m, Data& d, const InputSignal& in, double t, const double* y,
                 const std::vector<int>& freeIndex, Eigen::MatrixXd& K);

 private:
  template <class Sink>
  void differentiate(const Model& m, Data& d, double t, Sink&& sink);
  template <class Sink>
  void differentiateJoints(const Model& m, Sink& sink);
  template <class Sink>
  void differentiateContacts(const Model& m, const Data& d, Sink& sink);
  void differentiateChamber(const Model& m, const Data& d, double* values);
  template <class Sink>
  void differentiateRotorElements(const Model& m, const Data& d, Sink& sink);
  int find(int64_t row, int64_t col) const;
  int genRow(const Model& m, int gen) const;  // state row of the acceleration of a generalized index

  std::vector<int64_t> colPtr_, rows_;
  std::vector<double> yWork_;
};

}  // namespace chaindrive
