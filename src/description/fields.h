// The field reader of the drive description: reads the fields of one JSON object with their
// types and allowed ranges, and collects every problem with its full field path (so that all
// errors of a file are reported at once). Every field asked for is remembered, so that finish()
// can report the keys nobody asked for.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "choice.h"
#include "description/drive_description.h"
#include "math/vec2.h"

namespace chaindrive {

/// A number as the problems print it (6 significant digits).
std::string formatNumber(double v);

class Fields {
 public:
  using json = nlohmann::json;

  /// Reader of *j at `path` ("" for the root); j == nullptr: a missing optional object (reads
  /// give the defaults and report nothing). A non-object is a problem.
  Fields(const json* j, std::string path, std::vector<std::string>& problems);

  bool valid() const { return j_ != nullptr; }
  const std::string& path() const { return path_; }
  std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  bool has(const std::string& key) const { return j_ && j_->contains(key); }
  void problem(const std::string& field, const std::string& what) { problems_.push_back(field + ": " + what); }

  /// The raw value of `key` (nullptr if absent); marks the key as known.
  const json* raw(const std::string& key);

  /// A number in [lo, hi]. Missing: the default if given, else a problem.
  double number(const std::string& key, double lo, double hi, std::optional<double> dflt, const char* unit,
                bool loOpen = false);
  std::optional<double> optionalNumber(const std::string& key, double lo, double hi, const char* unit,
                                       bool loOpen = false);
  /// An angle given either as `key` [rad] or as `key_deg` [deg]; returned in rad.
  double angle(const std::string& key, double loRad, double hiRad, std::optional<double> dfltRad);
  int integer(const std::string& key, int lo, int hi, std::optional<int> dflt);
  /// A string out of `allowed` (any non-empty string when `allowed` is empty).
  std::string string(const std::string& key, const std::vector<std::string>& allowed, std::optional<std::string> dflt);
  /// A choice by its name (choice.h). Missing: the default if given, else a problem.
  template <class E>
  E choice(const std::string& key, std::optional<E> dflt) {
    const std::string name = string(key, choiceNames<E>(), dflt ? std::optional<std::string>(choiceName(*dflt)) : std::nullopt);
    return choiceOf<E>(name).value_or(dflt.value_or(ChoiceNames<E>::table[0].value));
  }
  bool boolean(const std::string& key, bool dflt);
  Vec2 vec2(const std::string& key, double bound, std::optional<Vec2> dflt, const char* unit);
  std::vector<std::string> strings(const std::string& key, bool required);
  Fields object(const std::string& key, bool required);
  /// Array of objects; returns the per-element readers (paths with [i]).
  std::vector<Fields> objects(const std::string& key, bool required);

  /// Reports every key of the object that was never asked for.
  void finish();

 private:
  const json* array(const std::string& key, bool required, const char* missingWhat, const char* wrongTypeWhat);
  static std::string rangeText(double lo, double hi, const char* unit, bool loOpen);
  static std::string allowedText(const std::vector<std::string>& allowed);

  const json* j_;
  std::string path_;
  std::vector<std::string>& problems_;
  std::set<std::string> seen_;
};

struct JointDesc;

/// The text parsed as JSON (comments allowed); a syntax error is a DescriptionError.
Fields::json parseJson(std::string_view text);
/// The text of a description file; an unreadable one is a DescriptionError naming the path.
std::string readDescriptionFile(const std::string& path);
/// parse(text of the file at path), its problems prefixed by the path.
template <class Parse>
auto parseDescriptionFile(const std::string& path, Parse parse) {
  const std::string text = readDescriptionFile(path);
  try {
    return parse(text);
  } catch (const DescriptionError& e) {
    std::vector<std::string> p;
    for (const auto& s : e.problems()) p.push_back(path + ": " + s);
    throw DescriptionError(p);
  }
}
/// The links' joint (the timing drive's and the CVT's descriptions): model, stiffness, damping,
/// clearance.
void readJoint(Fields jt, JointDesc& joint);
/// The hydraulic tensioner's block (tensioner.hydraulic), every field with its range; a missing
/// field keeps the default of HydraulicTensionerDesc.
void readHydraulicTensioner(Fields f, HydraulicTensionerDesc& h);

}  // namespace chaindrive
