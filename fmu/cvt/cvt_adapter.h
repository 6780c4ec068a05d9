// Which model adapter CVTChain.fmu exports (Reference-FMUs' config.h): the chain CVT's,
// CvtChainModel (cvt_model.h). cvt_fmu.cpp compiles the FMI 2.0 functions (fmi2_functions.h)
// for it.
#pragma once

#include "cvt_model.h"

namespace chaindrive::fmu {

using ExportedAdapter = CvtChainModel;

}  // namespace chaindrive::fmu
