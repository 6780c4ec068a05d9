#include "fuzz_supervisor.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "fuzz_values.h"
#include "run/drive_defaults.h"

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

namespace chaindrive::fuzz {

void FuzzTotals::add(const SequenceStats& s) {
  Reach& plan = plans[std::min(s.plan, kPlanCount - 1)];
  ++plan.sequences;
  plan.initialized += s.initializations > 0;
  plan.stepped += s.completedSteps > 0;
  if (static_cast<Plan>(s.plan) == Plan::OtherMethod) {
    if (combinations.size() < methodCombinationCount()) combinations.resize(methodCombinationCount());
    Reach& c = combinations[std::min<std::size_t>(s.combination, combinations.size() - 1)];
    ++c.sequences;
    c.initialized += s.initializations > 0;
    c.stepped += s.completedSteps > 0;
  }
  calls += s.calls;
  initializations += s.initializations;
  completedSteps += s.completedSteps;
  drivesExported += s.driveExported;
  for (std::size_t i = 0; i < 4; ++i) statusCounts[i] += s.statusCounts[i];
}

FuzzTotals::Reach FuzzTotals::all() const {
  Reach sum;
  for (const Reach& r : plans) {
    sum.sequences += r.sequences;
    sum.initialized += r.initialized;
    sum.stepped += r.stepped;
  }
  return sum;
}

namespace {

// The message of a child: a sequence begins (stats empty) or ends. Smaller than PIPE_BUF, so a
// write is atomic and the parent never sees half a record.
struct Record {
  std::uint64_t index = 0;
  std::uint32_t ended = 0;
  std::uint32_t leaked = 0;      // LeakSanitizer reported leaks of the group ending here; the child stops
  std::uint64_t groupFirst = 0;  // first sequence of that group
  SequenceStats stats;
};

// A leak check costs some 35 ms under the sanitizers (half a sequence): the child checks after
// every group of sequences, and the sequences of a leaking group are rerun alone.
constexpr std::uint64_t kLeakCheckGroup = 10;

// What the parent saw of one child process.
struct ChildRun {
  std::optional<std::uint64_t> running;  // begun and not ended when the child stopped
  std::optional<std::uint64_t> leakFirst, leakLast;  // the group whose leaks stopped the child
  std::vector<std::uint64_t> violating;  // sequences that failed an invariant
  bool hung = false;
  int waitStatus = 0;
  bool clean() const { return !hung && WIFEXITED(waitStatus) && WEXITSTATUS(waitStatus) == 0; }
};

bool writeAll(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

bool readAll(int fd, void* data, std::size_t size) {
  char* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = read(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// Whether memory allocated since the last check is unreachable now; LeakSanitizer prints the
// allocation stacks. A sequence frees everything it made, so a leak belongs to the sequences run
// since the last check.
bool leakedSinceLastCheck() {
#if defined(__SANITIZE_ADDRESS__)
  return __lsan_do_recoverable_leak_check() != 0;
#else
  return false;
#endif
}

[[noreturn]] void runChild(int fd, const FuzzOptions& o, const FuzzPaths& paths, std::uint64_t first,
                           std::uint64_t last) {
  for (std::uint64_t i = first; i < last; ++i) {
    Record r;
    r.index = i;
    if (!writeAll(fd, &r, sizeof r)) std::_Exit(3);
    r.stats = runSequence(o.seed + i, paths, o.trace);
    r.ended = 1;
    r.groupFirst = i - (i - first) % kLeakCheckGroup;
    const bool groupEnds = i + 1 == last || (i + 1 - first) % kLeakCheckGroup == 0;
    r.leaked = groupEnds && leakedSinceLastCheck() ? 1 : 0;
    if (!writeAll(fd, &r, sizeof r)) std::_Exit(3);
    if (r.leaked) std::_Exit(1);  // a later check would report the same leaks again
  }
  close(fd);
  std::exit(0);  // not _Exit: the leak checker runs at exit
}

// Reads the child's records until it closes the pipe or makes no progress for the timeout.
void watchChild(int fd, pid_t child, const FuzzOptions& o, FuzzTotals* totals, ChildRun& run) {
  const int timeoutMs = static_cast<int>(std::min(o.timeoutSeconds * 1000.0, 2e9));
  for (;;) {
    pollfd p{fd, POLLIN, 0};
    const int ready = poll(&p, 1, timeoutMs);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) {
      kill(child, SIGKILL);
      run.hung = true;
      return;
    }
    Record r;
    if (!readAll(fd, &r, sizeof r)) return;  // the child has ended
    if (!r.ended) {
      run.running = r.index;
      continue;
    }
    run.running.reset();
    if (totals) totals->add(r.stats);
    if (r.stats.violations > 0) run.violating.push_back(r.index);
    if (r.leaked) {
      run.leakFirst = r.groupFirst;
      run.leakLast = r.index;
    }
  }
}

ChildRun runInChild(const FuzzOptions& o, const FuzzPaths& paths, std::uint64_t first, std::uint64_t last,
                    FuzzTotals* totals) {
  int fds[2];
  if (pipe(fds) != 0) {
    std::perror("fmi_call_fuzz: pipe");
    std::exit(2);
  }
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t child = fork();
  if (child < 0) {
    std::perror("fmi_call_fuzz: fork");
    std::exit(2);
  }
  if (child == 0) {
    close(fds[0]);
    runChild(fds[1], o, paths, first, last);
  }
  close(fds[1]);
  ChildRun run;
  watchChild(fds[0], child, o, totals, run);
  close(fds[0]);
  while (waitpid(child, &run.waitStatus, 0) < 0 && errno == EINTR) {
  }
  return run;
}

std::string describe(const ChildRun& run, double timeoutSeconds) {
  if (run.hung) {
    char text[96];
    std::snprintf(text, sizeof text, "no progress for %g s (a hang; the process was killed)", timeoutSeconds);
    return text;
  }
  if (WIFSIGNALED(run.waitStatus)) return "process killed by signal " + std::to_string(WTERMSIG(run.waitStatus));
  if (WIFEXITED(run.waitStatus))
    return "process exited with status " + std::to_string(WEXITSTATUS(run.waitStatus)) + " (sanitizer report above)";
  return "process ended abnormally";
}

class Supervisor {
 public:
  Supervisor(const FuzzOptions& o, const FuzzPaths& paths, FuzzTotals& totals) : o_(o), paths_(paths), totals_(totals) {}
  std::vector<FuzzFailure> run();

 private:
  std::uint64_t runBatch(std::uint64_t first, std::uint64_t last);
  void attributeFailure(std::uint64_t first, std::uint64_t last, const std::string& reason);
  void fail(std::uint64_t index, const std::string& reason);

  const FuzzOptions& o_;
  const FuzzPaths& paths_;
  FuzzTotals& totals_;
  std::vector<FuzzFailure> failures_;
};

namespace {

void ignoreLogMessage(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...) {}

// The span model's calibration is computed once per drive and source and then read from the
// cache (span/calibration_cache.h): seconds in a release build, a minute or more under the
// sanitizers on a slow host, all of it inside one fmi2ExitInitializationMode. A sequence that
// picks the span fidelity with the cache cold looks hung to the watchdog, and a child killed
// before it writes the cache leaves it cold for the next. So the default drive's calibration is
// made here first, outside any watchdog; a sequence then pays for it only when it sets
// parameters the calibration depends on. (Nothing is written where the cache is switched off or
// not writable: the sequences then pay as before.)
void warmSpanCalibration(const FuzzPaths& paths) {
  fmi2CallbackFunctions callbacks{};
  callbacks.logger = ignoreLogMessage;
  const std::string location = "file://" + paths.resourceDir;  // (the default drive's FMU)
  fmi2Component c = fmi2Instantiate("span calibration", fmi2CoSimulation, fmu::kGuid, location.c_str(), &callbacks,
                                    fmi2False, fmi2False);
  if (!c) return;
  const fmi2ValueReference fidelity = fmu::kFidelity;
  const fmi2String span = "span";
  const bool initialized = fmi2SetString(c, &fidelity, 1, &span) == fmi2OK &&
                           fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 1.0) == fmi2OK &&
                           fmi2EnterInitializationMode(c) == fmi2OK && fmi2ExitInitializationMode(c) == fmi2OK;
  if (initialized) fmi2Terminate(c);
  fmi2FreeInstance(c);
}

// Likewise the spring-damper variant's link steps: another drive than the default, so that a
// sequence on its FMU with solver.step 0 has its step checked by the probe (run/step_probe.h), a
// ladder of 0.2 s runs, seconds each under the sanitizers; made here and cached, outside any watchdog.
void warmStepProbes(const FuzzPaths& paths) {
  try {
    const Model m = assemble(loadDriveDescription(paths.springDamperFile));
    for (const bool clearanceOrRigid : {false, true})
      driveRow(m, solverDefaults(Scene::TimingDrive, Fidelity::Link, clearanceOrRigid));
  } catch (const std::exception& e) {
    std::printf("fmi_call_fuzz: the spring-damper drive's step probe was not made beforehand: %s\n", e.what());
  }
}

}  // namespace

std::vector<FuzzFailure> Supervisor::run() {
  warmSpanCalibration(paths_);
  if (!paths_.drivePlanOnly) warmStepProbes(paths_);  // (the drive plan gives its step: no probe)
  std::uint64_t next = 0;
  while (next < o_.count && failures_.size() < o_.maxFailures)
    next = runBatch(next, std::min(o_.count, next + std::max<std::uint64_t>(o_.batch, 1)));
  return failures_;
}

// Runs [first, last) in one child; returns the index to continue from.
std::uint64_t Supervisor::runBatch(std::uint64_t first, std::uint64_t last) {
  const ChildRun run = runInChild(o_, paths_, first, last, &totals_);
  for (std::uint64_t index : run.violating) fail(index, "an invariant failed (see above)");
  if (run.leakFirst) {
    attributeFailure(*run.leakFirst, *run.leakLast + 1, "memory leak (LeakSanitizer report above)");
    return *run.leakLast + 1;
  }
  if (run.clean()) return last;
  if (run.running) {
    fail(*run.running, describe(run, o_.timeoutSeconds));
    return *run.running + 1;
  }
  attributeFailure(first, last, describe(run, o_.timeoutSeconds) + " at exit");
  return last;
}

// A child found a leak after several sequences, or failed at exit: rerun them alone (each child
// then checks for leaks after its one sequence) to name the one that fails.
void Supervisor::attributeFailure(std::uint64_t first, std::uint64_t last, const std::string& reason) {
  std::printf("fmi_call_fuzz: %s in sequences %" PRIu64 "..%" PRIu64 "; rerunning them one by one\n", reason.c_str(),
              o_.seed + first, o_.seed + last - 1);
  for (std::uint64_t i = first; i < last; ++i) {
    const ChildRun alone = runInChild(o_, paths_, i, i + 1, nullptr);
    if (alone.leakFirst) return fail(i, "memory leak (LeakSanitizer report above)");
    if (!alone.clean()) return fail(i, describe(alone, o_.timeoutSeconds));
  }
  fail(first, reason + ", but no sequence of the group fails alone");
}

void Supervisor::fail(std::uint64_t index, const std::string& reason) {
  const std::uint64_t seed = o_.seed + index;
  for (FuzzFailure& known : failures_) {
    if (known.seed != seed) continue;
    known.reason += "; " + reason;
    return;
  }
  std::printf("fmi_call_fuzz: FAILED sequence with seed %" PRIu64 ": %s; replay: fmi_call_fuzz --seed %" PRIu64
              " --count 1\n",
              seed, reason.c_str(), seed);
  std::fflush(stdout);
  failures_.push_back({seed, reason});
}

std::vector<FuzzFailure> runInThisProcess(const FuzzOptions& o, const FuzzPaths& paths, FuzzTotals& totals) {
  std::vector<FuzzFailure> failures;
  for (std::uint64_t i = 0; i < o.count && failures.size() < o.maxFailures; ++i) {
    const SequenceStats s = runSequence(o.seed + i, paths, o.trace);
    totals.add(s);
    if (s.violations > 0) failures.push_back({o.seed + i, "an invariant failed (see above)"});
  }
  return failures;
}

}  // namespace

std::vector<FuzzFailure> runSequences(const FuzzOptions& options, const FuzzPaths& paths, FuzzTotals& totals) {
  if (options.inProcess) return runInThisProcess(options, paths, totals);
  Supervisor supervisor(options, paths, totals);
  return supervisor.run();
}

}  // namespace chaindrive::fuzz
