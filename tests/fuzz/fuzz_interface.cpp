#include "fuzz_interface.h"

namespace chaindrive::fmu {

namespace {

Type typeOf(VarType t) {
  return t == VarType::Real ? Type::Real : t == VarType::Integer ? Type::Integer
                                          : t == VarType::Boolean ? Type::Boolean : Type::String;
}

Causality causalityOf(VarCausality c) {
  return c == VarCausality::Input ? Causality::Input : c == VarCausality::Output ? Causality::Output
                                                                                  : Causality::Parameter;
}

const DriveInterface& defaultInterface() {
  static const DriveInterface di = driveInterface(defaultDriveDescription());
  return di;
}

}  // namespace

std::vector<Variable> protocolVariables(const DriveInterface& di) {
  std::vector<Variable> v;
  for (const InterfaceVariable& iv : di.variables)
    v.push_back({iv.name.c_str(), iv.vr, typeOf(iv.type), causalityOf(iv.causality), iv.start.c_str()});
  return v;
}

const std::vector<Variable>& defaultVariables() {
  static const std::vector<Variable> variables = protocolVariables(defaultInterface());
  return variables;
}

std::string checkDefaultValueReferences() {
  const std::pair<const char*, unsigned> named[] = {
      {"crankshaft.w", kCrankshaftW}, {"camshaftIntake.tau", kCamshaftIntakeTau},
      {"camshaftExhaust.tau", kCamshaftExhaustTau}, {"tensioner.supplyPressure", kTensionerSupplyPressure},
      {"crankshaft.phi", kCrankshaftPhi}, {"driveFile", kDriveFile}, {"link.index", kLinkIndex},
      {"solver.method", kSolverMethod}, {"solver.tolerance", kSolverTolerance}, {"solver.step", kSolverStep},
      {"solver.preload", kSolverPreload}, {"contact.method", kContactMethod}, {"chain.jointModel", kChainJointModel},
      {"fidelity", kFidelity}, {"solver.newmarkGamma", kSolverNewmarkGamma}, {"tensioner.preload", kTensionerPreload},
      {"tensioner.stiffness", kTensionerStiffness}, {"tensioner.damping", kTensionerDamping},
      {"tensioner.dampingExtension", kTensionerDampingExtension}, {"tensioner.oilTemperature", kTensionerOilTemperature},
      {"solver.threads", kSolverThreads}};
  for (const auto& [name, vr] : named) {
    bool found = false;
    for (const Variable& v : defaultVariables()) found = found || (v.vr == vr && std::string(v.name) == name);
    if (!found) return std::string(name) + " is not value reference " + std::to_string(vr);
  }
  return "";
}

}  // namespace chaindrive::fmu
