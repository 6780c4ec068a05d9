#include "span/span_model.h"

#include "span/span_calibration.h"
#include "math/elementary.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace chaindrive::span {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kTableNodes = 241;       // over the guide's angle range (0.05 deg apart for +-6 deg)
constexpr double kHighestOrder = 20.0; // engine orders a span's first mode must lie above ...
constexpr double kHighestSpeed = 6500.0 / 60.0;  // ... at the highest engine speed [rev/s]

double wrapAngle(double a) { return a - 2.0 * kPi * std::floor(a / (2.0 * kPi) + 0.5); }
double wrapPitch(double a, double pitchAngle) { return a - pitchAngle * std::floor(a / pitchAngle + 0.5); }

// The route: sprocket or guide per route index, the element's index and name.
struct RouteItem {
  bool sprocket = false;
  int index = -1;
  std::string name;
};

std::vector<RouteItem> routeItems(const DriveDescription& desc) {
  std::vector<RouteItem> out;
  for (const std::string& name : desc.chain.route) {
    RouteItem it;
    it.sprocket = desc.sprocketIndex(name) >= 0;
    it.index = it.sprocket ? desc.sprocketIndex(name) : desc.guideIndex(name);
    it.name = name;
    out.push_back(it);
  }
  return out;
}

// The circles of the assembled path (arc r is route element r).
std::vector<RouteCircle> pathCircles(const ChainPath& path) {
  std::vector<RouteCircle> c;
  for (std::size_t i = 0; i < path.segments().size(); i += 2)
    c.push_back(RouteCircle{path.segments()[i].center, path.segments()[i].signedRadius});
  return c;
}

double exitAngle(const ChainPath& p, int r) {
  const PathSegment& s = p.segments()[2 * r];
  return s.angle0 + s.sweep;
}
double arrivalAngle(const ChainPath& p, int r) { return p.segments()[2 * r].angle0; }

// Path length from the reference tangent point where the chain leaves route element a to the one
// where it arrives on b (reference: the assembled path), along `path`.
double referenceLength(const ChainPath& path, const ChainPath& ref, int a, int b) {
  const int nSeg = static_cast<int>(path.segments().size());
  double len = 0.0;
  for (int i = 2 * a + 1; i % nSeg != 2 * b; ++i) len += path.segments()[i % nSeg].length;
  const double ra = path.segments()[2 * a].signedRadius, rb = path.segments()[2 * b].signedRadius;
  len += wrapAngle(exitAngle(path, a) - exitAngle(ref, a)) * ra;
  len += wrapAngle(arrivalAngle(ref, b) - arrivalAngle(path, b)) * rb;
  return len;
}

Vec2 runningTangent(double polarAngle, double signedRadius) {
  const double sg = signedRadius > 0.0 ? 1.0 : -1.0;
  return sg * Vec2{-math::sin(polarAngle), math::cos(polarAngle)};
}

// One node of a guide table: the span's length from a to b and the guide torque coefficients
// with the wrapped arc of route element g turned by dPsi about the guide's pivot.
bool tableNode(const Model& m, const std::vector<RouteCircle>& circles0, int a, int b, int g, Vec2 pivot,
               double dPsi, double& length, double& torqueIn, double& torqueOut) {
  std::vector<RouteCircle> c = circles0;
  c[g].center = pivot + rotate(circles0[g].center - pivot, dPsi);
  ChainPath path;
  try {
    path = ChainPath::through(c);
  } catch (const std::invalid_argument&) {
    return false;
  }
  length = referenceLength(path, m.path, a, b);
  const PathSegment& arc = path.segments()[2 * g];
  const Vec2 lever = arc.center - pivot;
  const Vec2 tIn = runningTangent(arc.angle0, arc.signedRadius);
  const Vec2 tOut = runningTangent(arc.angle0 + arc.sweep, arc.signedRadius);
  torqueIn = -(cross(lever, tIn) + arc.signedRadius);
  torqueOut = cross(lever, tOut) + arc.signedRadius;
  return true;
}

// The table of the pivoting guide at route index g, over its angle range (trimmed to the angles
// where the route has a path); slopes by central differences.
GuideTable guideTable(const Model& m, int a, int b, int g, const GuideModel& guide, const GuideDesc& gd) {
  GuideTable t;
  t.rotor = guide.rotor;
  const double psi0 = m.rotors[guide.rotor].initialAngle;
  const std::vector<RouteCircle> circles0 = pathCircles(m.path);
  const double h = 1e-6;
  t.dAngle = (gd.angleMax - gd.angleMin) / (kTableNodes - 1);
  bool started = false;
  for (int i = 0; i < kTableNodes; ++i) {
    const double psi = gd.angleMin + i * t.dAngle;
    double len, lp, lm, tin, tout, dummy1, dummy2;
    const bool ok = tableNode(m, circles0, a, b, g, guide.pivot, psi - psi0, len, tin, tout) &&
                    tableNode(m, circles0, a, b, g, guide.pivot, psi - psi0 + h, lp, dummy1, dummy2) &&
                    tableNode(m, circles0, a, b, g, guide.pivot, psi - psi0 - h, lm, dummy1, dummy2);
    if (!ok) {
      if (started && psi > psi0) break;  // the valid range around the assembled angle ends here
      continue;
    }
    if (!started) t.angle0 = psi;
    started = true;
    t.length.push_back(len);
    t.slope.push_back((lp - lm) / (2.0 * h));
    t.torqueIn.push_back(tin);
    t.torqueOut.push_back(tout);
  }
  return t;
}

SpanEnd spanEnd(const Model& m, int sprocket, double tangentAngle) {
  const SprocketModel& s = m.sprockets[sprocket];
  SpanEnd e;
  e.rotor = s.rotor;
  e.radius = s.gap.pitchRadius;
  e.toothAngle = s.gap.gapAngle;
  e.pitch = m.chain.pitch;
  // a tooth gap (a seated roller) sits at the rotor's initial angle
  e.phase = wrapPitch(m.sense * (m.rotors[s.rotor].initialAngle - tangentAngle), e.toothAngle);
  e.passedAtPhase = e.radius * math::sin(e.phase);
  return e;
}

// The span from the sprocket at route index a to the next sprocket b, with the guides between.
Span buildSpan(const Model& m, const std::vector<RouteItem>& route, int a, int b, std::vector<GuideTable>& tables,
               std::vector<std::string>& problems) {
  const int n = static_cast<int>(route.size());
  const auto& segs = m.path.segments();
  Span sp;
  sp.name = route[a].name + "->" + route[b].name;
  sp.from = spanEnd(m, route[a].index, exitAngle(m.path, a));
  sp.to = spanEnd(m, route[b].index, arrivalAngle(m.path, b));
  double total = segs[2 * a + 1].length;
  sp.parts.push_back(segs[2 * a + 1].length);
  for (int r = (a + 1) % n; r != b; r = (r + 1) % n) {
    const GuideModel& guide = m.guides[route[r].index];
    total += segs[2 * r].length + segs[2 * r + 1].length;
    sp.wraps.push_back(std::fabs(segs[2 * r].sweep));
    sp.parts.push_back(segs[2 * r + 1].length);
    if (guide.rotor < 0) continue;
    if (sp.table >= 0) {
      problems.push_back("chain.route[" + std::to_string(r) + "]: the span model allows one pivoting guide per span; '" +
                         guide.name + "' is the second in the span " + sp.name);
      continue;
    }
    sp.tableGuide = static_cast<int>(sp.wraps.size()) - 1;
    sp.table = static_cast<int>(tables.size());
    tables.push_back(guideTable(m, a, b, r, guide, m.description.guides[route[r].index]));
  }
  for (double part : sp.parts) sp.partsLength += part;
  sp.length0 = referenceLength(m.path, m.path, a, b);
  const ChainModel& ch = m.chain;
  sp.links = total / ch.pitch;
  sp.stiffness = ch.jointStiffness / sp.links;
  sp.damping = ch.jointDamping / sp.links;
  sp.mass = ch.mass * sp.links;
  const double waveSpeed = std::sqrt(ch.jointStiffness * ch.pitch / (ch.mass / ch.pitch));
  sp.firstModeFrequency = waveSpeed / (2.0 * total);
  return sp;
}

}  // namespace

namespace {

// Rotor inertias with the chain lumped on the sprockets: the links wrapped on each and half of
// every span that ends there, at the pitch radius.
std::vector<double> lumpedInertia(const Model& m, const SpanModel& sm, const std::vector<RouteItem>& route) {
  std::vector<double> J;
  for (const RotorModel& r : m.rotors) J.push_back(r.inertia);
  const double rho = m.chain.mass / m.chain.pitch;
  for (std::size_t r = 0; r < route.size(); ++r)
    if (route[r].sprocket) {
      const SprocketModel& s = m.sprockets[route[r].index];
      const double R = s.gap.pitchRadius;
      J[s.rotor] += rho * m.path.segments()[2 * r].length * R * R;
    }
  for (const Span& sp : sm.spans) {
    J[sp.from.rotor] += 0.5 * sp.mass * sp.from.radius * sp.from.radius;
    J[sp.to.rotor] += 0.5 * sp.mass * sp.to.radius * sp.to.radius;
  }
  return J;
}

// What each segment of the assembled path is in the span model (sprocket wrap, guide wrap, free
// part), and the probes of the measured spans.
void mapPath(const Model& m, const std::vector<RouteItem>& route, const std::vector<int>& spanOfRoute,
             SpanModel& sm) {
  const int n = static_cast<int>(route.size());
  sm.pathParts.assign(2 * n, PathPart{});
  for (int r = 0; r < n; ++r) {
    const int span = spanOfRoute[r];
    PathPart arc, free;
    arc.span = free.span = span;
    if (route[r].sprocket) {
      arc.kind = PathPart::Kind::Sprocket;
      arc.spanIn = spanOfRoute[(r + n - 1) % n];
      free.part = 0;
    } else {
      arc.kind = PathPart::Kind::Guide;
      int before = 0;  // guides of the span before this one
      for (int q = r; !route[(q + n - 1) % n].sprocket; q = (q + n - 1) % n) ++before;
      arc.part = before;
      free.part = before + 1;
    }
    sm.pathParts[2 * r] = arc;
    sm.pathParts[2 * r + 1] = free;
  }
  auto probe = [&](const std::vector<std::string>& names, SpanModel::Probe& pr) {
    if (names.size() != 2) return;
    for (int r = 0; r < n; ++r)
      if (route[r].name == names[0]) pr = {true, sm.pathParts[2 * r + 1].span, sm.pathParts[2 * r + 1].part};
  };
  probe(m.description.measurement.tightSpan, sm.tightProbe);
  probe(m.description.measurement.slackSpan, sm.slackProbe);
}

// Path positions of the link centres at the assembled pose (pins from the middle of the first
// wrap, one pitch apart, as the link model places them).
std::vector<double> linkCentres(const Model& m) {
  const int n = m.chain.links;
  std::vector<double> pin(n + 1);
  pin[0] = m.path.arcMiddle(0);
  for (int k = 0; k < n; ++k) pin[k + 1] = m.path.nextPin(pin[k], m.chain.pitch);
  if (pin[n] < pin[0]) pin[n] += m.path.length();
  std::vector<double> c(n);
  for (int k = 0; k < n; ++k) {
    double b = pin[k + 1];
    if (b < pin[k]) b += m.path.length();
    c[k] = 0.5 * (pin[k] + b);
  }
  return c;
}

void layOutState(const Model& m, SpanModel& sm) {
  int idx = 0;
  for (const RotorModel& r : m.rotors) {
    sm.stateAngle.push_back(idx++);
    sm.stateRate.push_back(r.prescribed ? -1 : idx++);
  }
  sm.stateInputWork = idx++;
  sm.stateDissipated = idx++;
  sm.stateChamberPressure = m.tensioner.hydraulicChamber() ? idx++ : -1;
  sm.nStates = idx;
}

void describeSpans(SpanModel& sm) {
  const double limit = kHighestOrder * kHighestSpeed;
  for (const Span& sp : sm.spans) {
    char line[240];
    std::snprintf(line, sizeof line, "span %s: %.1f links, stiffness %.4g N/m, first longitudinal mode %.0f Hz%s",
                  sp.name.c_str(), sp.links, sp.stiffness, sp.firstModeFrequency,
                  sp.firstModeFrequency < limit ? " (below 20 engine orders at 6500 rpm: its mass lumped at the "
                                                  "ends misplaces this mode)" : "");
    sm.notes.push_back(line);
  }
}

}  // namespace

// A table of contents: the route's spans, the chain lumped on the sprockets, the map of the
// path, the state layout.
SpanModel assembleSpanModel(const Model& m, bool measureSlack) {
  const std::vector<RouteItem> route = routeItems(m.description);
  const int n = static_cast<int>(route.size());
  std::vector<int> sprockets;
  for (int r = 0; r < n; ++r)
    if (route[r].sprocket) sprockets.push_back(r);
  if (sprockets.size() < 2)
    throw DescriptionError({"chain.route: the span model needs at least two sprockets in the route (it has " +
                            std::to_string(sprockets.size()) + ")"});
  SpanModel sm;
  sm.links = &m;
  std::vector<std::string> problems;
  std::vector<int> spanOfRoute(n, -1);
  for (std::size_t i = 0; i < sprockets.size(); ++i) {
    const int a = sprockets[i], b = sprockets[(i + 1) % sprockets.size()];
    sm.spans.push_back(buildSpan(m, route, a, b, sm.tables, problems));
    for (int r = a; r != b; r = (r + 1) % n) spanOfRoute[r] = static_cast<int>(i);
  }
  if (!problems.empty()) throw DescriptionError(problems);
  for (const GuideTable& t : sm.tables)
    if (t.length.size() < 2)
      throw DescriptionError({"guides: the chain has no path over the angle range of the guide of rotor '" +
                              m.rotors[t.rotor].name + "'"});
  sm.chainDensity = m.chain.mass / m.chain.pitch;
  sm.guideFriction = m.plateGuide.friction;
  sm.frictionRegularization = m.frictionRegularization;
  sm.rotorInertia = lumpedInertia(m, sm, route);
  sm.sprocketSpanIn.assign(m.rotors.size(), -1);
  sm.sprocketSpanOut.assign(m.rotors.size(), -1);
  for (std::size_t i = 0; i < sm.spans.size(); ++i) {
    sm.sprocketSpanOut[sm.spans[i].from.rotor] = static_cast<int>(i);
    sm.sprocketSpanIn[sm.spans[i].to.rotor] = static_cast<int>(i);
  }
  mapPath(m, route, spanOfRoute, sm);
  sm.monitoredStart = linkCentres(m);
  layOutState(m, sm);
  describeSpans(sm);
  if (measureSlack) measureSeatingSlack(sm);
  return sm;
}

namespace {

// sin and cos of |x| <= pi / z (at most 0.53 rad for z >= 6) by their Taylor series to x^13 and
// x^14 in Horner form (error below 4e-16 for z >= 6, 3e-24 for z = 21): a third of the library
// functions' cost, and the same bits on every platform.
void smallSinCos(double x, double& s, double& c) {
  const double x2 = x * x;
  constexpr double s3 = -1.0 / 6.0, s5 = 1.0 / 120.0, s7 = -1.0 / 5040.0, s9 = 1.0 / 362880.0,
                   s11 = -1.0 / 39916800.0, s13 = 1.0 / 6227020800.0;
  constexpr double c2 = -0.5, c4 = 1.0 / 24.0, c6 = -1.0 / 720.0, c8 = 1.0 / 40320.0, c10 = -1.0 / 3628800.0,
                   c12 = 1.0 / 479001600.0, c14 = -1.0 / 87178291200.0;
  s = x + x * x2 * (s3 + x2 * (s5 + x2 * (s7 + x2 * (s9 + x2 * (s11 + x2 * s13)))));
  c = 1.0 + x2 * (c2 + x2 * (c4 + x2 * (c6 + x2 * (c8 + x2 * (c10 + x2 * (c12 + x2 * c14))))));
}

}  // namespace

double chainPassed(const SpanEnd& e, double theta, double& effectiveRadius) {
  const double u = (theta + e.phase) / e.toothAngle;
  const double k = std::floor(u + 0.5);
  double s, c;
  smallSinCos((u - k) * e.toothAngle, s, c);
  effectiveRadius = e.radius * c;
  return k * e.pitch + e.radius * s - e.passedAtPhase;
}

}  // namespace chaindrive::span
