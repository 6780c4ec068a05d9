#include "description/drive_description.h"

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "description/fields.h"
#include "math/elementary.h"
#include "utf8_path.h"

namespace chaindrive {

extern const std::string_view kDefaultDriveJson;  // generated at build time

using json = nlohmann::json;

namespace {

std::string joinLines(const std::vector<std::string>& problems) {
  std::string s = "invalid drive description:";
  for (const auto& p : problems) s += "\n  " + p;
  return s;
}

// ---- readers of the sections, in file order ----

// The drive's name, rotation sense and gravity (the top-level fields).
void readHeader(Fields& top, DriveDescription& desc) {
  top.string("schema", {"chaindrive.drive/1"}, std::string("chaindrive.drive/1"));
  desc.name = top.string("name", {}, std::string("unnamed drive"));
  top.string("description", {}, std::string(""));
  desc.rotationSense = rotationSense(top.choice<Rotation>("rotation", Rotation::Clockwise));
  desc.gravity = top.vec2("gravity", 100.0, Vec2{0.0, -9.81}, "m/s^2");
}

// The chain: its links, their joint and the route the chain wraps.
void readChain(Fields& top, DriveDescription& desc) {
  Fields c = top.object("chain", true);
  if (!c.valid()) return;
  ChainDesc& chain = desc.chain;
  chain.pitch = c.number("pitch", 1e-3, 0.1, std::nullopt, "m");
  chain.numberOfLinks = c.integer("numberOfLinks", 10, 10000, std::nullopt);
  if (chain.numberOfLinks % 2 != 0)
    c.problem(c.at("numberOfLinks"), std::to_string(chain.numberOfLinks) +
                                         " is odd; a roller chain alternates inner and outer links, so the "
                                         "number must be even");
  chain.linkMass = c.number("linkMass", 0.0, 10.0, std::nullopt, "kg", true);
  chain.linkInertia = c.number("linkInertia", 0.0, 1.0, std::nullopt, "kg m^2", true);
  chain.rollerDiameter = c.number("rollerDiameter", 1e-4, 0.1, std::nullopt, "m");
  chain.plateHeight = c.number("plateHeight", 1e-4, 0.2, std::nullopt, "m");
  c.string("standard", {}, std::string(""));
  if (std::isfinite(chain.rollerDiameter) && std::isfinite(chain.pitch) && chain.rollerDiameter >= chain.pitch)
    c.problem(c.at("rollerDiameter"), formatNumber(chain.rollerDiameter) + " m must be smaller than the pitch " +
                                          formatNumber(chain.pitch) + " m");
  readJoint(c.object("joint", true), chain.joint);
  chain.route = c.strings("route", true);
  c.finish();
}

// Sprockets and guides share one set of names: the route refers to both.
struct ElementNames {
  std::set<std::string> taken;
  void claim(Fields& f, const std::string& n) {
    if (n.empty()) return;
    if (!taken.insert(n).second) f.problem(f.at("name"), "'" + n + "' is used twice; sprocket and guide names must be unique");
  }
};

// The ISO 606 tooth form of a sprocket, with optional overrides of its dimensions.
void readToothProfile(Fields tp, ToothProfileDesc& profile) {
  if (!tp.valid()) return;
  tp.string("standard", {"ISO 606"}, std::string("ISO 606"));
  profile.form = tp.string("form", {"min", "mean", "max"}, std::string("mean"));
  profile.seatRadius = tp.optionalNumber("seatRadius", 0.0, 0.05, "m", true);
  if (tp.has("seatAngle") || tp.has("seatAngle_deg"))
    profile.seatAngle = tp.angle("seatAngle", 60.0 * kPi / 180.0, 170.0 * kPi / 180.0, std::nullopt);
  else
    tp.angle("seatAngle", 0.0, 1.0, 0.0);  // mark both spellings as known
  profile.flankRadius = tp.optionalNumber("flankRadius", 0.0, 10.0, "m", true);
  profile.tipDiameter = tp.optionalNumber("tipDiameter", 0.0, 10.0, "m", true);
  tp.finish();
}

// One sprocket: prescribed sprockets may leave out the inertia (the input drives them).
SprocketDesc readSprocket(Fields& f, ElementNames& names) {
  SprocketDesc s;
  s.name = f.string("name", {}, std::nullopt);
  names.claim(f, s.name);
  s.center = f.vec2("center", 10.0, std::nullopt, "m");
  s.teeth = f.integer("teeth", 6, 200, std::nullopt);
  const std::string motion = f.string("motion", {"prescribed", "free", "idler"}, std::nullopt);
  s.prescribed = motion == "prescribed";
  s.loaded = motion == "free";
  s.inertia = f.number("inertia", 0.0, 1e3, s.prescribed ? std::optional<double>(0.0) : std::nullopt, "kg m^2",
                       !s.prescribed);
  readToothProfile(f.object("toothProfile", false), s.toothProfile);
  f.finish();
  return s;
}

// At least two sprockets, at most one of them prescribed (the crankshaft).
void readSprockets(Fields& top, DriveDescription& desc, ElementNames& names) {
  auto list = top.objects("sprockets", true);
  if (top.has("sprockets") && list.size() < 2) top.problem("sprockets", "at least two sprockets are needed");
  if (list.size() > static_cast<std::size_t>(kMaxSprockets))
    top.problem("sprockets", std::to_string(list.size()) + " sprockets; at most " + std::to_string(kMaxSprockets) +
                                 " are supported");
  for (auto& f : list)
    if (f.valid()) desc.sprockets.push_back(readSprocket(f, names));
  int nPrescribed = 0;
  for (const auto& s : desc.sprockets) nPrescribed += s.prescribed ? 1 : 0;
  if (nPrescribed > 1)
    top.problem("sprockets", std::to_string(nPrescribed) + " sprockets have motion 'prescribed'; at most one may");
}

// The admissible rotation of a pivoting guide, as angleRange [rad] or angleRange_deg [deg].
void readAngleRange(Fields& f, GuideDesc& g) {
  if (!f.has("angleRange") && !f.has("angleRange_deg")) {
    f.raw("angleRange");
    f.raw("angleRange_deg");
    return;
  }
  const bool deg = f.has("angleRange_deg");
  const json* v = f.raw(deg ? "angleRange_deg" : "angleRange");
  f.raw(deg ? "angleRange" : "angleRange_deg");
  const double s = deg ? kPi / 180.0 : 1.0;
  if (!v->is_array() || v->size() != 2 || !(*v)[0].is_number() || !(*v)[1].is_number() ||
      !((*v)[0].get<double>() < 0.0 && (*v)[1].get<double>() > 0.0 && (*v)[1].get<double>() * s < 1.0 &&
        (*v)[0].get<double>() * s > -1.0)) {
    f.problem(f.at(deg ? "angleRange_deg" : "angleRange"),
              "must be [min, max] with -57.3 deg < min < 0 < max < 57.3 deg (rotation from the drawn pose)");
  } else {
    g.angleMin = (*v)[0].get<double>() * s;
    g.angleMax = (*v)[1].get<double>() * s;
  }
}

// The pivot, inertia, weight, friction and admissible rotation of a pivoting guide.
void readPivot(Fields& f, GuideDesc& g) {
  g.pivot = f.vec2("pivot", 10.0, std::nullopt, "m");
  g.inertia = f.number("inertia", 0.0, 1e3, std::nullopt, "kg m^2", true);
  g.mass = f.number("mass", 0.0, 1e3, 0.0, "kg");
  g.centerOfMass = f.vec2("centerOfMass", 10.0, g.pivot, "m");
  g.pivotDamping = f.number("pivotDamping", 0.0, 1e6, 0.0, "N m s/rad");
  readAngleRange(f, g);
}

// One element of a guide profile: an arc (angles in rad or deg) or a straight line.
GuideFeatureDesc readFeature(Fields f) {
  GuideFeatureDesc g;
  const std::string type = f.string("type", {"arc", "line"}, std::nullopt);
  if (type == "arc") {
    g.type = GuideFeatureDesc::Type::Arc;
    g.center = f.vec2("center", 10.0, std::nullopt, "m");
    g.radius = f.number("radius", 1e-4, 100.0, std::nullopt, "m");
    g.startAngle = f.angle("startAngle", -4.0 * kPi, 4.0 * kPi, std::nullopt);
    g.endAngle = f.angle("endAngle", -4.0 * kPi, 4.0 * kPi, std::nullopt);
    const std::string side = f.string("chainSide", {"outside", "inside"}, std::string("outside"));
    g.convex = side == "outside";
    if (std::isfinite(g.startAngle) && std::isfinite(g.endAngle) &&
        !(g.endAngle > g.startAngle && g.endAngle - g.startAngle < 2.0 * kPi))
      f.problem(f.at("endAngle"), "must exceed startAngle by less than a full turn (the arc runs counterclockwise "
                                  "from startAngle to endAngle)");
  } else if (type == "line") {
    g.type = GuideFeatureDesc::Type::Line;
    g.from = f.vec2("from", 10.0, std::nullopt, "m");
    g.to = f.vec2("to", 10.0, std::nullopt, "m");
    const std::string side = f.string("chainSide", {"left", "right"}, std::nullopt);
    g.leftSide = side == "left";
    if (norm(g.to - g.from) < 1e-6) f.problem(f.at("to"), "the line must be longer than 1 um");
  }
  f.finish();
  return g;
}

// One guide: fixed or pivoting, with a profile of at least one arc or line.
GuideDesc readGuide(Fields& f, ElementNames& names) {
  GuideDesc g;
  g.name = f.string("name", {}, std::nullopt);
  names.claim(f, g.name);
  const std::string motion = f.string("motion", {"fixed", "pivoting"}, std::nullopt);
  g.pivoting = motion == "pivoting";
  if (g.pivoting) readPivot(f, g);
  for (auto& pf : f.objects("profile", true)) {
    if (pf.valid()) g.profile.push_back(readFeature(pf));
  }
  if (f.has("profile") && g.profile.empty()) f.problem(f.at("profile"), "must contain at least one arc or line");
  f.finish();
  return g;
}

// The guides (optional section).
void readGuides(Fields& top, DriveDescription& desc, ElementNames& names) {
  auto list = top.objects("guides", false);
  if (list.size() > static_cast<std::size_t>(kMaxGuides))
    top.problem("guides", std::to_string(list.size()) + " guides; at most " + std::to_string(kMaxGuides) +
                              " are supported");
  for (auto& f : list)
    if (f.valid()) desc.guides.push_back(readGuide(f, names));
}

// The tensioner pushes a pivoting guide (named before it, in the guides section).
void readTensioner(Fields& top, DriveDescription& desc) {
  Fields f = top.object("tensioner", false);
  if (!f.valid()) return;
  TensionerDesc& t = desc.tensioner;
  t.present = true;
  t.guide = f.string("guide", {}, std::nullopt);
  t.housing = f.vec2("housing", 10.0, std::nullopt, "m");
  t.direction = f.vec2("direction", 1e6, std::nullopt, "(unit vector)");
  t.contactPoint = f.vec2("contactPoint", 10.0, std::nullopt, "m");
  t.preload = f.number("preload", 0.0, 1e5, std::nullopt, "N");
  t.stiffness = f.number("stiffness", 0.0, 1e9, 0.0, "N/m");
  t.damping = f.number("damping", 0.0, 1e7, 0.0, "N s/m");
  t.kind = f.choice<TensionerKind>("model", TensionerKind::SpringDamper);
  if (t.kind == TensionerKind::Hydraulic) {  // (its oil damps: a damping given would be ignored)
    for (const char* key : {"damping", "dampingExtension"})
      if (f.has(key)) f.problem(f.at(key), "applies to the model 'spring-damper' only; the model is 'hydraulic'");
  } else if (f.has("hydraulic")) {
    f.problem(f.at("hydraulic"), "applies to the model 'hydraulic' only; the model is 'spring-damper'");
  }
  readHydraulicTensioner(f.object("hydraulic", false), t.hydraulic);
  t.dampingExtension = f.number("dampingExtension", 0.0, 1e7, t.damping, "N s/m");
  const double n = norm(t.direction);
  if (std::isfinite(n)) {
    if (n < 1e-12) f.problem(f.at("direction"), "must not be the zero vector");
    else t.direction = (1.0 / n) * t.direction;
  }
  if (!t.guide.empty()) {
    const int gi = desc.guideIndex(t.guide);
    if (gi < 0) f.problem(f.at("guide"), "'" + t.guide + "' is not the name of a guide");
    else if (!desc.guides[gi].pivoting) f.problem(f.at("guide"), "'" + t.guide + "' is a fixed guide; a tensioner needs a pivoting guide");
  }
  f.finish();
}

// A contact law; a missing optional one keeps the defaults. Damping fields of the other model
// are errors, so that a value given is never silently ignored.
ContactLawDesc readContactLaw(Fields f) {
  ContactLawDesc c;
  if (!f.valid()) return c;
  c.model = f.choice<ContactLawModel>("model", ContactLawModel::HuntCrossley);
  c.stiffness = f.number("stiffness", 0.0, 1e12, std::nullopt, "N/m^exponent", true);
  c.exponent = f.number("exponent", 1.0, 2.0, 1.0, "");
  c.dampingFactor = f.number("dampingFactor", 0.0, 100.0, 0.0, "s/m");
  c.damping = f.number("damping", 0.0, 1e7, 0.0, "N s/m");
  c.friction = f.number("friction", 0.0, 2.0, 0.0, "");
  c.restitution = f.number("restitution", 0.0, 1.0, 0.5, "");
  if (c.model == ContactLawModel::HuntCrossley && f.has("damping"))
    f.problem(f.at("damping"), "not used by model 'hunt-crossley' (give 'dampingFactor' in s/m)");
  if (c.model == ContactLawModel::SpringDamper && f.has("dampingFactor"))
    f.problem(f.at("dampingFactor"), "not used by model 'spring-damper' (give 'damping' in N s/m)");
  f.finish();
  return c;
}

// The contact laws; plateGuide is required only when there are guides.
void readContact(Fields& top, DriveDescription& desc) {
  Fields f = top.object("contact", true);
  if (!f.valid()) return;
  desc.contact.method = f.choice<ContactMethod>("method", ContactMethod::Compliant);
  desc.contact.frictionRegularization = f.number("frictionRegularization", 1e-6, 10.0, 0.05, "m/s");
  desc.contact.rollerSprocket = readContactLaw(f.object("rollerSprocket", true));
  desc.contact.plateGuide = readContactLaw(f.object("plateGuide", !desc.guides.empty()));
  f.finish();
}

// A guide-angle closure takes its range from the guide's angle range.
void readGuideClosure(Fields& f, const DriveDescription& desc, ClosureDesc& c) {
  c.kind = ClosureDesc::Kind::Guide;
  const int gi = desc.guideIndex(c.element);
  if (!c.element.empty() && (gi < 0 || !desc.guides[gi].pivoting))
    f.problem(f.at("element"), "'" + c.element + "' is not a pivoting guide");
  else if (gi >= 0) {
    c.rangeMin = desc.guides[gi].angleMin;
    c.rangeMax = desc.guides[gi].angleMax;
  }
}

// A sprocket-shift closure moves the sprocket along a direction, within [shiftMin, shiftMax].
void readSprocketClosure(Fields& f, const DriveDescription& desc, ClosureDesc& c) {
  c.kind = ClosureDesc::Kind::Sprocket;
  if (!c.element.empty() && desc.sprocketIndex(c.element) < 0)
    f.problem(f.at("element"), "'" + c.element + "' is not a sprocket");
  c.direction = f.vec2("direction", 1e6, std::nullopt, "(unit vector)");
  const double n = norm(c.direction);
  if (std::isfinite(n) && n > 1e-12) c.direction = (1.0 / n) * c.direction;
  else f.problem(f.at("direction"), "must be a non-zero vector");
  c.rangeMin = f.number("shiftMin", -1.0, 0.0, -0.01, "m");
  c.rangeMax = f.number("shiftMax", 0.0, 1.0, 0.01, "m");
}

// The element that closes the chain (optional: the tensioner's guide by default, see below).
void readClosure(Fields& top, DriveDescription& desc) {
  Fields f = top.object("closure", false);
  if (!f.valid()) return;
  ClosureDesc c;
  const std::string kind = f.string("kind", {"guide-angle", "sprocket-shift"}, std::nullopt);
  c.element = f.string("element", {}, std::nullopt);
  if (kind == "guide-angle") readGuideClosure(f, desc, c);
  else if (kind == "sprocket-shift") readSprocketClosure(f, desc, c);
  f.finish();
  desc.closure = c;
}

// A field that is a number in [lo, hi] (`given`) or one of two words: `off` (the default) or
// "identified".
SpanModelDesc::Source spanSource(Fields& f, const std::string& key, const char* off, double lo, double hi,
                                 const char* unit, double& given) {
  const Fields::json* v = f.raw(key);
  if (!v) return SpanModelDesc::Source::Off;
  if (v->is_number()) {
    given = f.number(key, lo, hi, std::nullopt, unit, true);
    return SpanModelDesc::Source::Given;
  }
  if (!v->is_string()) {
    f.problem(f.at(key), std::string("must be a number (") + unit + ") or \"" + off + "\" or \"identified\"");
    return SpanModelDesc::Source::Off;
  }
  return f.string(key, {off, "identified"}, std::nullopt) == "identified" ? SpanModelDesc::Source::Identified
                                                                           : SpanModelDesc::Source::Off;
}

// The span fidelity's dynamics (optional section).
void readSpanModel(Fields& top, DriveDescription& desc) {
  Fields f = top.object("spanModel", false);
  if (!f.valid()) return;
  SpanModelDesc& s = desc.spanModel;
  s.guideSeat = spanSource(f, "guideSeat", "none", 0.0, 1e9, "N m/rad", s.guideSeatStiffness);
  s.damping = spanSource(f, "damping", "joints", 0.0, 1e3, "", s.dampingScale);
  f.finish();
}

// The measured spans and the monitored link (optional section).
void readMeasurement(Fields& top, DriveDescription& desc) {
  Fields f = top.object("measurement", false);
  if (!f.valid()) return;
  desc.measurement.tightSpan = f.strings("tightSpan", false);
  desc.measurement.slackSpan = f.strings("slackSpan", false);
  desc.measurement.monitoredLink = f.integer("monitoredLink", 0, 9999, 0);
  f.finish();
}


// ---- cross-checks between the sections ----

// Every route element is a sprocket or a guide, named once; every sprocket is wrapped; at least
// two sprockets are.
void checkRoute(const DriveDescription& desc, std::vector<std::string>& problems) {
  std::map<std::string, int> count;
  for (std::size_t i = 0; i < desc.chain.route.size(); ++i) {
    const auto& n = desc.chain.route[i];
    ++count[n];
    if (desc.sprocketIndex(n) < 0 && desc.guideIndex(n) < 0)
      problems.push_back("chain.route[" + std::to_string(i) + "]: '" + n + "' is neither a sprocket nor a guide");
  }
  for (const auto& [n, k] : count)
    if (k > 1) problems.push_back("chain.route: '" + n + "' appears " + std::to_string(k) + " times; at most once");
  for (std::size_t i = 0; i < desc.sprockets.size(); ++i)
    if (!desc.sprockets[i].name.empty() && !count.count(desc.sprockets[i].name))
      problems.push_back("sprockets[" + std::to_string(i) + "]: '" + desc.sprockets[i].name +
                         "' is not in chain.route; every sprocket must be wrapped by the chain");
  int nSprocketsInRoute = 0;
  for (const auto& n : desc.chain.route) nSprocketsInRoute += desc.sprocketIndex(n) >= 0 ? 1 : 0;
  if (nSprocketsInRoute < 2 && !desc.chain.route.empty())
    problems.push_back("chain.route: needs at least two sprockets");
}

// A measured span names two elements that follow each other in the route (running order).
void checkSpan(const std::vector<std::string>& route, const std::vector<std::string>& span, const char* field,
               std::vector<std::string>& problems) {
  if (span.empty()) return;
  bool ok = span.size() == 2;
  if (ok) {
    ok = false;
    for (std::size_t i = 0; i < route.size(); ++i)
      if (route[i] == span[0] && route[(i + 1) % route.size()] == span[1]) ok = true;
  }
  if (!ok)
    problems.push_back(std::string("measurement.") + field +
                       ": must name two elements that follow each other in chain.route, in running order");
}

// The measured spans exist and the monitored link is one of the chain.
void checkMeasurement(const DriveDescription& desc, std::vector<std::string>& problems) {
  checkSpan(desc.chain.route, desc.measurement.tightSpan, "tightSpan", problems);
  checkSpan(desc.chain.route, desc.measurement.slackSpan, "slackSpan", problems);
  if (desc.chain.numberOfLinks > 0 && desc.measurement.monitoredLink >= desc.chain.numberOfLinks)
    problems.push_back("measurement.monitoredLink: " + std::to_string(desc.measurement.monitoredLink) +
                       " is out of range; allowed 0.." + std::to_string(desc.chain.numberOfLinks - 1));
}

// Without a closure section the tensioner's guide closes the chain; without either it is an
// error (reported only when nothing else is wrong, since it is often a consequence).
void defaultClosure(DriveDescription& desc, std::vector<std::string>& problems) {
  if (desc.closure) return;
  if (desc.tensioner.present && desc.guideIndex(desc.tensioner.guide) >= 0 &&
      desc.guides[desc.guideIndex(desc.tensioner.guide)].pivoting) {
    ClosureDesc c;
    c.kind = ClosureDesc::Kind::Guide;
    c.element = desc.tensioner.guide;
    const auto& g = desc.guides[desc.guideIndex(c.element)];
    c.rangeMin = g.angleMin;
    c.rangeMax = g.angleMax;
    desc.closure = c;
  } else if (problems.empty()) {
    problems.push_back("closure: missing; without a tensioner, name the element that closes the chain "
                       "({\"kind\": \"guide-angle\" | \"sprocket-shift\", \"element\": ...})");
  }
}

// A closing guide must be wrapped by the chain, or rotating it would not change the path.
void checkClosureInRoute(const DriveDescription& desc, std::vector<std::string>& problems) {
  if (!desc.closure || desc.closure->kind != ClosureDesc::Kind::Guide) return;
  bool inRoute = false;
  for (const auto& n : desc.chain.route) inRoute = inRoute || n == desc.closure->element;
  if (!inRoute && !desc.closure->element.empty())
    problems.push_back("closure.element: guide '" + desc.closure->element + "' must be in chain.route to close the chain");
}

// The JSON text (comments allowed); a syntax error is the only problem reported.

}  // namespace

// The pin-bushing joint of the links (journal bearing or ideal).
void readJoint(Fields jt, JointDesc& joint) {
  if (!jt.valid()) return;
  joint.model = jt.choice<JointModel>("model", JointModel::JournalBearing);
  joint.stiffness = jt.number("stiffness", 0.0, 1e12, std::nullopt, "N/m", true);
  joint.damping = jt.number("damping", 0.0, 1e6, 0.0, "N s/m");
  joint.clearance = jt.number("clearance", 0.0, 1e-3, 0.0, "m");
  jt.finish();
}

Fields::json parseJson(std::string_view text) {
  try {
    return json::parse(text.begin(), text.end(), nullptr, true, /*ignore_comments=*/true);
  } catch (const json::exception& e) {  // (a syntax error, or a number beyond a double: 1e999)
    const std::string what = e.what();
    const std::size_t tag = what.rfind("] ", what.find(' ') + 1);  // "[json.exception.parse_error.101] "
    throw DescriptionError({"(file): not valid JSON: " + (tag == std::string::npos ? what : what.substr(tag + 2))});
  }
}

namespace {

// A problem as one line: the control characters of a name quoted in it (a line break typed into
// a name) written as escapes.
std::string printable(std::string problem) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (const char c : problem) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (u < 0x20 || u == 0x7f) out += std::string("\\x") + kHex[u >> 4] + kHex[u & 15];
    else out += c;
  }
  return out;
}

std::vector<std::string> printable(std::vector<std::string> problems) {
  for (std::string& p : problems) p = printable(std::move(p));
  return problems;
}

}  // namespace

DescriptionError::DescriptionError(std::vector<std::string> problems)
    : std::runtime_error(joinLines(printable(problems))), problems_(printable(std::move(problems))) {}

int DriveDescription::sprocketIndex(std::string_view n) const {
  for (std::size_t i = 0; i < sprockets.size(); ++i)
    if (sprockets[i].name == n) return static_cast<int>(i);
  return -1;
}

int DriveDescription::guideIndex(std::string_view n) const {
  for (std::size_t i = 0; i < guides.size(); ++i)
    if (guides[i].name == n) return static_cast<int>(i);
  return -1;
}

Iso606ToothForm iso606ToothForm(int z, double pitch, double d1, const std::string& form) {
  // ISO 606 empirical formulas are written in millimetres.
  const double d1mm = d1 * 1e3, pmm = pitch * 1e3;
  const double dz = static_cast<double>(z);
  const double riMin = 0.505 * d1mm, riMax = 0.505 * d1mm + 0.069 * math::cbrt(d1mm);
  const double reMinGap = 0.008 * d1mm * (dz * dz + 180.0);  // flank radius of the minimum tooth gap form
  const double reMaxGap = 0.12 * d1mm * (dz + 2.0);           // flank radius of the maximum tooth gap form
  const double aMinGap = (140.0 - 90.0 / dz) * kPi / 180.0;  // seating angle, minimum gap form
  const double aMaxGap = (120.0 - 90.0 / dz) * kPi / 180.0;
  const double pitchDiameter = pmm / math::sin(kPi / dz);
  const double daMax = pitchDiameter + 1.25 * pmm - d1mm, daMin = pitchDiameter + pmm * (1.0 - 1.6 / dz) - d1mm;
  Iso606ToothForm t{};
  if (form == "min") {
    t = {riMin, aMinGap, reMinGap, daMax};
  } else if (form == "max") {
    t = {riMax, aMaxGap, reMaxGap, daMin};
  } else {
    t = {0.5 * (riMin + riMax), 0.5 * (aMinGap + aMaxGap), 0.5 * (reMinGap + reMaxGap), 0.5 * (daMin + daMax)};
  }
  t.seatRadius *= 1e-3;
  t.flankRadius *= 1e-3;
  t.tipDiameter *= 1e-3;
  return t;
}

// A table of contents: the JSON, the sections in file order (each reads what it needs of the
// ones before it), then the checks across sections. Every problem is collected before throwing.
DriveDescription parseDriveDescription(std::string_view text) {
  // syntax errors stop here: nothing can be read
  const json root = parseJson(text);
  std::vector<std::string> problems;
  Fields top(&root, "", problems);
  if (!top.valid()) throw DescriptionError(problems);

  // the sections, in the order their problems are reported
  DriveDescription desc;
  readHeader(top, desc);
  readChain(top, desc);
  ElementNames names;
  readSprockets(top, desc, names);
  readGuides(top, desc, names);
  readTensioner(top, desc);
  readContact(top, desc);
  readClosure(top, desc);
  readMeasurement(top, desc);
  readSpanModel(top, desc);
  top.finish();

  // cross-checks: names in the route and spans, the monitored link, the closing element
  if (!desc.chain.route.empty() || top.has("chain")) checkRoute(desc, problems);
  checkMeasurement(desc, problems);
  defaultClosure(desc, problems);
  checkClosureInRoute(desc, problems);
  if (!problems.empty()) throw DescriptionError(problems);
  desc.canonicalText = root.dump();  // keys sorted, no white space: the same text for the same content
  return desc;
}

std::string readDescriptionFile(const std::string& path) {
  std::ifstream in(utf8Path(path), std::ios::binary);
  if (!in) throw DescriptionError({"(file) " + path + ": cannot be opened for reading"});
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw DescriptionError({"(file) " + path + ": read error"});
  return ss.str();
}

DriveDescription loadDriveDescription(const std::string& path) {
  return parseDescriptionFile(path, [](std::string_view text) { return parseDriveDescription(text); });
}

std::string_view defaultDriveJson() { return kDefaultDriveJson; }

DriveDescription defaultDriveDescription() { return parseDriveDescription(kDefaultDriveJson); }

bool isDefaultDrive(const DriveDescription& desc) {
  static const std::string kDefaultText = defaultDriveDescription().canonicalText;  // (immutable once made)
  return desc.canonicalText == kDefaultText;
}

}  // namespace chaindrive
