// The contact of a CVT chain's rocker pins with a pulley's two conical sheaves (paper section 4.1,
// its Figure 4), in the plane of the chain: a pin at radius rho inside the sheaves' free radius
// rho0 is compressed axially by u = 2 tan(beta) (rho0 - rho) (beta: the wedge half-angle), its
// axial force F_a = k_a u + c_a du/dt (>= 0) presses each sheave face with N = F_a / cos(beta),
// whose radial parts push the pin outwards with F_n = 2 F_a tan(beta); the friction on the two
// faces, at most 2 mu N, opposes the pin's sliding over the sheaves in both directions of the
// sheave plane, radial and circumferential (regularised Coulomb, as the roller contacts': the
// paper's two friction components of its Figure 9). The friction's axial parts cancel between
// the two faces.
#pragma once

#include "assembly/model.h"
#include "dynamics/data.h"

namespace chaindrive {

struct PinSheaveForce {
  double axial = 0.0;                  // F_a [N] (the pin's share of the clamping force)
  double normal = 0.0;                 // F_n [N], radially outwards on the pin
  double frictionRadial = 0.0;         // [N] on the pin, along the outward radius
  double frictionCircumferential = 0.0;  // [N] on the pin, along the counterclockwise tangent
  double dampingPower = 0.0;           // [W] dissipated by the axial damping
  double frictionPower = 0.0;          // [W] dissipated by the friction
  double energy = 0.0;                 // [J] elastic, in the pin
};

/// The law for a pin `penetration` [m] inside the free radius (> 0: compressed) sliding over
/// the sheaves at vRadial and vCircumferential [m/s] (pin minus sheave), the friction
/// regularised over vReg [m/s].
PinSheaveForce pinSheaveForce(const PinSheaveLaw& law, double vReg, double penetration, double vRadial,
                              double vCircumferential);

/// The Coulomb bound of the friction in the sheave plane on a pin pressed with `axial` [N]: mu N
/// on each of the two faces, N = axial / cos(beta).
inline double pinFrictionLimit(const PinSheaveLaw& law, double axial) { return 2.0 * law.friction * axial / law.cosWedge; }

/// The power dissipated at a pin contact c whose friction forces (fNFriction, fT) are a
/// constraint's: its axial damping by the law and the friction's on the pin's sliding.
double constrainedPinPower(const Model& m, const ContactPoint& c);

/// Stage 4 on a CVT: the sheaves placed at the ratio input (d.pulleyFreeRadius and
/// pulleyRunningRadius from Model::ratioTable; the assembled ones without), then every pin (link
/// i's rear pin) against every pulley (Model::pulleys), its
/// forces added to the links' and pulleys' generalized forces in d.gen when `forces` (without
/// the friction when d.pinFriction is off), each closed
/// contact listed from d.contacts[count] on when d lists them, d.deepestGap lowered to the
/// deepest. Returns the number of contacts listed in all; adds the dissipated power to `power`.
int pinSheaveContacts(const Model& m, Data& d, double margin, bool forces, int count, double& power);

}  // namespace chaindrive
