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
  double v = 0.0;
  try {
    v = std::stod(text, &pos);
  } catch (const std::exception&) {  // (std::stod's own message is only "stod")
    pos = 0;
  }
  if (pos == 0 || pos != text.size() || !std::isfinite(v))
    throw std::invalid_argument("option " + current_ + ": '" + text + "' is not a number");
  return v;
}

void printError(const char* tool, const std::string& message) { std::fprintf(stderr, "%s: %s\n", tool, message.c_str()); }

int userError(const char* tool, const std::string& message) {
  std::fprintf(stderr, "%s: error: %s\n", tool, message.c_str());
  return 2;
}

int argumentError(const char* tool, const std::string& message) {
  return userError(tool, message + " (" + tool + " --help shows the options)");
}

std::string oneLine(const DescriptionError& e) {
  std::string s;
  for (const std::string& p : e.problems()) s += (s.empty() ? "" : " | ") + p;
  return s.empty() ? e.what() : s;
}

DriveDescription loadDrive(const std::string& path) {
  return path.empty() ? defaultDriveDescription() : loadDriveDescription(path);
}

int Arguments::wholeNumber(int least, int most) {
  const std::string text = value();
  const double x = number(text);
  if (x != static_cast<double>(static_cast<long long>(x)) || x < least || x > most)
    throw std::invalid_argument("option " + current_ + ": '" + text + "' is not a whole number from " +
                                std::to_string(least) + " to " + std::to_string(most));
  return static_cast<int>(x);
}

}  // namespace chaindrive::cli
