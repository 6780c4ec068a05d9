// The interface a drive shows as an FMU: every input, output and parameter, named after the
// drive's own elements (its sprockets, pivoting guides and spans) or after the drive as a whole
// (tensioner, chain, link, energy, solver), with its value reference, type, unit and description,
// and what it sets or reads in a run (its binding). Generated from the description alone, so that
// the exporter (chaindrive-info --fmu-files) and the FMU binary, which checks the table in its
// resources against the drive beside it, make the same table. docs/fmu.md states the rules.
#pragma once

#include <string>
#include <vector>

#include "description/drive_description.h"

namespace chaindrive {

enum class VarType { Real, Integer, Boolean, String };
enum class VarCausality { Input, Output, Parameter };

/// What a variable sets (inputs, parameters) or reads (outputs) in a run.
enum class Binding {
  // inputs
  CrankSpeed, LoadTorque, SupplyPressure,
  // outputs of one element (InterfaceVariable::element, ::index)
  RotorAngle, RotorRate, CrankTorque, RotorChainTorque, CrankTorqueStepMean, RotorChainTorqueStepMean, SpanForce,
  // outputs of the drive
  TightSpanForce, SlackSpanForce, TensionerForce, TensionerStroke, TensionerRate, ChamberPressure, CheckValveFlow,
  LeakFlow, LinkTension, LinkNormalForce, LinkSprocketForce, LinkGuideForce, LinkX, LinkY, EnergyKinetic,
  EnergyElastic, EnergyDissipated, EnergyInput, MaxJointDeformation, Contacts, SolverSteps, SolverTime,
  // parameters
  DriveFile, LinkIndex, SolverMethod, SolverTolerance, SolverStep, SolverPreload, TensionerPreload,
  TensionerStiffness, TensionerDamping, TensionerDampingExtension, ContactMethod, JointModel, Fidelity,
  NewmarkGamma, OilTemperature, SolverThreads,
};

struct InterfaceVariable {
  std::string name;
  unsigned vr = 0;
  VarType type = VarType::Real;
  VarCausality causality = VarCausality::Output;
  Binding binding = Binding::SolverTime;
  std::string element;  // the sprocket or guide of an element's output or input ("" for the drive's)
  int index = -1;       // a load's sprocket (DriveDescription::sprockets), a span's route element
  std::string variability, initial;              // FMI's attributes ("" where FMI's default holds)
  std::string declaredType, unit, displayUnit;   // "" where none
  std::string start, min, max;                   // as the model description writes them; "" none
  std::string description;
  bool dependsOnCrankSpeed = false;  // an output the crankshaft-speed input reaches within a step
};

struct DriveInterface {
  std::string modelIdentifier;  // "ChainDrive" for the default drive, else from the drive's name
  std::string guid;             // the default drive's fixed GUID, else from the description's content
  std::string modelName, description;
  std::vector<InterfaceVariable> variables;  // in the model description's order
  bool defaultDrive = false;
};

/// The interface of a drive. Throws DescriptionError naming the element whose name cannot name
/// FMU variables (not an FMI identifier, or reserved by the drive's own variables) and a drive
/// without a prescribed sprocket (the speed input drives it).
DriveInterface driveInterface(const DriveDescription& desc);

/// The value references of the default drive's FMU before every drive had its own; an element's
/// variables keep them where the scheme (docs/fmu.md) gives them.
constexpr const char* kDefaultDriveGuid = "{b6f8c2a4-7d1e-4f3a-9e2b-5c8d1a0f4e21}";
constexpr const char* kDefaultModelIdentifier = "ChainDrive";

/// The value references every drive's FMU shares: the outputs and parameters of the drive as a
/// whole, and the two the protocol answers itself.
constexpr unsigned kVrSolverTime = 34, kVrSolverSteps = 41;

/// The first component of a variable name that no element may take (the drive's own variables).
bool reservedName(const std::string& name);

const char* typeName(VarType t);
const char* causalityName(VarCausality c);

}  // namespace chaindrive
