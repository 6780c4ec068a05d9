// What the command-line tools share: reading the command line, the drive to work on, and how a
// problem is reported (messages on stderr prefixed with the tool's name; a user's mistake, a bad
// command line or an invalid description file, in one line "<tool>: error: ..." with exit code 2;
// a failed run with exit code 1).
#pragma once

#include <cstdio>
#include <string>

#include "description/drive_description.h"

namespace chaindrive::cli {

/// The arguments argv[1..] one after the other, and the values of options.
class Arguments {
 public:
  Arguments(int argc, char** argv) : argc_(argc), argv_(argv) {}

  /// Moves to the next argument; false after the last one, and at -h or --help (then help()).
  bool next();
  bool help() const { return help_; }
  /// The argument moved to (an option, whose values value() and number() consume).
  const std::string& current() const { return current_; }
  /// Another argument follows.
  bool hasValue() const { return index_ + 1 < argc_; }
  /// The next argument as the value of the current option; throws std::invalid_argument
  /// ("option X needs a value") if there is none.
  std::string value();
  /// value() as a finite number.
  double number() { return number(value()); }
  /// Text of the current option's value (or of a part of it) as a finite number; throws
  /// std::invalid_argument ("option X: 'S' is not a number").
  double number(const std::string& text) const;
  /// value() as a choice (choice.h); throws std::invalid_argument ("option X: 'S' is unknown;
  /// allowed: ...").
  /// value() as a whole number from `least` to `most`; throws std::invalid_argument naming them.
  int wholeNumber(int least, int most);
  template <class E>
  E choice() {
    return parseChoice<E>(value(), "option " + current_);
  }

 private:
  int argc_;
  char** argv_;
  int index_ = 0;
  std::string current_;
  bool help_ = false;
};

/// "<tool>: <message>" on stderr.
void printError(const char* tool, const std::string& message);

/// A user's mistake: "<tool>: error: <message>" on stderr, one line; exit code 2.
int userError(const char* tool, const std::string& message);

/// A bad command line: userError with where the options are shown (-h, --help); exit code 2.
int argumentError(const char* tool, const std::string& message);

/// The problems of an invalid description in one line, " | " between them.
std::string oneLine(const DescriptionError& e);

/// The drive description of --drive FILE; the embedded default drive when `path` is empty.
DriveDescription loadDrive(const std::string& path);

/// Runs a tool's work and returns its exit code; an invalid description (a user's mistake) is
/// reported by userError with its problems (exit code 2), any other error as "<tool>: <what>"
/// (exit code 1).
template <class Work>
int reportingErrors(const char* tool, Work&& work) {
  try {
    return work();
  } catch (const DescriptionError& e) {
    return userError(tool, oneLine(e));
  } catch (const std::exception& e) {
    printError(tool, e.what());
    return 1;
  }
}

/// The main of a tool: its command line read by parse(Arguments&), which throws std::exception
/// for a bad argument (then argumentError, exit code 2); -h/--help: the usage text, exit code 0;
/// then work(what parse returned), its errors reported as by reportingErrors.
template <class Parse, class Work>
int runTool(const char* tool, int argc, char** argv, void (*usage)(), Parse&& parse, Work&& work) {
  Arguments args(argc, argv);
  decltype(parse(args)) parsed;
  try {
    parsed = parse(args);
  } catch (const std::exception& e) {
    return argumentError(tool, e.what());
  }
  if (args.help()) {
    usage();
    return 0;
  }
  return reportingErrors(tool, [&] { return work(parsed); });
}

}  // namespace chaindrive::cli
