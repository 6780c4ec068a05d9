#include "host.h"

#include <cstdarg>
#include <cstdio>
#include <cstring>

namespace chaindrive::fmu {

namespace {

const char* stateName(unsigned s) {
  switch (s) {
    case kInstantiated: return "instantiated";
    case kInitializationMode: return "initialization mode";
    case kStepComplete: return "step complete";
    case kStepFailed: return "step failed";
    case kTerminated: return "terminated";
    case kError: return "error";
    default: return "unknown";
  }
}

constexpr const char* kKnownCategories[] = {"logEvents", "logStatusWarning", "logStatusDiscard",
                                            "logStatusError", "logStatusFatal", "logAll"};

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string percentDecoded(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && hexValue(s[i + 1]) >= 0 && hexValue(s[i + 2]) >= 0) {
      out.push_back(static_cast<char>(16 * hexValue(s[i + 1]) + hexValue(s[i + 2])));
      i += 2;
    } else {
      out.push_back(s[i]);
    }
  }
  return out;
}

bool isDriveLetter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

/// The Windows path of a file URI's path (after the authority): /C:/dir (or the old /C|/dir)
/// is C:/dir; //server/share/dir (file:////server/share) stays a UNC path.
std::string windowsPath(std::string path) {
  if (path.size() >= 3 && path[0] == '/' && isDriveLetter(path[1]) && (path[2] == ':' || path[2] == '|')) {
    path = path.substr(1);
    path[1] = ':';
  }
  return path;
}

}  // namespace

std::string resourceDirectory(const char* location, PathStyle style) {
  if (!location || !*location) return "";
  std::string s(location);
  const std::string scheme = "file:";
  if (s.compare(0, scheme.size(), scheme) != 0) return "";
  s = s.substr(scheme.size());
  // file:///dir, file:////dir, file://localhost/dir, file:/dir
  if (s.compare(0, 11, "//localhost") == 0) s = s.substr(11);
  std::string out;
  if (style == PathStyle::Windows) {
    // an empty authority (file:///C:/dir, file:////server/share) dropped; file://server/share
    // keeps its host: both are the UNC path //server/share
    if (s.compare(0, 3, "///") == 0) s = s.substr(2);
    out = windowsPath(percentDecoded(s));
  } else {
    while (s.size() > 1 && s[0] == '/' && s[1] == '/') s = s.substr(1);
    out = percentDecoded(s);
  }
  const std::size_t root = style == PathStyle::Windows && out.size() >= 2 && out[1] == ':' ? 3 : 1;
  while (out.size() > root && out.back() == '/') out.pop_back();
  return out;
}

Host::Host(const char* instanceName, const fmi2CallbackFunctions* callbacks, const char* resourceLocation,
           bool loggingOn)
    : name_(instanceName ? instanceName : ""), callbacks_(*callbacks),
      resourceDir_(resourceDirectory(resourceLocation, kNativePathStyle)), loggingOn_(loggingOn) {}

void Host::log(fmi2Status status, const char* category, const char* fmt, ...) {
  // errors and warnings always; other messages when logging is on and their category enabled
  if (!callbacks_.logger) return;
  const bool always = status >= fmi2Warning;
  if (!always) {
    if (!loggingOn_) return;
    if (!categories_.empty()) {
      bool on = false;
      for (const auto& c : categories_) on = on || c == category || c == "logAll";
      if (!on) return;
    }
  }
  // the message, formatted
  char buf[2048];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  // the message is passed as the format string with '%' doubled, so that importers that print it
  // without formatting show it as well as those that format it
  char escaped[4096];
  std::size_t k = 0;
  for (const char* p = buf; *p && k + 2 < sizeof escaped; ++p) {
    if (*p == '%') escaped[k++] = '%';
    escaped[k++] = *p;
  }
  escaped[k] = '\0';
  callbacks_.logger(callbacks_.componentEnvironment, name_.c_str(), status, category, escaped);
}

fmi2Status Host::setDebugLogging(bool on, std::size_t n, const fmi2String categories[]) {
  loggingOn_ = on;
  categories_.clear();
  fmi2Status st = fmi2OK;
  for (std::size_t i = 0; i < n; ++i) {
    if (!categories || !categories[i]) continue;
    bool known = false;
    for (const char* k : kKnownCategories) known = known || std::strcmp(k, categories[i]) == 0;
    if (!known) {
      log(fmi2Warning, "logStatusWarning", "fmi2SetDebugLogging: unknown log category '%s'", categories[i]);
      st = fmi2Warning;
      continue;
    }
    categories_.emplace_back(categories[i]);
  }
  return st;
}

bool Host::allowed(const char* function, unsigned allowedStates) {
  if (state_ & allowedStates) return true;
  log(fmi2Error, "logStatusError", "%s: not allowed in state '%s'", function, stateName(state_));
  return false;
}

}  // namespace chaindrive::fmu
