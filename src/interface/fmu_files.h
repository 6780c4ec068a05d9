// The files that make a drive's FMU its own, besides the binaries: modelDescription.xml generated
// from the drive's interface, and in resources/ the drive and its interface as a table, which the
// binary reads at instantiation and checks against the drive (so that a drive file changed in the
// FMU, or a binary of another interface, is an error, never a silently different drive).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "interface/drive_interface.h"

namespace chaindrive {

/// The file names in an FMU's resources folder.
constexpr const char* kInterfaceFile = "interface.json";
constexpr const char* kDriveFile = "drive.json";
constexpr const char* kInterfaceSchema = "chaindrive.interface/1";

/// The interface as resources/interface.json holds it.
nlohmann::json interfaceJson(const DriveInterface& di);

/// The variables of two interface tables (interfaceJson's "variables"): "" when they are the same,
/// else the first difference in words ("variable 12: 'a.phi' here, 'b.phi' there"). With
/// `namesOnly`, only names, value references, types and causalities are compared.
std::string interfaceDifference(const nlohmann::json& mine, const nlohmann::json& theirs, bool namesOnly);

/// The FMI 2.0 co-simulation model description of the interface.
std::string modelDescriptionXml(const DriveInterface& di);

/// Writes dir/modelDescription.xml, dir/resources/interface.json and dir/resources/drive.json (the
/// drive's text as given) for the drive in `driveText`; returns its interface. Throws
/// DescriptionError for a drive that has no FMU interface, std::runtime_error when a file cannot
/// be written.
DriveInterface writeFmuFiles(const std::string& dir, const std::string& driveText);

}  // namespace chaindrive
