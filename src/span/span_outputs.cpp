#include "span/span_outputs.h"

#include <algorithm>
#include <cmath>

namespace chaindrive::span {

double tensionAt(const SpanModel& m, const SpanData& d, double s) {
  const ChainPath& path = m.links->path;
  const int seg = path.segmentAt(s);
  const PathSegment& sg = path.segments()[seg];
  const PathPart& part = m.pathParts[seg];
  const SpanState& sp = d.spans[part.span];
  if (part.kind == PathPart::Kind::Free) return sp.partTension(part.part);
  // on a wrap: from the tension arriving to the tension leaving, linear along the arc
  double f = sg.length > 0.0 ? (s - sg.start) / sg.length : 0.0;
  if (f < 0.0) f += path.length() / sg.length;
  f = std::min(std::max(f, 0.0), 1.0);
  const double in = part.kind == PathPart::Kind::Sprocket ? d.spans[part.spanIn].tensionTo : sp.partTension(part.part);
  const double outT = part.kind == PathPart::Kind::Sprocket ? sp.tensionFrom : sp.partTension(part.part + 1);
  return (1.0 - f) * in + f * outT;
}

namespace {

// The monitored link moves with the chain leaving the first span's sprocket.
void monitoredLinkOutputs(const SpanModel& m, const SpanData& d, int monitoredLink, Outputs& out) {
  const Model& lm = *m.links;
  const int n = lm.chain.links;
  const int L = (monitoredLink >= 0 && monitoredLink < n) ? monitoredLink : lm.monitoredLink;
  const Span& first = m.spans[0];
  const double theta = lm.sense * (d.rotorAngle[first.from.rotor] - lm.rotors[first.from.rotor].initialAngle);
  double r;
  const double travel = chainPassed(first.from, theta, r);
  const double len = lm.path.length();
  double s = std::fmod(m.monitoredStart[L] + travel, len);
  if (s < 0.0) s += len;
  out.linkTension = tensionAt(m, d, s);
  out.linkPosition = lm.path.point(s);
  out.linkNormalForce = out.linkSprocketForce = out.linkGuideForce = 0.0;
}

}  // namespace

void computeSpanOutputs(const SpanModel& m, SpanData& d, const InputSignal& in, double t, const double* y,
                        int monitoredLink, Outputs& out) {
  d.quasiStatic = d.chamber.held = false;
  evaluateSpanForces(m, d, in, t, y);
  const Model& lm = *m.links;
  out.time = t;
  out.rotorTorque = d.chainTorque;  // same size after the first call: no allocation
  finishRotorOutputs(lm, d.rotorAngle, d.rotorRate, m.chainImpulse, y, out);
  out.tensionerForce = d.tensionerForce;
  out.tensionerStroke = d.tensionerStroke;
  out.tensionerRate = d.tensionerRate;
  out.chamberPressure = d.chamberPressure;
  out.tensionerFlows = d.tensionerFlows;
  auto probe = [&](const SpanModel::Probe& p) { return p.present ? d.spans[p.span].partTension(p.part) : 0.0; };
  out.tightSpanForce = probe(m.tightProbe);
  out.slackSpanForce = probe(m.slackProbe);
  out.spanForce.resize(m.spanProbes.size());
  for (std::size_t r = 0; r < m.spanProbes.size(); ++r) out.spanForce[r] = probe(m.spanProbes[r]);
  monitoredLinkOutputs(m, d, monitoredLink, out);
  out.energy = spanEnergy(m, d, y);
  out.contacts = 0;
  out.maxJointDeformation = 0.0;
  for (const SpanState& s : d.spans)
    out.maxJointDeformation = std::max(out.maxJointDeformation, std::fabs(s.tension) / lm.chain.jointStiffness);
}

}  // namespace chaindrive::span
