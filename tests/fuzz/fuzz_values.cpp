#include "fuzz_values.h"

#include <cfloat>
#include <climits>
#include <cmath>
#include <iterator>
#include <limits>

namespace chaindrive::fuzz {

namespace {

using namespace fmu;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// numbers a careless importer or a broken signal produces
constexpr double kExtremeReals[] = {kNaN, kInf, -kInf, 1e300, -1e300, DBL_MAX, -DBL_MAX, 4.9e-324, -0.0, 0.0, -1.0, 1e6};

// value references that name no variable (gaps between the blocks, beyond the end, the extremes)
constexpr unsigned kInvalidValueReferences[] = {0u, 4u, 9u, 35u, 42u, 99u, 114u, 120u, 1000u, 0xFFFFFFFFu};

const std::string kLongString(3000, 'x');
// a string that crashes a logger which uses it as a printf format
constexpr const char* kFormatString = "%s%n%s%d%%";

const std::vector<std::string> kIntegrators = {"fixed-verlet", "fixed-newmark", "arkode-erk", "arkode-erk-fixed",
                                               "cvode-bdf-klu", "cvode-bdf-band"};
const std::vector<std::string> kContactMethods = {"", "compliant", "time-stepping", "event-driven"};
const std::vector<std::string> kJointModels = {"", "journal-bearing", "ideal"};
const std::vector<std::string> kFidelities = {"link", "span"};
const std::vector<std::string> kBadNames = {"no-such-method", "FIXED-VERLET", "fixed-verlet ", " ", "rigid", "welded",
                                            "-1", kFormatString, kLongString};

}  // namespace

Assignment realAssignment(unsigned vr, double value) {
  Assignment a;
  a.vr = vr;
  a.type = Type::Real;
  a.real = value;
  return a;
}

Assignment integerAssignment(unsigned vr, fmi2Integer value) {
  Assignment a;
  a.vr = vr;
  a.type = Type::Integer;
  a.integer = value;
  return a;
}

Assignment booleanAssignment(unsigned vr, bool value) {
  Assignment a;
  a.vr = vr;
  a.type = Type::Boolean;
  a.boolean = value ? fmi2True : fmi2False;
  return a;
}

Assignment stringAssignment(unsigned vr, std::string value) {
  Assignment a;
  a.vr = vr;
  a.type = Type::String;
  a.text = std::move(value);
  return a;
}

unsigned anyValueReference(Rng& rng) {
  if (rng.chance(0.1)) return rng.pick(kInvalidValueReferences);
  return rng.pick(defaultVariables()).vr;
}

unsigned valueReferenceFor(Rng& rng, Type type) {
  if (rng.chance(0.15)) return anyValueReference(rng);
  std::vector<unsigned> matching;
  for (const Variable& v : defaultVariables())
    if (v.type == type) matching.push_back(v.vr);
  return rng.pick(matching);
}

double goodReal(Rng& rng, unsigned vr) {
  switch (vr) {
    case kCrankshaftW: return rng.uniform(0.0, 700.0);  // (negative speeds are refused)
    case kCamshaftIntakeTau:
    case kCamshaftExhaustTau: return rng.uniform(-60.0, 60.0);
    case kSolverTolerance: return rng.logUniform(1e-7, 1e-3);
    // short fixed steps keep a communication step cheap; 0.1..1 ms are accepted but unstable:
    // the run must end in a detected blow-up (fmi2Discard), never in garbage
    case kSolverStep: return rng.chance(0.85) ? rng.uniform(1e-6, 3e-6) : rng.logUniform(1e-4, 1e-3);
    case kSolverNewmarkGamma: return rng.uniform(0.5, 1.0);
    case kTensionerPreload: return rng.chance(0.3) ? -1.0 : rng.uniform(0.0, 300.0);
    case kTensionerStiffness: return rng.chance(0.3) ? -1.0 : rng.logUniform(1e3, 1e6);
    case kTensionerDamping:
    case kTensionerDampingExtension: return rng.chance(0.3) ? -1.0 : rng.logUniform(1.0, 1e4);
    case kTensionerSupplyPressure: return rng.uniform(0.0, 8e5);        // gauge, 0..8 bar
    case kTensionerOilTemperature: return rng.uniform(293.15, 423.15);  // the oil law's range
    default: return rng.uniform(-1.0, 1.0);  // outputs, not real variables: the setter refuses
  }
}

double badReal(Rng& rng, unsigned vr) {
  switch (vr) {
    case kCrankshaftW: return rng.pick({-1.0, -1e9, 1e9, kNaN, -kInf});
    case kSolverStep: return rng.pick({0.0, -1.0, 1e-12, 0.5, 1e300, kNaN, kInf});
    case kSolverTolerance: return rng.pick({0.0, 0.5, -1e-5, 1e-13, kNaN, -kInf});
    case kSolverNewmarkGamma: return rng.pick({0.0, 0.4999, 1.0001, -0.5, kNaN, kInf});
    case kTensionerPreload: return rng.pick({1e6, 1e300, kNaN, kInf});
    case kTensionerStiffness: return rng.pick({1e10, 1e300, kNaN, -kInf});
    case kTensionerDamping:
    case kTensionerDampingExtension: return rng.pick({1e8, DBL_MAX, kNaN, kInf});
    case kTensionerSupplyPressure: return rng.pick({-2e5, 1e9, kNaN, -kInf});
    case kTensionerOilTemperature: return rng.pick({0.0, 200.0, 500.0, kNaN, kInf});
    default: return rng.pick(kExtremeReals);
  }
}

fmi2Integer goodInteger(Rng& rng, unsigned vr) {
  if (vr == kLinkIndex) return rng.chance(0.3) ? -1 : static_cast<fmi2Integer>(rng.below(120));
  // (one thread: the fuzz runs two processes side by side on two cores under the sanitizers, where
  // spinning threads would wait on each other; several threads' runs and rollback are tested apart)
  if (vr == kSolverThreads) return 1;
  return static_cast<fmi2Integer>(rng.below(200)) - 100;
}

fmi2Integer badInteger(Rng& rng) { return rng.pick({-2, 120, 1000, INT_MIN, INT_MAX}); }

std::optional<std::string> goodString(Rng& rng, unsigned vr, const FuzzPaths& paths) {
  switch (vr) {
    case kDriveFile: return rng.chance(0.5) ? std::string() : paths.driveFile;
    case kSolverMethod: return rng.pick(kIntegrators);
    case kContactMethod: return rng.pick(kContactMethods);
    case kChainJointModel: return rng.pick(kJointModels);
    case kFidelity: return rng.pick(kFidelities);
    default: return rng.pick(kBadNames);  // not a string variable: the setter refuses
  }
}

std::optional<std::string> badString(Rng& rng, unsigned vr, const FuzzPaths& paths) {
  if (rng.chance(0.15)) return std::nullopt;
  if (vr == kDriveFile) {
    const std::string files[] = {"/nonexistent/drive.json", "/tmp", paths.notADriveFile, paths.resourceDir,
                                 kFormatString, kLongString};
    return rng.pick(files);
  }
  return rng.pick(kBadNames);
}

ResourceLocation resourceLocation(Rng& rng, const std::string& resourceDir) {
  switch (rng.below(30)) {  // (a quarter of them not the resources folder: refused)
    case 0: return {std::nullopt, false};
    case 1: return {std::string(), false};
    case 2: return {std::string("file:///nonexistent"), false};
    case 3: return {std::string("file:////tmp"), false};
    case 4: return {"file:////" + resourceDir + "/", true};
    case 5: return {"file://localhost" + resourceDir, true};
    case 6: return {std::string("http://example.com/resources"), false};
    case 7: return {std::string("file:///tmp/%4") + kFormatString + "%zz%", false};
    case 8: return {"file://" + kLongString, false};
    default: return {"file://" + resourceDir, true};
  }
}

std::vector<Assignment> poisonAssignments(Rng& rng, const FuzzPaths& paths) {
  switch (rng.below(11)) {
    case 0: return {stringAssignment(kSolverMethod, rng.pick(kBadNames))};
    case 1: return {stringAssignment(kContactMethod, "rigid")};
    case 2: return {stringAssignment(kChainJointModel, kFormatString)};
    case 3: return {realAssignment(kSolverStep, rng.pick({0.0, -2.5e-6, 1e-12, 0.01}))};
    case 4: return {realAssignment(kSolverTolerance, rng.pick({0.0, 1.0, -1e-5}))};
    case 5: return {realAssignment(rng.pick({kTensionerPreload, kTensionerStiffness, kTensionerDamping,
                                            kTensionerDampingExtension, kTensionerOilTemperature}), 1e300)};
    case 6: return {stringAssignment(kDriveFile, rng.pick({std::string("/nonexistent/drive.json"),
                                                          paths.notADriveFile, std::string("/tmp")}))};
    // rejected after the assembly (cheap) but before the start-state solve
    case 7:
      return {rng.chance(0.5) ? integerAssignment(kLinkIndex, rng.pick({-2, 120, INT_MAX}))
                              : integerAssignment(kSolverThreads, rng.pick({0, 17, INT_MIN}))};
    case 8: return {stringAssignment(kChainJointModel, "ideal"), stringAssignment(kContactMethod, "compliant")};
    case 9:  // an unknown fidelity, or the span fidelity with what it does not take
      switch (rng.below(3)) {
        case 0: return {stringAssignment(kFidelity, "span"), stringAssignment(kContactMethod, "time-stepping")};
        case 1: return {stringAssignment(kFidelity, "span"), stringAssignment(kChainJointModel, "ideal")};
        default:
          return {stringAssignment(kFidelity, rng.pick({std::string("beam"), std::string("Span"), std::string(),
                                                        std::string(kFormatString)}))};
      }
    default: return {stringAssignment(kSolverMethod, "")};
  }
}

namespace {

struct MethodCombination {
  const char* integrator;
  const char* contact;  // "": the drive's (compliant)
  const char* joints;   // "": the drive's (journal-bearing)
  int steps;            // communication steps of 10 us
  bool springDamper = false;  // on the FMU of the drive with the spring-damper tensioner law (event-driven
                              // does not integrate the default drive's hydraulic chamber)
};

// Event-driven integration with ideal joints runs into its event storm in the second 10 us
// (docs/limits.md): some 15 s under the sanitizers, so it gets one step.
constexpr MethodCombination kMethodCombinations[] = {
    {"arkode-erk", "compliant", "journal-bearing", 2},    {"arkode-erk-fixed", "", "", 2},
    {"cvode-bdf-klu", "", "", 2},                         {"cvode-bdf-band", "", "", 2},
    {"fixed-newmark", "", "", 2},
    {"fixed-verlet", "time-stepping", "", 2},             {"fixed-verlet", "time-stepping", "ideal", 2},
    {"arkode-erk", "event-driven", "journal-bearing", 2, true}, {"arkode-erk", "event-driven", "ideal", 1, true},
};

}  // namespace

std::size_t methodCombinationCount() { return std::size(kMethodCombinations); }

std::string methodCombinationName(std::size_t index) {
  const MethodCombination& c = kMethodCombinations[index];
  return std::string(c.integrator) + "/" + (*c.contact ? c.contact : "compliant") + "/" +
         (*c.joints ? c.joints : "journal-bearing");
}

int methodCombinationSteps(std::size_t index) { return kMethodCombinations[index].steps; }

std::vector<Assignment> spanAssignments(Rng& rng) {
  return {stringAssignment(kFidelity, "span"), stringAssignment(kSolverMethod, rng.pick(kIntegrators)),
          stringAssignment(kContactMethod, rng.pick({"", "compliant"})),
          stringAssignment(kChainJointModel, rng.pick({"", "journal-bearing"}))};
}

std::vector<Assignment> methodAssignments(std::size_t index) {
  const MethodCombination& c = kMethodCombinations[index];
  return {stringAssignment(kSolverMethod, c.integrator), stringAssignment(kContactMethod, c.contact),
          stringAssignment(kChainJointModel, c.joints), stringAssignment(kFidelity, "link"),
          booleanAssignment(kSolverPreload, false)};
}

bool methodCombinationSpringDamper(std::size_t index) { return kMethodCombinations[index].springDamper; }

}  // namespace chaindrive::fuzz
