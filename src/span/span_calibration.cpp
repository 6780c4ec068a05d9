#include "span/span_calibration.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "statics/preload.h"
#include "span/span_system.h"

namespace chaindrive::span {

namespace {

// The span model's static guide angle at rest without loads, with `slack` in span i.
double staticGuideAngle(SpanModel& sm, int span, double slack, int rotor, const InputValues& rest) {
  sm.spans[span].slack = slack;
  PreloadReport report;
  const std::vector<double> y = spanInitialState(sm, rest, PreloadOptions{}, report);
  if (!report.converged) throw std::runtime_error("span model: " + report.message);
  return y[sm.stateAngle[rotor]];
}

}  // namespace

void measureSeatingSlack(SpanModel& sm) {
  const Model& m = *sm.links;
  if (!m.tensioner.present || m.rotors[m.tensioner.rotor].isSprocket) {
    sm.notes.push_back("seating slack: not measured (no tensioned pivoting guide)");
    return;
  }
  const int rotor = m.tensioner.rotor;
  int span = -1;
  for (std::size_t i = 0; i < sm.spans.size(); ++i)
    if (sm.spans[i].table >= 0 && sm.tables[sm.spans[i].table].rotor == rotor) span = static_cast<int>(i);
  if (span < 0) return;
  // the link model's static guide angle at rest without loads
  InputValues rest;
  rest.loadTorque.assign(m.rotors.size(), 0.0);
  rest.supplyPressure = m.tensioner.hydraulic.supplyPressure;
  PreloadReport linkReport;
  const std::vector<double> yLink = initialState(m, rest, PreloadOptions{}, linkReport);
  const double target = yLink[m.rotors[rotor].stateAngle];
  // secant iterations on the slack
  double s0 = 0.0, s1 = 1e-4;
  double f0 = staticGuideAngle(sm, span, s0, rotor, rest) - target;
  double f1 = staticGuideAngle(sm, span, s1, rotor, rest) - target;
  for (int it = 0; it < 30 && std::fabs(f1) > 1e-9 && f1 != f0; ++it) {
    const double s2 = s1 - f1 * (s1 - s0) / (f1 - f0);
    s0 = s1;
    f0 = f1;
    s1 = s2;
    f1 = staticGuideAngle(sm, span, s1, rotor, rest) - target;
  }
  sm.spans[span].slack = s1;
  char line[200];
  std::snprintf(line, sizeof line, "seating slack %.4f mm in span %s: the tension guide at %.4f deg at rest, as in "
                "the link model (residual %.1e deg)", s1 * 1e3, sm.spans[span].name.c_str(),
                m.rotorOutputSign[rotor] * target * 57.29577951308232, f1 * 57.29577951308232);
  sm.notes.push_back(line);
}

}  // namespace chaindrive::span
