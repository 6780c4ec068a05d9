#include "cvt/cvt_description.h"

#include <cmath>

#include "description/fields.h"

namespace chaindrive {

extern const std::string_view kDefaultCvtJson;  // generated at build time

namespace {

void readHeader(Fields& top, CvtDescription& d) {
  top.string("schema", {"chaindrive.cvt/1"}, std::nullopt);
  d.name = top.string("name", {}, std::string("unnamed CVT"));
  top.string("description", {}, std::string(""));
  d.rotationSense = rotationSense(top.choice<Rotation>("rotation", Rotation::Counterclockwise));
  d.gravity = top.vec2("gravity", 100.0, Vec2{0.0, -9.81}, "m/s^2");
}

// The rocker-pin chain: its links, their joints and the pins' axial stiffness.
void readChain(Fields& top, CvtDescription& d) {
  Fields c = top.object("chain", true);
  if (!c.valid()) return;
  c.string("type", {"rocker-pin"}, std::string("rocker-pin"));
  d.pitch = c.number("pitch", 1e-3, 0.1, std::nullopt, "m");
  d.numberOfLinks = c.integer("numberOfLinks", 10, 10000, std::nullopt);
  d.linkMass = c.number("linkMass", 0.0, 10.0, std::nullopt, "kg", true);
  d.linkInertia = c.number("linkInertia", 0.0, 1.0, std::nullopt, "kg m^2", true);
  readJoint(c.object("joint", true), d.joint);
  if (d.joint.model != JointModel::JournalBearing)
    c.problem(c.at("joint.model"), "'" + std::string(choiceName(d.joint.model)) + "': a CVT chain's joints are 'journal-bearing' (the rolling "
                                   "pins as a stiff spring-damper); ideal joints need a rigid-contact method, "
                                   "which does not handle the pin-sheave contacts");
  Fields pin = c.object("pin", true);
  if (pin.valid()) {
    d.pinAxialStiffness = pin.number("axialStiffness", 0.0, 1e12, std::nullopt, "N/m", true);
    d.pinAxialDamping = pin.number("axialDamping", 0.0, 1e6, 0.0, "N s/m");
    pin.finish();
  }
  c.finish();
}

// The range a ratio input may move the sheaves over, [min, max] around the ratio (default: the
// ratio alone, fixed sheaves).
void readRatioRange(Fields& p, CvtDescription& d) {
  d.ratioMin = d.ratioMax = d.ratio;
  const Fields::json* v = p.raw("ratioRange");
  if (!v) return;
  const bool pair = v->is_array() && v->size() == 2 && (*v)[0].is_number() && (*v)[1].is_number();
  const double lo = pair ? (*v)[0].get<double>() : 0.0, hi = pair ? (*v)[1].get<double>() : 0.0;
  if (!pair || !(lo >= 0.2 && lo <= d.ratio && d.ratio <= hi && hi <= 5.0))
    p.problem(p.at("ratioRange"), "must be [min, max] with 0.2 <= min <= ratio (" + formatNumber(d.ratio) +
                                      ") <= max <= 5");
  else
    d.ratioMin = lo, d.ratioMax = hi;
}

void readPulleys(Fields& top, CvtDescription& d) {
  Fields p = top.object("pulleys", true);
  if (!p.valid()) return;
  d.centerDistance = p.number("centerDistance", 0.01, 2.0, std::nullopt, "m");
  d.wedgeHalfAngle = p.angle("wedgeHalfAngle", 2.0 * kPi / 180.0, 30.0 * kPi / 180.0, std::nullopt);
  d.drivenInertia = p.number("drivenInertia", 0.0, 100.0, std::nullopt, "kg m^2", true);
  d.ratio = p.number("ratio", 0.2, 5.0, std::nullopt, "");
  readRatioRange(p, d);
  d.clampingForce = p.number("clampingForce", 0.0, 1e6, std::nullopt, "N", true);
  p.finish();
}

void readContact(Fields& top, CvtDescription& d) {
  Fields c = top.object("contact", true);
  if (!c.valid()) return;
  d.friction = c.number("friction", 0.0, 1.0, std::nullopt, "");
  d.frictionRegularization = c.number("frictionRegularization", 0.0, 1.0, 0.02, "m/s", true);
  d.restitution = c.number("restitution", 0.0, 1.0, 0.0, "");
  c.finish();
}

}  // namespace

CvtDescription parseCvtDescription(std::string_view text) {
  const Fields::json root = parseJson(text);
  std::vector<std::string> problems;
  Fields top(&root, "", problems);
  if (!top.valid()) throw DescriptionError(problems);
  CvtDescription d;
  readHeader(top, d);
  readChain(top, d);
  readPulleys(top, d);
  readContact(top, d);
  top.finish();
  if (!problems.empty()) throw DescriptionError(problems);
  return d;
}

CvtDescription loadCvtDescription(const std::string& path) {
  return parseDescriptionFile(path, [](std::string_view text) { return parseCvtDescription(text); });
}

std::string_view defaultCvtJson() { return kDefaultCvtJson; }

CvtDescription defaultCvtDescription() { return parseCvtDescription(kDefaultCvtJson); }

}  // namespace chaindrive
