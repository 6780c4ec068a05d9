#include "dynamics/contact_compliant.h"

#include <cmath>

#include "dynamics/contact_kinematics.h"

namespace chaindrive {

CompliantResult compliantContactForce(const ContactLaw& law, double vReg, ContactPoint& c) {
  CompliantResult r;
  c.fN = c.fT = 0.0;
  if (c.gap >= 0.0) return r;
  const double delta = -c.gap;        // penetration
  const double deltaRate = -c.vN;     // penetration rate
  const double spring = law.exponent == 1.0 ? law.stiffness * delta : law.stiffness * std::pow(delta, law.exponent);
  double f = law.huntCrossley ? spring * (1.0 + 1.5 * law.dampingFactor * deltaRate) : spring + law.damping * deltaRate;
  if (f < 0.0) f = 0.0;
  c.fN = f;
  // regularised Coulomb friction: -mu fN v / sqrt(v^2 + vReg^2)
  const double ft = -law.friction * f * c.vT / std::sqrt(c.vT * c.vT + vReg * vReg);
  c.fT = ft;
  r.power = (f - spring) * deltaRate - ft * c.vT;
  r.energy = spring * delta / (law.exponent + 1.0);
  return r;
}

void addContactGen(const Model& m, const ContactPoint& c, double* gen) {
  const Vec2 f = c.fN * c.normal + c.fT * c.tangent;
  double* g = gen + 3 * c.link;
  g[0] += f.x;
  g[1] += f.y;
  g[2] += cross(c.rLink, f);
  if (c.rotor >= 0) gen[m.rotorGen(c.rotor)] -= cross(c.rRotor, f);
}

double evaluateCompliantContacts(const Model& m, Data& d) {
  double power = 0.0;
  for (int i = 0; i < d.nContacts; ++i) {
    ContactPoint& c = d.contacts[i];
    const ContactLaw& law = c.kind == ContactPoint::Kind::RollerSprocket ? m.rollerSprocket : m.plateGuide;
    power += compliantContactForce(law, m.frictionRegularization, c).power;
    addContactGen(m, c, d.gen.data());
  }
  return power;
}

}  // namespace chaindrive
