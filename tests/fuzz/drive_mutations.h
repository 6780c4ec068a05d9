// Random drive descriptions for the drive plan of the fuzz (call_sequence.h, Plan::Drive): a valid
// drive (the default or a test drive) with one to three changes. Four in ten are plausible (a
// sprocket moved by up to 3 mm, a guide by up to 1 mm, a positive number such as an inertia, a
// stiffness or a force scaled by 1/2 to 2: most still close and run), the rest degenerate:
// a number made NaN, infinite, zero, negative, tiny or huge (NaN and infinity as the JSON text a
// hand or another tool writes: NaN, Infinity, 1e999); a sprocket moved onto another (overlapping),
// mirrored across the crankshaft's line to another sprocket (the chain would wrap it from outside)
// or shifted; a guide moved across the chain; tiny and huge link counts; names duplicated,
// reserved for the FMU's own variables, or not valid in FMI; keys removed, elements duplicated,
// arrays emptied, values of another type.
#pragma once

#include <string>
#include <vector>

#include "fuzz_rng.h"

namespace chaindrive::fuzz {

/// A mutated drive description's text from one of `bases` (valid drive texts); `what` receives the
/// mutations in words ("sprockets/1/center/0 = NaN; chain/numberOfLinks = 3").
std::string mutatedDrive(Rng& rng, const std::vector<std::string>& bases, std::string& what);

}  // namespace chaindrive::fuzz
