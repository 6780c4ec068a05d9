#include "dynamics/link_modes.h"

#include <cmath>

#include "integrators/stable_step.h"
#include "math/elementary.h"

namespace chaindrive {

namespace {

// A contact law's slope [N/m] and damping [N s/m] at the normal force f: k delta^n has the slope
// n k^(1/n) f^((n-1)/n) there; the Hunt-Crossley damping is 1.5 alpha times the spring force, the
// spring-damper's its constant.
struct ContactAtForce {
  double stiffness = 0.0, damping = 0.0;
};
ContactAtForce contactAtForce(const ContactLaw& law, double f) {
  if (!(law.stiffness > 0.0)) return {};
  const double n = law.exponent;
  const double slope = n == 1.0 ? law.stiffness : n * math::pow(law.stiffness, 1.0 / n) * math::pow(f, (n - 1.0) / n);
  return {slope, law.huntCrossley ? 1.5 * law.dampingFactor * f : law.damping};
}

}  // namespace

LinkModeStep linkModeStep(const Model& m, bool jointDampingExplicit) {
  const ChainModel& ch = m.chain;
  // the stiffer contact law at the reference force
  const ContactAtForce rollers = contactAtForce(m.rollerSprocket, kReferenceContactForce);
  const ContactAtForce plates = contactAtForce(m.plateGuide, kReferenceContactForce);
  const bool rollersStiffer = rollers.stiffness >= plates.stiffness;
  const ContactAtForce& c = rollersStiffer ? rollers : plates;
  const double kj = ch.jointStiffness, cj = jointDampingExplicit ? ch.jointDamping : 0.0;
  // the two modes of a link with both rollers seated between neighbours moving against it
  const double arm2 = ch.pitch * ch.pitch;  // (p/2)^2 at each of the two pins, times 4 below
  const double omegaT = std::sqrt((4.0 * kj + 2.0 * c.stiffness) / ch.mass);
  const double rateT = (4.0 * cj + 2.0 * c.damping) / ch.mass;
  const double omegaR = std::sqrt((kj + 0.5 * c.stiffness) * arm2 / ch.inertia);
  const double rateR = (cj + 0.5 * c.damping) * arm2 / ch.inertia;
  const double stepT = verletStableStep(omegaT, rateT), stepR = verletStableStep(omegaR, rateR);
  LinkModeStep s;
  s.step = stepT < stepR ? stepT : stepR;
  s.mode = stepT < stepR ? "translation" : "rotation";
  // the joints alone: translation 4 c / m against sqrt(4 k / m), rotation c p^2 / J against sqrt(k p^2 / J)
  s.jointDampingRatio = stepT < stepR ? ch.jointDamping / std::sqrt(kj * ch.mass)
                                      : 0.5 * ch.jointDamping * ch.pitch / std::sqrt(kj * ch.inertia);
  s.contact = rollersStiffer ? "roller-sprocket" : "plate-guide";
  s.contactStiffness = c.stiffness;
  s.contactDamping = c.damping;
  return s;
}

}  // namespace chaindrive
