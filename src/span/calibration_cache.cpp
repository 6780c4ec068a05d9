#include "span/calibration_cache.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

#include "description/drive_description.h"
#include "utf8_path.h"

namespace chaindrive {
extern const std::string_view kSourceHash;  // generated: the solver's sources, hashed (CMakeLists.txt)
}

namespace chaindrive::span {

namespace {

using json = nlohmann::json;
constexpr int kFormat = 2;  // of the cache file (2: the guide seats)

std::uint64_t fnv1a(std::string_view text) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char ch : text) h = (h ^ ch) * 1099511628211ull;
  return h;
}

std::string hex(double x) { return hexNumber(x); }

std::string bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  char s[24];
  std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(b));
  return s;
}

json hexArray(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(hex(x));
  return a;
}

std::vector<double> fromHex(const json& a) {
  std::vector<double> v;
  for (const json& x : a) v.push_back(fromHexNumber(x.get<std::string>()));
  return v;
}

json toJson(const SpanCalibration& c, const std::string& key) {
  json laws = json::array(), seats = json::array();
  for (const EngagementLaw& law : c.laws)
    laws.push_back({{"stretch_m", hexArray(law.stretch)}, {"tension_N", hexArray(law.tension)},
                    {"energy_J", hexArray(law.energy)}});
  for (const SeatIdentification& s : c.seats)
    seats.push_back(hexArray({s.seat.stiffness, s.seat.torque0, s.seat.spanStiffness, s.linkStiffness, s.linkDamping,
                              s.spanDamping, s.tensionerStiffness}));
  return {{"format", kFormat}, {"key", key}, {"laws", laws}, {"seats", seats}, {"poses", c.poses}, {"posesRejected", c.posesRejected},
          {"residualRms_m", hexArray(c.residualRms)}, {"residualMax_m", hexArray(c.residualMax)},
          {"leverRatioMin", hexArray(c.leverRatioMin)}, {"leverRatioMax", hexArray(c.leverRatioMax)},
          {"cpuSeconds", c.cpuSeconds}};
}

// The calibration in the file, if it is one of this key for this many spans; else why not ("" when
// it is).
std::string readCalibration(const std::string& file, const std::string& key, std::size_t spans, std::size_t tables,
                            SpanCalibration& c) {
  std::ifstream in(utf8Path(file), std::ios::binary);
  if (!in) return "no such file, or not readable";
  try {
    const json j = json::parse(in);
    if (j.at("format") != kFormat) return "format " + j.at("format").dump() + ", not " + std::to_string(kFormat);
    if (j.at("key") != key)
      return "key " + j.at("key").dump() + ", not this drive's \"" + key + "\" (another drive, other parameter " +
             "overrides or other code)";
    if (j.at("laws").size() != spans)
      return std::to_string(j.at("laws").size()) + " laws for " + std::to_string(spans) + " spans";
    for (const json& law : j.at("laws"))
      c.laws.push_back(EngagementLaw{fromHex(law.at("stretch_m")), fromHex(law.at("tension_N")),
                                     fromHex(law.at("energy_J"))});
    for (const json& seat : j.at("seats")) {  // (the order toJson writes)
      const std::vector<double> v = fromHex(seat);
      if (v.size() != 7) return "a seat of " + std::to_string(v.size()) + " numbers, not 7";
      c.seats.push_back(SeatIdentification{GuideSeat{v[0], v[1], v[2]}, v[3], v[4], v[5], v[6]});
      if (c.seats.size() > tables) return std::to_string(c.seats.size()) + " seats for " + std::to_string(tables) +
                                          " pivoting guides";
    }
    c.poses = j.at("poses");
    c.posesRejected = j.at("posesRejected");
    c.residualRms = fromHex(j.at("residualRms_m"));
    c.residualMax = fromHex(j.at("residualMax_m"));
    c.leverRatioMin = fromHex(j.at("leverRatioMin"));
    c.leverRatioMax = fromHex(j.at("leverRatioMax"));
    c.cpuSeconds = j.at("cpuSeconds");
    return "";
  } catch (const json::exception& e) {
    c = SpanCalibration{};  // a damaged file: calibrate afresh
    return std::string("not a calibration (") + e.what() + ")";
  }
}

}  // namespace

std::string hexNumber(double x) {
  char s[40];
  std::snprintf(s, sizeof s, "%a", x);
  return s;
}

double fromHexNumber(const std::string& text) { return std::strtod(text.c_str(), nullptr); }

// Written beside and renamed into place: an instance reading meanwhile sees the old file or the new.
bool writeCacheFile(const std::string& dir, const std::string& file, const std::string& text) {
  std::error_code error;
  std::filesystem::create_directories(utf8Path(dir), error);
  const std::string tmp = file + ".tmp" + std::to_string(reinterpret_cast<std::uintptr_t>(&text));
  {
    std::ofstream out(utf8Path(tmp), std::ios::binary);
    if (!out) return false;
    out << text;
    if (!out) return false;
  }
  std::filesystem::rename(utf8Path(tmp), utf8Path(file), error);  // replaces the file atomically
  if (error) std::filesystem::remove(utf8Path(tmp), error);
  return !error;
}

bool readCacheFile(const std::string& file, int format, nlohmann::json& j) {
  std::ifstream in(utf8Path(file), std::ios::binary);
  if (!in) return false;
  try {
    j = nlohmann::json::parse(in);
    return j.at("format") == format;
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

std::string calibrationKey(const Model& m) {
  const TensionerDesc& t = m.description.tensioner;
  // the FMU's parameters that override the description, by their bits (printf's %a differs
  // between C libraries: a Windows binary would miss the calibration a Linux tool wrote)
  const std::string overrides = bits(t.preload) + " " + bits(t.stiffness) + " " + bits(t.damping) + " " +
                                bits(t.dampingExtension) + " " + bits(t.hydraulic.oilTemperature);
  char key[40];
  std::snprintf(key, sizeof key, "%016llx",
                static_cast<unsigned long long>(fnv1a(m.description.canonicalText + "|" + overrides + "|" +
                                                      std::string(kSourceHash))));
  return key;
}

std::string calibrationCacheDir() {
  const char* own = std::getenv("CHAINDRIVE_CACHE_DIR");
  if (own) return std::string(own) == "none" ? "" : own;
#ifdef _WIN32
  const char* local = std::getenv("LOCALAPPDATA");
  return local ? std::string(local) + "\\chaindrive" : "";
#else
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && *xdg) return std::string(xdg) + "/chaindrive";
  const char* home = std::getenv("HOME");
  return home ? std::string(home) + "/.cache/chaindrive" : "";
#endif
}

namespace {

// calibrateSpanModel, the calibration itself in c.
CalibrationOrigin calibrate(SpanModel& sm, const std::string& file, SpanCalibration& c, std::string* path) {
  const std::string key = calibrationKey(*sm.links);
  if (!file.empty()) {
    const std::string why = readCalibration(file, key, sm.spans.size(), sm.tables.size(), c);
    if (why.empty()) {
      applyCalibration(sm, c);
      for (const std::string& line : describeCalibration(sm, c)) sm.notes.push_back("calibration: " + line);
      sm.notes.push_back("calibration: key " + key + ", from the file " + file);
      if (path) *path = file;
      return CalibrationOrigin::File;
    }
    sm.notes.push_back("calibration: the file " + file + " passed over: " + why);
  }
  const std::string dir = calibrationCacheDir();
  const std::string cacheFile = dir.empty() ? "" : dir + "/span-" + key + ".json";
  const bool cached = !cacheFile.empty() && readCalibration(cacheFile, key, sm.spans.size(), sm.tables.size(), c).empty();
  if (!cached) {
    try {
      c = identifySpanLaws(sm);
    } catch (const std::runtime_error& e) {  // a drive whose statics leave spans slack: no laws
      if (sm.links->description.spanModel.guideSeat != SpanModelDesc::Source::Off)  // (its preload is identified)
        throw DescriptionError({std::string("spanModel.guideSeat: the seat needs the span model's calibration, which "
                                            "found none (") + e.what() + "); allowed here: \"none\""});
      sm.notes.push_back(std::string("calibration: none (") + e.what() + "); the spans keep the joints' stiffness");
      if (path) path->clear();
      return CalibrationOrigin::None;
    }
  }
  applyCalibration(sm, c);
  for (const std::string& line : describeCalibration(sm, c)) sm.notes.push_back("calibration: " + line);
  const bool written = !cached && !cacheFile.empty() && writeCacheFile(dir, cacheFile, toJson(c, key).dump(1) + "\n");
  sm.notes.push_back("calibration: key " + key + (cached ? ", from the cache " + cacheFile
                                                  : written ? ", written to the cache " + cacheFile
                                                            : ", not cached (" + (dir.empty() ? std::string("no cache folder")
                                                                                             : "cannot write " + cacheFile) + ")"));
  if (path) *path = cacheFile;
  return cached ? CalibrationOrigin::Cache : CalibrationOrigin::Identified;
}

}  // namespace

CalibrationOrigin calibrateSpanModel(SpanModel& sm, const std::string& file, std::string* path) {
  SpanCalibration c;
  return calibrate(sm, file, c, path);
}

void calibrateSpanModel(SpanModel& sm, bool* fromCache, std::string* file) {
  SpanCalibration c;
  const CalibrationOrigin origin = calibrate(sm, "", c, file);
  if (fromCache) *fromCache = origin == CalibrationOrigin::Cache;
}

CalibrationOrigin writeCalibrationFile(SpanModel& sm, const std::string& file) {
  SpanCalibration c;
  const CalibrationOrigin origin = calibrate(sm, "", c, nullptr);
  if (origin == CalibrationOrigin::None)
    throw std::runtime_error("the span model of this drive cannot be calibrated: " + sm.notes.back());
  const std::size_t slash = file.find_last_of("/\\");
  const std::string dir = slash == std::string::npos ? "." : file.substr(0, std::max<std::size_t>(slash, 1));
  if (!writeCacheFile(dir, file, toJson(c, calibrationKey(*sm.links)).dump(1) + "\n"))
    throw std::runtime_error("cannot write " + file);
  sm.notes.push_back("calibration: written to " + file);
  return origin;
}

}  // namespace chaindrive::span
