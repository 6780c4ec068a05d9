#include "assembly/preload.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include <Eigen/Dense>

#include "dynamics/dynamics.h"
#include "dynamics/contact_compliant.h"
#include "dynamics/jacobian.h"

namespace chaindrive {

namespace {

double cpuNow() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// Angular speed of each rotor in the nominal motion (math sense) for a crankshaft speed
// (running direction).
std::vector<double> nominalRotorRates(const Model& m, double crankSpeed) {
  std::vector<double> rates(m.rotors.size(), 0.0);
  int ref = m.drivenRotor;
  if (ref < 0)
    for (std::size_t r = 0; r < m.rotors.size() && ref < 0; ++r)
      if (m.rotors[r].isSprocket) ref = static_cast<int>(r);
  const int zRef = m.sprockets[m.rotors[ref].element].gap.teeth;
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    if (!m.rotors[r].isSprocket) continue;
    const int z = m.sprockets[m.rotors[r].element].gap.teeth;
    rates[r] = m.sense * crankSpeed * zRef / z;
  }
  return rates;
}

struct PinMotion {
  Vec2 v, a;
};

PinMotion pinMotion(const Model& m, const PinNominal& p, const std::vector<double>& rates, double chainSpeed) {
  PinMotion pm;
  switch (p.on) {
    case PinNominal::On::Sprocket: {
      const double w = rates[p.rotor];
      pm.v = crossWz(w, p.position - p.center);
      pm.a = -(w * w) * (p.position - p.center);
      break;
    }
    case PinNominal::On::Guide: {
      pm.v = chainSpeed * p.tangent;
      const double w = chainSpeed / p.radius;
      pm.a = -(w * w) * (p.position - p.center);
      break;
    }
    case PinNominal::On::Span:
      pm.v = chainSpeed * p.tangent;
      break;
  }
  (void)m;
  return pm;
}

double chainSpeedOf(const Model& m, const std::vector<double>& rates) {
  int ref = m.drivenRotor;
  if (ref < 0)
    for (std::size_t r = 0; r < m.rotors.size() && ref < 0; ++r)
      if (m.rotors[r].isSprocket) ref = static_cast<int>(r);
  return std::fabs(rates[ref]) * m.sprockets[m.rotors[ref].element].gap.pitchRadius;
}

}  // namespace

std::vector<double> nominalState(const Model& m, double crankSpeed) {
  const int n = m.chain.links;
  std::vector<double> y(m.nStates, 0.0);
  const std::vector<double> rates = nominalRotorRates(m, crankSpeed);
  const double v = chainSpeedOf(m, rates);
  for (int i = 0; i < n; ++i) {
    const PinNominal& a = m.pins[i];
    const PinNominal& b = m.pins[(i + 1) % n];
    const Vec2 d = b.position - a.position;
    const Vec2 c = 0.5 * (a.position + b.position);
    const double len = norm(d);
    const Vec2 e = (1.0 / len) * d;
    const PinMotion ma = pinMotion(m, a, rates, v), mb = pinMotion(m, b, rates, v);
    double* s = &y[6 * i];
    s[0] = c.x;
    s[1] = c.y;
    s[2] = angleOf(d);
    const Vec2 vc = 0.5 * (ma.v + mb.v);
    s[3] = vc.x;
    s[4] = vc.y;
    s[5] = cross(e, mb.v - ma.v) / len;
  }
  // keep link angles continuous along the chain (no jumps of 2 pi between neighbours)
  for (int i = 1; i < n; ++i) {
    double& g = y[6 * i + 2];
    const double prev = y[6 * (i - 1) + 2];
    g = prev + wrapAngle(g - prev);
  }
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    const RotorModel& ro = m.rotors[r];
    y[ro.stateAngle] = ro.initialAngle;
    if (ro.stateRate >= 0) y[ro.stateRate] = rates[r];
  }
  return y;
}

std::vector<double> initialState(const Model& m, const InputValues& inputs, const PreloadOptions& opt,
                                 PreloadReport& report) {
  const double t0 = cpuNow();
  std::vector<double> y = nominalState(m, inputs.crankSpeed);
  report = PreloadReport{};
  if (!opt.enabled) {
    report.converged = true;
    report.message = "preload disabled";
    return y;
  }
  const int n = m.chain.links;
  // nominal accelerations (d'Alembert forces)
  const std::vector<double> rates = nominalRotorRates(m, inputs.crankSpeed);
  const double v = chainSpeedOf(m, rates);
  std::vector<double> inertial(m.nGen, 0.0);
  for (int i = 0; i < n; ++i) {
    const PinMotion ma = pinMotion(m, m.pins[i], rates, v), mb = pinMotion(m, m.pins[(i + 1) % n], rates, v);
    const Vec2 ac = 0.5 * (ma.a + mb.a);
    inertial[3 * i] = m.chain.mass * ac.x;
    inertial[3 * i + 1] = m.chain.mass * ac.y;
  }
  // free generalized coordinates: all links and the free rotors
  std::vector<int> freeIndex(m.nGen, -1);
  std::vector<int> stateOf;  // free index -> state index
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      freeIndex[3 * i + k] = static_cast<int>(stateOf.size());
      stateOf.push_back(6 * i + k);
    }
  for (std::size_t r = 0; r < m.rotors.size(); ++r)
    if (!m.rotors[r].prescribed) {
      freeIndex[m.rotorGen(static_cast<int>(r))] = static_cast<int>(stateOf.size());
      stateOf.push_back(m.rotors[r].stateAngle);
    }
  const int nf = static_cast<int>(stateOf.size());
  Data d(m);
  HeldInputs held(m);
  held.values = inputs;
  held.values.loadTorque.resize(m.rotors.size(), 0.0);
  // The solve runs at zero velocities (no damping, no regularised friction: their position
  // derivatives at the span/sprocket transitions, where the nominal velocity fields disagree,
  // would make the problem non-symmetric and indefinite). The nominal motion enters through the
  // d'Alembert forces and the guide friction at the nominal sliding velocity, added below.
  held.values.crankSpeed = 0.0;
  const std::vector<double> yNominal = y;
  for (int i = 0; i < n; ++i)
    for (int k = 3; k < 6; ++k) y[6 * i + k] = 0.0;
  for (const auto& r : m.rotors)
    if (r.stateRate >= 0) y[r.stateRate] = 0.0;
  auto addGuideFriction = [&]() {
    for (int c = 0; c < d.nContacts; ++c) {
      const ContactPoint& cp = d.contacts[c];
      if (cp.kind != ContactPoint::Kind::PlateGuide || cp.fN <= 0.0) continue;
      const double* s = &yNominal[6 * cp.link];
      const Vec2 vl = Vec2{s[3], s[4]} + crossWz(s[5], cp.rLink);  // guides are at rest
      const double vT = dot(vl, cp.tangent);
      const double fT = -m.plateGuide.friction * cp.fN * vT / std::sqrt(vT * vT + m.frictionRegularization * m.frictionRegularization);
      ContactPoint f = cp;
      f.fN = 0.0;
      f.fT = fT;
      addContactGen(m, f, d.gen.data());
    }
  };
  JacobianAssembler jac(m);
  Eigen::MatrixXd K(nf, nf);
  Eigen::VectorXd res(nf), step(nf);
  // residual scaling: torques on links by the pitch, on rotors by their radius ~ 0.05 m
  std::vector<double> scale(nf, 1.0);
  for (int i = 0; i < n; ++i) scale[freeIndex[3 * i + 2]] = 1.0 / m.chain.pitch;
  for (std::size_t r = 0; r < m.rotors.size(); ++r)
    if (!m.rotors[r].prescribed) scale[freeIndex[m.rotorGen(static_cast<int>(r))]] = 1.0 / 0.05;
  // merit: root-mean-square of the scaled residuals; convergence: their maximum
  double maxScaled = 0.0;
  auto residual = [&](const std::vector<double>& yy, Eigen::VectorXd& out) {
    generalizedForces(m, d, held, 0.0, yy.data());
    addGuideFriction();
    double mx = 0.0, ss = 0.0;
    for (int g = 0; g < m.nGen; ++g) {
      const int f = freeIndex[g];
      if (f < 0) continue;
      out[f] = d.gen[g] - inertial[g];
      const double sv = std::fabs(out[f]) * scale[f];
      mx = std::max(mx, sv);
      ss += sv * sv;
    }
    maxScaled = mx;
    return std::sqrt(ss / nf);
  };
  // Total potential of the conservative forces: elastic (joints, contacts, tensioner spring),
  // gravity, the load torques and the d'Alembert forces of the nominal motion. The residual is
  // (nearly) minus its gradient; friction at the nominal sliding velocities is the small rest.
  auto potential = [&](const std::vector<double>& yy) {
    generalizedForces(m, d, held, 0.0, yy.data());
    const EnergyTerms e = energyTerms(m, d, yy.data());
    double p = e.elastic + e.gravity;
    for (int g = 0; g < m.nGen; ++g) {
      const int f = freeIndex[g];
      if (f < 0) continue;
      p += inertial[g] * yy[stateOf[f]];
    }
    for (std::size_t r = 0; r < m.rotors.size(); ++r)
      if (m.rotors[r].isSprocket && !m.rotors[r].prescribed)
        p -= (-m.sense * held.values.loadTorque[r]) * yy[m.rotors[r].stateAngle];
    return p;
  };
  // Newton on the potential with a mass-proportional shift (Levenberg-Marquardt): the shift
  // makes the matrix positive definite where the unloaded pose has no stiffness (rollers not
  // yet seated, slack spans) and vanishes near the solution. Steps are accepted by an Armijo
  // line search on the potential, or, near the end where friction makes the residual
  // non-conservative, by a decrease of the residual.
  std::vector<double> massDiag(nf, m.chain.mass);
  for (int i = 0; i < n; ++i) massDiag[freeIndex[3 * i + 2]] = m.chain.inertia;
  for (std::size_t r = 0; r < m.rotors.size(); ++r)
    if (!m.rotors[r].prescribed) massDiag[freeIndex[m.rotorGen(static_cast<int>(r))]] = m.rotors[r].inertia;
  double lambda = std::pow(2.0 * kPi * 100.0, 2);
  double r0 = residual(y, res);
  double rMax = maxScaled;
  double p0 = potential(y);
  int it = 0;
  std::vector<double> trial(y);
  Eigen::VectorXd rt(nf);
  Eigen::MatrixXd A(nf, nf);
  for (; it < opt.maxIterations && rMax > opt.forceTolerance; ++it) {
    jac.stiffness(m, d, held, 0.0, y.data(), freeIndex, K);
    bool accepted = false;
    for (int tries = 0; tries < 20 && !accepted; ++tries) {
      A = -K;
      for (int f = 0; f < nf; ++f) A(f, f) += lambda * massDiag[f];
      Eigen::LLT<Eigen::MatrixXd> llt(A);
      if (llt.info() != Eigen::Success) {
        lambda = std::max(lambda * 10.0, 1.0);
        continue;
      }
      step = llt.solve(res);
      const double slope = -res.dot(step);  // directional derivative of the potential (< 0)
      double alpha = 1.0;
      for (int ls = 0; ls < 12; ++ls, alpha *= 0.5) {
        for (int f = 0; f < nf; ++f) trial[stateOf[f]] = y[stateOf[f]] + alpha * step[f];
        const double p1 = potential(trial);
        const double r1 = residual(trial, rt);
        const double rMax1 = maxScaled;
        if (std::isfinite(p1) && std::isfinite(r1) && (p1 <= p0 + 1e-4 * alpha * slope || r1 < 0.5 * r0)) {
          y.swap(trial);
          res = rt;
          p0 = p1;
          r0 = r1;
          rMax = rMax1;
          accepted = true;
          break;
        }
      }
      lambda = accepted ? lambda * (alpha == 1.0 ? 0.1 : 1.0) : lambda * 10.0;
    }
    if (!accepted) {
      report.message = "preload solve stalled (no step lowers the potential or the residual)";
      break;
    }
  }
  for (int i = 0; i < n; ++i)
    for (int k = 3; k < 6; ++k) y[6 * i + k] = yNominal[6 * i + k];
  for (const auto& r : m.rotors)
    if (r.stateRate >= 0) y[r.stateRate] = yNominal[r.stateRate];
  report.iterations = it;
  report.residual = rMax;
  report.converged = rMax <= opt.forceTolerance;
  report.cpuSeconds = cpuNow() - t0;
  if (!report.converged && report.message.empty())
    report.message = "preload solve stopped after " + std::to_string(it) + " iterations with residual " +
                     std::to_string(rMax) + " N";
  else if (report.converged)
    report.message = "preload converged in " + std::to_string(it) + " Newton iterations";
  if (!std::isfinite(r0)) throw std::runtime_error("preload solve diverged (non-finite residual)");
  return y;
}

}  // namespace chaindrive
