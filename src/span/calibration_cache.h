// The span model's calibration (span_calibration.h) kept once per drive and code: a file per key
// in a cache folder, the key a hash of the drive description (as given, with the FMU's parameter
// overrides) and of the solver's sources. Numbers are stored in hexadecimal floating point, so a
// model from the cache has the same bits as one calibrated afresh.
// The folder: $CHAINDRIVE_CACHE_DIR, else $XDG_CACHE_HOME/chaindrive, else ~/.cache/chaindrive
// (%LOCALAPPDATA%\chaindrive on Windows); "none" or an unwritable folder: no cache (the
// calibration runs each time the span model is assembled).
// A read-only calibration file of the same format (an exported FMU's resources/
// span_calibration.json, written by chaindrive-info --span-calibration) is looked in first: taken
// when its key is the model's, passed over with a note otherwise (another drive, other parameter
// overrides, other code, a damaged file).
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "span/span_calibration.h"

namespace chaindrive::span {

/// The cache key of a link model's calibration: its description and the code, hashed.
std::string calibrationKey(const Model& m);

/// A number in hexadecimal floating point (the cache's: read back to the bit), and back.
std::string hexNumber(double x);
double fromHexNumber(const std::string& text);

/// The cache folder ("" when there is none).
std::string calibrationCacheDir();

/// Writes `text` into `file` in the cache folder `dir` (made if missing): beside it first, then
/// renamed into place, so that an instance reading meanwhile sees the old file or the new. False
/// when it cannot be written (no cache: the caller computes again next time).
bool writeCacheFile(const std::string& dir, const std::string& file, const std::string& text);

/// The JSON of a cache file written with `format` (its "format" field) into j; false when the
/// file is missing, not JSON or of another format (the caller computes afresh).
bool readCacheFile(const std::string& file, int format, nlohmann::json& j);

/// Where a calibration came from.
enum class CalibrationOrigin { File, Cache, Identified, None };

/// Calibrates sm (assembled without laws) from the read-only `file` when it holds this model's
/// key ("": none), else from the cache, else by identification (then written to the cache); puts
/// the laws in and notes what it did, a file passed over and why. Returns where the laws came
/// from (None: the identification failed, the spans keep the joints' stiffness); `path` receives
/// the file read or the cache file ("" when none).
CalibrationOrigin calibrateSpanModel(SpanModel& sm, const std::string& file, std::string* path = nullptr);

/// The same without a read-only file; `fromCache` says whether the cache held it.
void calibrateSpanModel(SpanModel& sm, bool* fromCache = nullptr, std::string* file = nullptr);

/// Writes sm's calibration (from the cache, else identified and written to the cache too) into
/// `file` in the cache's format with its key: the read-only file an FMU carries. Notes what it
/// did in sm.notes and returns where the calibration came from (Cache or Identified); throws
/// std::runtime_error when the drive cannot be calibrated or the file cannot be written.
CalibrationOrigin writeCalibrationFile(SpanModel& sm, const std::string& file);

}  // namespace chaindrive::span
