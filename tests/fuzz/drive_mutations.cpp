#include "drive_mutations.h"

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace chaindrive::fuzz {

namespace {

using json = nlohmann::json;

// Values JSON cannot hold, written into the text where a placeholder string stands (the reader
// must refuse them with a line naming the place, as it refuses any text that is no JSON).
const char* const kRawNumbers[] = {"NaN", "Infinity", "-Infinity", "1e999", "-1e999", "nan"};
const std::string kRawMark = "@@raw:";

// Names an engineer might type or another tool might write: duplicates are made elsewhere.
const char* const kBadNames[] = {"", " ", "hp pump", "1cam", "cam.shaft", "der(x)", "tensioner", "chain", "link",
                                 "solver", "energy", "fidelity", "contact", "contacts", "driveFile", "Nockenwelle ä",
                                 "a\"b", "<cam>", "cam\tshaft", "cam\nshaft", "x[1]", "_", "crankshaft"};
// Strings of the schema's choices and others, for any string field.
const char* const kWords[] = {"free", "idler", "prescribed", "fixed", "pivoting", "outside", "inside", "arc", "line",
                              "hunt-crossley", "spring-damper", "hydraulic", "journal-bearing", "ideal",
                              "time-stepping", "event-driven", "compliant", "clockwise", "counterclockwise", "mean",
                              "ISO 606", "chaindrive.drive/1", "chaindrive.drive/2", "", "?"};

std::string raw(const char* number) { return kRawMark + number; }

// The leaves of the description (numbers, strings, booleans) by their JSON pointers.
std::vector<std::string> leaves(const json& j) {
  std::vector<std::string> paths;
  const json flat = j.flatten();
  for (const auto& item : flat.items())
    if (!item.value().is_null()) paths.push_back(item.key());
  return paths;
}

json mutatedNumber(Rng& rng, double x) {
  switch (rng.below(10)) {
    case 0: return raw(rng.pick(kRawNumbers));
    case 1: return 0.0;
    case 2: return -x;
    case 3: return x * 1e6;
    case 4: return x * 1e-6;
    case 5: return rng.pick({1e-300, 1e300, -1e300, 5e-324});
    case 6: return x * rng.uniform(0.5, 1.5);
    case 7: return static_cast<long long>(rng.below(5)) - 2;  // an integer of -2..2
    case 8: return x + rng.uniform(-0.05, 0.05);               // a coordinate moved by up to 5 cm
    default: return rng.pick({json("3"), json(true), json::array(), json::object()});  // another type
  }
}

// One leaf changed according to its type.
std::string mutateLeaf(Rng& rng, json& j) {
  const std::vector<std::string> paths = leaves(j);
  if (paths.empty()) return "nothing";
  const json::json_pointer at(rng.pick(paths));
  json& v = j[at];
  if (v.is_number()) v = mutatedNumber(rng, v.get<double>());
  else if (v.is_string()) v = at.back() == "name" || rng.chance(0.3) ? rng.pick(kBadNames) : rng.pick(kWords);
  else if (v.is_boolean()) v = !v.get<bool>();
  return at.to_string() + " = " + v.dump();
}

json* element(Rng& rng, json& j, const char* array) {
  if (!j.contains(array) || !j[array].is_array() || j[array].empty()) return nullptr;
  return &j[array][rng.below(j[array].size())];
}

// Every pair of numbers in v (centres, pivots, points) moved by (dx, dy).
void shiftPoints(json& v, double dx, double dy) {
  if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number()) {
    v[0] = v[0].get<double>() + dx;
    v[1] = v[1].get<double>() + dy;
    return;
  }
  if (v.is_object())
    for (auto& item : v.items())
      if (item.key().find("_deg") == std::string::npos) shiftPoints(item.value(), dx, dy);
  if (v.is_array())
    for (json& e : v) shiftPoints(e, dx, dy);
}

std::string overlapSprockets(Rng& rng, json& j) {
  json* a = element(rng, j, "sprockets");
  json* b = element(rng, j, "sprockets");
  if (!a || !b) return "nothing";
  (*a)["center"] = (*b)["center"];
  if (rng.chance(0.5)) shiftPoints((*a)["center"], rng.uniform(-0.01, 0.01), rng.uniform(-0.01, 0.01));
  return "sprocket " + (*a)["name"].dump() + " onto " + (*b)["name"].dump();
}

// A sprocket mirrored across the line from the first sprocket's centre to another's: the chain
// would reach it from the other side.
std::string mirrorSprocket(Rng& rng, json& j) {
  json* s = element(rng, j, "sprockets");
  json* axis = element(rng, j, "sprockets");
  if (!s || !axis || !j["sprockets"][0].contains("center")) return "nothing";
  try {
    const double ax = j["sprockets"][0]["center"][0], ay = j["sprockets"][0]["center"][1];
    const double bx = (*axis)["center"][0], by = (*axis)["center"][1];
    const double px = (*s)["center"][0], py = (*s)["center"][1];
    const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    if (!(len2 > 0.0)) return "nothing";
    const double t = ((px - ax) * dx + (py - ay) * dy) / len2;
    (*s)["center"] = {2.0 * (ax + t * dx) - px, 2.0 * (ay + t * dy) - py};
  } catch (const json::exception&) {
    return "nothing";  // (an earlier mutation left no numbers there)
  }
  return "sprocket " + (*s)["name"].dump() + " mirrored";
}

std::string shiftGuide(Rng& rng, json& j) {
  json* g = element(rng, j, "guides");
  if (!g) return "nothing";
  const double dx = rng.uniform(-0.06, 0.06), dy = rng.uniform(-0.06, 0.06);
  shiftPoints(*g, dx, dy);
  return "guide " + (*g)["name"].dump() + " moved by (" + std::to_string(dx) + ", " + std::to_string(dy) + ") m";
}

std::string linkCount(Rng& rng, json& j) {
  const json count = rng.pick({json(0), json(1), json(2), json(3), json(7), json(61), json(131), json(500),
                               json(5000), json(100000), json(-4), json(2.5), json(1e12)});
  j["chain"]["numberOfLinks"] = count;
  return "chain/numberOfLinks = " + count.dump();
}

// A name duplicated (another element's) or replaced, in the elements or the route.
std::string rename(Rng& rng, json& j) {
  json* e = element(rng, j, rng.chance(0.6) ? "sprockets" : "guides");
  if (!e) return "nothing";
  json* other = element(rng, j, rng.chance(0.5) ? "sprockets" : "guides");
  (*e)["name"] = other && rng.chance(0.5) ? (*other)["name"] : json(rng.pick(kBadNames));
  if (rng.chance(0.3) && j["chain"].contains("route") && j["chain"]["route"].is_array())
    for (json& r : j["chain"]["route"])
      if (rng.chance(0.3)) r = (*e)["name"];
  return "a name = " + (*e)["name"].dump();
}

// Structure: a key removed, an element duplicated, an array emptied.
std::string restructure(Rng& rng, json& j) {
  const std::vector<std::string> paths = leaves(j);
  if (paths.empty()) return "nothing";
  json::json_pointer at(rng.pick(paths));
  for (std::size_t up = rng.below(3); up > 0 && !at.empty(); --up) at.pop_back();
  if (at.empty()) return "nothing";
  const json::json_pointer parent = at.parent_pointer();
  json& container = j[parent];
  const std::string key = at.back();
  switch (rng.below(3)) {
    case 0:
      if (container.is_object()) container.erase(key);
      else if (container.is_array() && !container.empty()) container.erase(container.size() - 1);
      return at.to_string() + " removed";
    case 1:
      if (container.is_array()) container.push_back(j[at]);
      return at.to_string() + " duplicated";
    default:
      j[at] = j[at].is_array() ? json::array() : json::object();
      return at.to_string() + " emptied";
  }
}

// A plausible change: a drive an engineer might draw instead, most of which still close and run
// (the tension guide's closure range takes up a small change of the path).
std::string nudge(Rng& rng, json& j) {
  switch (rng.below(4)) {
    case 0: {
      json* s = element(rng, j, "sprockets");
      if (!s) return "nothing";
      shiftPoints((*s)["center"], rng.uniform(-0.003, 0.003), rng.uniform(-0.003, 0.003));
      return "sprocket " + (*s)["name"].dump() + " moved by up to 3 mm";
    }
    case 1: {
      json* g = element(rng, j, "guides");
      if (!g) return "nothing";
      shiftPoints(*g, rng.uniform(-0.001, 0.001), rng.uniform(-0.001, 0.001));
      return "guide " + (*g)["name"].dump() + " moved by up to 1 mm";
    }
    default: {  // a positive number scaled by 1/2 to 2 (an inertia, a stiffness, a damping, a force)
      std::vector<std::string> positive;
      const json flat = j.flatten();
      for (const auto& item : flat.items())
        if (item.value().is_number_float() && item.value().get<double>() > 0.0 && item.key().find("center") == std::string::npos &&
            item.key().find("pivot") == std::string::npos)
          positive.push_back(item.key());
      if (positive.empty()) return "nothing";
      const json::json_pointer at(rng.pick(positive));
      j[at] = j[at].get<double>() * rng.logUniform(0.5, 2.0);
      return at.to_string() + " = " + j[at].dump();
    }
  }
}

std::string mutate(Rng& rng, json& j) {
  switch (rng.below(8)) {
    case 0:
    case 1: return mutateLeaf(rng, j);
    case 2: return overlapSprockets(rng, j);
    case 3: return mirrorSprocket(rng, j);
    case 4: return shiftGuide(rng, j);
    case 5: return linkCount(rng, j);
    case 6: return rename(rng, j);
    default: return restructure(rng, j);
  }
}

// The text with the raw numbers in place of their placeholders.
std::string withRawNumbers(std::string text) {
  for (std::size_t at = text.find("\"" + kRawMark); at != std::string::npos; at = text.find("\"" + kRawMark, at)) {
    const std::size_t end = text.find('"', at + 1);
    const std::string number = text.substr(at + 1 + kRawMark.size(), end - at - 1 - kRawMark.size());
    text.replace(at, end + 1 - at, number);
  }
  return text;
}

}  // namespace

std::string mutatedDrive(Rng& rng, const std::vector<std::string>& bases, std::string& what) {
  json j = json::parse(rng.pick(bases));
  what.clear();
  const bool plausible = rng.chance(0.4);  // (else degenerate: mostly refused, which is their test)
  const std::size_t count = 1 + rng.below(3);
  for (std::size_t i = 0; i < count; ++i) {
    std::string m;
    try {
      m = plausible ? nudge(rng, j) : mutate(rng, j);
    } catch (const json::exception& e) {  // (an earlier mutation changed the shape this one expects)
      m = std::string("skipped: ") + e.what();
    }
    what += (what.empty() ? "" : "; ") + m;
  }
  return withRawNumbers(j.dump(1));
}

}  // namespace chaindrive::fuzz
