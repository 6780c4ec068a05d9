/* The main job's closed loop at compiled speed (harness/fmu/loop.py loads it with ctypes): on an
 * FMU instance fmpy has instantiated and initialized, for every communication step it reads the
 * sprockets' angles, looks the inputs up in their tables at those angles, sets them, calls
 * fmi2DoStep and records the time, the outputs and the inputs in one row. The same arithmetic as
 * the Python loop (harness/job.py: np.interp with a period, math.degrees), in the same order, so
 * both loops give the same bits (a test). Nothing here allocates or prints: a refused call returns
 * its status and the step, and the caller reads the FMU's log. */
#include <math.h>
#include <stddef.h>
#include <time.h>

#include "fmi2FunctionTypes.h"

#define PI 3.14159265358979323846 /* Python's math.pi, and math.degrees' 180 / pi */

/* An input's value from the angles [deg] read before the step. */
enum TermKind {
  TERM_CONSTANT = 0, /* value */
  TERM_SHIFTED = 1,  /* table at angle + a (a sprocket's own-angle table and its phase) */
  TERM_SCALED = 2,   /* table at angle * a (a crank-angle table turned by the sprocket's ratio) */
  TERM_SPEED = 3     /* a * table at angle, the table in rpm (rpm != 0) or rad/s */
};

typedef struct {
  int kind, angle, rpm, n; /* n: points of the table as np.interp extends it over one period */
  const double* x;         /* [deg] np.interp's sorted abscissae, one point beyond each end */
  const double* y;
  double period, a, value;
} Term;

/* A run-up (harness/sweep/cases.py runup_inputs): the mean speed ramped from rpm to rpmEnd over
 * rampTime from rampStart, every input blended linearly in engine speed between its values at the
 * two nearest tabulated speeds, the crankshaft speed's fluctuation relative to each table's speed. */
typedef struct {
  int nSpeeds, speedInput; /* [rpm] the tabulated speeds, ascending; the crankshaft speed's input */
  const double* speeds;
  const Term* terms; /* nSpeeds rows of the loop's nInputs terms */
  double rpm, rpmEnd, rampStart, rampTime;
} RunUp;

typedef struct {
  fmi2Component component;
  fmi2DoStepTYPE* doStep;
  fmi2SetRealTYPE* setReal;
  fmi2GetRealTYPE* getReal;
  fmi2GetIntegerTYPE* getInteger;
  double step;
  int nAngles, nInputs, nReals, nIntegers, nColumns;
  const fmi2ValueReference *angleRefs, *inputRefs, *realRefs, *integerRefs;
  const int *realColumns, *integerColumns; /* the outputs' columns of a row; the inputs' follow them */
  int firstInputColumn;
  const Term* terms;
  const RunUp* runUp; /* or NULL: the terms alone */
  double *angles, *inputs, *reals; /* work areas of nAngles, nInputs, nReals and nIntegers */
  fmi2Integer* integers;
  int wallClock; /* a step's time by the wall clock (the FMU's step on several threads), else this thread's CPU */
} Loop;

/* Python's max and min (the first argument unless the second is greater, or smaller) */
static double pyMax(double a, double b) { return b > a ? b : a; }
static double pyMin(double a, double b) { return b < a ? b : a; }
static double radPerSecond(double rpm) { return rpm * 2.0 * PI / 60.0; }

/* numpy's remainder of a float by a positive period: the result in [0, period) */
static double remainderOf(double a, double period) {
  double mod = fmod(a, period);
  if (mod != 0.0) {
    if ((period < 0.0) != (mod < 0.0)) mod += period;
  } else {
    mod = copysign(0.0, period);
  }
  return mod;
}

/* numpy's compiled interp at one abscissa of a table extended over the period (np.interp's own
 * preparation, harness/fmu/loop.py): the index i with x[i] <= key < x[i + 1], then its line */
static double interpolated(const Term* t, double angle) {
  const double key = remainderOf(angle, t->period);
  const double *x = t->x, *y = t->y;
  const int n = t->n;
  if (isnan(key)) return key;
  if (key > x[n - 1]) return y[n - 1];
  if (key < x[0]) return y[0];
  int lo = 0, hi = n - 1; /* x[lo] <= key, and key < x[hi] or hi the last */
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    if (key < x[mid])
      hi = mid;
    else
      lo = mid;
  }
  const int j = key >= x[n - 1] ? n - 1 : lo;
  if (j == n - 1 || x[j] == key) return y[j];
  const double slope = (y[j + 1] - y[j]) / (x[j + 1] - x[j]);
  double value = slope * (key - x[j]) + y[j];
  if (isnan(value)) {
    value = slope * (key - x[j + 1]) + y[j + 1];
    if (isnan(value) && y[j] == y[j + 1]) value = y[j];
  }
  return value;
}

/* one input's value at the angles [deg] read (exported for tests/python/test_loop.py) */
double inputValue(const Term* t, const double* angles) {
  const double angle = t->kind == TERM_CONSTANT ? 0.0 : angles[t->angle];
  switch (t->kind) {
    case TERM_SHIFTED:
      return interpolated(t, angle + t->a);
    case TERM_SCALED:
      return interpolated(t, angle * t->a);
    case TERM_SPEED: {
      double v = interpolated(t, angle);
      if (t->rpm) v = radPerSecond(v);
      return t->a * v;
    }
    default:
      return t->value;
  }
}

static void runUpInputs(const Loop* L, const RunUp* R, double t) {
  const double ramp = pyMin(pyMax((t - R->rampStart) / R->rampTime, 0.0), 1.0);
  const double rpm = R->rpm + (R->rpmEnd - R->rpm) * ramp;
  const int n = R->nSpeeds;
  int above = 0; /* numpy's searchsorted: the first speed at or above rpm */
  while (above < n && R->speeds[above] < rpm) ++above;
  const int last = n - 2 > 0 ? n - 2 : 0;
  const int i = above - 1 < 0 ? 0 : (above - 1 > last ? last : above - 1), i2 = i + 1 < n - 1 ? i + 1 : n - 1;
  const double r1 = R->speeds[i], r2 = R->speeds[i2];
  const double w = r2 > r1 ? pyMin(pyMax((rpm - r1) / (r2 - r1), 0.0), 1.0) : 0.0;
  for (int k = 0; k < L->nInputs; ++k) {
    const double a1 = inputValue(&R->terms[i * L->nInputs + k], L->angles);
    const double a2 = inputValue(&R->terms[i2 * L->nInputs + k], L->angles);
    if (k == R->speedInput)
      L->inputs[k] = radPerSecond(rpm) * ((1.0 - w) * (a1 / radPerSecond(r1)) + w * (a2 / radPerSecond(r2)));
    else
      L->inputs[k] = (1.0 - w) * a1 + w * a2;
  }
}

static double stepClock(const Loop* L) {
  struct timespec ts;
  clock_gettime(L->wallClock ? CLOCK_MONOTONIC : CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One step k: the inputs from the angles, fmi2DoStep over [k h, (k + 1) h], the row. Returns the
 * first status worse than fmi2Warning, and which call gave it (*call: 1 set, 2 step, 3 get). */
static fmi2Status oneStep(const Loop* L, long k, double* row, double* cpu, int* call) {
  fmi2Status s = L->getReal(L->component, L->angleRefs, (size_t)L->nAngles, L->angles);
  if (s > fmi2Warning) return *call = 3, s;
  for (int i = 0; i < L->nAngles; ++i) L->angles[i] = L->angles[i] * (180.0 / PI);
  if (L->runUp)
    runUpInputs(L, L->runUp, (double)k * L->step);
  else
    for (int i = 0; i < L->nInputs; ++i) L->inputs[i] = inputValue(&L->terms[i], L->angles);
  s = L->setReal(L->component, L->inputRefs, (size_t)L->nInputs, L->inputs);
  if (s > fmi2Warning) return *call = 1, s;
  const double cpu0 = stepClock(L);
  s = L->doStep(L->component, (double)k * L->step, L->step, fmi2True);
  *cpu = stepClock(L) - cpu0;
  if (s > fmi2Warning) return *call = 2, s;
  s = L->getReal(L->component, L->realRefs, (size_t)L->nReals, L->reals);
  if (s <= fmi2Warning && L->nIntegers > 0)
    s = L->getInteger(L->component, L->integerRefs, (size_t)L->nIntegers, L->integers);
  if (s > fmi2Warning) return *call = 3, s;
  row[0] = (double)(k + 1) * L->step;
  for (int i = 0; i < L->nReals; ++i) row[L->realColumns[i]] = L->reals[i];
  for (int i = 0; i < L->nIntegers; ++i) row[L->integerColumns[i]] = (double)L->integers[i];
  for (int i = 0; i < L->nInputs; ++i) row[L->firstInputColumn + i] = L->inputs[i];
  return fmi2OK;
}

/* Steps k0 .. k0 + steps - 1, row k + 1 of `rows` for step k, each step's CPU time inside
 * fmi2DoStep into cpus[k]; stops after the row whose column stopColumn (>= 0) reaches stopAt.
 * Returns the steps done; *status and *call the refusal that ended them early (else fmi2OK). */
long runSteps(const Loop* L, long k0, long steps, int stopColumn, double stopAt, double* rows, double* cpus,
              int* status, int* call) {
  *status = fmi2OK;
  *call = 0;
  for (long k = k0; k < k0 + steps; ++k) {
    double* row = rows + (size_t)(k + 1) * (size_t)L->nColumns;
    const fmi2Status s = oneStep(L, k, row, &cpus[k], call);
    if (s != fmi2OK && s != fmi2Warning) return *status = (int)s, k - k0;
    if (stopColumn >= 0 && row[stopColumn] >= stopAt) return k - k0 + 1;
  }
  return steps;
}
