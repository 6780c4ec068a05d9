#include "span/span_model.h"

#include "span/calibration_cache.h"
#include "math/elementary.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace chaindrive::span {

namespace {

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

// A guide's face where the chain runs over it: polar angles of its ends about the path circle's
// centre (assembled pose, counterclockwise from start to end) and the pitch line's height over the
// face; present only for a convex arc face whose centre is the path circle's.
struct GuideFace {
  bool present = false;
  double start = 0.0, end = 0.0;  // [rad]
  Vec2 faceStart, faceEnd;        // [m] face ends, assembled pose
  double height = 0.0;            // [m]
};

GuideFace guideFace(const GuideDesc& gd, Vec2 pivot, double assembledAngle, const RouteCircle& c) {
  GuideFace f;
  for (const GuideFeatureDesc& ft : gd.profile) {
    const Vec2 center = pivot + rotate(ft.center - pivot, assembledAngle);
    if (ft.type != GuideFeatureDesc::Type::Arc || !ft.convex || norm(center - c.center) > 1e-9 * ft.radius) continue;
    f.present = true;
    f.start = ft.startAngle + assembledAngle;
    f.end = ft.endAngle + assembledAngle;
    f.faceStart = center + ft.radius * unit(f.start);
    f.faceEnd = center + ft.radius * unit(f.end);
    f.height = std::fabs(c.signedRadius) - ft.radius;
  }
  return f;
}

// Whether polar angle a (assembled pose) lies on the face.
bool onFace(const GuideFace& f, double a) {
  double span = f.end - f.start, rel = a - f.start;
  span -= 2.0 * kPi * std::floor(span / (2.0 * kPi));
  rel -= 2.0 * kPi * std::floor(rel / (2.0 * kPi));
  return rel <= span;
}

// A circle the chain runs on between two sprockets; `junction`: the chain passes from it to the
// next circle at polar angle junctionAngle without a free line (a guide's face and the corner at
// its end, both touching there).
struct RunCircle {
  RouteCircle c;
  bool junction = false;
  double junctionAngle = 0.0;
};

// Polar angles where the chain leaves each circle (departure) and arrives on it (arrival), and
// the free lines' lengths; false when two circles have no common tangent.
bool runTangents(const std::vector<RunCircle>& run, std::vector<double>& departure, std::vector<double>& arrival,
                 std::vector<double>& freeLength) {
  const std::size_t k = run.size();
  departure.assign(k, 0.0);
  arrival.assign(k, 0.0);
  freeLength.assign(k, 0.0);
  for (std::size_t i = 0; i + 1 < k; ++i) {
    if (run[i].junction) {
      departure[i] = arrival[i + 1] = run[i].junctionAngle;
      continue;
    }
    Vec2 m;
    if (!commonTangent(run[i].c, run[i + 1].c, m)) return false;
    const double si = run[i].c.signedRadius > 0.0 ? 1.0 : -1.0, sj = run[i + 1].c.signedRadius > 0.0 ? 1.0 : -1.0;
    departure[i] = angleOf(si * m);
    arrival[i + 1] = angleOf(sj * m);
    freeLength[i] = norm(run[i + 1].c.center + run[i + 1].c.signedRadius * m - run[i].c.center - run[i].c.signedRadius * m);
  }
  return true;
}

Vec2 pointAt(const RouteCircle& c, double polarAngle) { return c.center + std::fabs(c.signedRadius) * unit(polarAngle); }

// The circles from sprocket a over the guides to sprocket b (route order, the pivoting guide g
// turned by dPsi about its pivot). Where the chain would touch guide g's circle beyond the end of
// its face, it bends over that end instead: a corner circle of the pitch line's height about the
// face's end, joined to the guide's circle there. `guide`: the index of g's circle in the run.
bool spanRun(const std::vector<RouteCircle>& c, int a, int b, int g, const GuideFace& face, double dPsi, Vec2 pivot,
             std::vector<RunCircle>& run, int& guide) {
  const int n = static_cast<int>(c.size());
  run.clear();
  for (int r = a;; r = (r + 1) % n) {
    if (r == g) guide = static_cast<int>(run.size());
    run.push_back(RunCircle{c[r], false, 0.0});
    if (r == b) break;
  }
  if (!face.present) return true;
  const bool ccw = c[g].signedRadius > 0.0;
  const double sg = ccw ? 1.0 : -1.0;
  // where the chain would arrive on and leave the guide's circle (no common tangent: the circles
  // overlap, the chain bends over the face's end)
  Vec2 mIn, mOut;
  const bool arrivesOnFace = commonTangent(run[guide - 1].c, run[guide].c, mIn) && onFace(face, angleOf(sg * mIn) - dPsi);
  const bool leavesOnFace = commonTangent(run[guide].c, run[guide + 1].c, mOut) && onFace(face, angleOf(sg * mOut) - dPsi);
  if (!leavesOnFace) {
    const Vec2 end = pivot + rotate((ccw ? face.faceEnd : face.faceStart) - pivot, dPsi);
    run[guide].junction = true;
    run[guide].junctionAngle = (ccw ? face.end : face.start) + dPsi;
    run.insert(run.begin() + guide + 1, RunCircle{RouteCircle{end, sg * face.height}, false, 0.0});
  }
  if (!arrivesOnFace) {
    const Vec2 start = pivot + rotate((ccw ? face.faceStart : face.faceEnd) - pivot, dPsi);
    run.insert(run.begin() + guide, RunCircle{RouteCircle{start, sg * face.height}, true, (ccw ? face.start : face.end) + dPsi});
    ++guide;
  }
  return true;
}

// One node of a guide table: the span's length from a to b and the guide torque coefficients
// with the wrapped arc of route element g turned by dPsi about the guide's pivot.
bool tableNode(const Model& m, const std::vector<RouteCircle>& circles0, const GuideFace& face, int a, int b, int g,
               Vec2 pivot, double dPsi, double& length, double& torqueIn, double& torqueOut) {
  std::vector<RouteCircle> c = circles0;
  c[g].center = pivot + rotate(circles0[g].center - pivot, dPsi);
  std::vector<RunCircle> run;
  int guide = -1;
  if (!spanRun(c, a, b, g, face, dPsi, pivot, run, guide)) return false;
  std::vector<double> dep, arr, len;
  if (!runTangents(run, dep, arr, len)) return false;
  const std::size_t k = run.size();
  length = 0.0;
  for (std::size_t i = 0; i + 1 < k; ++i) length += len[i];
  for (std::size_t i = 1; i + 1 < k; ++i) {  // the arcs between the end sprockets, in the running sense
    double sweep = dep[i] - arr[i];
    if (run[i].c.signedRadius < 0.0) sweep = -sweep;
    sweep -= 2.0 * kPi * std::floor(sweep / (2.0 * kPi));
    if (sweep > 2.0 * kPi - 1e-9) sweep = 0.0;
    length += std::fabs(run[i].c.signedRadius) * sweep;
  }
  // the ends: from the reference tangent points on a and b (the assembled path)
  length += wrapAngle(dep.front() - exitAngle(m.path, a)) * c[a].signedRadius;
  length += wrapAngle(arrivalAngle(m.path, b) - arr.back()) * c[b].signedRadius;
  // the guide's loads: the tension along the free line arriving at its first contact and along
  // the one leaving its last (corners included)
  const int first = run[guide - 1].junction ? guide - 1 : guide;
  const int last = run[guide].junction ? guide + 1 : guide;
  const Vec2 pIn = pointAt(run[first].c, arr[first]), pOut = pointAt(run[last].c, dep[last]);
  const Vec2 tIn = pIn - pointAt(run[first - 1].c, dep[first - 1]);
  const Vec2 tOut = pointAt(run[last + 1].c, arr[last + 1]) - pOut;
  torqueIn = -cross(pIn - pivot, tIn) / norm(tIn);
  torqueOut = cross(pOut - pivot, tOut) / norm(tOut);
  return true;
}

// The table of the pivoting guide at route index g, over its angle range (trimmed to the angles
// where the route has a path); slopes by central differences.
GuideTable guideTable(const Model& m, int a, int b, int g, const GuideModel& guide, const GuideDesc& gd) {
  GuideTable t;
  t.rotor = guide.rotor;
  const double psi0 = m.rotors[guide.rotor].initialAngle;
  const std::vector<RouteCircle> circles0 = pathCircles(m.path);
  const GuideFace face = guideFace(gd, guide.pivot, psi0, circles0[g]);
  const double h = 1e-6;
  t.dAngle = (gd.angleMax - gd.angleMin) / (kTableNodes - 1);
  bool started = false;
  for (int i = 0; i < kTableNodes; ++i) {
    const double psi = gd.angleMin + i * t.dAngle;
    double len, lp, lm, tin, tout, dummy1, dummy2;
    const bool ok = tableNode(m, circles0, face, a, b, g, guide.pivot, psi - psi0, len, tin, tout) &&
                    tableNode(m, circles0, face, a, b, g, guide.pivot, psi - psi0 + h, lp, dummy1, dummy2) &&
                    tableNode(m, circles0, face, a, b, g, guide.pivot, psi - psi0 - h, lm, dummy1, dummy2);
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
  sp.damping = sp.jointDamping = ch.jointDamping / sp.links;
  sp.mass = ch.mass * sp.links;
  const double waveSpeed = std::sqrt(ch.jointStiffness * ch.pitch / (ch.mass / ch.pitch));
  sp.firstModeFrequency = waveSpeed / (2.0 * total);
  return sp;
}

}  // namespace

namespace {

// Rotor inertias with the chain lumped on the sprockets: the links wrapped on each and half of
// every span that ends there, at the pitch radius.
// The chain on a pivoting guide's face moves with the guide across its path: the guide's turn
// by w moves the chain at s across by w (x(s) - pivot) . t(s) (t the path's tangent), so its links
// add rho * integral of that lever squared over the wrap at the assembled pose (midpoint rule).
// The free parts beside the face are left out: their transverse modes (about 250 Hz on the
// default drive) lie among the guide's own, where they do not move with it as a rigid mass.
double chainOnGuideInertia(const Model& m, const GuideModel& g, const PathSegment& wrap) {
  constexpr int kPoints = 64;
  const double rho = m.chain.mass / m.chain.pitch, ds = wrap.length / kPoints;
  double J = 0.0;
  for (int k = 0; k < kPoints; ++k) {
    const double s = wrap.start + (k + 0.5) * ds;
    const double lever = dot(m.path.point(s) - g.pivot, m.path.tangent(s));
    J += rho * lever * lever * ds;
  }
  return J;
}

// (the guides' additions noted in sm.notes)
std::vector<double> lumpedInertia(const Model& m, SpanModel& sm, const std::vector<RouteItem>& route) {
  std::vector<double> J;
  for (const RotorModel& r : m.rotors) J.push_back(r.inertia);
  const double rho = m.chain.mass / m.chain.pitch;
  for (std::size_t r = 0; r < route.size(); ++r)
    if (route[r].sprocket) {
      const SprocketModel& s = m.sprockets[route[r].index];
      const double R = s.gap.pitchRadius;
      J[s.rotor] += rho * m.path.segments()[2 * r].length * R * R;
    } else if (const GuideModel& g = m.guides[route[r].index]; g.rotor >= 0) {
      const double added = chainOnGuideInertia(m, g, m.path.segments()[2 * r]);
      J[g.rotor] += added;
      char line[200];
      std::snprintf(line, sizeof line, "guide %s: inertia %.4g kg m2, of which the chain on its face %.4g",
                    g.name.c_str(), J[g.rotor], added);
      sm.notes.push_back(line);
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
  for (int r = 0; r < n; ++r) sm.spanProbes.push_back({true, sm.pathParts[2 * r + 1].span, sm.pathParts[2 * r + 1].part});
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
  sm.stateChamberOil = m.tensioner.hydraulicChamber() ? idx++ : -1;
  sm.chainImpulse = layOutImpulseStates(idx, static_cast<int>(m.rotors.size()));
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
SpanModel assembleSpanModel(const Model& m, bool calibrate) {
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
  sm.seats.assign(sm.tables.size(), GuideSeat{});
  mapPath(m, route, spanOfRoute, sm);
  sm.monitoredStart = linkCentres(m);
  layOutState(m, sm);
  describeSpans(sm);
  if (calibrate) calibrateSpanModel(sm);
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

namespace {

// The segment of a law's nodes that holds e: the first below the first node, the last above.
std::size_t segmentOf(const EngagementLaw& law, double e) {
  std::size_t k = 0;
  while (k + 2 < law.stretch.size() && e >= law.stretch[k + 1]) ++k;
  return k;
}

}  // namespace

double EngagementLaw::tensionAt(double e, double* slope) const {
  const std::size_t k = segmentOf(*this, e);
  const double s = (tension[k + 1] - tension[k]) / (stretch[k + 1] - stretch[k]);
  if (slope) *slope = s;
  return tension[k] + s * (e - stretch[k]);
}

double EngagementLaw::energyAt(double e) const {
  const std::size_t k = segmentOf(*this, e);
  return energy[k] + 0.5 * (tension[k] + tensionAt(e)) * (e - stretch[k]);
}

void setDampingScale(SpanModel& sm, double scale) {
  sm.dampingScale = scale;
  for (Span& sp : sm.spans) sp.damping = scale * sp.jointDamping;
}

double chainPassed(const SpanEnd& e, double theta, double& effectiveRadius) {
  const double u = (theta + e.phase) / e.toothAngle;
  const double k = std::floor(u + 0.5);
  double s, c;
  smallSinCos((u - k) * e.toothAngle, s, c);
  effectiveRadius = e.radius * c;
  return k * e.pitch + e.radius * s - e.passedAtPhase;
}

}  // namespace chaindrive::span
