#include "interface/drive_interface.h"

#include <cstdint>
#include <cstdio>
#include <string_view>

namespace chaindrive {

namespace {

// ---- the drive's own variables (every drive's FMU has them, with these value references) ----

// Which drives have a variable of the drive as a whole.
enum class When { Always, Tensioner, Hydraulic, TightSpan, SlackSpan };

struct DriveVariable {
  const char* name;
  unsigned vr;
  VarType type;
  VarCausality causality;
  Binding binding;
  When when;
  const char* declaredType;  // or the unit, after a '|': "|Pa|bar" is unit Pa, display unit bar
  const char* start;
  const char* range;  // "min|max" ("" none)
  const char* description;
};

constexpr VarType R = VarType::Real, I = VarType::Integer, B = VarType::Boolean, S = VarType::String;
constexpr VarCausality In = VarCausality::Input, Out = VarCausality::Output, Par = VarCausality::Parameter;

// clang-format off
// (the outputs and parameters of the drive as a whole, in the model description's order; the
// outputs after the elements' ones, the parameters after every output)
constexpr DriveVariable kDriveOutputs[] = {
  {"tensioner.F", 18, R, Out, Binding::TensionerForce, When::Tensioner, "Force", "", "",
   "tensioner plunger force on the tension guide; span fidelity: the same"},
  {"tensioner.s", 19, R, Out, Binding::TensionerStroke, When::Tensioner, "Length", "", "",
   "tensioner stroke: plunger extension from the drawn pose; span fidelity: the same"},
  {"tensioner.v", 20, R, Out, Binding::TensionerRate, When::Tensioner, "Velocity", "", "",
   "tensioner plunger velocity, positive when extending; span fidelity: the same"},
  {"tensioner.chamberPressure", 42, R, Out, Binding::ChamberPressure, When::Hydraulic, "|Pa|bar", "", "",
   "gauge pressure in the hydraulic tensioner's chamber; span fidelity: the same"},
  {"tensioner.checkValveFlow", 43, R, Out, Binding::CheckValveFlow, When::Hydraulic, "|m3/s|l/min", "", "",
   "oil flow into the hydraulic tensioner's chamber through its check valve (never negative); span fidelity: the "
   "same"},
  {"tensioner.leakFlow", 44, R, Out, Binding::LeakFlow, When::Hydraulic, "|m3/s|l/min", "", "",
   "oil flow out of the hydraulic tensioner's chamber through the plunger's clearance (leak-down); span fidelity: "
   "the same"},
  {"chain.Ftight", 21, R, Out, Binding::TightSpanForce, When::TightSpan, "Force", "", "",
   "chain force in the tight span (the drive's measurement.tightSpan, at the middle of its free part); span "
   "fidelity: the tension of the span at the probe"},
  {"chain.Fslack", 22, R, Out, Binding::SlackSpanForce, When::SlackSpan, "Force", "", "",
   "chain force in the slack span (the drive's measurement.slackSpan, at the middle of its free part); span "
   "fidelity: the tension of the span at the probe"},
  {"link.F", 23, R, Out, Binding::LinkTension, When::Always, "Force", "", "",
   "tensile force of the monitored link; span fidelity: the chain tension where the monitored link is on the "
   "nominal path (moved with the chain)"},
  {"link.Fn", 24, R, Out, Binding::LinkNormalForce, When::Always, "Force", "", "",
   "sum of the contact normal forces on the monitored link; span fidelity: 0 (not computed)"},
  {"link.FnSprocket", 25, R, Out, Binding::LinkSprocketForce, When::Always, "Force", "", "",
   "contact normal force of the monitored link with sprockets; span fidelity: 0 (not computed)"},
  {"link.FnGuide", 26, R, Out, Binding::LinkGuideForce, When::Always, "Force", "", "",
   "contact normal force of the monitored link with guides; span fidelity: 0 (not computed)"},
  {"link.x", 27, R, Out, Binding::LinkX, When::Always, "Length", "", "",
   "position of the monitored link's centre, x; span fidelity: its position on the nominal path (moved with the "
   "chain)"},
  {"link.y", 28, R, Out, Binding::LinkY, When::Always, "Length", "", "",
   "position of the monitored link's centre, y; span fidelity: its position on the nominal path (moved with the "
   "chain)"},
  {"energy.kinetic", 29, R, Out, Binding::EnergyKinetic, When::Always, "Energy", "", "",
   "kinetic energy of chain and free bodies; span fidelity: of the free rotors with the chain lumped on them"},
  {"energy.elastic", 30, R, Out, Binding::EnergyElastic, When::Always, "Energy", "", "",
   "elastic energy of joints, contacts and the tensioner spring; span fidelity: of the span springs and the "
   "tensioner spring"},
  {"energy.dissipated", 31, R, Out, Binding::EnergyDissipated, When::Always, "Energy", "", "",
   "energy dissipated since the start; span fidelity: in the span dampers, guide friction, guide pivot and "
   "tensioner"},
  {"energy.input", 32, R, Out, Binding::EnergyInput, When::Always, "Energy", "", "",
   "work done on the chain drive by the crankshaft drive and the load torques since the start; span fidelity: that "
   "of the span model"},
  {"chain.maxJointDeformation", 33, R, Out, Binding::MaxJointDeformation, When::Always, "Length", "", "",
   "largest joint deformation (diagnostic); span fidelity: largest span tension / joint stiffness"},
  {"contacts", 40, I, Out, Binding::Contacts, When::Always, "", "", "",
   "number of closed contacts; span fidelity: 0 (spans have no contacts)"},
  {"solver.steps", kVrSolverSteps, I, Out, Binding::SolverSteps, When::Always, "", "", "",
   "integrator steps since the start (of the span model in the span fidelity)"},
  {"solver.time", kVrSolverTime, R, Out, Binding::SolverTime, When::Always, "|s", "", "",
   "time of the solver state the outputs belong to: the point of the FMU's time grid assigned to the communication "
   "point (equal to it when it lies on the grid, otherwise the grid point before it); the same in both fidelities"},
};

constexpr DriveVariable kDriveParameters[] = {
  {"driveFile", 100, S, Par, Binding::DriveFile, When::Always, "", "", "",
   "a drive description (JSON) with this FMU's interface (the same elements, names and tensioner: other masses, "
   "stiffnesses, geometry); empty: the drive in the FMU's resources"},
  {"link.index", 101, I, Par, Binding::LinkIndex, When::Always, "", "-1", "-1|",
   "monitored link; -1: as in the drive description"},
  {"solver.method", 102, S, Par, Binding::SolverMethod, When::Always, "", "", "",
   "integrator of the compliant contact method and of the span fidelity: fixed-verlet, "
   "fixed-verlet-implicit-joint-damping (the real-time method: the joints' damping implicit), "
   "fixed-verlet-implicit-damping, fixed-newmark (these three: link fidelity), arkode-erk, arkode-erk-fixed, "
   "cvode-bdf-klu, cvode-bdf-band (span fidelity). Empty (the default): the fidelity's own, "
   "fixed-verlet-implicit-joint-damping (link) or fixed-verlet (span); a drive whose joints have clearance, or rigid "
   "contacts: fixed-verlet (link), the same defaults as every entry point (chaindrive-info --defaults)"},
  {"solver.tolerance", 103, R, Par, Binding::SolverTolerance, When::Always, "", "1e-5", "1e-12|0.1",
   "relative tolerance of the adaptive integrators and of the event-driven contact method"},
  {"solver.step", 104, R, Par, Binding::SolverStep, When::Always, "|s|us", "0", "0|1e-3",
   "step of the fixed-step integrators and of time stepping, exactly: they step on the grid t_k = startTime + k "
   "solver.step; a communication point within 1 % of a step from a grid point is that point, one farther off is "
   "integrated to the grid point before it (solver.time), the remainder carried. Adaptive methods stop on a 1 us "
   "grid by the same rule. 0 (the default): the drive's own step for the fidelity and method, from its stiffest "
   "joint and contact against its lightest link, checked by a short run of the drive at 6000 rpm (computed once "
   "per machine and cached; chaindrive-info --defaults --drive FILE prints it and why, the FMU "
   "logs it at initialization); the default drive's: 3.5714285714285718e-6 s (link), 3.3333333333333335e-5 s "
   "(span) or 2.5e-6 s (link, a drive whose joints have clearance, or rigid contacts)"},
  {"solver.preload", 105, B, Par, Binding::SolverPreload, When::Always, "", "true", "",
   "start from the pre-loaded (kinetostatic) state; false: from the unloaded nominal pose"},
  {"tensioner.preload", 110, R, Par, Binding::TensionerPreload, When::Tensioner, "Force", "-1", "",
   "tensioner force at the drawn pose; negative: as in the drive description"},
  {"tensioner.stiffness", 111, R, Par, Binding::TensionerStiffness, When::Tensioner, "|N/m|N/mm", "-1", "",
   "tensioner spring rate; negative: as in the drive description"},
  {"tensioner.damping", 112, R, Par, Binding::TensionerDamping, When::Tensioner, "|N.s/m", "-1", "",
   "tensioner damping while the plunger retracts (the spring-damper law; refused for a hydraulic tensioner); "
   "negative: as in the drive description"},
  {"tensioner.dampingExtension", 113, R, Par, Binding::TensionerDampingExtension, When::Tensioner, "|N.s/m", "-1", "",
   "tensioner damping while the plunger extends (the spring-damper law; refused for a hydraulic tensioner); "
   "negative: as in the drive description"},
  {"contact.method", 106, S, Par, Binding::ContactMethod, When::Always, "", "", "",
   "contact method: compliant, event-driven or time-stepping; empty: as in the drive description"},
  {"chain.jointModel", 107, S, Par, Binding::JointModel, When::Always, "", "", "",
   "chain joints: journal-bearing or ideal (bilateral constraints, rigid-contact methods only); empty: as in the "
   "drive description"},
  {"fidelity", 108, S, Par, Binding::Fidelity, When::Always, "", "link", "",
   "model of the chain: link (the link-by-link model, default) or span (the span model: rotors, guides and "
   "tensioner joined by spans, each a spring-damper with its chain mass lumped on its sprockets; compliant contact "
   "method and journal-bearing joints only; no per-link contact forces)"},
  {"solver.newmarkGamma", 109, R, Par, Binding::NewmarkGamma, When::Always, "", "0.5", "0.5|1",
   "fixed-newmark: Newmark's gamma (beta = (gamma + 1/2)^2 / 4); 0.5 keeps the amplitude of every mode, more damps "
   "the modes the step cannot resolve"},
  {"solver.threads", 115, I, Par, Binding::SolverThreads, When::Always, "", "1", "1|16",
   "threads of each evaluation of the link model (the same results for every number): the links' stages split "
   "among them, a barrier between stages; for fixed-verlet and fixed-verlet-implicit-joint-damping with compliant "
   "contacts only (refused otherwise); they spin between steps. Pays only where each thread has a core of its own "
   "and the cores exchange data fast (docs/benchmark_threads.md)"},
  {"tensioner.oilTemperature", 114, R, Par, Binding::OilTemperature, When::Hydraulic, "|K|degC", "363.15", "",
   "temperature of the hydraulic tensioner's oil: its viscosity (the drive description's viscosity law, within its "
   "range), so its leak-down"},
};
// clang-format on

constexpr const char* kReservedNames[] = {"tensioner", "chain", "link", "solver", "energy", "fidelity",
                                          "contact", "contacts", "driveFile"};

bool applies(When when, const DriveDescription& desc) {
  switch (when) {
    case When::Always: return true;
    case When::Tensioner: return desc.tensioner.present;
    case When::Hydraulic: return desc.tensioner.present && desc.tensioner.kind == TensionerKind::Hydraulic;
    case When::TightSpan: return desc.measurement.tightSpan.size() == 2;
    case When::SlackSpan: return desc.measurement.slackSpan.size() == 2;
  }
  return false;
}

// "Force" is a declared type; "|Pa|bar" the unit Pa with the display unit bar.
void setUnits(InterfaceVariable& v, std::string_view spec) {
  if (spec.empty()) return;
  if (spec[0] != '|') {
    v.declaredType = std::string(spec);
    return;
  }
  const std::size_t bar = spec.find('|', 1);
  v.unit = std::string(spec.substr(1, bar == std::string_view::npos ? std::string_view::npos : bar - 1));
  if (bar != std::string_view::npos) v.displayUnit = std::string(spec.substr(bar + 1));
}

InterfaceVariable fromTable(const DriveVariable& d) {
  InterfaceVariable v;
  v.name = d.name;
  v.vr = d.vr;
  v.type = d.type;
  v.causality = d.causality;
  v.binding = d.binding;
  v.variability = d.causality == Par ? "fixed" : d.type == R || d.causality == In ? "continuous" : "discrete";
  v.initial = d.causality == Par ? "exact" : d.causality == Out ? "calculated" : "";
  setUnits(v, d.declaredType);
  v.start = d.start;
  const std::string_view range = d.range;
  if (const std::size_t bar = range.find('|'); bar != std::string_view::npos) {
    v.min = std::string(range.substr(0, bar));
    v.max = std::string(range.substr(bar + 1));
  }
  v.description = d.description;
  return v;
}

// ---- the elements' variables ----

/// A rotor of the interface: a sprocket or a pivoting guide, by its index in the description.
struct RotorRef {
  bool sprocket;
  int index;
};

// The rotors in the interface's order: the prescribed sprocket, then the route's rotors against
// the running direction (its tight side first, as the load flows from the crankshaft), then the
// pivoting guides outside the route.
std::vector<RotorRef> rotorOrder(const DriveDescription& desc, int prescribed) {
  std::vector<RotorRef> order{{true, prescribed}};
  const std::vector<std::string>& route = desc.chain.route;
  const int n = static_cast<int>(route.size());
  int start = 0;
  for (int r = 0; r < n; ++r)
    if (route[r] == desc.sprockets[prescribed].name) start = r;
  for (int i = 1; i < n; ++i) {
    const std::string& name = route[((start - i) % n + n) % n];
    if (const int s = desc.sprocketIndex(name); s >= 0) order.push_back({true, s});
    else if (const int g = desc.guideIndex(name); g >= 0 && desc.guides[g].pivoting) order.push_back({false, g});
  }
  for (int g = 0; g < static_cast<int>(desc.guides.size()); ++g) {
    bool inRoute = false;
    for (const auto& name : route) inRoute = inRoute || name == desc.guides[g].name;
    if (desc.guides[g].pivoting && !inRoute) order.push_back({false, g});
  }
  return order;
}

// The value-reference scheme (docs/fmu.md): rotor k's block is 1000 + 10 k ... + 9 (slot 0 its
// input, 1 its angle, 2 its speed or the prescribed sprocket's torque, 3 the chain's torque on a
// free sprocket or the prescribed one's step mean, 4 a free sprocket's step mean); the first
// rotors keep the numbers the default drive's FMU always had: the inputs
// of rotors 0-2 are 1-3, the angle and speed (torque) of rotors 0-3 are 10-17. A span's force is
// 2000 + its route element.
unsigned rotorVr(int k, int slot) {
  if (slot == 0 && k <= 2) return 1u + static_cast<unsigned>(k);
  if ((slot == 1 || slot == 2) && k <= 3) return 10u + 2u * static_cast<unsigned>(k) + (slot == 2 ? 1u : 0u);
  return 1000u + 10u * static_cast<unsigned>(k) + static_cast<unsigned>(slot);
}
constexpr unsigned kSpanVrBase = 2000;

InterfaceVariable elementVariable(const std::string& element, const char* quantity, unsigned vr, VarCausality c,
                                  Binding b, const char* declaredType, std::string description) {
  InterfaceVariable v;
  v.name = element + "." + quantity;
  v.vr = vr;
  v.causality = c;
  v.binding = b;
  v.element = element;
  v.variability = "continuous";
  v.initial = c == Out ? "calculated" : "";
  v.declaredType = declaredType;
  v.description = std::move(description);
  return v;
}

// The chain's torque on a sprocket averaged over the last communication step: what a coupling
// passes on (the roller impacts, 14-20 us, are not sampled at its step; src/assembly/model.h).
InterfaceVariable stepMeanVariable(const std::string& sprocket, const char* quantity, unsigned vr, Binding b,
                                   const std::string& quoted) {
  return elementVariable(sprocket, quantity, vr, Out, b, "Torque",
                         "chain torque on sprocket " + quoted + " averaged over the last communication step (its "
                         "angular impulse over the step divided by the step; at the start the torque itself), sign "
                         "as its instantaneous torque; NaN with rigid contacts; span fidelity: the same, of the spans' "
                         "torque");
}

// The prescribed sprocket: its speed input, its angle and the chain's torque on it.
void prescribedVariables(const SprocketDesc& s, std::vector<InterfaceVariable>& inputs,
                         std::vector<InterfaceVariable>& outputs) {
  const std::string q = "'" + s.name + "'";
  InterfaceVariable w = elementVariable(s.name, "w", rotorVr(0, 0), In, Binding::CrankSpeed, "AngularVelocity",
                                        "angular velocity of the prescribed sprocket " + q + " (the crankshaft), with its "
                                        "rotational vibration, positive in the running direction");
  w.start = "314.1592653589793";
  inputs.push_back(w);
  outputs.push_back(elementVariable(s.name, "phi", rotorVr(0, 1), Out, Binding::RotorAngle, "Angle",
                                    "angle of the prescribed sprocket " + q + " from the start, running direction; span "
                                    "fidelity: the same"));
  InterfaceVariable tau = elementVariable(
      s.name, "tau", rotorVr(0, 2), Out, Binding::CrankTorque, "Torque",
      "chain torque on the prescribed sprocket " + q + ", positive in the running direction (negative when the chain "
      "loads the crankshaft); span fidelity: from the tensions of the spans leaving and arriving at the sprocket");
  tau.dependsOnCrankSpeed = true;
  outputs.push_back(tau);
  InterfaceVariable mean = stepMeanVariable(s.name, "tauMean", rotorVr(0, 3), Binding::CrankTorqueStepMean, q);
  mean.dependsOnCrankSpeed = true;  // (at the start: the torque itself)
  outputs.push_back(mean);
}

// A free sprocket (loaded or an idler): its load input, its angle, speed and the chain's torque.
void freeSprocketVariables(const DriveDescription& desc, int index, int k, std::vector<InterfaceVariable>& inputs,
                           std::vector<InterfaceVariable>& outputs) {
  const SprocketDesc& s = desc.sprockets[index];
  const std::string q = "'" + s.name + "' (" + std::to_string(s.teeth) + " teeth" + (s.loaded ? "" : ", an idler") + ")";
  if (s.loaded) {
    InterfaceVariable tau = elementVariable(s.name, "tau", rotorVr(k, 0), In, Binding::LoadTorque, "Torque",
                                            "load torque on sprocket " + q + ", positive when it opposes the rotation");
    tau.start = "0";
    tau.index = index;
    inputs.push_back(tau);
  }
  outputs.push_back(elementVariable(s.name, "phi", rotorVr(k, 1), Out, Binding::RotorAngle, "Angle",
                                    "angle of sprocket " + q + " from the start, running direction; span fidelity: the "
                                    "same"));
  outputs.push_back(elementVariable(s.name, "w", rotorVr(k, 2), Out, Binding::RotorRate, "AngularVelocity",
                                    "angular velocity of sprocket " + q + ", positive in the running direction; span "
                                    "fidelity: the same"));
  outputs.push_back(elementVariable(s.name, "tauChain", rotorVr(k, 3), Out, Binding::RotorChainTorque, "Torque",
                                    "chain torque on sprocket " + q + ", positive in the running direction (in steady "
                                    "running it balances the load torque); span fidelity: from the tensions of the "
                                    "spans leaving and arriving at the sprocket"));
  outputs.push_back(stepMeanVariable(s.name, "tauChainMean", rotorVr(k, 4), Binding::RotorChainTorqueStepMean, q));
}

// A pivoting guide: its angle and speed.
void guideVariables(const DriveDescription& desc, int index, int k, std::vector<InterfaceVariable>& outputs) {
  const std::string& name = desc.guides[index].name;
  const bool tensioned = desc.tensioner.present && desc.tensioner.guide == name;
  const std::string what = tensioned ? "the tension guide '" + name + "'" : "guide '" + name + "'";
  const std::string sense = tensioned ? "positive towards the chain" : "counterclockwise positive";
  outputs.push_back(elementVariable(name, "phi", rotorVr(k, 1), Out, Binding::RotorAngle, "Angle",
                                    "rotation of " + what + " from its drawn pose, " + sense + "; span fidelity: the "
                                    "same"));
  InterfaceVariable w = elementVariable(name, "w", rotorVr(k, 2), Out, Binding::RotorRate, "AngularVelocity",
                                        "angular velocity of " + what + ", " + sense + "; span fidelity: the same");
  w.displayUnit = "deg/s";
  outputs.push_back(w);
}

// The chain force in each span, named by the elements it runs between (chain.<from>.<to>.F).
void spanVariables(const DriveDescription& desc, std::vector<InterfaceVariable>& outputs) {
  const std::vector<std::string>& route = desc.chain.route;
  for (std::size_t r = 0; r < route.size(); ++r) {
    const std::string& from = route[r];
    const std::string& to = route[(r + 1) % route.size()];
    InterfaceVariable f = elementVariable("chain." + from + "." + to, "F", kSpanVrBase + static_cast<unsigned>(r), Out,
                                          Binding::SpanForce, "Force",
                                          "chain force in the span from '" + from + "' to '" + to + "' (running order), "
                                          "at the middle of its free part; span fidelity: the tension of the span there");
    f.element.clear();
    f.index = static_cast<int>(r);
    outputs.push_back(f);
  }
}

// ---- names, the model identifier and the GUID ----

bool fmiIdentifier(const std::string& name) {
  if (name.empty() || (name[0] >= '0' && name[0] <= '9')) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

// Every sprocket and every guide names variables (its own, or a span's): an FMI identifier that
// no variable of the drive as a whole starts with.
void checkElementNames(const DriveDescription& desc, std::vector<std::string>& problems) {
  auto check = [&](const std::string& field, const std::string& name) {
    if (!fmiIdentifier(name))
      problems.push_back(field + ": '" + name + "' cannot name the FMU's variables; a name is letters, digits and '_', "
                         "not starting with a digit");
    else if (reservedName(name))
      problems.push_back(field + ": '" + name + "' is reserved for the drive's own variables (tensioner, chain, link, "
                         "solver, energy, fidelity, contact, contacts, driveFile); give the element another name");
  };
  for (std::size_t i = 0; i < desc.sprockets.size(); ++i)
    check("sprockets[" + std::to_string(i) + "].name", desc.sprockets[i].name);
  for (std::size_t i = 0; i < desc.guides.size(); ++i) check("guides[" + std::to_string(i) + "].name", desc.guides[i].name);
}

std::uint64_t fnv1a(std::string_view text, std::uint64_t basis) {
  std::uint64_t h = basis;
  for (unsigned char ch : text) h = (h ^ ch) * 1099511628211ull;
  return h;
}

// A version-8 (vendor-specific) UUID from two 64-bit hashes of the description's canonical text.
std::string contentGuid(const std::string& text) {
  std::uint64_t hi = fnv1a(text, 14695981039346656037ull), lo = fnv1a(text, 0x6c62272e07bb0142ull);
  hi = (hi & ~0xF000ull) | 0x8000ull;                         // version 8
  lo = (lo & ~(0xC0ull << 56)) | (0x80ull << 56);             // the RFC's variant
  char s[40];
  std::snprintf(s, sizeof s, "{%08x-%04x-%04x-%04x-%012llx}", static_cast<unsigned>(hi >> 32),
                static_cast<unsigned>((hi >> 16) & 0xFFFF), static_cast<unsigned>(hi & 0xFFFF),
                static_cast<unsigned>(lo >> 48), static_cast<unsigned long long>(lo & 0xFFFFFFFFFFFFull));
  return s;
}

// The drive's name as an identifier: runs of other characters become one '_'.
std::string identifierOf(const std::string& name) {
  std::string id;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (ok) id += c;
    else if (!id.empty() && id.back() != '_') id += '_';
  }
  while (!id.empty() && id.back() == '_') id.pop_back();
  if (id.size() > 60) id.resize(60);
  if (id.empty() || (id[0] >= '0' && id[0] <= '9')) id = "drive_" + id;
  return id;
}

bool sameIgnoringCase(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if ((a[i] | 0x20) != (b[i] | 0x20)) return false;
  return true;
}

// The model identifier and GUID: the default drive's, or the drive's name and content's.
void identify(const DriveDescription& desc, DriveInterface& di, std::vector<std::string>& problems) {
  di.defaultDrive = isDefaultDrive(desc);
  if (di.defaultDrive) {
    di.modelIdentifier = kDefaultModelIdentifier;
    di.guid = kDefaultDriveGuid;
    return;
  }
  di.modelIdentifier = identifierOf(desc.name);
  di.guid = contentGuid(desc.canonicalText);
  for (const char* taken : {kDefaultModelIdentifier, "CVTChain"})
    if (sameIgnoringCase(di.modelIdentifier, taken))
      problems.push_back("name: '" + desc.name + "' gives the model identifier '" + di.modelIdentifier +
                         "', which is the shipped FMU " + taken + ".fmu's; give the drive another name");
}

int prescribedSprocket(const DriveDescription& desc, std::vector<std::string>& problems) {
  for (std::size_t i = 0; i < desc.sprockets.size(); ++i)
    if (desc.sprockets[i].prescribed) return static_cast<int>(i);
  problems.push_back("sprockets: no sprocket has motion 'prescribed'; the FMU's speed input drives one (the "
                     "crankshaft's)");
  return -1;
}

std::string modelDescriptionText(const DriveDescription& desc) {
  std::string s = "Timing-chain drive '" + desc.name + "' (Pfeiffer, Fritz, Srnik 1997) in two fidelities (parameter "
                  "fidelity): link by link or as spans. " + std::to_string(desc.chain.numberOfLinks) +
                  "-link roller chain; sprockets";
  for (const SprocketDesc& sp : desc.sprockets)
    s += " " + sp.name + " (" + std::to_string(sp.teeth) + " teeth, " +
         (sp.prescribed ? "prescribed speed" : sp.loaded ? "load torque" : "idler") + "),";
  s.back() = ';';
  if (!desc.guides.empty()) {
    s += " guides";
    for (const GuideDesc& g : desc.guides) s += " " + g.name + (g.pivoting ? " (pivoting)," : " (fixed),");
    s.back() = ';';
  }
  if (desc.tensioner.present)
    s += std::string(" ") + (desc.tensioner.kind == TensionerKind::Hydraulic ? "hydraulic" : "spring-damper") +
         " tensioner on " + desc.tensioner.guide + ";";
  s.back() = '.';
  return s;
}

}  // namespace

bool reservedName(const std::string& name) {
  for (const char* r : kReservedNames)
    if (name == r) return true;
  return false;
}

const char* typeName(VarType t) {
  switch (t) {
    case VarType::Real: return "Real";
    case VarType::Integer: return "Integer";
    case VarType::Boolean: return "Boolean";
    case VarType::String: return "String";
  }
  return "?";
}

const char* causalityName(VarCausality c) {
  switch (c) {
    case VarCausality::Input: return "input";
    case VarCausality::Output: return "output";
    case VarCausality::Parameter: return "parameter";
  }
  return "?";
}

DriveInterface driveInterface(const DriveDescription& desc) {
  std::vector<std::string> problems;
  checkElementNames(desc, problems);
  DriveInterface di;
  identify(desc, di, problems);
  const int prescribed = prescribedSprocket(desc, problems);
  if (!problems.empty()) throw DescriptionError(problems);
  di.modelName = di.modelIdentifier;
  di.description = modelDescriptionText(desc);
  std::vector<InterfaceVariable> inputs, outputs;
  const std::vector<RotorRef> order = rotorOrder(desc, prescribed);
  for (int k = 0; k < static_cast<int>(order.size()); ++k) {
    const RotorRef& rotor = order[k];
    if (k == 0) prescribedVariables(desc.sprockets[rotor.index], inputs, outputs);
    else if (rotor.sprocket) freeSprocketVariables(desc, rotor.index, k, inputs, outputs);
    else guideVariables(desc, rotor.index, k, outputs);
  }
  if (applies(When::Hydraulic, desc)) {
    InterfaceVariable p = fromTable({"tensioner.supplyPressure", 4, R, In, Binding::SupplyPressure, When::Hydraulic,
                                     "|Pa|bar", "300000", "",
                                     "gauge pressure of the engine's oil gallery feeding the hydraulic tensioner through "
                                     "its check valve (the engine's oil circuit)"});
    inputs.push_back(p);
  }
  spanVariables(desc, outputs);
  for (const DriveVariable& d : kDriveOutputs)
    if (applies(d.when, desc)) outputs.push_back(fromTable(d));
  for (InterfaceVariable& v : outputs)  // the monitored link's contact with the prescribed sprocket
    v.dependsOnCrankSpeed = v.dependsOnCrankSpeed || v.binding == Binding::LinkNormalForce ||
                            v.binding == Binding::LinkSprocketForce;
  di.variables = inputs;
  di.variables.insert(di.variables.end(), outputs.begin(), outputs.end());
  for (const DriveVariable& d : kDriveParameters)
    if (applies(d.when, desc)) di.variables.push_back(fromTable(d));
  return di;
}

}  // namespace chaindrive
