// What every FMU's variable table is made of: each model adapter answers the variable of a value
// reference from its table (CVTChain: cvt_variables.h, mirroring its model description; ChainDrive:
// the table generated from the drive, src/interface/).
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

/// The variable of value reference vr in a table; nullptr if none.
template <std::size_t N>
const Variable* findIn(const Variable (&table)[N], unsigned vr) {
  for (const Variable& v : table)
    if (v.vr == vr) return &v;
  return nullptr;
}

}  // namespace chaindrive::fmu
