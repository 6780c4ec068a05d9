// Which model this FMU's protocol serves (fmu/chaindrive/model_adapter.h lists the members): the
// chain CVT of CVTChain.fmu.
#pragma once

#include "cvt_model.h"

namespace chaindrive::fmu {

using ModelAdapter = CvtChainModel;

}  // namespace chaindrive::fmu
