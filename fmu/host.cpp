#include "host.h"

#include <algorithm>
#include <cmath>
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

// ---- the state machine's transitions ----

bool Host::setExperiment(double startTime, bool stopTimeDefined, double stopTime) {
  if (!std::isfinite(startTime)) {
    log(fmi2Error, "logStatusError", "fmi2SetupExperiment: startTime %g is not finite", startTime);
    return false;
  }
  if (stopTimeDefined && !(stopTime >= startTime)) {
    log(fmi2Error, "logStatusError", "fmi2SetupExperiment: stopTime %g is before startTime %g", stopTime, startTime);
    return false;
  }
  startTime_ = time_ = lastSuccessfulTime_ = startTime;
  stopTimeDefined_ = stopTimeDefined;
  stopTime_ = stopTime;
  return true;
}

fmi2Status Host::enterInitializationMode() {
  state_ = kInitializationMode;
  return fmi2OK;
}

// The step: positive, from the FMU's time (within a relative drift), not past the stop time.
bool Host::stepAcceptable(double cp, double h, double& tEnd) {
  if (!std::isfinite(h) || h <= 0.0) {
    log(fmi2Error, "logStatusError", "fmi2DoStep: communicationStepSize %g must be positive and finite", h);
    return false;
  }
  const double tol = 1e-9 * std::max(1.0, std::fabs(time_));
  if (!std::isfinite(cp) || std::fabs(cp - time_) > tol) {
    log(fmi2Error, "logStatusError", "fmi2DoStep: currentCommunicationPoint %.17g does not match the FMU time %.17g", cp,
        time_);
    return false;
  }
  tEnd = cp + h;
  if (stopTimeDefined_ && tEnd > stopTime_ * (1.0 + 1e-12) + 1e-12) {
    log(fmi2Error, "logStatusError", "fmi2DoStep: the step ends at %.17g, after the stop time %.17g", tEnd, stopTime_);
    return false;
  }
  return true;
}

void Host::stepCompleted(double tEnd) {
  time_ = tEnd;
  lastSuccessfulTime_ = tEnd;
}

void Host::stepDiscarded() {
  lastSuccessfulTime_ = time_;
  state_ = kStepFailed;
}

fmi2Status Host::terminate() {
  state_ = kTerminated;
  return fmi2OK;
}

void Host::resetProtocol() {
  time_ = startTime_ = stopTime_ = lastSuccessfulTime_ = 0.0;
  stopTimeDefined_ = false;
  state_ = kInstantiated;
}

// ---- status queries and FMU states ----

fmi2Status Host::getRealStatus(fmi2StatusKind kind, fmi2Real* value) {
  if (kind == fmi2LastSuccessfulTime) {
    *value = lastSuccessfulTime_;
    return fmi2OK;
  }
  log(fmi2Error, "logStatusError", "fmi2GetRealStatus: status kind %d is not provided", static_cast<int>(kind));
  return fmi2Discard;
}

fmi2Status Host::getStatus(fmi2StatusKind kind, fmi2Status* value) {
  if (kind == fmi2DoStepStatus) {
    *value = state_ == kStepFailed ? fmi2Discard : fmi2OK;
    return fmi2OK;
  }
  log(fmi2Error, "logStatusError", "fmi2GetStatus: status kind %d is not provided", static_cast<int>(kind));
  return fmi2Discard;
}

void Host::restoreProtocol(const ProtocolSnapshot& s) {
  // a state taken after a failed step or in the error state is restored ready for the next step
  state_ = s.state == kStepFailed || s.state == kError ? kStepComplete : s.state;
  time_ = s.time;
  lastSuccessfulTime_ = s.lastSuccessfulTime;
  log(fmi2OK, "logEvents", "state restored at t = %.9g s", time_);
}

}  // namespace chaindrive::fmu
