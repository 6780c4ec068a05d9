// fmi_call_fuzz: random FMI 2.0 call sequences against ChainDrive.fmu's C interface, for the
// sanitizer build (./run.sh test runs it as the ctest FmiCallFuzz there). The FMU sources are
// linked into this program and the fmi2* functions called directly, so that the sanitizers see
// every allocation and report with full stacks, without preloading their runtimes into a host.
//
//   fmi_call_fuzz [--seed S] [--count N] [--batch B] [--timeout SECONDS] [--max-failures F]
//                 [--in-process] [--trace] [--source-dir DIR] [--work-dir DIR] [--drives]
//
// --drives: every sequence is one of random drive descriptions (Plan::Drive, drive_mutations.h)
// through the export's files and the FMU's instantiation and initialization.
//
// Sequence k runs with seed S + k; a failing sequence is printed with its seed and replays alone
// with --seed <its seed> --count 1. Exit status 0 when every sequence passed.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "description/fields.h"
#include "interface/fmu_files.h"

#include "fuzz_supervisor.h"
#include "fuzz_values.h"

namespace {

using namespace chaindrive::fuzz;
using namespace chaindrive;

// Measured so that the sanitizer stage of ./run.sh test (build, ctest, this fuzz) stays within
// about 12 minutes on 2 cores; see docs/tests.md.
constexpr std::uint64_t kDefaultCount = 3000;

void usage() {
  std::fprintf(stderr,
               "usage: fmi_call_fuzz [--seed S] [--count N] [--batch B] [--timeout SECONDS] [--max-failures F]\n"
               "                     [--in-process] [--trace] [--source-dir DIR] [--work-dir DIR] [--drives]\n"
               "  --seed S          sequence k runs with seed S + k (default 1)\n"
               "  --count N         number of sequences (default %" PRIu64 ")\n"
               "  --batch B         sequences per child process (default 100)\n"
               "  --timeout S       a sequence making no progress for S seconds is a hang (default 60)\n"
               "  --max-failures F  stop after F failing sequences (default 10)\n"
               "  --in-process      run in this process (for a debugger; a crash ends the run)\n"
               "  --trace           print every FMI call with its status and the FMU's message\n"
               "  --source-dir DIR  the source tree (drive files; default %s)\n"
               "  --work-dir DIR    where the FMUs' resources are written (default %s; one per\n"
               "                    program running at the same time)\n"
               "  --drives          random drive descriptions instead of call sequences: each through the\n"
               "                    export's files, the FMU's instantiation and initialization\n",
               kDefaultCount, CHAINDRIVE_SOURCE_DIR, CHAINDRIVE_FUZZ_WORK_DIR);
}

bool parseOptions(int argc, char** argv, FuzzOptions& o, std::string& sourceDir, std::string& workDir, bool& drives) {
  o.count = kDefaultCount;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--in-process") o.inProcess = true;
    else if (arg == "--drives") drives = true;
    else if (arg == "--trace") o.trace = true;
    else if (arg == "--seed" && hasValue) o.seed = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--count" && hasValue) o.count = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--batch" && hasValue) o.batch = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--timeout" && hasValue) o.timeoutSeconds = std::strtod(argv[++i], nullptr);
    else if (arg == "--max-failures" && hasValue) o.maxFailures = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--source-dir" && hasValue) sourceDir = argv[++i];
    else if (arg == "--work-dir" && hasValue) workDir = argv[++i];
    else return false;
  }
  return o.timeoutSeconds > 0.0;
}

// The FMUs' resources folders (their drives and interface tables) written into workDir, as an
// exporter writes them, and the files of the source tree.
FuzzPaths pathsIn(const std::string& sourceDir, const std::string& workDir) {
  FuzzPaths p;
  writeFmuFiles(workDir + "/default", std::string(defaultDriveJson()));
  p.resourceDir = workDir + "/default/resources";
  p.driveFile = sourceDir + "/src/drives/default_drive.json";
  // the default drive with the spring-damper tensioner law, an FMU of its own: the method
  // combinations that take only that law (event-driven) run on it, with their bounded number of
  // steps; a random sequence that picks event-driven meets the default drive's hydraulic
  // tensioner and is refused (an event storm of a random sequence, unbounded, can take a minute
  // under the sanitizers)
  const std::string springDamper = sourceDir + "/tests/data/drives/default_drive_spring_damper.json";
  auto table = std::make_shared<DriveInterface>(writeFmuFiles(workDir + "/spring_damper", readDescriptionFile(springDamper)));
  p.springDamperResourceDir = workDir + "/spring_damper/resources";
  p.springDamperFile = springDamper;
  p.springDamperGuid = table->guid;
  p.springDamperVariables = fmu::protocolVariables(*table);
  p.springDamperInterface = table;
  p.notADriveFile = sourceDir + "/CMakeLists.txt";
  return p;
}

// The drives the drive plan mutates: the default, its spring-damper variant and the test drives.
void addDriveBases(const std::string& sourceDir, const std::string& workDir, FuzzPaths& p) {
  p.drivePlanOnly = true;
  p.driveWorkDir = workDir + "/drive";
  p.driveBases = {std::string(defaultDriveJson())};
  for (const char* file : {"/tests/data/drives/default_drive_spring_damper.json", "/tests/drives/dohc_8mm.json",
                           "/tests/drives/sohc_single_cam.json", "/tests/drives/diesel_pump.json", "/tests/drives/idler.json"})
    p.driveBases.push_back(readDescriptionFile(sourceDir + file));
}

void printSummary(const FuzzOptions& o, const FuzzTotals& t, double seconds, std::size_t failures) {
  const FuzzTotals::Reach all = t.all();
  std::printf("fmi_call_fuzz: %" PRIu64 " sequences, seeds %" PRIu64 "..%" PRIu64 " (--seed %" PRIu64 " --count %" PRIu64
              "), %.1f s wall\n",
              all.sequences, o.seed, o.seed + o.count - 1, o.seed, o.count, seconds);
  for (std::uint32_t p = 0; p < kPlanCount; ++p)
    std::printf("  plan %-12s %6" PRIu64 " sequences, %6" PRIu64 " initialized, %6" PRIu64 " completed a doStep\n",
                planName(p), t.plans[p].sequences, t.plans[p].initialized, t.plans[p].stepped);
  for (std::size_t c = 0; c < t.combinations.size(); ++c)
    std::printf("    %-40s %4" PRIu64 " sequences, %4" PRIu64 " initialized, %4" PRIu64 " completed a doStep\n",
                methodCombinationName(c).c_str(), t.combinations[c].sequences, t.combinations[c].initialized,
                t.combinations[c].stepped);
  std::printf("  reached initialization: %" PRIu64 " sequences (%" PRIu64 " initializations); completed a doStep: %" PRIu64
              " sequences (%" PRIu64 " doSteps)\n",
              all.initialized, t.initializations, all.stepped, t.completedSteps);
  if (t.plans[static_cast<std::uint32_t>(Plan::Drive)].sequences > 0)
    std::printf("  drives: %" PRIu64 " generated, %" PRIu64 " exported (the rest refused by the export with one line)\n",
                t.plans[static_cast<std::uint32_t>(Plan::Drive)].sequences, t.drivesExported);
  std::printf("  FMI calls: %" PRIu64 " (OK %" PRIu64 ", warning %" PRIu64 ", discard %" PRIu64 ", error %" PRIu64 ")\n",
              t.calls, t.statusCounts[0], t.statusCounts[1], t.statusCounts[2], t.statusCounts[3]);
  std::printf("  failing sequences: %zu\n", failures);
}

}  // namespace

int main(int argc, char** argv) {
  FuzzOptions options;
  std::string sourceDir = CHAINDRIVE_SOURCE_DIR;
  std::string workDir = CHAINDRIVE_FUZZ_WORK_DIR;
  bool drives = false;
  if (!parseOptions(argc, argv, options, sourceDir, workDir, drives)) {
    usage();
    return 2;
  }
  std::printf("fmi_call_fuzz: %" PRIu64 " sequences from seed %" PRIu64 "\n", options.count, options.seed);
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  FuzzTotals totals;
  if (const std::string wrong = fmu::checkDefaultValueReferences(); !wrong.empty()) {
    std::printf("fmi_call_fuzz: the default drive's interface changed: %s (tests/fuzz/fuzz_interface.h)\n", wrong.c_str());
    return 1;
  }
  FuzzPaths paths = pathsIn(sourceDir, workDir);
  if (drives) addDriveBases(sourceDir, workDir, paths);
  const std::vector<FuzzFailure> failures = runSequences(options, paths, totals);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  printSummary(options, totals, seconds, failures.size());
  for (const FuzzFailure& f : failures)
    std::printf("  seed %" PRIu64 ": %s (replay: --seed %" PRIu64 " --count 1)\n", f.seed, f.reason.c_str(), f.seed);
  return failures.empty() ? 0 : 1;
}
