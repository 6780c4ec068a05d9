// The variables the FMI call fuzz knows ChainDrive.fmu by: the default drive's interface
// (src/interface/, as its FMU's resources hold it), with the value references the fuzz sets by
// name, and the resources folders it points the FMU at, written at the start of a run.
#pragma once

#include <string>
#include <vector>

#include "interface/drive_interface.h"
#include "variable.h"

namespace chaindrive::fmu {

// The default drive's value references (its interface: docs/fmu.md's scheme; checked against the
// generated table when the fuzz starts).
enum Vr : unsigned {
  kCrankshaftW = 1, kCamshaftIntakeTau = 2, kCamshaftExhaustTau = 3, kTensionerSupplyPressure = 4,
  kCrankshaftPhi = 10,
  kDriveFile = 100, kLinkIndex = 101, kSolverMethod = 102, kSolverTolerance = 103, kSolverStep = 104,
  kSolverPreload = 105, kContactMethod = 106, kChainJointModel = 107, kFidelity = 108, kSolverNewmarkGamma = 109,
  kTensionerPreload = 110, kTensionerStiffness = 111, kTensionerDamping = 112, kTensionerDampingExtension = 113,
  kTensionerOilTemperature = 114, kSolverThreads = 115,
};
constexpr const char* kGuid = chaindrive::kDefaultDriveGuid;

/// The default drive's variables, as the FMU's protocol sees them.
const std::vector<Variable>& defaultVariables();
/// The variables of an interface, as the FMU's protocol sees them (pointing into it).
std::vector<Variable> protocolVariables(const DriveInterface& di);

/// "" when the value references above are the default drive's interface's, else the first that is not.
std::string checkDefaultValueReferences();

}  // namespace chaindrive::fmu
