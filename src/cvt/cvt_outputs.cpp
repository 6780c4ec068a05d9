#include "cvt/cvt_outputs.h"

#include "cvt/cvt_assembly.h"

namespace chaindrive {

void placeStrandProbes(Model& m) {
  // path segments: driving arc, strand to the driven pulley, driven arc, strand back
  const PathSegment& leaving = m.path.segments()[1];
  const PathSegment& entering = m.path.segments()[3];
  auto probe = [](const PathSegment& s, SpanProbe& p) {
    p.present = true;
    p.point = 0.5 * (s.from + s.to);
    p.direction = (1.0 / norm(s.to - s.from)) * (s.to - s.from);
  };
  probe(entering, m.tightSpan);
  probe(leaving, m.slackSpan);
}

CvtOutputs cvtOutputs(const Model& m, const Data& d, const Outputs& out, int monitoredLink) {
  CvtOutputs c;
  c.drivingSpeed = out.rotorRate[kDrivingPulley];
  c.drivenSpeed = out.rotorRate[kDrivenPulley];
  // (the running radii where the ratio input has put the sheaves)
  const double geometric = d.pulleyRunningRadius[kDrivingPulley] / d.pulleyRunningRadius[kDrivenPulley];
  c.slip = c.drivingSpeed != 0.0 ? 1.0 - c.drivenSpeed / c.drivingSpeed / geometric : 0.0;
  c.tightStrandForce = out.tightSpanForce;
  c.slackStrandForce = out.slackSpanForce;
  c.drivingTorque = -out.rotorTorque[kDrivingPulley];
  c.drivenTorque = out.rotorTorque[kDrivenPulley];
  c.powerLoss = d.powerDissipated;
  c.linkTension = out.linkTension;
  const int pin = monitoredLink >= 0 && monitoredLink < m.chain.links ? monitoredLink : m.monitoredLink;
  const double wedge = 2.0 * m.pinSheave.tanWedge;  // (the wedge's normal force over the pin's axial force)
  for (int i = 0; i < d.nContacts; ++i) {
    const ContactPoint& p = d.contacts[i];
    if (p.kind != ContactPoint::Kind::PinSheave || p.fN <= 0.0) continue;  // (pressed: compliant or rigid)
    const double axial = p.fN / wedge;
    c.clampingForce[p.element] += axial;
    c.pinsInContact[p.element] += axial > 0.0 ? 1 : 0;
    if (p.link != pin) continue;
    c.pinPulley = p.element;
    c.pinNormalForce = p.fN;
    c.pinRadialFriction = p.fNFriction;
    c.pinCircumferentialFriction = m.sense * p.fT;  // (forwards: the running direction)
    c.pinAxialForce = axial;
  }
  return c;
}

}  // namespace chaindrive
