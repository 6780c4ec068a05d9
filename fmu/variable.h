// What every FMU's variable table is made of (each FMU's <adapter>_variables.h lists its variables, which
// mirror its model description), and what the protocol reads of it.
#pragma once

#include <cstddef>

namespace chaindrive::fmu {

enum class Type { Real, Integer, Boolean, String };
enum class Causality { Input, Output, Parameter };

struct Variable {
  const char* name;
  unsigned vr;
  Type type;
  Causality causality;
  const char* start;  // start value as written in the model description ("" for outputs)
};

/// What the protocol reads of an FMU's modelDescription.xml, from the <adapter>_variables.h of its model
/// adapter (every model adapter names its own: adapter_contract.h).
struct ModelDescription {
  const char* modelIdentifier;
  const char* guid;                          // the GUID fmi2Instantiate checks
  const Variable* (*variable)(unsigned vr);  // the variable of a value reference; nullptr if none
  unsigned solverTime, solverSteps;          // the outputs the protocol answers itself
};

/// The variable of value reference vr in a table; nullptr if none.
template <std::size_t N>
const Variable* findIn(const Variable (&table)[N], unsigned vr) {
  for (const Variable& v : table)
    if (v.vr == vr) return &v;
  return nullptr;
}

}  // namespace chaindrive::fmu
