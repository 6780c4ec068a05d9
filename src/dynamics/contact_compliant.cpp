#include "dynamics/contact_compliant.h"

#include <cmath>

#include "dynamics/contact_kinematics.h"

namespace chaindrive {

namespace {
// the elastic part of the normal force at penetration delta
double springForce(const ContactLaw& law, double delta) {
  return law.exponent == 1.0 ? law.stiffness * delta : law.stiffness * std::pow(delta, law.exponent);
}
}  // namespace

CompliantResult compliantContactForce(const ContactLaw& law, double vReg, ContactPoint& c) {
  CompliantResult r;
  c.fN = c.fT = 0.0;
  if (c.gap >= 0.0) return r;
  const double delta = -c.gap;        // penetration
  const double deltaRate = -c.vN;     // penetration rate
  const double spring = springForce(law, delta);
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

CompliantSlopes compliantContactSlopes(const ContactLaw& law, double vReg, const ContactPoint& c) {
  CompliantSlopes k;
  if (c.gap >= 0.0 || c.fN <= 0.0) return k;
  const double delta = -c.gap, deltaRate = -c.vN;
  const double spring = springForce(law, delta);
  const double springRate = law.exponent * spring / delta;  // d(spring)/d(delta)
  k.byPenetration = law.huntCrossley ? springRate * (1.0 + 1.5 * law.dampingFactor * deltaRate) : springRate;
  k.byPenetrationRate = law.huntCrossley ? 1.5 * law.dampingFactor * spring : law.damping;
  const double vReg2 = vReg * vReg, slide2 = c.vT * c.vT + vReg2;
  k.bySliding = law.friction * c.fN * vReg2 / (slide2 * std::sqrt(slide2));
  return k;
}

void addContactGen(const Model& m, const ContactPoint& c, double* gen) {
  const Vec2 f = c.fN * c.normal + c.fT * c.tangent;
  gen[m.linkGen(c.link, Model::kX)] += f.x;
  gen[m.linkGen(c.link, Model::kY)] += f.y;
  gen[m.linkGen(c.link, Model::kGamma)] += cross(c.rLink, f);
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
