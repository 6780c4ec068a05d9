// A drive's FMU's variables at run time. One binary serves every drive's FMU: at instantiation it
// reads the interface table in its resources folder (resources/interface.json, written with the
// model description by chaindrive-info --fmu-files) and checks it against the drive beside it
// (resources/drive.json) by generating the drive's interface again (src/interface/), and the GUID
// against the importer's. A missing folder, a damaged file or a mismatch is an error naming it.
#pragma once

#include <string>
#include <vector>

#include "description/drive_description.h"
#include "interface/drive_interface.h"
#include "variable.h"

namespace chaindrive::fmu {

class FmuInterface {
 public:
  /// Loads the interface of the FMU in resourceDir for the importer's GUID; "" when it loaded, else
  /// the problem (one line).
  std::string load(const std::string& resourceDir, const char* guid);

  const DriveDescription& drive() const { return drive_; }
  const std::string& drivePath() const { return drivePath_; }
  const DriveInterface& table() const { return table_; }
  const std::string& modelIdentifier() const { return table_.modelIdentifier; }
  /// The variable of a value reference and its place in table().variables; nullptr / -1 if none.
  const Variable* find(unsigned vr) const { return at(vr) >= 0 ? &variables_[at(vr)] : nullptr; }
  int at(unsigned vr) const { return vr < byVr_.size() ? byVr_[vr] : -1; }

  FmuInterface() = default;
  FmuInterface(const FmuInterface&) = delete;  // (variables_ point into table_)
  FmuInterface& operator=(const FmuInterface&) = delete;

 private:
  std::string check(const std::string& resourceDir, const std::string& interfaceText, const char* guid);
  void index();

  DriveDescription drive_;
  std::string drivePath_;
  DriveInterface table_;
  std::vector<Variable> variables_;  // the protocol's view of table_'s variables (names, starts point into it)
  std::vector<int> byVr_;            // value reference -> index into variables_, -1 for none
};

/// The names of another drive's interface against this one's: "" when a drive file with that
/// interface may replace the FMU's drive (parameter driveFile), else the first difference.
std::string interfaceMismatch(const DriveInterface& mine, const DriveDescription& other);

}  // namespace chaindrive::fmu
