// What the fixed-step mechanical schemes share: the state split into positions (with the index
// of their velocity), velocities and other components (no velocity state: prescribed angles,
// energy accumulators), whole steps on the time grid from the last reset, and the derivative
// of the current state carried from step to step (one force evaluation per step).
#pragma once

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "integrators/ode_system.h"
#include "integrators/time_grid.h"

namespace chaindrive {

/// A set of state components, each with a partner (component i + offset; offset 0 when there is
/// none), stored as runs of `width` consecutive components repeated `count` times at a stride, so
/// that the schemes' loops need no index arrays (a multibody state repeats the same few components
/// per body). forEach visits the components in increasing order, as a plain index list would.
class ComponentSet {
 public:
  /// From (component, partner offset) pairs in increasing order of component.
  explicit ComponentSet(const std::vector<std::pair<int, int>>& items) {
    std::vector<Block> runs;  // maximal runs of consecutive components with one offset
    for (const auto& [i, offset] : items) {
      if (!runs.empty() && i == runs.back().first + runs.back().width && offset == runs.back().partnerOffset)
        ++runs.back().width;
      else
        runs.push_back(Block{i, 1, 1, 0, offset});
    }
    for (const Block& r : runs) {  // equal runs at a constant stride make one block
      if (!blocks_.empty()) {
        Block& b = blocks_.back();
        const int stride = r.first - b.first;
        if (r.width == b.width && r.partnerOffset == b.partnerOffset && (b.count == 1 || stride == b.count * b.stride)) {
          if (b.count == 1) b.stride = stride;
          ++b.count;
          continue;
        }
      }
      blocks_.push_back(r);
    }
  }

  /// Calls f(i, partner of i) for every component.
  template <class F>
  void forEach(F f) const {
    forEachRun([&f](int first, int partner, int count) {
      for (int c = 0; c < count; ++c) f(first + c, partner + c);
    });
  }

  /// Calls f(first, its partner, count) for every run of consecutive components (their partners
  /// consecutive too), in increasing order: the schemes' loops over contiguous memory (a drive's
  /// links are one run, model.h).
  template <class F>
  void forEachRun(F f) const {
    for (const Block& b : blocks_)
      for (int k = 0, i = b.first; k < b.count; ++k, i += b.stride) f(i, i + b.partnerOffset, b.width);
  }

 private:
  struct Block {
    int first, width, count, stride, partnerOffset;
  };
  std::vector<Block> blocks_;
};

/// y[i] += a x[i] for i < n, x and y not overlapping: the schemes' kicks and drifts, one loop in
/// vector instructions (AVX2 where the CPU has it; each element the same operations as one at a
/// time, without FMA: the same bits on every x86-64 machine).
void addScaled(double* __restrict y, const double* __restrict x, double a, int n);
/// v[i] += hh a[i], then x[i] += h v[i], for i < n (x, v and a not overlapping): a kick and the
/// drift it feeds in one pass, the same operations as addScaled twice.
void kickAndDrift(double* __restrict x, double* __restrict v, const double* __restrict a, double hh, double h, int n);
/// The same with a factor per element: v[i] += factor[i] a[i], then x[i] += h v[i].
void kickAndDriftBy(double* __restrict x, double* __restrict v, const double* __restrict a,
                    const double* __restrict factor, double h, int n);
/// y[i] += factor[i] x[i] for i < n.
void addScaledBy(double* __restrict y, const double* __restrict x, const double* __restrict factor, int n);


/// The components of a system in the schemes' three roles.
struct ComponentRoles {
  explicit ComponentRoles(const OdeSystem& sys);
  std::vector<std::pair<int, int>> positions, velocities, others;  // (component, partner offset)
  bool velocitiesArePartners = false;  // every velocity the partner of one position, and no other
};

inline ComponentRoles::ComponentRoles(const OdeSystem& sys) {
  std::vector<int> partners;
  for (int i = 0; i < sys.size(); ++i) {
    const int v = sys.velocityOf(i);
    if (v >= 0) positions.push_back({i, v - i}), partners.push_back(v);
    else if (sys.isVelocity(i)) velocities.push_back({i, 0});
    else others.push_back({i, 0});
  }
  std::sort(partners.begin(), partners.end());
  velocitiesArePartners = partners.size() == velocities.size() &&
                          std::equal(partners.begin(), partners.end(), velocities.begin(),
                                     [](int p, const std::pair<int, int>& v) { return p == v.first; });
}

class FixedStepScheme : public Integrator {
 public:
  FixedStepScheme(OdeSystem& sys, const FixedStepOptions& s, const std::string& name)
      : FixedStepScheme(sys, s, name, ComponentRoles(sys)) {}

  void reset(double t0, const double* y0) override {
    std::memcpy(y_.data(), y0, sizeof(double) * y_.size());
    grid_.start = t0;
    k_ = 0;
    check(t0, sys_.rhs(t0, y_.data(), f_.data()), "right-hand side failed: ");
    ++stats_.rhsEvaluations;
  }

  void advance(double tout, double* y) override {
    // whole steps of exactly h on the grid from the last reset: the step times are t0 + k h,
    // whatever way the caller formed tout
    const long long target = grid_.indexOf(tout);
    for (; k_ < target; ++k_) step(grid_.unit, grid_.time(k_ + 1));
    std::memcpy(y, y_.data(), sizeof(double) * y_.size());
  }

  double fixedStep() const override { return grid_.unit; }
  IntegratorStats stats() const override { return stats_; }

 protected:
  FixedStepScheme(OdeSystem& sys, const FixedStepOptions& s, const std::string& name, const ComponentRoles& roles)
      : sys_(sys),
        positions_(roles.positions),
        velocities_(roles.velocities),
        others_(roles.others),
        velocitiesArePartners_(roles.velocitiesArePartners) {
    if (!(s.step > 0.0)) throw std::invalid_argument(name + " needs a positive fixed step");
    const int n = sys.size();
    y_.assign(n, 0.0);
    f_.assign(n, 0.0);
    fNew_.assign(n, 0.0);
    grid_.unit = s.step;
  }
  /// One step of length h to the grid time tNext: y_ and f_ (its derivative) advanced.
  virtual void step(double h, double tNext) = 0;

  void check(double t, int flag, const char* what) {
    if (flag != 0) throw IntegrationError(t, sys_.lastError().kind, what + sys_.lastError().reason);
  }
  /// Counts the step and checks the state it reached.
  void finishStep(double h, double tNext) {
    f_.swap(fNew_);
    ++stats_.steps;
    ++stats_.rhsEvaluations;
    stats_.lastStep = h;
    Failure why;
    if (!sys_.healthy(tNext, y_.data(), why)) throw IntegrationError(tNext, why);
  }

  OdeSystem& sys_;
  std::vector<double> y_, f_, fNew_;  // f_: derivative of y_; fNew_: the step's new one
  ComponentSet positions_;            // partner: the component holding the velocity
  ComponentSet velocities_, others_;
  bool velocitiesArePartners_;        // (ComponentRoles)
  TimeGrid grid_;     // t0 (the last reset) + k h
  long long k_ = 0;   // grid index of the state y_
  IntegratorStats stats_;
};

}  // namespace chaindrive
