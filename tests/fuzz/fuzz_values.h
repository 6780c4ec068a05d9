// Values the FMI call-sequence fuzz passes to ChainDrive.fmu: value references (those of the
// model description and invalid ones), good and bad values per variable, odd resource locations,
// and the parameter assignments that decide how far (and at what cost) a sequence can get.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fmi2Functions.h"
#include "fuzz_rng.h"
#include "fuzz_interface.h"

namespace chaindrive::fuzz {

/// Files and folders of the source tree the fuzz points the FMU at.
struct FuzzPaths {
  std::string resourceDir;    // the default drive's FMU's resources folder (its drive and interface)
  std::string driveFile;      // a valid drive description (the default drive's file)
  // the resources of the FMU of the default drive with the spring-damper tensioner law, its GUID
  std::string springDamperResourceDir, springDamperGuid, springDamperFile;
  std::shared_ptr<const DriveInterface> springDamperInterface;
  std::vector<fmu::Variable> springDamperVariables;  // (pointing into springDamperInterface)
  std::string notADriveFile;  // an existing file that is not JSON
  // Plan::Drive: every sequence mutates one of these drive texts (the default and the test drives)
  // and writes its FMU's files into driveWorkDir
  bool drivePlanOnly = false;
  std::vector<std::string> driveBases;
  std::string driveWorkDir;
};

/// An fmuResourceLocation and whether it is the file URI of the resources folder.
struct ResourceLocation {
  std::optional<std::string> uri;  // nullopt: NULL
  bool valid = false;
};

/// One parameter value set through the FMI setter of its type.
struct Assignment {
  unsigned vr = 0;
  fmu::Type type = fmu::Type::Real;
  double real = 0.0;
  fmi2Integer integer = 0;
  fmi2Boolean boolean = fmi2False;
  std::string text;
};

Assignment realAssignment(unsigned vr, double value);
Assignment integerAssignment(unsigned vr, fmi2Integer value);
Assignment booleanAssignment(unsigned vr, bool value);
Assignment stringAssignment(unsigned vr, std::string value);

/// A value reference of the model description (mostly) or one that names no variable.
unsigned anyValueReference(Rng& rng);
/// A value reference of a variable of the given type, sometimes one of another type or none.
unsigned valueReferenceFor(Rng& rng, fmu::Type type);

/// A value the variable accepts and the initialization accepts, chosen to keep runs cheap
/// (fixed steps of 1..3 us, no run-time cost from tolerances).
double goodReal(Rng& rng, unsigned vr);
/// NaN, infinities, huge, tiny, negative, or out of the parameter's range.
double badReal(Rng& rng, unsigned vr);
fmi2Integer goodInteger(Rng& rng, unsigned vr);
fmi2Integer badInteger(Rng& rng);
/// std::nullopt stands for a NULL string.
std::optional<std::string> goodString(Rng& rng, unsigned vr, const FuzzPaths& paths);
std::optional<std::string> badString(Rng& rng, unsigned vr, const FuzzPaths& paths);

/// fmuResourceLocation values importers pass: good, odd and broken (the FMU refuses those that
/// are not the resources folder's).
ResourceLocation resourceLocation(Rng& rng, const std::string& resourceDir);

/// One or two assignments that the setters accept and the initialization rejects cheaply
/// (before the start-state solve).
std::vector<Assignment> poisonAssignments(Rng& rng, const FuzzPaths& paths);
/// The span fidelity with one of the integrators and the contact method and joints it takes.
std::vector<Assignment> spanAssignments(Rng& rng);
/// Combinations of integrator, contact method and joint model other than the default one.
std::size_t methodCombinationCount();
/// "integrator/contact method/joint model"
std::string methodCombinationName(std::size_t index);
/// Communication steps of 10 us a sequence with the combination makes (they dominate its cost).
int methodCombinationSteps(std::size_t index);
/// The assignments of a combination, with the start-state solve switched off.
std::vector<Assignment> methodAssignments(std::size_t index);
/// Whether the combination runs on the FMU of the drive with the spring-damper tensioner law.
bool methodCombinationSpringDamper(std::size_t index);

}  // namespace chaindrive::fuzz
