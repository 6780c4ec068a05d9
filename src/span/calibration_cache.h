// The span model's calibration (span_calibration.h) kept once per drive and code: a file per key
// in a cache folder, the key a hash of the drive description (as given, with the FMU's parameter
// overrides) and of the solver's sources. Numbers are stored in hexadecimal floating point, so a
// model from the cache has the same bits as one calibrated afresh.
// The folder: $CHAINDRIVE_CACHE_DIR, else $XDG_CACHE_HOME/chaindrive, else ~/.cache/chaindrive
// (%LOCALAPPDATA%\chaindrive on Windows); "none" or an unwritable folder: no cache (the
// calibration runs each time the span model is assembled).
#pragma once

#include <string>

#include "span/span_calibration.h"

namespace chaindrive::span {

/// The cache key of a link model's calibration: its description and the code, hashed.
std::string calibrationKey(const Model& m);

/// The cache folder ("" when there is none).
std::string calibrationCacheDir();

/// Calibrates sm (assembled without laws) from the cache or by identification (then written to
/// the cache), puts the laws in and notes what it did. `fromCache` and `file` say where it came from.
void calibrateSpanModel(SpanModel& sm, bool* fromCache = nullptr, std::string* file = nullptr);

}  // namespace chaindrive::span
