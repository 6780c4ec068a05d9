#include "cli/arguments.h"

#include <cmath>
#include <stdexcept>

namespace chaindrive::cli {

bool Arguments::next() {
  if (++index_ >= argc_) return false;
  current_ = argv_[index_];
  help_ = current_ == "-h" || current_ == "--help";
  return !help_;
}

std::string Arguments::value() {
  if (!hasValue()) throw std::invalid_argument("option " + current_ + " needs a value");
  return argv_[++index_];
}

double Arguments::number(const std::string& text) const {
  std::size_t pos = 0;
  const double v = std::stod(text, &pos);
  if (pos != text.size() || !std::isfinite(v))
    throw std::invalid_argument("option " + current_ + ": '" + text + "' is not a number");
  return v;
}

void printError(const char* tool, const std::string& message) { std::fprintf(stderr, "%s: %s\n", tool, message.c_str()); }

DriveDescription loadDrive(const std::string& path) {
  return path.empty() ? defaultDriveDescription() : loadDriveDescription(path);
}

}  // namespace chaindrive::cli
