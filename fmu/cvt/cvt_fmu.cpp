// The FMI 2.0 functions of CVTChain.fmu: the protocol (fmi2_functions.h) compiled for the model
// adapter that cvt_adapter.h names.
#include "cvt_adapter.h"
#include "fmi2_functions.h"
