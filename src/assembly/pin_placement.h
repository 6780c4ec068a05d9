// The chain's pins at the nominal pose, shared by the timing drive's and the CVT's assembly: the
// polygon of links inscribed in the chain path, each pin with what carries it there.
#pragma once

#include <vector>

#include "assembly/model.h"

namespace chaindrive {

/// What carries the pins on the wrap of one route element: a sprocket or pulley (On::Sprocket)
/// or a guide (On::Guide), with its rotor (-1 for a fixed guide).
struct WrapCarrier {
  PinNominal::On on = PinNominal::On::Sprocket;
  int rotor = -1;
};

/// Places the model's m.chain.links pins along m.path, chords of `chord` apart from the middle of
/// the first wrap: a pin on a wrap is carried as wrapCarriers[its route element] says (with the
/// wrap's centre and radius), a pin between wraps is on a span. Sets the gap of the closing joint
/// (m.assembly.closureResidual) and the largest deviation of a joint from `chord`
/// (m.assembly.maxJointGap).
void placePins(Model& m, double chord, const std::vector<WrapCarrier>& wrapCarriers);

}  // namespace chaindrive
