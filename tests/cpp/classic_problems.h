// The classic nonsmooth test problems of NUMERICS.md as NonsmoothSystems: bouncing ball,
// stick-slip oscillator on a belt, block on an incline, Painleve rod, Newton's cradle.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "nonsmooth/system.h"

namespace chaindrive::test {

using ns::ConstraintSet;
using ns::Contact;
using ns::NonsmoothSystem;

/// A point ball above a floor: q = (y), gap = y.
class BouncingBall : public NonsmoothSystem {
 public:
  BouncingBall(double e, double g = 9.81) : e_(e), g_(g) {}
  int size() const override { return 1; }
  const std::vector<double>& inverseMass() const override { return minv_; }
  void forces(double, const double*, const double*, double* h) override { h[0] = -g_; }
  void constraints(double, const double* q, const double*, double margin, bool, ConstraintSet& out) override {
    out.clear();
    if (q[0] >= margin) return;
    Contact c;
    c.id = 1;
    c.gap = q[0];
    c.wN.add(0, 1.0);
    c.restitution = e_;
    out.contacts.push_back(c);
  }

 private:
  double e_, g_;
  std::vector<double> minv_{1.0};
};

/// A mass on a belt moving at vBelt, held by a spring to the wall: q = (x, y, s) with s the belt
/// position (prescribed). Normal force from gravity; static and kinetic friction.
class BeltOscillator : public NonsmoothSystem {
 public:
  BeltOscillator(double m, double k, double vBelt, double muStatic, double mu, double g = 9.81)
      : m_(m), k_(k), vb_(vBelt), muS_(muStatic), mu_(mu), g_(g), minv_{1.0 / m, 1.0 / m, 0.0} {}
  int size() const override { return 3; }
  const std::vector<double>& inverseMass() const override { return minv_; }
  void prescribed(double, double* v, double* a) const override {
    v[2] = vb_;
    a[2] = 0.0;
  }
  void forces(double, const double* q, const double*, double* h) override {
    h[0] = -k_ * q[0];
    h[1] = -m_ * g_;
    h[2] = 0.0;
  }
  void constraints(double, const double* q, const double*, double margin, bool, ConstraintSet& out) override {
    out.clear();
    if (q[1] >= margin) return;
    Contact c;
    c.id = 1;
    c.gap = q[1];
    c.wN.add(1, 1.0);
    c.wT.add(0, 1.0);
    c.wT.add(2, -1.0);  // relative to the belt
    c.mu = mu_;
    c.muStatic = muS_;
    out.contacts.push_back(c);
  }
  // period of the stick-slip cycle (NUMERICS.md)
  double period() const {
    const double w = std::sqrt(k_ / m_), D = (muS_ - mu_) * m_ * g_ / k_, phi = std::atan(w * D / vb_);
    return 2.0 * D / vb_ + 2.0 * (3.14159265358979323846 - phi) / w;
  }

 private:
  double m_, k_, vb_, muS_, mu_, g_;
  std::vector<double> minv_;
};

/// A block (point mass) on an incline of angle alpha: q = (x along the slope, y normal).
class InclineBlock : public NonsmoothSystem {
 public:
  InclineBlock(double alpha, double mu, double g = 9.81) : alpha_(alpha), mu_(mu), g_(g) {}
  int size() const override { return 2; }
  const std::vector<double>& inverseMass() const override { return minv_; }
  void forces(double, const double*, const double*, double* h) override {
    h[0] = -g_ * std::sin(alpha_);
    h[1] = -g_ * std::cos(alpha_);
  }
  void constraints(double, const double* q, const double*, double margin, bool, ConstraintSet& out) override {
    out.clear();
    if (q[1] >= margin) return;
    Contact c;
    c.id = 1;
    c.gap = q[1];
    c.wN.add(1, 1.0);
    c.wT.add(0, 1.0);
    c.mu = c.muStatic = mu_;
    out.contacts.push_back(c);
  }

 private:
  double alpha_, mu_, g_;
  std::vector<double> minv_{1.0, 1.0};
};

/// A puck of unit mass on a table, pressed onto it by a known normal force (a compliant normal:
/// only the friction is a constraint, bounded by `bound` in the table's plane) and pushed with
/// force F at angle theta: q = (x, y).
class PressedPuck : public NonsmoothSystem {
 public:
  PressedPuck(double push, double theta, double bound) : push_(push), theta_(theta), bound_(bound) {}
  int size() const override { return 2; }
  const std::vector<double>& inverseMass() const override { return minv_; }
  void forces(double, const double*, const double*, double* h) override {
    h[0] = push_ * std::cos(theta_);
    h[1] = push_ * std::sin(theta_);
  }
  void constraints(double, const double*, const double*, double, bool, ConstraintSet& out) override {
    out.clear();
    Contact c;
    c.id = 1;
    c.wT.add(0, 1.0);
    c.wT2.add(1, 1.0);
    c.frictionBound = bound_;
    out.contacts.push_back(c);
  }
  double inputPower(double t, const double* q, const double* v) override {
    double h[2];
    forces(t, q, v, h);
    return h[0] * v[0] + h[1] * v[1];
  }

 private:
  double push_, theta_, bound_;
  std::vector<double> minv_{1.0, 1.0};
};

/// Uniform rod of half-length l, its lower end on the ground: q = (x, y, theta) of the centre,
/// theta from the horizontal, the contact end at (x - l cos th, y - l sin th).
class PainleveRod : public NonsmoothSystem {
 public:
  PainleveRod(double l, double mu, double g = 9.81) : l_(l), mu_(mu), g_(g) {
    const double m = 1.0, J = m * l * l / 3.0;
    minv_ = {1.0 / m, 1.0 / m, 1.0 / J};
  }
  int size() const override { return 3; }
  const std::vector<double>& inverseMass() const override { return minv_; }
  void forces(double, const double*, const double*, double* h) override {
    h[0] = 0.0;
    h[1] = -g_;
    h[2] = 0.0;
  }
  void constraints(double, const double* q, const double* v, double margin, bool acc, ConstraintSet& out) override {
    out.clear();
    const double s = std::sin(q[2]), c = std::cos(q[2]);
    const double gap = q[1] - l_ * s;
    if (gap >= margin) return;
    Contact k;
    k.id = 1;
    k.gap = gap;
    k.wN.add(1, 1.0);
    k.wN.add(2, -l_ * c);
    k.wT.add(0, 1.0);
    k.wT.add(2, l_ * s);
    if (acc) {
      k.wbarN = l_ * s * v[2] * v[2];
      k.wbarT = l_ * c * v[2] * v[2];
    }
    k.mu = k.muStatic = mu_;
    out.contacts.push_back(k);
  }
  /// The normal-acceleration coefficient A of NUMERICS.md when the contact end slides towards -x
  /// (friction pushes it to +x).
  double coefficientA(double theta) const {
    const double s = std::sin(theta), c = std::cos(theta);
    return 1.0 + 3.0 * c * c - 3.0 * mu_ * s * c;
  }

 private:
  double l_, mu_, g_;
  std::vector<double> minv_;
};

/// Balls of radius r on a line: q = (x1, ..., xn), contacts between neighbours.
class NewtonsCradle : public NonsmoothSystem {
 public:
  NewtonsCradle(int n, double r, double e) : n_(n), r_(r), e_(e), minv_(n, 1.0) {}
  int size() const override { return n_; }
  const std::vector<double>& inverseMass() const override { return minv_; }
  void forces(double, const double*, const double*, double* h) override {
    for (int i = 0; i < n_; ++i) h[i] = 0.0;
  }
  void constraints(double, const double* q, const double*, double margin, bool, ConstraintSet& out) override {
    out.clear();
    for (int i = 0; i + 1 < n_; ++i) {
      const double gap = q[i + 1] - q[i] - 2.0 * r_;
      if (gap >= margin) continue;
      Contact c;
      c.id = i + 1;
      c.gap = gap;
      c.wN.add(i, -1.0);
      c.wN.add(i + 1, 1.0);
      c.restitution = e_;
      out.contacts.push_back(c);
    }
  }

 private:
  int n_;
  double r_, e_;
  std::vector<double> minv_;
};

}  // namespace chaindrive::test

namespace chaindrive::test {

/// Two uniform links of length L in absolute coordinates (x, y, theta) per link, the first
/// link's rear end pinned at the origin, the links joined by an ideal joint (bilateral
/// constraints written like the chain's: front pin of link 1 = rear pin of link 2). Gravity -y.
class DoublePendulum : public NonsmoothSystem {
 public:
  explicit DoublePendulum(double L, double g = 9.81) : L_(L), g_(g) {
    const double m = 1.0, J = m * L * L / 12.0;
    minv_ = {1.0 / m, 1.0 / m, 1.0 / J, 1.0 / m, 1.0 / m, 1.0 / J};
  }
  int size() const override { return 6; }
  const std::vector<double>& inverseMass() const override { return minv_; }
  void forces(double, const double*, const double*, double* h) override {
    for (int i = 0; i < 6; ++i) h[i] = 0.0;
    h[1] = h[4] = -g_;
  }
  void constraints(double, const double* q, const double* v, double, bool acc, ConstraintSet& out) override {
    out.clear();
    const double hl = 0.5 * L_;
    auto pin = [&](int link, double sign, double& px, double& py) {  // sign +1 front, -1 rear
      px = q[3 * link] + sign * hl * std::cos(q[3 * link + 2]);
      py = q[3 * link + 1] + sign * hl * std::sin(q[3 * link + 2]);
    };
    double ax, ay, bx, by, cx, cy;
    pin(0, -1.0, ax, ay);  // rear pin of link 1 at the origin
    pin(0, 1.0, bx, by);   // front pin of link 1
    pin(1, -1.0, cx, cy);  // rear pin of link 2
    const double c1 = std::cos(q[2]), s1 = std::sin(q[2]), c2 = std::cos(q[5]), s2 = std::sin(q[5]);
    const double w1 = v[2], w2 = v[5];
    // ground pin: rear of link 1 = 0
    for (int axis = 0; axis < 2; ++axis) {
      ns::Bilateral b;
      b.g = axis == 0 ? ax : ay;
      b.w.add(axis, 1.0);
      b.w.add(2, axis == 0 ? hl * s1 : -hl * c1);  // d/dtheta of (-hl cos, -hl sin)
      b.wbar = acc ? (axis == 0 ? hl * c1 * w1 * w1 : hl * s1 * w1 * w1) : 0.0;
      out.bilateral.push_back(b);
    }
    // joint: front of link 1 - rear of link 2 = 0
    for (int axis = 0; axis < 2; ++axis) {
      ns::Bilateral b;
      b.g = axis == 0 ? bx - cx : by - cy;
      b.w.add(axis, 1.0);
      b.w.add(2, axis == 0 ? -hl * s1 : hl * c1);
      b.w.add(3 + axis, -1.0);
      b.w.add(5, axis == 0 ? -hl * s2 : hl * c2);
      b.wbar = acc ? (axis == 0 ? -hl * (c1 * w1 * w1 + c2 * w2 * w2) : -hl * (s1 * w1 * w1 + s2 * w2 * w2)) : 0.0;
      out.bilateral.push_back(b);
    }
  }
  double energy(const double* q, const double* v) const {
    double e = 0.0;
    for (int k = 0; k < 2; ++k) {
      e += 0.5 * (v[3 * k] * v[3 * k] + v[3 * k + 1] * v[3 * k + 1]) / minv_[0] +
           0.5 * v[3 * k + 2] * v[3 * k + 2] / minv_[2] + g_ * q[3 * k + 1] / minv_[0];
    }
    return e;
  }
  double violation(const double* q) const {
    const double hl = 0.5 * L_;
    const double ax = q[0] - hl * std::cos(q[2]), ay = q[1] - hl * std::sin(q[2]);
    const double bx = q[0] + hl * std::cos(q[2]) - (q[3] - hl * std::cos(q[5]));
    const double by = q[1] + hl * std::sin(q[2]) - (q[4] - hl * std::sin(q[5]));
    return std::max({std::fabs(ax), std::fabs(ay), std::fabs(bx), std::fabs(by)});
  }

 private:
  double L_, g_;
  std::vector<double> minv_;
};

}  // namespace chaindrive::test
