// The rollback check: ChainDrive promises that a communication step repeated from a restored FMU
// state gives the same outputs, bit for bit (docs/fmu.md, tests/python/fmu/test_fmu.py). Here the state is
// taken at random points of a random sequence, also before the end of the initialization.
#include <cstdio>
#include <cstring>

#include "call_sequence_internal.h"

namespace chaindrive::fuzz::detail {

// The outputs of the model description, in its order.
struct Outputs {
  std::vector<fmi2ValueReference> realVrs, integerVrs;
  std::vector<fmi2Real> reals;
  std::vector<fmi2Integer> integers;
};

namespace {

Outputs outputVariables(const std::vector<fmu::Variable>& variables) {
  Outputs o;
  for (const fmu::Variable& v : variables) {
    if (v.causality != fmu::Causality::Output) continue;
    if (v.type == fmu::Type::Real) o.realVrs.push_back(v.vr);
    else o.integerVrs.push_back(v.vr);
  }
  o.reals.resize(o.realVrs.size());
  o.integers.resize(o.integerVrs.size());
  return o;
}

// The first output that differs between two readings ("" if none); doubles are compared as bits.
std::string firstDifference(const Outputs& a, const Outputs& b) {
  for (std::size_t i = 0; i < a.reals.size(); ++i) {
    if (std::memcmp(&a.reals[i], &b.reals[i], sizeof(double)) == 0) continue;
    char text[160];
    std::snprintf(text, sizeof text, "value reference %u: %.17g, then %.17g", a.realVrs[i], a.reals[i], b.reals[i]);
    return text;
  }
  for (std::size_t i = 0; i < a.integers.size(); ++i)
    if (a.integers[i] != b.integers[i])
      return "value reference " + std::to_string(a.integerVrs[i]) + ": " + std::to_string(a.integers[i]) + ", then " +
             std::to_string(b.integers[i]);
  return "";
}

}  // namespace

bool CallSequence::readOutputs(Outputs& o) {
  const fmi2Status r = invoke("fmi2GetReal", [&] {
    return fmi2GetReal(instance_, o.realVrs.data(), o.realVrs.size(), o.reals.data());
  });
  const fmi2Status i = invoke("fmi2GetInteger", [&] {
    return fmi2GetInteger(instance_, o.integerVrs.data(), o.integerVrs.size(), o.integers.data());
  });
  return r == fmi2OK && i == fmi2OK;
}

// Takes a state (in initialization mode or after a step), steps, restores, steps again with the
// same arguments and compares the outputs. Costs two short steps; not for the slow methods, and
// in initialization mode not where the initialization solves the start state (it runs twice).
void CallSequence::checkRollback() {
  const Plan plan = static_cast<Plan>(stats_.plan);
  const bool beforeStart = phase_ == Phase::Initializing;
  if (plan == Plan::OtherMethod || stepsLeft_ < 2 || (beforeStart && plan == Plan::FullInit)) return;
  if (!beforeStart && phase_ != Phase::Stepping) return;
  fmi2FMUstate state = nullptr;
  if (invoke("fmi2GetFMUstate", [&] { return fmi2GetFMUstate(instance_, &state); }) != fmi2OK) return;
  const std::vector<fmu::Variable>& variables = springDamper_ ? paths_.springDamperVariables : fmu::defaultVariables();
  Outputs first = outputVariables(variables), second = outputVariables(variables);
  const double stepSize = rng_.logUniform(shortestStep_, longestStep_);
  double communicationPoint = 0.0;
  const bool firstDone = stepFrom(beforeStart, stepSize, communicationPoint) && readOutputs(first);
  if (firstDone) {
    const std::string taken = beforeStart ? " (state taken in initialization mode)" : " (state taken after a step)";
    if (invoke("fmi2SetFMUstate", [&] { return fmi2SetFMUstate(instance_, state); }) != fmi2OK)
      violation("fmi2SetFMUstate refused a state of fmi2GetFMUstate" + taken);
    double repeatedPoint = 0.0;
    if (!stepFrom(beforeStart, stepSize, repeatedPoint) || !readOutputs(second))
      violation("a step repeated from a restored state failed where the first one succeeded" + taken);
    else if (repeatedPoint != communicationPoint)
      violation("after fmi2SetFMUstate the FMU is at another time than when the state was taken" + taken);
    else if (const std::string d = firstDifference(first, second); !d.empty())
      violation("a step repeated from a restored state gave other outputs: " + d + taken);
  }
  if (invoke("fmi2FreeFMUstate", [&] { return fmi2FreeFMUstate(instance_, &state); }) != fmi2OK || state)
    violation("fmi2FreeFMUstate of a state the FMU made failed");
}

// Ends the initialization if asked to, then makes one good communication step; false if the
// FMU did not complete both (the step may fail numerically: then there is nothing to compare).
bool CallSequence::stepFrom(bool endInitialization, double stepSize, double& communicationPoint) {
  if (endInitialization) {
    exitInitialization();
    if (phase_ != Phase::Stepping) return false;
  }
  communicationPoint = currentTime();
  --stepsLeft_;
  const fmi2Status s = invoke("fmi2DoStep", [&] { return fmi2DoStep(instance_, communicationPoint, stepSize, fmi2False); });
  if (s == fmi2OK) {
    ++stats_.completedSteps;
    time_ = communicationPoint + stepSize;
  } else if (s == fmi2Discard) {
    phase_ = Phase::StepFailed;
  }
  return s == fmi2OK;
}

}  // namespace chaindrive::fuzz::detail
