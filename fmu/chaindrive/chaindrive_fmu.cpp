// The FMI 2.0 functions of ChainDrive.fmu: the protocol (fmi2_functions.h) compiled for the model
// adapter that chaindrive_adapter.h names.
#include "chaindrive_adapter.h"
#include "fmi2_functions.h"
