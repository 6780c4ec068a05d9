#include "fmu_state.h"

#include <cmath>

namespace chaindrive::fmu {

void writeProtocolFields(const ProtocolSnapshot& s, std::vector<char>& out) {
  putField(out, s.state);
  putField(out, s.time);
  putField(out, s.lastSuccessfulTime);
}

void readProtocolFields(ByteReader& in, ProtocolSnapshot& s) {
  in.field(s.state);
  in.field(s.time);
  in.field(s.lastSuccessfulTime);
}

const char* invalidProtocolField(const ProtocolSnapshot& s) {
  if (s.state == 0 || (s.state & (s.state - 1)) != 0 || (s.state & ~kAllStates) != 0) return "state";
  if (!std::isfinite(s.time) || !std::isfinite(s.lastSuccessfulTime)) return "time";
  return nullptr;
}

}  // namespace chaindrive::fmu
