/* A minimal FMI 2.0 co-simulation master that replays a scenario: it loads an FMU's binary,
 * instantiates it with a given resource URI (Windows importers write file:///C:/...), sets the
 * parameters, then for every communication step sets the inputs of that step and calls
 * fmi2DoStep, and writes the outputs after the initialization and after every step. Every
 * number crosses as its 64 bits in hexadecimal, so nothing is rounded on the way.
 *
 *   fmi2_master <binary> <guid> <resource URI> <scenario> <outputs>
 *
 * scenario (whitespace-separated tokens):
 *   parameters <n>  then n times: <vr> r <bits> | <vr> i <integer> | <vr> b <0|1> | <vr> s <string>
 *   inputs <n> <vr>...    reals <n> <vr>...    integers <n> <vr>...
 *   steps <count> <step size bits>
 *   then count + 1 rows of the inputs' bits: row 0 before the initialization, row k before step k
 * outputs: count + 1 lines, each the reals' bits then the integers, after the initialization and
 * after every step. The FMU's log goes to standard output, one message per line.
 *
 * The last line says how many steps ran and the CPU time of the thread inside fmi2DoStep, summed
 * over the steps (a C master's view of the FMU's cost, without an interpreter's call overhead).
 *
 * harness/package/compare.py builds it with zig (for win64, run under wine) and replays there
 * the inputs of a linux64 closed-loop run, so that both platforms see the same input bits;
 * harness/bench/fidelity_cost.py builds it for linux64 and times the FMU's models with it. */
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _WIN32
#include <windows.h>
#else
#include <dlfcn.h>
#include <time.h>
#endif

#include "fmi2Functions.h"

#define MAX_VARIABLES 256

static void logMessage(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status, fmi2String category,
                       fmi2String message, ...) {
  (void)env;
  (void)instance;
  printf("%d %s %s\n", (int)status, category, message);
  fflush(stdout);
}

/* every failure says what failed, on standard output, before the exit code 1 */
static void fail(const char* format, ...) {
  va_list args;
  va_start(args, format);
  printf("fmi2_master: ");
  vprintf(format, args);
  printf("\n");
  va_end(args);
  fflush(stdout);
  exit(1);
}

static double fromBits(const char* token) {
  uint64_t bits = strtoull(token, NULL, 16);
  double x;
  memcpy(&x, &bits, sizeof x);
  return x;
}

static void writeBits(FILE* out, double x) {
  uint64_t bits;
  memcpy(&bits, &x, sizeof bits);
  fprintf(out, "%016llx ", (unsigned long long)bits);
}

/* [s] the CPU time of the calling thread */
static double threadCpu(void) {
#ifdef _WIN32
  FILETIME created, exited, kernel, user;
  GetThreadTimes(GetCurrentThread(), &created, &exited, &kernel, &user);
  const double ticks = (double)(((uint64_t)kernel.dwHighDateTime << 32 | kernel.dwLowDateTime) +
                                ((uint64_t)user.dwHighDateTime << 32 | user.dwLowDateTime));
  return ticks * 1e-7; /* 100 ns ticks */
#else
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
#endif
}

static void* symbol(void* library, const char* name) {
#ifdef _WIN32
  void* f = (void*)GetProcAddress((HMODULE)library, name);
#else
  void* f = dlsym(library, name);
#endif
  if (!f) fail("%s not found", name);
  return f;
}

static void* load(const char* path) {
#ifdef _WIN32
  void* library = (void*)LoadLibraryA(path);
#else
  void* library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
#endif
  if (!library) fail("cannot load %s", path);
  return library;
}

static int readCount(FILE* in, const char* keyword, int max) {
  char word[64];
  int n = -1;
  if (fscanf(in, "%63s %d", word, &n) != 2 || strcmp(word, keyword) != 0 || n < 0 || n > max)
    fail("scenario: expected '%s <count>'", keyword);
  return n;
}

static void readReferences(FILE* in, const char* keyword, fmi2ValueReference* vr, int* n) {
  *n = readCount(in, keyword, MAX_VARIABLES);
  for (int i = 0; i < *n; ++i)
    if (fscanf(in, "%u", &vr[i]) != 1) fail("scenario: a value reference expected");
}

static int check(int status, const char* what) {
  if (status > fmi2Warning) fail("%s returned %d", what, status);
  return status;
}

/* parameters: one by one with the setter of their type */
static void setParameters(void* library, fmi2Component c, FILE* in) {
  fmi2SetRealTYPE* setReal = (fmi2SetRealTYPE*)symbol(library, "fmi2SetReal");
  fmi2SetIntegerTYPE* setInteger = (fmi2SetIntegerTYPE*)symbol(library, "fmi2SetInteger");
  fmi2SetBooleanTYPE* setBoolean = (fmi2SetBooleanTYPE*)symbol(library, "fmi2SetBoolean");
  fmi2SetStringTYPE* setString = (fmi2SetStringTYPE*)symbol(library, "fmi2SetString");
  const int n = readCount(in, "parameters", MAX_VARIABLES);
  for (int i = 0; i < n; ++i) {
    fmi2ValueReference vr;
    char type[4], value[1024];
    if (fscanf(in, "%u %3s %1023s", &vr, type, value) != 3) fail("scenario: a parameter expected");
    if (type[0] == 'r') {
      const fmi2Real x = fromBits(value);
      check(setReal(c, &vr, 1, &x), "fmi2SetReal");
    } else if (type[0] == 'i' || type[0] == 'b') {
      const int x = atoi(value);
      check(type[0] == 'i' ? setInteger(c, &vr, 1, &x) : setBoolean(c, &vr, 1, &x), "fmi2SetInteger/Boolean");
    } else {
      const fmi2String x = value;
      check(setString(c, &vr, 1, &x), "fmi2SetString");
    }
  }
}

static void setInputs(fmi2SetRealTYPE* setReal, fmi2Component c, FILE* in, const fmi2ValueReference* vr, int n) {
  fmi2Real values[MAX_VARIABLES];
  char token[32];
  for (int i = 0; i < n; ++i) {
    if (fscanf(in, "%31s", token) != 1) fail("scenario: an input value expected");
    values[i] = fromBits(token);
  }
  if (n > 0) check(setReal(c, vr, (size_t)n, values), "fmi2SetReal");
}

static void writeOutputs(void* library, fmi2Component c, FILE* out, const fmi2ValueReference* realVr, int nReal,
                         const fmi2ValueReference* intVr, int nInt) {
  fmi2GetRealTYPE* getReal = (fmi2GetRealTYPE*)symbol(library, "fmi2GetReal");
  fmi2GetIntegerTYPE* getInteger = (fmi2GetIntegerTYPE*)symbol(library, "fmi2GetInteger");
  fmi2Real reals[MAX_VARIABLES];
  fmi2Integer integers[MAX_VARIABLES];
  if (nReal > 0) check(getReal(c, realVr, (size_t)nReal, reals), "fmi2GetReal");
  if (nInt > 0) check(getInteger(c, intVr, (size_t)nInt, integers), "fmi2GetInteger");
  for (int i = 0; i < nReal; ++i) writeBits(out, reals[i]);
  for (int i = 0; i < nInt; ++i) fprintf(out, "%d ", integers[i]);
  fprintf(out, "\n");
}

int main(int argc, char** argv) {
  if (argc != 6) {
    printf("usage: fmi2_master <binary> <guid> <resource URI> <scenario> <outputs>\n");
    return 2;
  }
  FILE* in = fopen(argv[4], "r");
  FILE* out = fopen(argv[5], "w");
  if (!in || !out) fail("cannot open %s or %s", argv[4], argv[5]);
  void* library = load(argv[1]);
  fmi2InstantiateTYPE* instantiate = (fmi2InstantiateTYPE*)symbol(library, "fmi2Instantiate");
  fmi2CallbackFunctions callbacks = {logMessage, calloc, free, NULL, NULL};
  fmi2Component c = instantiate("master", fmi2CoSimulation, argv[2], argv[3], &callbacks, fmi2False, fmi2True);
  if (!c) fail("fmi2Instantiate failed");
  /* the order of harness/fmu/fmu.py's Slave.initialize: experiment, parameters, inputs */
  check(((fmi2SetupExperimentTYPE*)symbol(library, "fmi2SetupExperiment"))(c, fmi2False, 0.0, 0.0, fmi2False, 0.0),
        "fmi2SetupExperiment");
  setParameters(library, c, in);
  fmi2ValueReference inputVr[MAX_VARIABLES], realVr[MAX_VARIABLES], intVr[MAX_VARIABLES];
  int nInputs, nReal, nInt;
  readReferences(in, "inputs", inputVr, &nInputs);
  readReferences(in, "reals", realVr, &nReal);
  readReferences(in, "integers", intVr, &nInt);
  const int steps = readCount(in, "steps", 100000000);
  char token[32];
  if (fscanf(in, "%31s", token) != 1) fail("scenario: the step size expected");
  const double h = fromBits(token);
  fmi2SetRealTYPE* setReal = (fmi2SetRealTYPE*)symbol(library, "fmi2SetReal");
  fmi2DoStepTYPE* doStep = (fmi2DoStepTYPE*)symbol(library, "fmi2DoStep");
  setInputs(setReal, c, in, inputVr, nInputs);
  check(((fmi2EnterInitializationModeTYPE*)symbol(library, "fmi2EnterInitializationMode"))(c),
        "fmi2EnterInitializationMode");
  check(((fmi2ExitInitializationModeTYPE*)symbol(library, "fmi2ExitInitializationMode"))(c),
        "fmi2ExitInitializationMode");
  writeOutputs(library, c, out, realVr, nReal, intVr, nInt);
  double doStepCpu = 0.0;
  for (int k = 0; k < steps; ++k) {
    setInputs(setReal, c, in, inputVr, nInputs);
    const double cpu0 = threadCpu();
    const int status = doStep(c, k * h, h, fmi2True);
    doStepCpu += threadCpu() - cpu0;
    check(status, "fmi2DoStep");
    writeOutputs(library, c, out, realVr, nReal, intVr, nInt);
  }
  ((fmi2FreeInstanceTYPE*)symbol(library, "fmi2FreeInstance"))(c);
  fclose(out);
  printf("fmi2_master: %d steps done, %.9f s CPU inside fmi2DoStep\n", steps, doStepCpu);
  fflush(stdout);
  return 0;
}
