#include "dynamics/pin_sheave.h"

#include <algorithm>
#include <cmath>


namespace chaindrive {

PinSheaveForce pinSheaveForce(const PinSheaveLaw& law, double vReg, double penetration, double vRadial,
                              double vCircumferential) {
  PinSheaveForce f;
  const double twoTan = 2.0 * law.tanWedge;
  const double u = twoTan * penetration, uRate = -twoTan * vRadial;  // the pin's compression and its rate
  const double spring = law.axialStiffness * u;
  f.axial = std::max(0.0, spring + law.axialDamping * uRate);
  f.normal = twoTan * f.axial;
  const double limit = pinFrictionLimit(law, f.axial);
  const double sliding = std::sqrt(vRadial * vRadial + vCircumferential * vCircumferential + vReg * vReg);
  f.frictionRadial = -limit * vRadial / sliding;
  f.frictionCircumferential = -limit * vCircumferential / sliding;
  f.dampingPower = (f.axial - spring) * uRate;
  f.frictionPower = -f.frictionRadial * vRadial - f.frictionCircumferential * vCircumferential;
  f.energy = 0.5 * spring * u;
  return f;
}

double constrainedPinPower(const Model& m, const ContactPoint& c) {
  if (c.gap >= 0.0) return 0.0;
  const PinSheaveForce f = pinSheaveForce(m.pinSheave, m.frictionRegularization, -c.gap, c.vN, c.vT);
  return f.dampingPower - c.fNFriction * c.vN - c.fT * c.vT;
}

namespace {

// One pin against one pulley whose sheaves stand at freeRadius: its contact point (gap,
// directions, relative velocities) when the pin lies within that radius grown by the margin;
// false otherwise.
bool pinContact(const PulleyModel& p, double freeRadius, const Data& d, int link, double margin, ContactPoint& c) {
  const Vec2 pin{d.links.rearX[link], d.links.rearY[link]};
  const Vec2 rel = pin - p.center;
  const double reach = freeRadius + margin;
  const double rho2 = dot(rel, rel);
  if (rho2 >= reach * reach) return false;
  const double rho = std::sqrt(rho2);
  c.kind = ContactPoint::Kind::PinSheave;
  c.link = link;
  c.end = 0;
  c.rotor = p.rotor;
  c.gap = rho - freeRadius;
  c.normal = (1.0 / rho) * rel;
  c.tangent = perp(c.normal);
  c.rLink = pin - Vec2{d.links.cx[link], d.links.cy[link]};
  c.rRotor = rel;
  const Vec2 vRel = Vec2{d.links.vRearX[link], d.links.vRearY[link]} - crossWz(d.rotorRate[p.rotor], rel);
  c.vN = dot(vRel, c.normal);
  c.vT = dot(vRel, c.tangent);
  return true;
}

// The contact's forces on its link and pulley, into the generalized forces.
void applyPinForce(const Model& m, Data& d, const ContactPoint& c) {
  const Vec2 f = contactForce(c);
  d.gen[m.linkGen(c.link, Model::kX)] += f.x;
  d.gen[m.linkGen(c.link, Model::kY)] += f.y;
  d.gen[m.linkGen(c.link, Model::kGamma)] += cross(c.rLink, f);
  d.gen[m.rotorGen(c.rotor)] -= cross(c.rRotor, f);
}

// The sheaves where the ratio input puts them: the radii of the model's ratio table at the input,
// or the assembled ones without an input (0) or a table.
void placeSheaves(const Model& m, Data& d) {
  if (m.ratioTable.empty() || !(d.inputs.ratio > 0.0)) {
    for (std::size_t k = 0; k < m.pulleys.size(); ++k) {
      d.pulleyFreeRadius[k] = m.pulleys[k].freeRadius;
      d.pulleyRunningRadius[k] = m.pulleys[k].runningRadius;
    }
    return;
  }
  m.ratioTable.at(d.inputs.ratio, d.pulleyRunningRadius.data(), d.pulleyFreeRadius.data());
}

}  // namespace

int pinSheaveContacts(const Model& m, Data& d, double margin, bool forces, int count, double& power) {
  const bool list = d.listsContacts(forces);
  placeSheaves(m, d);
  for (std::size_t k = 0; k < m.pulleys.size(); ++k) {
    const PulleyModel& p = m.pulleys[k];
    for (int i = 0; i < m.chain.links; ++i) {
      ContactPoint c;
      if (!pinContact(p, d.pulleyFreeRadius[k], d, i, margin, c)) continue;
      c.element = static_cast<int>(k);
      d.deepestGap = std::min(d.deepestGap, c.gap);
      if (forces && c.gap < 0.0) {
        const PinSheaveForce f = pinSheaveForce(m.pinSheave, m.frictionRegularization, -c.gap, c.vN, c.vT);
        // without d.pinFriction the friction is a constraint's: its force and power left out
        c.fN = f.normal;
        c.fNFriction = d.pinFriction ? f.frictionRadial : 0.0;
        c.fT = d.pinFriction ? f.frictionCircumferential : 0.0;
        power += f.dampingPower + (d.pinFriction ? f.frictionPower : 0.0);
        applyPinForce(m, d, c);
      }
      if (list) d.contacts[count++] = c;
    }
  }
  return count;
}

}  // namespace chaindrive
