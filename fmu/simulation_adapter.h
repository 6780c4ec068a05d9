// What every model adapter of this project's FMUs shares: a Simulation (src/run/simulation.h) on
// its time grid, its inputs held over a communication step, the values by value reference
// through the adapter's tables, the communication step and the solver's part of an FMU state.
// These public members are what the protocol (instance.h, fmi2_functions.h) calls. A model
// adapter derives from SimulationAdapter<itself, its number of Real inputs> and provides the
// hooks of the ModelAdapter concept (adapter_contract.h), which this class calls through self().
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fmi2Functions.h"
#include "host.h"
#include "run/simulation.h"
#include "state_bytes.h"
#include "utf8_path.h"
#include "variable.h"

namespace chaindrive::fmu {

template <class Derived, int kInputCount>
class SimulationAdapter {
 public:
  static constexpr int kInputs = kInputCount;  // the Real inputs

  /// The model's part of an FMU state (fmu_state.h): the inputs, the solver state on its time
  /// grid (y empty when the model was not prepared) and the integrator's step figures.
  struct Snapshot {
    double stepHint = 0.0;
    long long steps = 0;
    double gridStart = 0.0, gridUnit = 0.0;  // the time grid, to check that a restore is on it
    long long gridIndex = 0;                 // grid point of the state y
    std::array<double, kInputs> inputs{};
    std::vector<double> y;
  };
  /// Bytes of the fixed fields of a serialized Snapshot (without y).
  static constexpr std::size_t kSnapshotFieldBytes = (3 + kInputs) * sizeof(double) + 2 * sizeof(long long);

  explicit SimulationAdapter(Host& host) : host_(host) {}

  bool prepared() const { return prepared_; }
  void requirePreparation() { prepared_ = false; }  // the start time changed

  /// The model and its start state at host.time(), from the parameters and the inputs: the
  /// adapter's parametersValid(), buildModel() (model_; false: a problem, logged) and
  /// startSimulation(). Any failure is logged and leaves the instance unprepared.
  fmi2Status prepare() {
    dropSimulation();
    if (!self().parametersValid()) return fmi2Error;
    try {
      if (self().buildModel()) {
        self().startSimulation();
        prepared_ = true;
        return fmi2OK;
      }
    } catch (const DescriptionError& e) {
      for (const auto& p : e.problems())
        host_.log(fmi2Error, "logStatusError", "%s description: %s", Derived::kModelWord, p.c_str());
    } catch (const std::exception& e) {
      host_.log(fmi2Error, "logStatusError", "initialization failed: %s", e.what());
    }
    dropSimulation();
    return fmi2Error;
  }

  /// Parameters and inputs to their start values (the adapter's resetSettings()), no run.
  void reset() {
    resetRun();
    self().resetSettings();
  }

  // ---- values by value reference (the checks and messages of the fmi2Get*/fmi2Set* functions) ----

  fmi2Status getReal(const fmi2ValueReference vr[], std::size_t n, fmi2Real v[]) {
    for (std::size_t i = 0; i < n; ++i) {
      const Variable* var = variable(vr[i]);
      if (!var || var->type != Type::Real) return badVr("fmi2GetReal", vr[i], "is not a Real variable");
      // parameters and inputs: their values at any time
      if (const double* setting = self().realSetting(vr[i])) {
        v[i] = *setting;
        continue;
      }
      // outputs: of the current state, prepared on demand in initialization mode
      if (!outputsReady()) return notAvailable("fmi2GetReal", *var);
      if (vr[i] == Derived::kSolverTime) v[i] = sim_->time();
      else if (!self().readRealOutput(vr[i], v[i])) return badVr("fmi2GetReal", vr[i], "is not readable");
    }
    return fmi2OK;
  }

  fmi2Status getInteger(const fmi2ValueReference vr[], std::size_t n, fmi2Integer v[]) {
    for (std::size_t i = 0; i < n; ++i) {
      const Variable* var = variable(vr[i]);
      if (!var || var->type != Type::Integer) return badVr("fmi2GetInteger", vr[i], "is not an Integer variable");
      if (const int* p = self().integerParameter(vr[i])) {
        v[i] = *p;
        continue;
      }
      if (!outputsReady()) return notAvailable("fmi2GetInteger", *var);
      int value = 0;
      if (vr[i] == Derived::kSolverSteps) value = static_cast<int>(steps_);
      else if (!self().readIntegerOutput(vr[i], value)) return badVr("fmi2GetInteger", vr[i], "is not readable");
      v[i] = value;
    }
    return fmi2OK;
  }

  fmi2Status getBoolean(const fmi2ValueReference vr[], std::size_t n, fmi2Boolean v[]) {
    for (std::size_t i = 0; i < n; ++i) {
      const bool* p = self().booleanParameter(vr[i]);
      if (!p) return badVr("fmi2GetBoolean", vr[i], "is not a Boolean variable");
      v[i] = *p ? fmi2True : fmi2False;
    }
    return fmi2OK;
  }

  fmi2Status getString(const fmi2ValueReference vr[], std::size_t n, fmi2String v[]) {
    // the returned pointers stay valid until the next call that changes the strings
    for (std::size_t i = 0; i < n; ++i) {
      const std::string* value = self().stringParameter(vr[i]);
      if (!value) return badVr("fmi2GetString", vr[i], "is not a String variable");
      v[i] = value->c_str();
    }
    return fmi2OK;
  }

  fmi2Status setReal(const fmi2ValueReference vr[], std::size_t n, const fmi2Real v[]) {
    for (std::size_t i = 0; i < n; ++i) {
      const Variable* var = variable(vr[i]);
      if (!var || var->type != Type::Real || var->causality == Causality::Output)
        return badVr("fmi2SetReal", vr[i], "is not a settable Real variable");
      if (!std::isfinite(v[i])) {
        host_.log(fmi2Error, "logStatusError", "fmi2SetReal: %s = %g is not a finite value", var->name, v[i]);
        return fmi2Error;
      }
      if (var->causality == Causality::Input) {
        if (!self().inputAcceptable(*var, v[i])) return fmi2Error;  // (logged by the adapter)
        *self().realSetting(vr[i]) = v[i];
        inputChange();
        continue;
      }
      if (parameterChange(*var) != fmi2OK) return fmi2Error;
      double* parameter = self().realSetting(vr[i]);
      if (!parameter) return badVr("fmi2SetReal", vr[i], "is not settable");
      *parameter = v[i];
    }
    return fmi2OK;
  }

  fmi2Status setInteger(const fmi2ValueReference vr[], std::size_t n, const fmi2Integer v[]) {
    for (std::size_t i = 0; i < n; ++i) {
      int* p = self().integerParameter(vr[i]);
      if (!p) return badVr("fmi2SetInteger", vr[i], "is not a settable Integer variable");
      if (parameterChange(*variable(vr[i])) != fmi2OK) return fmi2Error;
      *p = v[i];
    }
    return fmi2OK;
  }

  fmi2Status setBoolean(const fmi2ValueReference vr[], std::size_t n, const fmi2Boolean v[]) {
    for (std::size_t i = 0; i < n; ++i) {
      bool* p = self().booleanParameter(vr[i]);
      if (!p) return badVr("fmi2SetBoolean", vr[i], "is not a settable Boolean variable");
      if (parameterChange(*variable(vr[i])) != fmi2OK) return fmi2Error;
      *p = v[i] != fmi2False;
    }
    return fmi2OK;
  }

  fmi2Status setString(const fmi2ValueReference vr[], std::size_t n, const fmi2String v[]) {
    for (std::size_t i = 0; i < n; ++i) {
      std::string* target = self().stringParameter(vr[i]);
      if (!target) return badVr("fmi2SetString", vr[i], "is not a settable String variable");
      if (!v[i]) {
        host_.log(fmi2Error, "logStatusError", "fmi2SetString: NULL string for value reference %u", vr[i]);
        return fmi2Error;
      }
      if (parameterChange(*variable(vr[i])) != fmi2OK) return fmi2Error;
      *target = v[i];
    }
    return fmi2OK;
  }

  // ---- the communication step ----

  /// The solver from the grid point of cp to the grid point of tEnd: fmi2OK, fmi2Error (logged:
  /// no simulation, beyond the grid) or fmi2Discard (logged: the integration failed; the state
  /// stays at the last successful step). A successful step of a fixed-step method allocates
  /// nothing, does no file I/O and logs nothing.
  fmi2Status doStep(double cp, double tEnd) {
    if (!sim_) {
      host_.log(fmi2Error, "logStatusError", "fmi2DoStep: the FMU is not initialized");
      return fmi2Error;
    }
    if (!sim_->grid().reaches(tEnd)) {
      host_.log(fmi2Error, "logStatusError", "fmi2DoStep: the step ends at %.17g s, beyond the range of the time grid",
                tEnd);
      return fmi2Error;
    }
    self().applyInputs();
    try {
      // Every communication step integrates from the current grid point to the grid point of
      // tEnd (src/run/time_grid.h: tEnd itself when it lies on the grid, else the point before
      // it), restarting the integrator there: a step depends on (state, inputs, grid points)
      // only, so a rollback with fmi2SetFMUstate is exact and every master that means the same
      // communication points gets the same bits, however it rounds them.
      sim_->restart(stepHint_);
      const long long base = sim_->integratorStats().steps;
      sim_->advanceTo(tEnd);
      const IntegratorStats st = sim_->integratorStats();
      steps_ += st.steps - base;
      if (st.lastStep > 0.0) stepHint_ = st.lastStep;
    } catch (const IntegrationError& e) {
      host_.log(fmi2Discard, "logStatusDiscard",
                "fmi2DoStep from t = %.9g s to %.9g s could not be completed: %s; the state is kept at t = %.9g s "
                "(fmi2SetFMUstate can restore an earlier one)",
                cp, tEnd, e.what(), sim_->time());
      return fmi2Discard;
    }
    outputsValid_ = false;
    return fmi2OK;
  }

  // ---- the model's part of an FMU state ----

  Snapshot snapshot() const {
    Snapshot s;
    s.stepHint = stepHint_;
    s.steps = steps_;
    s.inputs = in_;
    if (sim_ && prepared_) {  // (parameters changed after the preparation: it runs again)
      s.y = sim_->state();
      s.gridStart = sim_->grid().start;
      s.gridUnit = sim_->grid().unit;
      s.gridIndex = sim_->gridIndex();
    }
    return s;
  }

  /// fmi2Error (logged) if the snapshot's solver state does not fit this instance (another model
  /// or fidelity: the state sizes differ).
  fmi2Status restore(const Snapshot& s) {
    if (!s.y.empty()) {
      // the solver state must be one of this model and fidelity (their state sizes differ), on
      // this instance's time grid
      const std::size_t size = sim_ ? sim_->state().size() : 0;
      if (s.y.size() != size) {
        host_.log(fmi2Error, "logStatusError", "fmi2SetFMUstate: the state has %zu components, this instance %zu "
                  "(initialize the instance with the same %s and fidelity first)", s.y.size(), size,
                  Derived::kModelWord);
        return fmi2Error;
      }
      const TimeGrid& grid = sim_->grid();
      if (s.gridStart != grid.start || s.gridUnit != grid.unit) {
        host_.log(fmi2Error, "logStatusError", "fmi2SetFMUstate: the state was taken on the time grid %.17g s + k "
                  "%.17g s, this instance runs on %.17g s + k %.17g s (same start time and solver.step needed)",
                  s.gridStart, s.gridUnit, grid.start, grid.unit);
        return fmi2Error;
      }
      sim_->restoreAt(s.gridIndex, s.y);
    } else {
      // A state taken before the model was prepared (instantiated, or initialization mode before
      // any output was asked for) holds no solver state: the solver state reached since is
      // dropped, and fmi2ExitInitializationMode prepares the start state again.
      dropSimulation();
    }
    stepHint_ = s.stepHint;
    steps_ = s.steps;
    in_ = s.inputs;
    outputsValid_ = false;
    return fmi2OK;
  }

  // the fixed fields of a serialized Snapshot, and the first field no instance can have written
  // (nullptr if none); `components` is the size of y
  static void writeFields(const Snapshot& s, std::vector<char>& out) {
    putField(out, s.stepHint);
    for (double v : s.inputs) putField(out, v);
    putField(out, s.gridStart);
    putField(out, s.gridUnit);
    putField(out, s.steps);
    putField(out, s.gridIndex);
  }

  static void readFields(ByteReader& in, Snapshot& s) {
    in.field(s.stepHint);
    for (double& v : s.inputs) in.field(v);
    in.field(s.gridStart);
    in.field(s.gridUnit);
    in.field(s.steps);
    in.field(s.gridIndex);
  }

  static const char* invalidField(const Snapshot& s, std::uint64_t components) {
    if (!std::isfinite(s.stepHint) || s.stepHint < 0.0) return "stepHint";
    if (s.steps < 0) return "steps";
    if (components == 0) return nullptr;
    if (!std::isfinite(s.gridStart) || !std::isfinite(s.gridUnit) || s.gridUnit <= 0.0) return "grid";
    return s.gridIndex < 0 ? "gridIndex" : nullptr;
  }

 protected:
  Derived& self() { return static_cast<Derived&>(*this); }
  const Variable* variable(unsigned vr) const { return static_cast<const Derived&>(*this).findVariable(vr); }

  /// Whether the importer's GUID is `own` (logged if not: the FMU's files are mixed up).
  bool guidMatches(const char* given, const char* own) {
    if (given && std::string(given) == own) return true;
    host_.log(fmi2Error, "logStatusError", "fmi2Instantiate: the GUID %s does not match this FMU's %s (wrong or "
              "mixed-up FMU files)", given ? given : "(NULL)", own);
    return false;
  }

  /// The description in `file` (a parameter); empty: `resource` in the FMU's resources folder, or
  /// the one built into the binary (with a warning) when the importer gave none. Logged.
  template <class Description>
  Description describedBy(const std::string& file, const std::string& resource, const char* what,
                          Description (*load)(const std::string&), Description (*builtIn)()) {
    const std::string& resourceDir = host_.resourceDir();
    const std::string path = !file.empty() ? file : resourceDir.empty() ? "" : resourceDir + "/" + resource;
    if (!file.empty() || (!path.empty() && std::ifstream(utf8Path(path)).good())) {
      Description desc = load(path);
      host_.log(fmi2OK, "logEvents", "%s: %s", what, path.c_str());
      return desc;
    }
    host_.log(fmi2Warning, "logStatusWarning",
              "no resources folder with %s (fmuResourceLocation '%s'); using the default %s built into the binary",
              resource.c_str(), resourceDir.c_str(), what);
    return builtIn();
  }

  /// A number as %g writes it (1e-10 reads as 1e-10, not 0.000000), its exponent without
  /// leading zeros (1e-9, not 1e-09), then the unit ("" for a pure number).
  static std::string quantity(double v, const char* unit = "") {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    std::string s = text;
    const std::size_t e = s.find('e');
    if (e != std::string::npos) {
      const std::size_t digits = e + 2;  // after the exponent's sign
      while (s.size() > digits + 1 && s[digits] == '0') s.erase(digits, 1);
    }
    return *unit ? s + " " + unit : s;
  }

  /// "NAME = VALUE UNIT is outside [LO UNIT, HI UNIT]", the message of a parameter or input out of
  /// its range (quantity()).
  static std::string outsideRange(const char* name, double value, double lo, double hi, const char* unit = "") {
    return std::string(name) + " = " + quantity(value, unit) + " is outside [" + quantity(lo, unit) + ", " +
           quantity(hi, unit) + "]";
  }

  /// A problem (outsideRange) unless lo <= value <= hi; a NaN is outside every range.
  static void checkRange(std::vector<std::string>& problems, const char* name, double value, double lo, double hi,
                         const char* unit = "") {
    if (!(value >= lo && value <= hi)) problems.push_back(outsideRange(name, value, lo, hi, unit));
  }

  /// A choice parameter's name parsed once (choice.h); an unknown name is a problem naming the
  /// parameter and the allowed names.
  template <class E>
  static void parseChoiceParameter(const char* parameter, const std::string& name, E& value,
                                   std::vector<std::string>& problems) {
    if (auto parsed = choiceOf<E>(name)) value = *parsed;
    else problems.push_back(std::string(parameter) + ": " + unknownChoiceText(name, choiceNames<E>()));
  }
  /// The same for a parameter whose empty name leaves the choice to the description (nullopt), or
  /// to what `emptyMeans` names.
  template <class E>
  static void parseChoiceParameter(const char* parameter, const std::string& name, std::optional<E>& value,
                                   std::vector<std::string>& problems, const char* emptyMeans = nullptr) {
    value.reset();
    if (name.empty()) return;
    if (auto parsed = choiceOf<E>(name)) value = *parsed;
    else problems.push_back(std::string(parameter) + ": " + unknownChoiceText(name, choiceNames<E>()) + " (or empty: " +
                            (emptyMeans ? std::string(emptyMeans) : "the " + std::string(Derived::kModelWord) + "'s") + ")");
  }

  /// The combination rules of a run's choices (run/simulation.h) for `opt` on model_, each one
  /// broken logged under its parameter's name; false if one was.
  bool choicesCombine(const SimulationOptions& opt) {
    static constexpr const char* kParameters[] = {"fidelity", "contact.method", "chain.jointModel", "solver.method",
                                                  "rigid pins"};
    const auto problems = combinationProblems(*model_, runChoices(*model_, opt));
    for (const auto& p : problems)
      host_.log(fmi2Error, "logStatusError", "%s: %s", kParameters[static_cast<int>(p.choice)], p.text.c_str());
    return problems.empty();
  }

  /// No model, no simulation: prepare() runs again.
  void dropSimulation() {
    sim_.reset();
    held_ = nullptr;
    model_.reset();
    prepared_ = false;
    outputsValid_ = false;
  }

  /// The counters of a new run (reset).
  void resetRun() {
    dropSimulation();
    steps_ = 0;
    stepHint_ = 0.0;
  }

  /// The simulation of model_ with `opt`, its inputs held at the values set through the FMI.
  void makeSimulation(const SimulationOptions& opt) {
    auto held = std::make_unique<HeldInputs>(*model_);
    held_ = held.get();
    sim_ = std::make_unique<Simulation>(model_, opt, std::move(held));
    self().applyInputs();
  }

  /// After the simulation started: the fidelity and the time grid logged, the run's counters
  /// started over.
  void runStarted() {
    host_.log(fmi2OK, "logEvents", "fidelity: %s (%zu states)", choiceName(sim_->fidelity()), sim_->state().size());
    const TimeGrid& grid = sim_->grid();
    host_.log(fmi2OK, "logEvents",
              "time grid: t_k = %.17g s + k %.17g s; a communication point within %.3g s of a grid point is that "
              "point, one farther off is integrated to the grid point before it (output solver.time)",
              grid.start, grid.unit, kSnapFraction * grid.unit);
    steps_ = 0;
    stepHint_ = 0.0;
    host_.runStarted();
  }

  bool outputsReady() {
    if (!prepared_) {
      if (host_.state() != kInitializationMode) return false;
      if (self().prepare() > fmi2Warning) return false;
    }
    if (!outputsValid_) {
      self().applyInputs();
      self().evaluateOutputs();
      outputsValid_ = true;
    }
    return true;
  }

  fmi2Status badVr(const char* function, fmi2ValueReference vr, const char* what) {
    host_.log(fmi2Error, "logStatusError", "%s: value reference %u %s", function, vr, what);
    return fmi2Error;
  }

  fmi2Status notAvailable(const char* function, const Variable& v) {
    host_.log(fmi2Error, "logStatusError", "%s: '%s' is not available before the initialization succeeded", function,
              v.name);
    return fmi2Error;
  }

  fmi2Status parameterChange(const Variable& v) {  // only before initialization ends
    if (host_.initializing()) {
      prepared_ = false;
      return fmi2OK;
    }
    host_.log(fmi2Error, "logStatusError", "parameter '%s' is fixed: it can only be set before the initialization ends",
              v.name);
    return fmi2Error;
  }

  void inputChange() {
    // the start state depends on the inputs at the start time
    if (host_.initializing()) prepared_ = false;
    outputsValid_ = false;  // outputs such as the driving torque depend directly on the speed input
  }

  Host& host_;
  std::array<double, kInputs> in_{};  // the Real inputs, in the order of the adapter's input indices
  long long steps_ = 0;               // integrator steps since the start (output solver.steps)
  double stepHint_ = 0.0;             // the first step adaptive methods try in the next communication step
  std::shared_ptr<const Model> model_;
  std::unique_ptr<Simulation> sim_;
  HeldInputs* held_ = nullptr;        // owned by sim_
  bool prepared_ = false;
  bool outputsValid_ = false;
};

}  // namespace chaindrive::fmu
