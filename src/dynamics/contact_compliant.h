// Compliant contact law: a normal force only under penetration (Hunt-Crossley or linear
// spring-damper, both clamped at zero) with Coulomb friction regularised by a continuous
// function of the sliding speed (the paper's remark on the CVT model).
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "dynamics/data.h"
#include "assembly/model.h"
#include "simd.h"
#include "math/elementary.h"

namespace chaindrive {

struct CompliantResult {
  double power = 0.0;   // dissipated power (normal damping and friction) [W]
  double energy = 0.0;  // elastic energy stored in the contact [J]
};

/// The elastic part of the normal force at penetration delta (T = double or a vector, simd.h).
template <class T>
CHAINDRIVE_ALWAYS_INLINE T springForce(const ContactLaw& law, T delta) {
  if (law.exponent == 1.0) return law.stiffness * delta;
  if constexpr (std::is_same_v<T, double>) {
    return law.stiffness * math::pow(delta, law.exponent);
  } else {
    for (int l = 0; l < simd::lanesOf<T>(); ++l) delta[l] = law.stiffness * math::pow(delta[l], law.exponent);
    return delta;
  }
}

/// The sliding speed regularised over vReg, sqrt(vT^2 + vReg^2), of the friction law.
template <class T>
CHAINDRIVE_ALWAYS_INLINE T regularisedSliding(double vReg, T vT) {
  return simd::sqrt(vT * vT + vReg * vReg);
}

/// The law for a closed contact (gap < 0) of one contact (T = double) or a vector of them: the
/// normal and friction forces on the chain from the gap and the normal and tangential relative
/// velocities (and the regularised sliding speed, regularisedSliding), and the power dissipated
/// (one definition: the contact search's rollers several at a time give the bits of one at a time).
template <class T>
CHAINDRIVE_ALWAYS_INLINE void contactLaw(const ContactLaw& law, T gap, T vN, T vT, T sliding, T& fN, T& fT, T& power) {
  const T delta = -gap;      // penetration
  const T deltaRate = -vN;   // penetration rate
  const T spring = springForce(law, delta);
  T f = law.huntCrossley ? spring * (1.0 + 1.5 * law.dampingFactor * deltaRate) : spring + law.damping * deltaRate;
  f = simd::select(f < 0.0, T{}, f);
  // regularised Coulomb friction: -mu fN v / sqrt(v^2 + vReg^2)
  fT = -law.friction * f * vT / sliding;
  fN = f;
  power = (f - spring) * deltaRate - fT * vT;
}

/// Sets c.fN and c.fT from the contact kinematics.
CompliantResult compliantContactForce(const ContactLaw& law, double vReg, ContactPoint& c);

/// The law's slopes at contact c's state (after compliantContactForce): the normal force's by
/// penetration [N/m] and by its rate [N s/m], the friction force's by sliding speed [N s/m]
/// (zero for an open contact or a normal force clamped at zero).
struct CompliantSlopes {
  double byPenetration = 0.0, byPenetrationRate = 0.0, bySliding = 0.0;
};
CompliantSlopes compliantContactSlopes(const ContactLaw& law, double vReg, const ContactPoint& c);

/// The two damping slopes of compliantContactSlopes alone (byPenetrationRate, bySliding) for a
/// closed contact (gap < 0, fN > 0), for one contact (T = double) or a vector of them.
template <class T>
CHAINDRIVE_ALWAYS_INLINE void dampingSlopes(const ContactLaw& law, double vReg, T gap, T fN, T sliding,
                                            T& byPenetrationRate, T& bySliding) {
  byPenetrationRate = law.huntCrossley ? 1.5 * law.dampingFactor * springForce(law, -gap) : T{} + law.damping;
  bySliding = law.friction * fN * (vReg * vReg) / (sliding * sliding * sliding);
}

/// What a closed contact's damping (dampingSlopes at the contact point) adds to its link's damping
/// rates along x, y and gamma [1/s] (the diagonal of the implicit-damping schemes, dynamics/
/// iteration_matrix.h): for one contact or a vector of them; zero where fN is not positive.
template <class T>
CHAINDRIVE_ALWAYS_INLINE void contactDampingRates(const Model& m, const ContactLaw& law, T gap, T fN, T sliding, T nx,
                                                  T ny, T tx, T ty, T rx, T ry, T& rateX, T& rateY, T& rateGamma) {
  T kn, kt;
  dampingSlopes(law, m.frictionRegularization, gap, fN, sliding, kn, kt);
  const auto closed = fN > 0.0;
  kn = simd::select(closed, kn, T{});
  kt = simd::select(closed, kt, T{});
  const T rn = rx * ny - ry * nx, rt = rx * ty - ry * tx;  // the lever arms about the link's centre
  const double invM = 1.0 / m.chain.mass, invJ = 1.0 / m.chain.inertia;
  rateX = (kn * nx * nx + kt * tx * tx) * invM;
  rateY = (kn * ny * ny + kt * ty * ty) * invM;
  rateGamma = (kn * rn * rn + kt * rt * rt) * invJ;
}

/// Adds closed contact c's damping rates to its link's entries of `rates` (laid out as the
/// generalized coordinates, model.h).
inline void addContactDamping(const Model& m, const ContactLaw& law, const ContactPoint& c, double* rates) {
  double x, y, gamma;
  contactDampingRates(m, law, c.gap, c.fN, regularisedSliding(m.frictionRegularization, c.vT), c.normal.x, c.normal.y,
                      c.tangent.x, c.tangent.y, c.rLink.x, c.rLink.y, x, y, gamma);
  rates[m.linkGen(c.link, Model::kX)] += x;
  rates[m.linkGen(c.link, Model::kY)] += y;
  rates[m.linkGen(c.link, Model::kGamma)] += gamma;
}

/// Adds the generalized forces of contact c (forces c.fN, c.fT) to the link and rotor entries.
inline void addContactLinkGen(const Model& m, const ContactPoint& c, Vec2 f, double* gen) {
  gen[m.linkGen(c.link, Model::kX)] += f.x;
  gen[m.linkGen(c.link, Model::kY)] += f.y;
  gen[m.linkGen(c.link, Model::kGamma)] += cross(c.rLink, f);
}
inline void addContactGen(const Model& m, const ContactPoint& c, double* gen) {
  const Vec2 f = contactForce(c);
  addContactLinkGen(m, c, f, gen);
  if (c.rotor >= 0) gen[m.rotorGen(c.rotor)] -= cross(c.rRotor, f);
}

/// The law's forces on contact c (compliantContactForce) added to d.gen, its gap to the deepest;
/// returns the dissipated power.
inline double addCompliantForce(const Model& m, const ContactLaw& law, ContactPoint& c, Data& d) {
  const double power = compliantContactForce(law, m.frictionRegularization, c).power;
  addContactGen(m, c, d.gen.data());
  d.deepestGap = std::min(d.deepestGap, c.gap);
  return power;
}

/// addCompliantForce for a plate contact found by one of several threads (the link is the
/// thread's): the forces on the link added, its share of the guide's rotor and its power kept in
/// the thread's part (face `face` of d.placedFaces), in link order, for plateSums.
inline void sharePlateForce(const Model& m, ContactPoint& c, Data& d, ThreadPart& part, int face) {
  const double power = compliantContactForce(m.plateGuide, m.frictionRegularization, c).power;
  const Vec2 f = contactForce(c);
  addContactLinkGen(m, c, f, d.gen.data());
  PlateShare& share = part.plates[static_cast<std::size_t>(face * m.chain.links + part.plateCount[face]++)];
  share = {c.link, c.rotor >= 0 ? cross(c.rRotor, f) : 0.0, power};
  part.deepestGap = std::min(part.deepestGap, c.gap);
}


}  // namespace chaindrive
