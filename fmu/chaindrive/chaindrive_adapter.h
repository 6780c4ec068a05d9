// Which model adapter ChainDrive.fmu exports (Reference-FMUs' config.h): the drive's,
// ChainDriveModel (chaindrive_model.h). chaindrive_fmu.cpp compiles the FMI 2.0 functions
// (fmi2_functions.h) for it.
#pragma once

#include "chaindrive_model.h"

namespace chaindrive::fmu {

using ExportedAdapter = ChainDriveModel;

}  // namespace chaindrive::fmu
