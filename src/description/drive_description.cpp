#include "description/drive_description.h"

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

namespace chaindrive {

extern const std::string_view kDefaultDriveJson;  // generated at build time

using json = nlohmann::json;

namespace {

std::string joinLines(const std::vector<std::string>& problems) {
  std::string s = "invalid drive description:";
  for (const auto& p : problems) s += "\n  " + p;
  return s;
}

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

std::string typeName(const json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_array()) return "an array";
  return "an object";
}

// Reads the fields of one JSON object, collecting problems with their full path. Every field read
// is remembered so that finish() can report unknown keys.
class Fields {
 public:
  Fields(const json* j, std::string path, std::vector<std::string>& problems)
      : j_(j), path_(std::move(path)), problems_(problems) {
    if (j_ && !j_->is_object()) {
      problem(path_, "must be an object, got " + typeName(*j_));
      j_ = nullptr;
    }
  }

  bool valid() const { return j_ != nullptr; }
  const std::string& path() const { return path_; }
  std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  bool has(const std::string& key) const { return j_ && j_->contains(key); }

  void problem(const std::string& field, const std::string& what) { problems_.push_back(field + ": " + what); }

  const json* raw(const std::string& key) {
    seen_.insert(key);
    if (!j_) return nullptr;
    auto it = j_->find(key);
    return it == j_->end() ? nullptr : &*it;
  }

  /// A number in [lo, hi]. Missing: the default if given, else a problem.
  double number(const std::string& key, double lo, double hi, std::optional<double> dflt, const char* unit,
                bool loOpen = false) {
    const json* v = raw(key);
    if (!v) {
      if (!dflt && j_) problem(at(key), std::string("missing; required, ") + rangeText(lo, hi, unit, loOpen));
      return dflt.value_or(std::nan(""));
    }
    if (!v->is_number()) {
      problem(at(key), "must be a number, got " + typeName(*v));
      return dflt.value_or(std::nan(""));
    }
    const double x = v->get<double>();
    if (!std::isfinite(x) || x < lo || x > hi || (loOpen && x == lo)) {
      problem(at(key), fmt(x) + " is out of range; allowed " + rangeText(lo, hi, unit, loOpen));
    }
    return x;
  }

  std::optional<double> optionalNumber(const std::string& key, double lo, double hi, const char* unit,
                                       bool loOpen = false) {
    if (!has(key)) {
      seen_.insert(key);
      return std::nullopt;
    }
    return number(key, lo, hi, std::nullopt, unit, loOpen);
  }

  /// An angle given either as `key` [rad] or as `key_deg` [deg]; returned in rad.
  double angle(const std::string& key, double loRad, double hiRad, std::optional<double> dfltRad) {
    const std::string keyDeg = key + "_deg";
    const bool r = has(key), d = has(keyDeg);
    seen_.insert(key);
    seen_.insert(keyDeg);
    if (r && d) {
      problem(at(key), "given both as '" + key + "' [rad] and '" + keyDeg + "' [deg]; give one");
      return std::nan("");
    }
    if (d) {
      const double deg = number(keyDeg, loRad * 180.0 / kPi, hiRad * 180.0 / kPi, std::nullopt, "deg");
      return deg * kPi / 180.0;
    }
    if (r) return number(key, loRad, hiRad, std::nullopt, "rad");
    if (!dfltRad && j_)
      problem(at(key), "missing; required (as '" + key + "' in rad or '" + keyDeg + "' in deg)");
    return dfltRad.value_or(std::nan(""));
  }

  int integer(const std::string& key, int lo, int hi, std::optional<int> dflt) {
    const json* v = raw(key);
    if (!v) {
      if (!dflt && j_) problem(at(key), "missing; required, an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
      return dflt.value_or(0);
    }
    if (!v->is_number_integer()) {
      problem(at(key), "must be an integer, got " + (v->is_number() ? fmt(v->get<double>()) : typeName(*v)));
      return dflt.value_or(0);
    }
    const long long x = v->get<long long>();
    if (x < lo || x > hi) {
      problem(at(key), std::to_string(x) + " is out of range; allowed an integer in " + std::to_string(lo) + ".." +
                           std::to_string(hi));
      return dflt.value_or(0);
    }
    return static_cast<int>(x);
  }

  std::string string(const std::string& key, const std::vector<std::string>& allowed, std::optional<std::string> dflt) {
    const json* v = raw(key);
    if (!v) {
      if (!dflt && j_) problem(at(key), "missing; required" + allowedText(allowed));
      return dflt.value_or("");
    }
    if (!v->is_string()) {
      problem(at(key), "must be a string, got " + typeName(*v));
      return dflt.value_or("");
    }
    std::string s = v->get<std::string>();
    if (!allowed.empty()) {
      bool ok = false;
      for (const auto& a : allowed) ok = ok || a == s;
      if (!ok) problem(at(key), "'" + s + "' is not allowed" + allowedText(allowed));
    } else if (s.empty()) {
      problem(at(key), "must not be empty");
    }
    return s;
  }

  bool boolean(const std::string& key, bool dflt) {
    const json* v = raw(key);
    if (!v) return dflt;
    if (!v->is_boolean()) {
      problem(at(key), "must be true or false, got " + typeName(*v));
      return dflt;
    }
    return v->get<bool>();
  }

  Vec2 vec2(const std::string& key, double bound, std::optional<Vec2> dflt, const char* unit) {
    const json* v = raw(key);
    if (!v) {
      if (!dflt && j_) problem(at(key), std::string("missing; required, [x, y] in ") + unit);
      return dflt.value_or(Vec2{std::nan(""), std::nan("")});
    }
    if (!v->is_array() || v->size() != 2 || !(*v)[0].is_number() || !(*v)[1].is_number()) {
      problem(at(key), std::string("must be an array of two numbers [x, y] in ") + unit);
      return dflt.value_or(Vec2{std::nan(""), std::nan("")});
    }
    Vec2 r{(*v)[0].get<double>(), (*v)[1].get<double>()};
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || std::fabs(r.x) > bound || std::fabs(r.y) > bound)
      problem(at(key), "[" + fmt(r.x) + ", " + fmt(r.y) + "] is out of range; allowed |x|, |y| <= " + fmt(bound) + " " + unit);
    return r;
  }

  std::vector<std::string> strings(const std::string& key, bool required) {
    std::vector<std::string> out;
    const json* v = raw(key);
    if (!v) {
      if (required && j_) problem(at(key), "missing; required, an array of names");
      return out;
    }
    if (!v->is_array()) {
      problem(at(key), "must be an array of names, got " + typeName(*v));
      return out;
    }
    for (std::size_t i = 0; i < v->size(); ++i) {
      if (!(*v)[i].is_string()) {
        problem(at(key) + "[" + std::to_string(i) + "]", "must be a string");
        continue;
      }
      out.push_back((*v)[i].get<std::string>());
    }
    return out;
  }

  Fields object(const std::string& key, bool required) {
    const json* v = raw(key);
    if (!v && required && j_) problem(at(key), "missing; required, an object");
    return Fields(v, at(key), problems_);
  }

  /// Array of objects; returns the per-element readers (paths with [i]).
  std::vector<Fields> objects(const std::string& key, bool required) {
    std::vector<Fields> out;
    const json* v = raw(key);
    if (!v) {
      if (required && j_) problem(at(key), "missing; required, an array of objects");
      return out;
    }
    if (!v->is_array()) {
      problem(at(key), "must be an array, got " + typeName(*v));
      return out;
    }
    for (std::size_t i = 0; i < v->size(); ++i) out.emplace_back(&(*v)[i], at(key) + "[" + std::to_string(i) + "]", problems_);
    return out;
  }

  /// Reports every key of the object that was never asked for.
  void finish() {
    if (!j_) return;
    for (auto it = j_->begin(); it != j_->end(); ++it) {
      if (!seen_.count(it.key())) {
        std::string known;
        for (const auto& k : seen_) known += (known.empty() ? "" : ", ") + k;
        problem(at(it.key()), "unknown key; known keys here: " + known);
      }
    }
  }

 private:
  static std::string rangeText(double lo, double hi, const char* unit, bool loOpen) {
    std::string u = unit && *unit ? std::string(" ") + unit : std::string();
    if (std::isinf(hi)) return (loOpen ? "> " : ">= ") + fmt(lo) + u;
    return (loOpen ? "(" : "[") + fmt(lo) + ", " + fmt(hi) + "]" + u;
  }
  static std::string allowedText(const std::vector<std::string>& allowed) {
    if (allowed.empty()) return "";
    std::string s = "; allowed: ";
    for (std::size_t i = 0; i < allowed.size(); ++i) s += (i ? ", " : "") + std::string("'") + allowed[i] + "'";
    return s;
  }

  const json* j_;
  std::string path_;
  std::vector<std::string>& problems_;
  std::set<std::string> seen_;
};

constexpr double kInf = std::numeric_limits<double>::infinity();

ContactLawDesc readContactLaw(Fields f) {
  ContactLawDesc c;
  if (!f.valid()) return c;
  c.model = f.string("model", {"hunt-crossley", "spring-damper"}, std::string("hunt-crossley"));
  c.stiffness = f.number("stiffness", 0.0, 1e12, std::nullopt, "N/m^exponent", true);
  c.exponent = f.number("exponent", 1.0, 2.0, 1.0, "");
  c.dampingFactor = f.number("dampingFactor", 0.0, 100.0, 0.0, "s/m");
  c.damping = f.number("damping", 0.0, 1e7, 0.0, "N s/m");
  c.friction = f.number("friction", 0.0, 2.0, 0.0, "");
  c.restitution = f.number("restitution", 0.0, 1.0, 0.5, "");
  if (c.model == "hunt-crossley" && f.has("damping"))
    f.problem(f.at("damping"), "not used by model 'hunt-crossley' (give 'dampingFactor' in s/m)");
  if (c.model == "spring-damper" && f.has("dampingFactor"))
    f.problem(f.at("dampingFactor"), "not used by model 'spring-damper' (give 'damping' in N s/m)");
  f.finish();
  return c;
}

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

}  // namespace

DescriptionError::DescriptionError(std::vector<std::string> problems)
    : std::runtime_error(joinLines(problems)), problems_(std::move(problems)) {}

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
  const double riMin = 0.505 * d1mm, riMax = 0.505 * d1mm + 0.069 * std::cbrt(d1mm);
  const double reMinGap = 0.008 * d1mm * (dz * dz + 180.0);  // flank radius of the minimum tooth gap form
  const double reMaxGap = 0.12 * d1mm * (dz + 2.0);           // flank radius of the maximum tooth gap form
  const double aMinGap = (140.0 - 90.0 / dz) * kPi / 180.0;  // seating angle, minimum gap form
  const double aMaxGap = (120.0 - 90.0 / dz) * kPi / 180.0;
  const double d = pmm / std::sin(kPi / dz);
  const double daMax = d + 1.25 * pmm - d1mm, daMin = d + pmm * (1.0 - 1.6 / dz) - d1mm;
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

DriveDescription parseDriveDescription(std::string_view text) {
  json root;
  try {
    root = json::parse(text.begin(), text.end(), nullptr, true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    throw DescriptionError({std::string("(file): not valid JSON: ") + e.what()});
  }
  std::vector<std::string> problems;
  Fields top(&root, "", problems);
  if (!top.valid()) throw DescriptionError(problems);

  DriveDescription d;
  top.string("schema", {"chaindrive.drive/1"}, std::string("chaindrive.drive/1"));
  d.name = top.string("name", {}, std::string("unnamed drive"));
  top.string("description", {}, std::string(""));
  const std::string rot = top.string("rotation", {"clockwise", "counterclockwise"}, std::string("clockwise"));
  d.rotationSense = rot == "clockwise" ? -1.0 : 1.0;
  d.gravity = top.vec2("gravity", 100.0, Vec2{0.0, -9.81}, "m/s^2");

  // ---- chain ----
  {
    Fields c = top.object("chain", true);
    if (c.valid()) {
      d.chain.pitch = c.number("pitch", 1e-3, 0.1, std::nullopt, "m");
      d.chain.numberOfLinks = c.integer("numberOfLinks", 10, 10000, std::nullopt);
      if (d.chain.numberOfLinks % 2 != 0)
        c.problem(c.at("numberOfLinks"), std::to_string(d.chain.numberOfLinks) +
                                             " is odd; a roller chain alternates inner and outer links, so the "
                                             "number must be even");
      d.chain.linkMass = c.number("linkMass", 0.0, 10.0, std::nullopt, "kg", true);
      d.chain.linkInertia = c.number("linkInertia", 0.0, 1.0, std::nullopt, "kg m^2", true);
      d.chain.rollerDiameter = c.number("rollerDiameter", 1e-4, 0.1, std::nullopt, "m");
      d.chain.plateHeight = c.number("plateHeight", 1e-4, 0.2, std::nullopt, "m");
      c.string("standard", {}, std::string(""));
      if (std::isfinite(d.chain.rollerDiameter) && std::isfinite(d.chain.pitch) && d.chain.rollerDiameter >= d.chain.pitch)
        c.problem(c.at("rollerDiameter"), fmt(d.chain.rollerDiameter) + " m must be smaller than the pitch " +
                                              fmt(d.chain.pitch) + " m");
      Fields jt = c.object("joint", true);
      if (jt.valid()) {
        d.chain.joint.model = jt.string("model", {"journal-bearing", "ideal"}, std::string("journal-bearing"));
        d.chain.joint.stiffness = jt.number("stiffness", 0.0, 1e12, std::nullopt, "N/m", true);
        d.chain.joint.damping = jt.number("damping", 0.0, 1e6, 0.0, "N s/m");
        d.chain.joint.clearance = jt.number("clearance", 0.0, 1e-3, 0.0, "m");
        jt.finish();
      }
      d.chain.route = c.strings("route", true);
      c.finish();
    }
  }

  // ---- sprockets ----
  std::set<std::string> names;
  auto claimName = [&](Fields& f, const std::string& n) {
    if (n.empty()) return;
    if (!names.insert(n).second) f.problem(f.at("name"), "'" + n + "' is used twice; sprocket and guide names must be unique");
  };
  {
    auto list = top.objects("sprockets", true);
    if (top.has("sprockets") && list.size() < 2) top.problem("sprockets", "at least two sprockets are needed");
    for (auto& f : list) {
      if (!f.valid()) continue;
      SprocketDesc s;
      s.name = f.string("name", {}, std::nullopt);
      claimName(f, s.name);
      s.center = f.vec2("center", 10.0, std::nullopt, "m");
      s.teeth = f.integer("teeth", 6, 200, std::nullopt);
      const std::string motion = f.string("motion", {"prescribed", "free"}, std::nullopt);
      s.prescribed = motion == "prescribed";
      s.inertia = f.number("inertia", 0.0, 1e3, s.prescribed ? std::optional<double>(0.0) : std::nullopt, "kg m^2",
                           !s.prescribed);
      Fields tp = f.object("toothProfile", false);
      if (tp.valid()) {
        tp.string("standard", {"ISO 606"}, std::string("ISO 606"));
        s.toothProfile.form = tp.string("form", {"min", "mean", "max"}, std::string("mean"));
        s.toothProfile.seatRadius = tp.optionalNumber("seatRadius", 0.0, 0.05, "m", true);
        if (tp.has("seatAngle") || tp.has("seatAngle_deg"))
          s.toothProfile.seatAngle = tp.angle("seatAngle", 60.0 * kPi / 180.0, 170.0 * kPi / 180.0, std::nullopt);
        else
          tp.angle("seatAngle", 0.0, 1.0, 0.0);  // mark both spellings as known
        s.toothProfile.flankRadius = tp.optionalNumber("flankRadius", 0.0, 10.0, "m", true);
        s.toothProfile.tipDiameter = tp.optionalNumber("tipDiameter", 0.0, 10.0, "m", true);
        tp.finish();
      }
      f.finish();
      d.sprockets.push_back(s);
    }
    int nPrescribed = 0;
    for (const auto& s : d.sprockets) nPrescribed += s.prescribed ? 1 : 0;
    if (nPrescribed > 1)
      top.problem("sprockets", std::to_string(nPrescribed) + " sprockets have motion 'prescribed'; at most one may");
  }

  // ---- guides ----
  {
    auto list = top.objects("guides", false);
    for (auto& f : list) {
      if (!f.valid()) continue;
      GuideDesc g;
      g.name = f.string("name", {}, std::nullopt);
      claimName(f, g.name);
      const std::string motion = f.string("motion", {"fixed", "pivoting"}, std::nullopt);
      g.pivoting = motion == "pivoting";
      if (g.pivoting) {
        g.pivot = f.vec2("pivot", 10.0, std::nullopt, "m");
        g.inertia = f.number("inertia", 0.0, 1e3, std::nullopt, "kg m^2", true);
        g.mass = f.number("mass", 0.0, 1e3, 0.0, "kg");
        g.centerOfMass = f.vec2("centerOfMass", 10.0, g.pivot, "m");
        g.pivotDamping = f.number("pivotDamping", 0.0, 1e6, 0.0, "N m s/rad");
        if (f.has("angleRange") || f.has("angleRange_deg")) {
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
        } else {
          f.raw("angleRange");
          f.raw("angleRange_deg");
        }
      }
      for (auto& pf : f.objects("profile", true)) {
        if (pf.valid()) g.profile.push_back(readFeature(pf));
      }
      if (f.has("profile") && g.profile.empty()) f.problem(f.at("profile"), "must contain at least one arc or line");
      f.finish();
      d.guides.push_back(g);
    }
  }

  // ---- tensioner ----
  {
    Fields f = top.object("tensioner", false);
    if (f.valid()) {
      TensionerDesc& t = d.tensioner;
      t.present = true;
      t.guide = f.string("guide", {}, std::nullopt);
      t.housing = f.vec2("housing", 10.0, std::nullopt, "m");
      t.direction = f.vec2("direction", 1e6, std::nullopt, "(unit vector)");
      t.contactPoint = f.vec2("contactPoint", 10.0, std::nullopt, "m");
      t.preload = f.number("preload", 0.0, 1e5, std::nullopt, "N");
      t.stiffness = f.number("stiffness", 0.0, 1e9, 0.0, "N/m");
      t.damping = f.number("damping", 0.0, 1e7, 0.0, "N s/m");
      t.dampingExtension = f.number("dampingExtension", 0.0, 1e7, t.damping, "N s/m");
      const double n = norm(t.direction);
      if (std::isfinite(n)) {
        if (n < 1e-12) f.problem(f.at("direction"), "must not be the zero vector");
        else t.direction = (1.0 / n) * t.direction;
      }
      if (!t.guide.empty()) {
        const int gi = d.guideIndex(t.guide);
        if (gi < 0) f.problem(f.at("guide"), "'" + t.guide + "' is not the name of a guide");
        else if (!d.guides[gi].pivoting) f.problem(f.at("guide"), "'" + t.guide + "' is a fixed guide; a tensioner needs a pivoting guide");
      }
      f.finish();
    }
  }

  // ---- contact ----
  {
    Fields f = top.object("contact", true);
    if (f.valid()) {
      d.contact.method = f.string("method", {"compliant", "event-driven", "time-stepping"}, std::string("compliant"));
      d.contact.frictionRegularization = f.number("frictionRegularization", 1e-6, 10.0, 0.05, "m/s");
      d.contact.rollerSprocket = readContactLaw(f.object("rollerSprocket", true));
      d.contact.plateGuide = readContactLaw(f.object("plateGuide", !d.guides.empty()));
      f.finish();
    }
  }

  // ---- closure ----
  {
    Fields f = top.object("closure", false);
    if (f.valid()) {
      ClosureDesc c;
      const std::string kind = f.string("kind", {"guide-angle", "sprocket-shift"}, std::nullopt);
      c.element = f.string("element", {}, std::nullopt);
      if (kind == "guide-angle") {
        c.kind = ClosureDesc::Kind::Guide;
        const int gi = d.guideIndex(c.element);
        if (!c.element.empty() && (gi < 0 || !d.guides[gi].pivoting))
          f.problem(f.at("element"), "'" + c.element + "' is not a pivoting guide");
        else if (gi >= 0) {
          c.rangeMin = d.guides[gi].angleMin;
          c.rangeMax = d.guides[gi].angleMax;
        }
      } else if (kind == "sprocket-shift") {
        c.kind = ClosureDesc::Kind::Sprocket;
        if (!c.element.empty() && d.sprocketIndex(c.element) < 0)
          f.problem(f.at("element"), "'" + c.element + "' is not a sprocket");
        c.direction = f.vec2("direction", 1e6, std::nullopt, "(unit vector)");
        const double n = norm(c.direction);
        if (std::isfinite(n) && n > 1e-12) c.direction = (1.0 / n) * c.direction;
        else f.problem(f.at("direction"), "must be a non-zero vector");
        c.rangeMin = f.number("shiftMin", -1.0, 0.0, -0.01, "m");
        c.rangeMax = f.number("shiftMax", 0.0, 1.0, 0.01, "m");
      }
      f.finish();
      d.closure = c;
    }
  }

  // ---- measurement ----
  {
    Fields f = top.object("measurement", false);
    if (f.valid()) {
      d.measurement.tightSpan = f.strings("tightSpan", false);
      d.measurement.slackSpan = f.strings("slackSpan", false);
      d.measurement.monitoredLink = f.integer("monitoredLink", 0, 9999, 0);
      f.finish();
    }
  }
  top.finish();

  // ---- cross references ----
  if (!d.chain.route.empty() || top.has("chain")) {
    std::map<std::string, int> count;
    for (std::size_t i = 0; i < d.chain.route.size(); ++i) {
      const auto& n = d.chain.route[i];
      ++count[n];
      if (d.sprocketIndex(n) < 0 && d.guideIndex(n) < 0)
        problems.push_back("chain.route[" + std::to_string(i) + "]: '" + n + "' is neither a sprocket nor a guide");
    }
    for (const auto& [n, k] : count)
      if (k > 1) problems.push_back("chain.route: '" + n + "' appears " + std::to_string(k) + " times; at most once");
    for (std::size_t i = 0; i < d.sprockets.size(); ++i)
      if (!d.sprockets[i].name.empty() && !count.count(d.sprockets[i].name))
        problems.push_back("sprockets[" + std::to_string(i) + "]: '" + d.sprockets[i].name +
                           "' is not in chain.route; every sprocket must be wrapped by the chain");
    int nSprocketsInRoute = 0;
    for (const auto& n : d.chain.route) nSprocketsInRoute += d.sprocketIndex(n) >= 0 ? 1 : 0;
    if (nSprocketsInRoute < 2 && !d.chain.route.empty())
      problems.push_back("chain.route: needs at least two sprockets");
  }
  auto checkSpan = [&](const std::vector<std::string>& span, const char* field) {
    if (span.empty()) return;
    const auto& r = d.chain.route;
    bool ok = span.size() == 2;
    if (ok) {
      ok = false;
      for (std::size_t i = 0; i < r.size(); ++i)
        if (r[i] == span[0] && r[(i + 1) % r.size()] == span[1]) ok = true;
    }
    if (!ok)
      problems.push_back(std::string("measurement.") + field +
                         ": must name two elements that follow each other in chain.route, in running order");
  };
  checkSpan(d.measurement.tightSpan, "tightSpan");
  checkSpan(d.measurement.slackSpan, "slackSpan");
  if (d.chain.numberOfLinks > 0 && d.measurement.monitoredLink >= d.chain.numberOfLinks)
    problems.push_back("measurement.monitoredLink: " + std::to_string(d.measurement.monitoredLink) +
                       " is out of range; allowed 0.." + std::to_string(d.chain.numberOfLinks - 1));
  if (!d.closure) {
    if (d.tensioner.present && d.guideIndex(d.tensioner.guide) >= 0 && d.guides[d.guideIndex(d.tensioner.guide)].pivoting) {
      ClosureDesc c;
      c.kind = ClosureDesc::Kind::Guide;
      c.element = d.tensioner.guide;
      const auto& g = d.guides[d.guideIndex(c.element)];
      c.rangeMin = g.angleMin;
      c.rangeMax = g.angleMax;
      d.closure = c;
    } else if (problems.empty()) {
      problems.push_back("closure: missing; without a tensioner, name the element that closes the chain "
                         "({\"kind\": \"guide-angle\" | \"sprocket-shift\", \"element\": ...})");
    }
  }
  if (d.closure && d.closure->kind == ClosureDesc::Kind::Guide) {
    bool inRoute = false;
    for (const auto& n : d.chain.route) inRoute = inRoute || n == d.closure->element;
    if (!inRoute && !d.closure->element.empty())
      problems.push_back("closure.element: guide '" + d.closure->element + "' must be in chain.route to close the chain");
  }
  if (!problems.empty()) throw DescriptionError(problems);
  return d;
}

DriveDescription loadDriveDescription(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DescriptionError({"(file) " + path + ": cannot be opened for reading"});
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw DescriptionError({"(file) " + path + ": read error"});
  try {
    return parseDriveDescription(ss.str());
  } catch (const DescriptionError& e) {
    std::vector<std::string> p;
    for (const auto& s : e.problems()) p.push_back(path + ": " + s);
    throw DescriptionError(p);
  }
}

std::string_view defaultDriveJson() { return kDefaultDriveJson; }

DriveDescription defaultDriveDescription() { return parseDriveDescription(kDefaultDriveJson); }

}  // namespace chaindrive
