#include "statics/preload.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include <Eigen/Dense>

#include "dynamics/body_forces.h"
#include "dynamics/dynamics.h"
#include "dynamics/hydraulic_tensioner.h"
#include "dynamics/contact_compliant.h"
#include "dynamics/jacobian.h"

namespace chaindrive {

namespace {

double cpuNow() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// Angular speed of each rotor in the nominal motion (math sense) for a crankshaft speed
// (running direction).

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

// ---- the steps of initialState() ----

// The loads of the solve besides the conservative forces: the d'Alembert forces of the nominal
// motion on the links (centripetal accelerations on sprockets and guides).
std::vector<double> dAlembertForces(const Model& m, double crankSpeed) {
  const int n = m.chain.links;
  const std::vector<double> rates = nominalRotorRates(m, crankSpeed);
  const double v = chainSpeedOf(m, rates);
  std::vector<double> inertial(m.nGen, 0.0);
  for (int i = 0; i < n; ++i) {
    const PinMotion ma = pinMotion(m, m.pins[i], rates, v), mb = pinMotion(m, m.pins[(i + 1) % n], rates, v);
    const Vec2 ac = 0.5 * (ma.a + mb.a);
    inertial[m.linkGen(i, Model::kX)] = m.chain.mass * ac.x;
    inertial[m.linkGen(i, Model::kY)] = m.chain.mass * ac.y;
  }
  return inertial;
}

// The free generalized coordinates: all links and the free rotors (the driven sprocket is held).
struct FreeCoordinates {
  std::vector<int> index;    // generalized index -> free index, -1 if held
  std::vector<int> stateOf;  // free index -> state index
};

FreeCoordinates freeCoordinates(const Model& m) {
  const int n = m.chain.links;
  FreeCoordinates fc;
  fc.index.assign(m.nGen, -1);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      fc.index[m.linkGen(i, k)] = static_cast<int>(fc.stateOf.size());
      fc.stateOf.push_back(m.linkState(i, k));
    }
  for (std::size_t r = 0; r < m.rotors.size(); ++r)
    if (!m.rotors[r].prescribed) {
      fc.index[m.rotorGen(static_cast<int>(r))] = static_cast<int>(fc.stateOf.size());
      fc.stateOf.push_back(m.rotors[r].stateAngle);
    }
  return fc;
}

// One value per free coordinate: `translation` for link positions, `rotation` for link angles,
// rotorValue(r) for free rotor r.
template <class RotorValue>
std::vector<double> perFreeCoordinate(const Model& m, const FreeCoordinates& fc, double translation, double rotation,
                                      RotorValue rotorValue) {
  std::vector<double> v(fc.stateOf.size(), translation);
  for (int i = 0; i < m.chain.links; ++i) v[fc.index[m.linkGen(i, Model::kGamma)]] = rotation;
  for (std::size_t r = 0; r < m.rotors.size(); ++r)
    if (!m.rotors[r].prescribed) v[fc.index[m.rotorGen(static_cast<int>(r))]] = rotorValue(r);
  return v;
}

// Link and rotor velocities of y: copied from `from`, or zero when `from` is null.
void setVelocities(const Model& m, std::vector<double>& y, const std::vector<double>* from) {
  for (int i = 0; i < m.chain.links; ++i)
    for (int k = 3; k < 6; ++k) y[m.linkState(i, k)] = from ? (*from)[m.linkState(i, k)] : 0.0;
  for (const auto& r : m.rotors)
    if (r.stateRate >= 0) y[r.stateRate] = from ? (*from)[r.stateRate] : 0.0;
}

// The kinetostatic solve over the free coordinates. It runs at zero velocities (no damping, no
// regularised friction: their position derivatives at the span/sprocket transitions, where the
// nominal velocity fields disagree, would make the problem non-symmetric and indefinite). The
// nominal motion enters through the d'Alembert forces and the guide friction at the nominal
// sliding velocity.
//
// Newton on the potential with a mass-proportional shift (Levenberg-Marquardt): the shift makes
// the matrix positive definite where the unloaded pose has no stiffness (rollers not yet seated,
// slack spans) and vanishes near the solution. Steps are accepted by an Armijo line search on the
// potential, or, near the end where friction makes the residual non-conservative, by a decrease
// of the residual.
struct PreloadSolve {
  PreloadSolve(const Model& model, const InputValues& inputs, const std::vector<double>& inertialForces,
               const std::vector<double>& nominal);

  /// Iterates on y (velocities zero) until the largest scaled residual is within the tolerance;
  /// returns the number of iterations. A stalled solve says so in report.message.
  int run(std::vector<double>& y, const PreloadOptions& opt, PreloadReport& report);

  void addGuideFriction();
  double residual(const std::vector<double>& yy, Eigen::VectorXd& out);
  double potential(const std::vector<double>& yy);
  bool dampedStep(std::vector<double>& y);
  bool lineSearch(std::vector<double>& y, double& alpha);

  const Model& m;
  const std::vector<double>& inertial;  // d'Alembert forces per generalized index
  const std::vector<double>& yNominal;  // the nominal state (its velocities)
  const FreeCoordinates free;
  const int nf;
  Data d;
  HeldInputs held;
  JacobianAssembler jac;
  Eigen::MatrixXd K, A;
  Eigen::VectorXd res, step, rt;
  std::vector<double> scale;     // of the residuals: torques on links by the pitch, on rotors by ~ 0.05 m
  std::vector<double> massDiag;  // of the Levenberg-Marquardt shift
  std::vector<double> trial;
  double lambda = (2.0 * kPi * 100.0) * (2.0 * kPi * 100.0);
  double maxScaled = 0.0;        // largest scaled residual of the last residual() call
  double r0 = 0.0, rMax = 0.0, p0 = 0.0;  // merit, largest scaled residual and potential at y
};

PreloadSolve::PreloadSolve(const Model& model, const InputValues& inputs, const std::vector<double>& inertialForces,
                           const std::vector<double>& nominal)
    : m(model),
      inertial(inertialForces),
      yNominal(nominal),
      free(freeCoordinates(model)),
      nf(static_cast<int>(free.stateOf.size())),
      d(model),
      held(model),
      jac(model),
      K(nf, nf),
      A(nf, nf),
      res(nf),
      step(nf),
      rt(nf) {
  held.values = inputs;
  held.values.loadTorque.resize(m.rotors.size(), 0.0);
  held.values.crankSpeed = 0.0;  // the driven sprocket is held at rest
  if (m.stateChamberOil >= 0) holdChamberAtRest(m.tensioner, inputs.supplyPressure, d.chamber);
  scale = perFreeCoordinate(m, free, 1.0, 1.0 / m.chain.pitch, [](std::size_t) { return 1.0 / 0.05; });
  massDiag = perFreeCoordinate(m, free, m.chain.mass, m.chain.inertia,
                               [this](std::size_t r) { return m.rotors[r].inertia; });
}

// Coulomb friction of the guides at the nominal sliding velocities (the guides are at rest).
void PreloadSolve::addGuideFriction() {
  for (int c = 0; c < d.nContacts; ++c) {
    const ContactPoint& cp = d.contacts[c];
    if (cp.kind != ContactPoint::Kind::PlateGuide || cp.fN <= 0.0) continue;
    const int L = cp.link;
    const Vec2 vl = Vec2{yNominal[m.linkState(L, Model::kVx)], yNominal[m.linkState(L, Model::kVy)]} +
                    crossWz(yNominal[m.linkState(L, Model::kOmega)], cp.rLink);  // guides are at rest
    const double vT = dot(vl, cp.tangent);
    const double fT = -m.plateGuide.friction * cp.fN * vT / std::sqrt(vT * vT + m.frictionRegularization * m.frictionRegularization);
    ContactPoint f = cp;
    f.fN = 0.0;
    f.fT = fT;
    addContactGen(m, f, d.gen.data());
  }
}

// The residual of the free coordinates at yy into `out`; returns the merit (root-mean-square of
// the scaled residuals) and leaves their maximum, the convergence measure, in maxScaled.
double PreloadSolve::residual(const std::vector<double>& yy, Eigen::VectorXd& out) {
  generalizedForces(m, d, held, 0.0, yy.data());
  addGuideFriction();
  double mx = 0.0, ss = 0.0;
  for (int g = 0; g < m.nGen; ++g) {
    const int f = free.index[g];
    if (f < 0) continue;
    out[f] = d.gen[g] - inertial[g];
    const double sv = std::fabs(out[f]) * scale[f];
    mx = std::max(mx, sv);
    ss += sv * sv;
  }
  maxScaled = mx;
  return std::sqrt(ss / nf);
}

// A hydraulic chamber at the pressure the solve holds: what it adds to the potential beyond the
// elastic energy (body_forces.h).
double heldChamberPotential(const Model& m, const Data& d) {
  if (!m.tensioner.hydraulicChamber()) return 0.0;
  const int r = m.tensioner.rotor;
  ChamberState oil = d.chamber;
  oil.supplyPressure = d.inputs.supplyPressure;
  const TensionerResult t = tensionerForce(m.tensioner, m.rotors[r].axis, d.rotorCos[r], d.rotorSin[r], d.rotorRate[r], oil);
  return heldChamberPotential(m.tensioner, t);
}

// Total potential of the conservative forces: elastic (joints, contacts, tensioner spring),
// gravity, the load torques and the d'Alembert forces of the nominal motion. The residual is
// (nearly) minus its gradient; friction at the nominal sliding velocities is the small rest.
double PreloadSolve::potential(const std::vector<double>& yy) {
  generalizedForces(m, d, held, 0.0, yy.data());
  const EnergyTerms e = energyTerms(m, d, yy.data());
  double p = e.elastic + e.gravity + heldChamberPotential(m, d);
  for (int g = 0; g < m.nGen; ++g) {
    const int f = free.index[g];
    if (f < 0) continue;
    p += inertial[g] * yy[free.stateOf[f]];
  }
  for (std::size_t r = 0; r < m.rotors.size(); ++r)
    if (m.rotors[r].isSprocket && !m.rotors[r].prescribed)
      p -= (-m.sense * held.values.loadTorque[r]) * yy[m.rotors[r].stateAngle];
  return p;
}

// Backtracking from the full step: accepts the first trial that lowers the potential enough
// (Armijo) or halves the merit; alpha is the accepted fraction of the step.
bool PreloadSolve::lineSearch(std::vector<double>& y, double& alpha) {
  const double slope = -res.dot(step);  // directional derivative of the potential (< 0)
  for (int ls = 0; ls < 12; ++ls, alpha *= 0.5) {
    for (int f = 0; f < nf; ++f) trial[free.stateOf[f]] = y[free.stateOf[f]] + alpha * step[f];
    const double p1 = potential(trial);
    const double r1 = residual(trial, rt);
    const double rMax1 = maxScaled;
    if (std::isfinite(p1) && std::isfinite(r1) && (p1 <= p0 + 1e-4 * alpha * slope || r1 < 0.5 * r0)) {
      y.swap(trial);
      res = rt;
      p0 = p1;
      r0 = r1;
      rMax = rMax1;
      return true;
    }
  }
  return false;
}

// One step at the stiffness K: the shift lambda grows until the shifted matrix factors and a
// step is accepted (up to 20 tries), and shrinks after a full step.
bool PreloadSolve::dampedStep(std::vector<double>& y) {
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
    double alpha = 1.0;
    accepted = lineSearch(y, alpha);
    lambda = accepted ? lambda * (alpha == 1.0 ? 0.1 : 1.0) : lambda * 10.0;
  }
  return accepted;
}

int PreloadSolve::run(std::vector<double>& y, const PreloadOptions& opt, PreloadReport& report) {
  r0 = residual(y, res);
  rMax = maxScaled;
  p0 = potential(y);
  int it = 0;
  trial = y;
  for (; it < opt.maxIterations && rMax > opt.forceTolerance; ++it) {
    jac.stiffness(m, d, held, 0.0, y.data(), free.index, K);
    if (!dampedStep(y)) {
      report.message = "preload solve stalled (no step lowers the potential or the residual)";
      break;
    }
  }
  return it;
}

// The report of a finished solve: iterations, largest scaled residual, CPU time, how it ended.
void finishReport(PreloadReport& report, int it, double rMax, const PreloadOptions& opt, double t0) {
  report.iterations = it;
  report.residual = rMax;
  report.converged = rMax <= opt.forceTolerance;
  report.cpuSeconds = cpuNow() - t0;
  if (!report.converged && report.message.empty())
    report.message = "preload solve stopped after " + std::to_string(it) + " iterations with residual " +
                     std::to_string(rMax) + " N";
  else if (report.converged)
    report.message = "preload converged in " + std::to_string(it) + " Newton iterations";
}

}  // namespace

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

std::vector<double> nominalState(const Model& m, double crankSpeed) {
  const std::vector<double> rates = nominalRotorRates(m, crankSpeed);
  return nominalState(m, rates, chainSpeedOf(m, rates));
}

std::vector<double> nominalState(const Model& m, const std::vector<double>& rates, double v) {
  const int n = m.chain.links;
  std::vector<double> y(m.nStates, 0.0);
  for (int i = 0; i < n; ++i) {
    const PinNominal& a = m.pins[i];
    const PinNominal& b = m.pins[(i + 1) % n];
    const Vec2 chord = b.position - a.position;
    const Vec2 c = 0.5 * (a.position + b.position);
    const double len = norm(chord);
    const Vec2 e = (1.0 / len) * chord;
    const PinMotion ma = pinMotion(m, a, rates, v), mb = pinMotion(m, b, rates, v);
    const Vec2 vc = 0.5 * (ma.v + mb.v);
    const double s[6] = {c.x, c.y, angleOf(chord), vc.x, vc.y, cross(e, mb.v - ma.v) / len};
    for (int k = 0; k < 6; ++k) y[m.linkState(i, k)] = s[k];
  }
  // keep link angles continuous along the chain (no jumps of 2 pi between neighbours)
  for (int i = 1; i < n; ++i) {
    double& g = y[m.linkState(i, Model::kGamma)];
    const double prev = y[m.linkState(i - 1, Model::kGamma)];
    g = prev + wrapAngle(g - prev);
  }
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    const RotorModel& ro = m.rotors[r];
    y[ro.stateAngle] = ro.initialAngle;
    if (ro.stateRate >= 0) y[ro.stateRate] = rates[r];
  }
  setChamberAtRest(m, m.tensioner.hydraulic.supplyPressure, y);
  return y;
}

void setChamberAtRest(const Model& m, double supplyPressure, std::vector<double>& y) {
  if (m.stateChamberOil < 0) return;
  y[m.stateChamberOil] = chamberOilAtRest(m, y[m.rotors[m.tensioner.rotor].stateAngle], supplyPressure);
}

// A table of contents: the nominal state, the loads, the solve at rest over the free
// coordinates, then the nominal velocities put back.
std::vector<double> initialState(const Model& m, const InputValues& inputs, const PreloadOptions& opt,
                                 PreloadReport& report, const std::vector<double>* guess) {
  const double t0 = cpuNow();
  std::vector<double> y = nominalState(m, inputs.crankSpeed);
  const std::vector<double> yNominal = y;
  if (guess) y = *guess;  // its velocities are set below, its chamber too
  // a hydraulic tensioner's chamber at rest: filled to the supply's pressure less the check
  // valve's cracking pressure (the valve just closed); the solve holds that pressure, the content
  // is then the one that fills the chamber with it at the solved pose
  setChamberAtRest(m, inputs.supplyPressure, y);
  report = PreloadReport{};
  if (!opt.enabled) {
    report.converged = true;
    report.message = "preload disabled";
    return y;
  }
  // loads: the d'Alembert forces of the nominal motion, fixed during the solve
  const std::vector<double> inertial = dAlembertForces(m, inputs.crankSpeed);
  // the solve runs at rest: keep the nominal velocities, zero them in y
  setVelocities(m, y, nullptr);
  // Newton solve over the free coordinates (links and free rotors)
  PreloadSolve solve(m, inputs, inertial, yNominal);
  const int it = solve.run(y, opt, report);
  // the start state: the preloaded pose with the nominal velocities
  setVelocities(m, y, &yNominal);
  setChamberAtRest(m, inputs.supplyPressure, y);
  finishReport(report, it, solve.rMax, opt, t0);
  if (!std::isfinite(solve.r0)) throw std::runtime_error("preload solve diverged (non-finite residual)");
  return y;
}

}  // namespace chaindrive
