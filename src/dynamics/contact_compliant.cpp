#include "dynamics/contact_compliant.h"

#include <cmath>

#include "dynamics/contact_kinematics.h"

namespace chaindrive {

CompliantResult compliantContactForce(const ContactLaw& law, double vReg, ContactPoint& c) {
  CompliantResult r;
  c.fN = c.fT = 0.0;
  if (c.gap >= 0.0) return r;
  contactLaw(law, c.gap, c.vN, c.vT, regularisedSliding(vReg, c.vT), c.fN, c.fT, r.power);
  r.energy = springForce(law, -c.gap) * -c.gap / (law.exponent + 1.0);
  return r;
}

CompliantSlopes compliantContactSlopes(const ContactLaw& law, double vReg, const ContactPoint& c) {
  CompliantSlopes k;
  if (c.gap >= 0.0 || c.fN <= 0.0) return k;
  const double delta = -c.gap, deltaRate = -c.vN;
  const double spring = springForce(law, delta);
  const double springRate = law.exponent * spring / delta;  // d(spring)/d(delta)
  k.byPenetration = law.huntCrossley ? springRate * (1.0 + 1.5 * law.dampingFactor * deltaRate) : springRate;
  dampingSlopes(law, vReg, c.gap, c.fN, regularisedSliding(vReg, c.vT), k.byPenetrationRate, k.bySliding);
  return k;
}

}  // namespace chaindrive
