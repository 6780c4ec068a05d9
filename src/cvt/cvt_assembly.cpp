#include "cvt/cvt_assembly.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "assembly/pin_placement.h"
#include "statics/preload.h"
#include "description/fields.h"
#include "cvt/cvt_outputs.h"
#include "math/elementary.h"

namespace chaindrive {

namespace {

// The path through the two pulleys' running circles, the driving one's radius r1.
ChainPath pathAt(const CvtDescription& d, double r1) {
  return ChainPath::through({{Vec2{0.0, 0.0}, d.rotationSense * r1},
                             {Vec2{d.centerDistance, 0.0}, d.rotationSense * d.ratio * r1}});
}

// The closure gap at driving radius r1: how far n chords, walked from the middle of the driving
// pulley's wrap, end beyond the start (> 0: the chain is longer than the path).
double closureGap(const CvtDescription& d, double r1, double chord) {
  const ChainPath path = pathAt(d, r1);
  const double s0 = path.arcMiddle(0);
  return walkChords(path, s0, d.numberOfLinks, chord, nullptr) - s0 - path.length();
}

// The driving running radius that closes the chain of chords `chord` (the gap falls as the radii
// grow), between a pitch and the radius at which the pulleys' circles touch.
double closingRadius(const CvtDescription& d, double chord) {
  double lo = d.pitch, hi = 0.98 * d.centerDistance / (1.0 + d.ratio);
  const double gLo = lo < hi ? closureGap(d, lo, chord) : 0.0, gHi = lo < hi ? closureGap(d, hi, chord) : 0.0;
  if (!(gLo > 0.0 && gHi < 0.0))
    throw DescriptionError({"chain.numberOfLinks: " + std::to_string(d.numberOfLinks) + " links of " + formatNumber(d.pitch) +
                            " m do not fit around pulleys " + formatNumber(d.centerDistance) + " m apart at ratio " +
                            formatNumber(d.ratio) + " with running radii from one pitch to where the pulleys touch"});
  // regula falsi with the Illinois halving (the gap is smooth between the radii at which a pin
  // passes from a wrap to a strand): a dozen evaluations instead of bisection's forty
  double fLo = gLo, fHi = gHi;
  int side = 0;
  for (int it = 0; it < 100 && hi - lo > 1e-13; ++it) {
    const double x = std::clamp((lo * fHi - hi * fLo) / (fHi - fLo), lo, hi);
    const double f = closureGap(d, x, chord);
    if (f == 0.0) return x;
    if (f > 0.0) {
      lo = x, fLo = f;
      if (side == 1) fHi *= 0.5;
      side = 1;
    } else {
      hi = x, fHi = f;
      if (side == -1) fLo *= 0.5;
      side = -1;
    }
    if (std::fabs(f) < 1e-14) return x;
  }
  return 0.5 * (lo + hi);
}

void setChain(const CvtDescription& d, Model& m) {
  m.name = d.name;
  m.sense = d.rotationSense;
  m.gravity = d.gravity;
  ChainModel& ch = m.chain;
  ch.links = d.numberOfLinks;
  ch.pitch = d.pitch;
  ch.mass = d.linkMass;
  ch.inertia = d.linkInertia;
  ch.depthScale = 0.25 * d.pitch;  // (a pin pushed in by an eighth of a pitch has tunnelled)
  ch.jointStiffness = d.joint.stiffness;
  ch.jointDamping = d.joint.damping;
  ch.jointClearance = d.joint.clearance;
  m.frictionRegularization = d.frictionRegularization;
  PinSheaveLaw& law = m.pinSheave;
  law.tanWedge = math::tan(d.wedgeHalfAngle);
  law.cosWedge = math::cos(d.wedgeHalfAngle);
  law.axialStiffness = d.pinAxialStiffness;
  law.axialDamping = d.pinAxialDamping;
  law.friction = d.friction;
  law.restitution = d.restitution;
}

void addPulley(Model& m, const std::string& name, Vec2 center, double inertia, bool prescribed) {
  RotorModel r;
  r.name = name;
  r.isSprocket = true;
  r.element = static_cast<int>(m.pulleys.size());
  r.axis = center;
  r.inertia = inertia;
  r.prescribed = prescribed;
  PulleyModel p;
  p.name = name;
  p.rotor = static_cast<int>(m.rotors.size());
  p.center = center;
  m.rotors.push_back(r);
  m.pulleys.push_back(p);
}

// Both pulleys carry the pins on their wraps (route element k is pulley k), as sprockets do.
std::vector<WrapCarrier> pulleyCarriers(const Model& m) {
  return {WrapCarrier{PinNominal::On::Sprocket, m.pulleys[kDrivingPulley].rotor},
          WrapCarrier{PinNominal::On::Sprocket, m.pulleys[kDrivenPulley].rotor}};
}

// The layout at ratio d.ratio: the pre-tension the driven pulley's clamping force holds,
// T = 2 tan(beta) F / phi (the pins' axial forces over its wrap phi, friction aside), the chord
// of a link stretched by it, the chain closed at that chord (three passes: the wrap moves a
// little with the chord); then each pulley's free radius: a pin on its running circle is pushed
// inwards by T chord / r (the two links pulling at it) and held by the sheaves' radial stiffness
// 4 k_a tan^2(beta).
CvtLayout layoutAt(const CvtDescription& d, const PinSheaveLaw& law) {
  CvtLayout out;
  out.chord = d.pitch;
  for (int pass = 0; pass < 3; ++pass) {
    out.runningRadius[0] = closingRadius(d, out.chord);
    const ChainPath path = pathAt(d, out.runningRadius[0]);
    out.wrapAngle[0] = std::fabs(path.segments()[0].sweep);
    out.wrapAngle[1] = std::fabs(path.segments()[2].sweep);
    out.pretension = 2.0 * law.tanWedge * d.clampingForce / out.wrapAngle[1];
    out.chord = d.pitch + out.pretension / d.joint.stiffness;
  }
  out.runningRadius[1] = d.ratio * out.runningRadius[0];
  const double radialStiffness = 4.0 * law.axialStiffness * law.tanWedge * law.tanWedge;
  for (int k = 0; k < 2; ++k) {
    const double depth = out.pretension * out.chord / (out.runningRadius[k] * radialStiffness);
    out.freeRadius[k] = out.runningRadius[k] + depth;
    const double pinsOnWrap = out.wrapAngle[k] * out.runningRadius[k] / out.chord;
    out.clampingForce[k] = pinsOnWrap * law.axialStiffness * 2.0 * law.tanWedge * depth;
  }
  return out;
}

// The sheaves over the description's ratio range, kRatioPoints layouts (none for a fixed ratio).
RatioTable ratioTable(const CvtDescription& d, const PinSheaveLaw& law) {
  RatioTable t;
  t.lo = d.ratioMin;
  if (!(d.ratioMax > d.ratioMin)) return t;
  t.step = (d.ratioMax - d.ratioMin) / (kRatioPoints - 1);
  CvtDescription at = d;
  for (int k = 0; k < kRatioPoints; ++k) {
    at.ratio = t.lo + t.step * k;
    CvtLayout l;
    try {
      l = layoutAt(at, law);
    } catch (const DescriptionError& e) {
      throw DescriptionError({"pulleys.ratioRange: [" + formatNumber(d.ratioMin) + ", " + formatNumber(d.ratioMax) +
                              "] reaches beyond the ratios the chain fits at: " + e.problems().front()});
    }
    for (int p = 0; p < 2; ++p) {
      t.running[p].push_back(l.runningRadius[p]);
      t.free[p].push_back(l.freeRadius[p]);
    }
  }
  return t;
}

void noteLayout(Model& m, const CvtLayout& out) {
  AssemblyReport& a = m.assembly;
  a.closureElement = "drivingPulley (running radius)";
  a.closureValue = out.runningRadius[0];
  a.pathLength = m.path.length();
  a.notes.push_back("running radii " + formatNumber(out.runningRadius[0]) + " m (driving) and " + formatNumber(out.runningRadius[1]) +
                    " m (driven)");
  a.notes.push_back("pre-tension " + formatNumber(out.pretension) + " N; clamping forces " + formatNumber(out.clampingForce[0]) +
                    " N (driving) and " + formatNumber(out.clampingForce[1]) + " N (driven)");
}

}  // namespace

Model assembleCvt(const CvtDescription& d, CvtLayout* layout) {
  Model m;
  setChain(d, m);
  addPulley(m, "drivingPulley", Vec2{0.0, 0.0}, 0.0, true);
  addPulley(m, "drivenPulley", Vec2{d.centerDistance, 0.0}, d.drivenInertia, false);
  m.drivenRotor = kDrivingPulley;  // (the rotor the speed input drives)
  const CvtLayout out = layoutAt(d, m.pinSheave);
  m.path = pathAt(d, out.runningRadius[0]);
  for (int k = 0; k < 2; ++k) {
    m.pulleys[k].runningRadius = out.runningRadius[k];
    m.pulleys[k].freeRadius = out.freeRadius[k];
  }
  m.ratioTable = ratioTable(d, m.pinSheave);
  placePins(m, out.chord, pulleyCarriers(m));  // from the middle of the driving pulley's wrap
  noteLayout(m, out);
  placeStrandProbes(m);
  layOutState(m);
  m.rotorOutputSign.assign(m.rotors.size(), m.sense);
  if (layout) *layout = out;
  return m;
}

void RatioTable::at(double i, double runningOut[2], double freeOut[2]) const {
  const int last = static_cast<int>(running[0].size()) - 1;
  const double x = std::clamp((i - lo) / step, 0.0, static_cast<double>(last));
  const int k = std::min(static_cast<int>(x), last - 1);
  const double w = x - k;
  for (int p = 0; p < 2; ++p) {
    runningOut[p] = (1.0 - w) * running[p][k] + w * running[p][k + 1];
    freeOut[p] = (1.0 - w) * free[p][k] + w * free[p][k + 1];
  }
}

std::vector<double> cvtNominalState(const Model& m, double drivingSpeed) {
  const double r1 = m.pulleys[kDrivingPulley].runningRadius, r2 = m.pulleys[kDrivenPulley].runningRadius;
  std::vector<double> rates(m.rotors.size(), 0.0);
  rates[kDrivingPulley] = m.sense * drivingSpeed;
  rates[kDrivenPulley] = m.sense * drivingSpeed * r1 / r2;
  return nominalState(m, rates, drivingSpeed * r1);
}

}  // namespace chaindrive
