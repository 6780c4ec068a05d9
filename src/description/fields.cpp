#include "description/fields.h"

#include <cmath>
#include <sstream>

namespace chaindrive {

namespace {

using json = nlohmann::json;

std::string typeName(const json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_array()) return "an array";
  return "an object";
}

}  // namespace

std::string formatNumber(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

Fields::Fields(const json* j, std::string path, std::vector<std::string>& problems)
    : j_(j), path_(std::move(path)), problems_(problems) {
  if (j_ && !j_->is_object()) {
    problem(path_, "must be an object, got " + typeName(*j_));
    j_ = nullptr;
  }
}

const Fields::json* Fields::raw(const std::string& key) {
  seen_.insert(key);
  if (!j_) return nullptr;
  auto it = j_->find(key);
  return it == j_->end() ? nullptr : &*it;
}

double Fields::number(const std::string& key, double lo, double hi, std::optional<double> dflt, const char* unit,
                      bool loOpen) {
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
    problem(at(key), formatNumber(x) + " is out of range; allowed " + rangeText(lo, hi, unit, loOpen));
  }
  return x;
}

std::optional<double> Fields::optionalNumber(const std::string& key, double lo, double hi, const char* unit,
                                             bool loOpen) {
  if (!has(key)) {
    seen_.insert(key);
    return std::nullopt;
  }
  return number(key, lo, hi, std::nullopt, unit, loOpen);
}

double Fields::angle(const std::string& key, double loRad, double hiRad, std::optional<double> dfltRad) {
  const std::string keyDeg = key + "_deg";
  const bool inRad = has(key), inDeg = has(keyDeg);
  seen_.insert(key);
  seen_.insert(keyDeg);
  if (inRad && inDeg) {
    problem(at(key), "given both as '" + key + "' [rad] and '" + keyDeg + "' [deg]; give one");
    return std::nan("");
  }
  if (inDeg) {
    const double deg = number(keyDeg, loRad * 180.0 / kPi, hiRad * 180.0 / kPi, std::nullopt, "deg");
    return deg * kPi / 180.0;
  }
  if (inRad) return number(key, loRad, hiRad, std::nullopt, "rad");
  if (!dfltRad && j_)
    problem(at(key), "missing; required (as '" + key + "' in rad or '" + keyDeg + "' in deg)");
  return dfltRad.value_or(std::nan(""));
}

int Fields::integer(const std::string& key, int lo, int hi, std::optional<int> dflt) {
  const json* v = raw(key);
  if (!v) {
    if (!dflt && j_) problem(at(key), "missing; required, an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
    return dflt.value_or(0);
  }
  if (!v->is_number_integer()) {
    problem(at(key), "must be an integer, got " + (v->is_number() ? formatNumber(v->get<double>()) : typeName(*v)));
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

std::string Fields::string(const std::string& key, const std::vector<std::string>& allowed,
                           std::optional<std::string> dflt) {
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
    if (!ok) problem(at(key), unknownChoiceText(s, allowed));
  } else if (s.empty()) {
    problem(at(key), "must not be empty");
  }
  return s;
}

bool Fields::boolean(const std::string& key, bool dflt) {
  const json* v = raw(key);
  if (!v) return dflt;
  if (!v->is_boolean()) {
    problem(at(key), "must be true or false, got " + typeName(*v));
    return dflt;
  }
  return v->get<bool>();
}

Vec2 Fields::vec2(const std::string& key, double bound, std::optional<Vec2> dflt, const char* unit) {
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
    problem(at(key), "[" + formatNumber(r.x) + ", " + formatNumber(r.y) + "] is out of range; allowed |x|, |y| <= " +
                         formatNumber(bound) + " " + unit);
  return r;
}

// The array at `key`, or nullptr when it is missing (a problem if required) or not an array.
const Fields::json* Fields::array(const std::string& key, bool required, const char* missingWhat,
                                  const char* wrongTypeWhat) {
  const json* v = raw(key);
  if (!v) {
    if (required && j_) problem(at(key), std::string("missing; required, ") + missingWhat);
    return nullptr;
  }
  if (!v->is_array()) {
    problem(at(key), std::string("must be ") + wrongTypeWhat + ", got " + typeName(*v));
    return nullptr;
  }
  return v;
}

std::vector<std::string> Fields::strings(const std::string& key, bool required) {
  std::vector<std::string> out;
  const json* v = array(key, required, "an array of names", "an array of names");
  if (!v) return out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    if (!(*v)[i].is_string()) {
      problem(at(key) + "[" + std::to_string(i) + "]", "must be a string");
      continue;
    }
    out.push_back((*v)[i].get<std::string>());
  }
  return out;
}

Fields Fields::object(const std::string& key, bool required) {
  const json* v = raw(key);
  if (!v && required && j_) problem(at(key), "missing; required, an object");
  return Fields(v, at(key), problems_);
}

std::vector<Fields> Fields::objects(const std::string& key, bool required) {
  std::vector<Fields> out;
  const json* v = array(key, required, "an array of objects", "an array");
  if (!v) return out;
  for (std::size_t i = 0; i < v->size(); ++i) out.emplace_back(&(*v)[i], at(key) + "[" + std::to_string(i) + "]", problems_);
  return out;
}

void Fields::finish() {
  if (!j_) return;
  for (auto it = j_->begin(); it != j_->end(); ++it) {
    if (!seen_.count(it.key())) {
      std::string known;
      for (const auto& k : seen_) known += (known.empty() ? "" : ", ") + k;
      problem(at(it.key()), "unknown key; known keys here: " + known);
    }
  }
}

std::string Fields::rangeText(double lo, double hi, const char* unit, bool loOpen) {
  std::string u = unit && *unit ? std::string(" ") + unit : std::string();
  if (std::isinf(hi)) return (loOpen ? "> " : ">= ") + formatNumber(lo) + u;
  return (loOpen ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) + "]" + u;
}

std::string Fields::allowedText(const std::vector<std::string>& allowed) {
  if (allowed.empty()) return "";
  return "; allowed: " + listOfNames(allowed);
}

}  // namespace chaindrive
