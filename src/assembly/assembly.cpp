// Assembly: description -> immutable Model with the chain at its nominal polygonal pose.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "assembly/model.h"

namespace chaindrive {

namespace {

std::string fmt(double v, int prec = 6) {
  std::ostringstream os;
  os.precision(prec);
  os << v;
  return os.str();
}

struct RouteElement {
  bool sprocket = true;
  int index = -1;  // sprocket or guide index
  int face = -1;   // guides: the face the chain wraps
};

// Pin circle radius of a convex guide arc: chords of one pitch whose plate edges (at half the
// plate height from the pin line) touch the arc.
double guidePinRadius(double faceRadius, double plateHalfHeight, double pitch) {
  const double mid = faceRadius + plateHalfHeight;
  return std::sqrt(mid * mid + 0.25 * pitch * pitch);
}

class Layout {
 public:
  Layout(const DriveDescription& d, const Model& m) : d_(d), m_(m) {
    for (const auto& name : d.chain.route) {
      RouteElement e;
      e.sprocket = d.sprocketIndex(name) >= 0;
      e.index = e.sprocket ? d.sprocketIndex(name) : d.guideIndex(name);
      route_.push_back(e);
    }
  }

  const std::vector<RouteElement>& route() const { return route_; }

  // Circles of the route at closure value x; picks the wrapped face of each guide. Returns an
  // empty string on success, else the reason.
  std::string circles(double x, std::vector<RouteCircle>& out) {
    const std::size_t n = route_.size();
    out.assign(n, RouteCircle{});
    for (std::size_t i = 0; i < n; ++i) {
      auto& e = route_[i];
      if (e.sprocket) {
        const SprocketModel& s = m_.sprockets[e.index];
        Vec2 c = s.center;
        if (isClosure(e)) c = c + x * d_.closure->direction;
        out[i] = RouteCircle{c, m_.sense * s.gap.pitchRadius};
      } else {
        if (e.face < 0) e.face = firstArc(e.index);
        if (e.face < 0) return "guides '" + d_.guides[e.index].name + "' has no convex arc (chainSide 'outside') to wrap";
        out[i] = guideCircle(e, x, e.face);
      }
    }
    // choose, for each guide, the arc whose tangent points lie inside its angle range
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t i = 0; i < n; ++i) {
        auto& e = route_[i];
        if (e.sprocket) continue;
        const GuideModel& g = m_.guides[e.index];
        bool found = false;
        for (std::size_t f = 0; f < g.faces.size() && !found; ++f) {
          if (g.faces[f].type != GuideFace::Type::ConvexArc) continue;
          const RouteCircle c = guideCircle(e, x, static_cast<int>(f));
          Vec2 m1, m2;
          if (!commonTangent(out[(i + n - 1) % n], c, m1) || !commonTangent(c, out[(i + 1) % n], m2)) continue;
          const double cg = std::cos(rot(e, x)), sg = std::sin(rot(e, x));
          const Vec2 d1 = rotate(c.signedRadius * m1, cg, -sg), d2 = rotate(c.signedRadius * m2, cg, -sg);
          if (g.faces[f].arc.contains(d1) && g.faces[f].arc.contains(d2)) {
            e.face = static_cast<int>(f);
            out[i] = c;
            found = true;
          }
        }
        if (!found && pass == 1)
          return "guide '" + g.name + "': the taut chain does not run along any of its arcs (the tangent points "
                 "fall outside every arc's angle range); move the guide or extend its arc";
      }
    }
    return "";
  }

  double rot(const RouteElement& e, double x) const { return (!e.sprocket && isClosure(e)) ? x : 0.0; }

  bool isClosure(const RouteElement& e) const {
    if (!d_.closure) return false;
    const bool guide = d_.closure->kind == ClosureDesc::Kind::Guide;
    if (e.sprocket == guide) return false;
    const std::string& nm = e.sprocket ? d_.sprockets[e.index].name : d_.guides[e.index].name;
    return nm == d_.closure->element;
  }

 private:
  int firstArc(int gi) const {
    const auto& faces = m_.guides[gi].faces;
    for (std::size_t f = 0; f < faces.size(); ++f)
      if (faces[f].type == GuideFace::Type::ConvexArc) return static_cast<int>(f);
    return -1;
  }
  RouteCircle guideCircle(const RouteElement& e, double x, int face) const {
    const GuideModel& g = m_.guides[e.index];
    const GuideFace& f = g.faces[face];
    const double a = rot(e, x);
    const Vec2 c = g.pivot + rotate(f.arc.center - g.pivot, a);
    return RouteCircle{c, -m_.sense * guidePinRadius(f.arc.radius, m_.chain.plateHalfHeight, m_.chain.pitch)};
  }

  const DriveDescription& d_;
  const Model& m_;
  std::vector<RouteElement> route_;
};

// Walks n chords of one pitch from s0; returns the arc length of the n-th pin (not wrapped).
double walk(const ChainPath& path, double s0, int n, double pitch, std::vector<double>* pins) {
  double s = s0;
  if (pins) pins->assign(1, s0);
  for (int k = 0; k < n; ++k) {
    s = path.nextPin(s, pitch);
    if (pins && k + 1 < n) pins->push_back(s);
  }
  return s;
}

}  // namespace

int Model::rotorIndex(const std::string& n) const {
  for (std::size_t i = 0; i < rotors.size(); ++i)
    if (rotors[i].name == n) return static_cast<int>(i);
  return -1;
}

Model assemble(const DriveDescription& d) {
  std::vector<std::string> problems;
  Model m;
  m.description = d;
  m.name = d.name;
  m.sense = d.rotationSense;
  m.gravity = d.gravity;
  m.frictionRegularization = d.contact.frictionRegularization;

  ChainModel& ch = m.chain;
  ch.links = d.chain.numberOfLinks;
  ch.pitch = d.chain.pitch;
  ch.mass = d.chain.linkMass;
  ch.inertia = d.chain.linkInertia;
  ch.rollerRadius = 0.5 * d.chain.rollerDiameter;
  ch.plateHalfHeight = 0.5 * d.chain.plateHeight;
  ch.jointStiffness = d.chain.joint.stiffness;
  ch.jointDamping = d.chain.joint.damping;
  ch.jointClearance = d.chain.joint.clearance;

  auto law = [](const ContactLawDesc& c) {
    ContactLaw l;
    l.huntCrossley = c.model == "hunt-crossley";
    l.stiffness = c.stiffness;
    l.exponent = c.exponent;
    l.dampingFactor = c.dampingFactor;
    l.damping = c.damping;
    l.friction = c.friction;
    l.restitution = c.restitution;
    return l;
  };
  m.rollerSprocket = law(d.contact.rollerSprocket);
  m.plateGuide = law(d.contact.plateGuide);

  // ---- sprockets and their rotors ----
  for (std::size_t i = 0; i < d.sprockets.size(); ++i) {
    const SprocketDesc& sd = d.sprockets[i];
    SprocketModel s;
    s.name = sd.name;
    s.center = sd.center;
    Iso606ToothForm f = iso606ToothForm(sd.teeth, d.chain.pitch, d.chain.rollerDiameter, sd.toothProfile.form);
    if (sd.toothProfile.seatRadius) f.seatRadius = *sd.toothProfile.seatRadius;
    if (sd.toothProfile.seatAngle) f.seatAngle = *sd.toothProfile.seatAngle;
    if (sd.toothProfile.flankRadius) f.flankRadius = *sd.toothProfile.flankRadius;
    if (sd.toothProfile.tipDiameter) f.tipDiameter = *sd.toothProfile.tipDiameter;
    try {
      s.gap = ToothGap::build(sd.teeth, d.chain.pitch, d.chain.rollerDiameter, f.seatRadius, f.seatAngle, f.flankRadius,
                              f.tipDiameter);
    } catch (const std::invalid_argument& e) {
      problems.push_back("sprockets[" + std::to_string(i) + "].toothProfile: " + e.what());
      continue;
    }
    const double reach = s.gap.tipRadius + ch.rollerRadius;
    s.reach2 = reach * reach;
    for (int k = 0; k < sd.teeth; ++k) s.gapDirs.push_back(unit(k * s.gap.gapAngle));
    RotorModel r;
    r.name = sd.name;
    r.isSprocket = true;
    r.element = static_cast<int>(i);
    r.axis = sd.center;
    r.inertia = sd.inertia;
    r.prescribed = sd.prescribed;
    s.rotor = static_cast<int>(m.rotors.size());
    if (r.prescribed) m.drivenRotor = s.rotor;
    m.rotors.push_back(r);
    m.sprockets.push_back(s);
  }
  if (!problems.empty()) throw DescriptionError(problems);
  for (std::size_t i = 0; i < m.sprockets.size(); ++i)
    for (std::size_t j = i + 1; j < m.sprockets.size(); ++j) {
      const double dist = norm(m.sprockets[i].center - m.sprockets[j].center);
      const double need = m.sprockets[i].gap.tipRadius + m.sprockets[j].gap.tipRadius + 2.0 * ch.rollerRadius;
      if (dist < need)
        problems.push_back("sprockets[" + std::to_string(j) + "].center: sprocket '" + m.sprockets[j].name +
                           "' overlaps '" + m.sprockets[i].name + "': centre distance " + fmt(dist) +
                           " m is less than the tip radii plus a roller diameter, " + fmt(need) + " m");
    }

  // ---- guides ----
  for (std::size_t i = 0; i < d.guides.size(); ++i) {
    const GuideDesc& gd = d.guides[i];
    GuideModel g;
    g.name = gd.name;
    g.pivot = gd.pivoting ? gd.pivot : Vec2{};
    g.mass = gd.mass;
    g.centerOfMass = gd.centerOfMass;
    g.pivotDamping = gd.pivotDamping;
    std::vector<Vec2> pts;
    for (std::size_t k = 0; k < gd.profile.size(); ++k) {
      const GuideFeatureDesc& fd = gd.profile[k];
      GuideFace f;
      if (fd.type == GuideFeatureDesc::Type::Arc) {
        if (fd.endAngle - fd.startAngle >= kPi) {
          problems.push_back("guides[" + std::to_string(i) + "].profile[" + std::to_string(k) +
                             "]: arcs must span less than 180 deg; split it into several arcs");
          continue;
        }
        f.type = fd.convex ? GuideFace::Type::ConvexArc : GuideFace::Type::ConcaveArc;
        f.arc = ArcRange{fd.center, fd.radius, unit(fd.startAngle), unit(fd.endAngle)};
        for (int q = 0; q <= 16; ++q)
          pts.push_back(fd.center + fd.radius * unit(fd.startAngle + (fd.endAngle - fd.startAngle) * q / 16.0));
      } else {
        f.type = GuideFace::Type::Line;
        f.from = fd.from;
        f.to = fd.to;
        f.lineLength = norm(fd.to - fd.from);
        const Vec2 dir = (1.0 / f.lineLength) * (fd.to - fd.from);
        f.lineNormal = fd.leftSide ? perp(dir) : -1.0 * perp(dir);
        pts.push_back(fd.from);
        pts.push_back(fd.to);
      }
      g.faces.push_back(f);
    }
    Vec2 c;
    for (const auto& p : pts) c += p;
    if (!pts.empty()) c = (1.0 / static_cast<double>(pts.size())) * c;
    double r = 0.0;
    for (const auto& p : pts) r = std::max(r, norm(p - c));
    g.boundCenter = c;
    g.boundRadius = r;
    if (gd.pivoting) {
      RotorModel rt;
      rt.name = gd.name;
      rt.isSprocket = false;
      rt.element = static_cast<int>(i);
      rt.axis = gd.pivot;
      rt.inertia = gd.inertia;
      g.rotor = static_cast<int>(m.rotors.size());
      m.rotors.push_back(rt);
    }
    m.guides.push_back(g);
  }

  // ---- tensioner ----
  if (d.tensioner.present) {
    TensionerModel& t = m.tensioner;
    t.present = true;
    t.rotor = m.rotorIndex(d.tensioner.guide);
    t.housing = d.tensioner.housing;
    t.direction = d.tensioner.direction;
    t.pad = d.tensioner.contactPoint;
    t.preload = d.tensioner.preload;
    t.stiffness = d.tensioner.stiffness;
    t.dampingRetract = d.tensioner.damping;
    t.dampingExtend = d.tensioner.dampingExtension;
    t.nominalStroke = dot(t.pad - t.housing, t.direction);
    if (t.nominalStroke <= 0.0)
      problems.push_back("tensioner.contactPoint: the pad lies behind the housing along 'direction' (stroke " +
                         fmt(t.nominalStroke) + " m); the plunger extends from the housing towards the guide");
  }
  if (!problems.empty()) throw DescriptionError(problems);

  // ---- chain path and closure ----
  Layout layout(d, m);
  const ClosureDesc& cl = *d.closure;
  std::vector<RouteCircle> circles;
  const int n = ch.links;
  const double p = ch.pitch;
  auto closureGap = [&](double x, double& fitLinks) -> double {
    const std::string why = layout.circles(x, circles);
    if (!why.empty()) return std::nan("");
    ChainPath path;
    try {
      path = ChainPath::through(circles);
    } catch (const std::invalid_argument&) {
      return std::nan("");
    }
    // a guide bends the chain by less than 90 degrees; a larger sweep means the taut chain
    // does not touch it (the tangents wrap around its far side)
    for (const PathSegment& seg : path.segments())
      if (seg.isArc && !layout.route()[seg.routeIndex].sprocket && std::fabs(seg.sweep) > 0.5 * kPi) return std::nan("");
    const double s0 = path.arcMiddle(0);
    const double g = walk(path, s0, n, p, nullptr) - s0 - path.length();
    fitLinks = n - g / p;
    return g;
  };
  const int nScan = 64;
  std::vector<double> xs(nScan + 1), gs(nScan + 1), fits(nScan + 1, std::nan(""));
  for (int k = 0; k <= nScan; ++k) {
    xs[k] = cl.rangeMin + (cl.rangeMax - cl.rangeMin) * k / nScan;
    gs[k] = closureGap(xs[k], fits[k]);
  }
  int best = -1;
  for (int k = 0; k < nScan; ++k) {
    if (std::isnan(gs[k]) || std::isnan(gs[k + 1])) continue;
    if ((gs[k] <= 0.0) != (gs[k + 1] <= 0.0)) {
      if (best < 0 || std::fabs(xs[k]) < std::fabs(xs[best])) best = k;
    }
  }
  const std::string unitName = cl.kind == ClosureDesc::Kind::Guide ? "rad" : "m";
  if (best < 0) {
    std::string why;
    {
      std::vector<RouteCircle> tmp;
      why = layout.circles(0.0, tmp);
      if (why.empty()) {
        try {
          ChainPath::through(tmp);
        } catch (const std::invalid_argument& e) {
          why = e.what();
        }
      }
    }
    double lo = 1e300, hi = -1e300;
    for (double f : fits)
      if (!std::isnan(f)) { lo = std::min(lo, f); hi = std::max(hi, f); }
    if (!why.empty()) {
      problems.push_back("chain.route: " + why);
    } else if (lo <= hi) {
      problems.push_back("chain.numberOfLinks: " + std::to_string(n) + " links cannot close around the layout; over the "
                         "closure range [" + fmt(cl.rangeMin) + ", " + fmt(cl.rangeMax) + "] " + unitName + " of '" +
                         cl.element + "' the path holds between " + fmt(lo, 5) + " and " + fmt(hi, 5) + " links");
    } else {
      problems.push_back("chain.route: no valid chain path over the closure range of '" + cl.element + "'");
    }
    throw DescriptionError(problems);
  }
  // refine the bracket (bisection with a secant guess)
  double a = xs[best], b = xs[best + 1], ga = gs[best], gb = gs[best + 1];
  double x = a, fit = 0.0;
  for (int it = 0; it < 200; ++it) {
    double c = (ga * b - gb * a) / (ga - gb);
    if (!(c > std::min(a, b) && c < std::max(a, b)) || it % 3 == 2) c = 0.5 * (a + b);
    const double gc = closureGap(c, fit);
    x = c;
    if (std::fabs(gc) < 1e-14 || std::fabs(b - a) < 1e-16) break;
    if ((gc <= 0.0) == (ga <= 0.0)) { a = c; ga = gc; }
    else { b = c; gb = gc; }
  }
  if (layout.circles(x, circles) != "") throw DescriptionError({"chain.route: internal: lost the path at the closure"});
  m.path = ChainPath::through(circles);
  m.assembly.closureElement = cl.element;
  m.assembly.closureValue = x;
  m.assembly.pathLength = m.path.length();

  if (cl.kind == ClosureDesc::Kind::Sprocket) {
    SprocketModel& s = m.sprockets[d.sprocketIndex(cl.element)];
    s.center = s.center + x * cl.direction;
    m.rotors[s.rotor].axis = s.center;
    m.assembly.notes.push_back("sprocket '" + s.name + "' shifted by " + fmt(x * 1e3) + " mm to close the chain");
  } else {
    m.rotors[m.rotorIndex(cl.element)].initialAngle = x;
    m.assembly.notes.push_back("guide '" + cl.element + "' at " + fmt(x * 180.0 / kPi) +
                               " deg from its drawn pose closes the chain");
  }

  // ---- pins at the nominal pose ----
  std::vector<double> spin;
  const double s0 = m.path.arcMiddle(0);
  const double sEnd = walk(m.path, s0, n, p, &spin);
  m.assembly.closureResidual = norm(m.path.point(sEnd) - m.path.point(s0));
  m.pins.resize(n);
  const auto& route = layout.route();
  for (int k = 0; k < n; ++k) {
    PinNominal& pn = m.pins[k];
    pn.position = m.path.point(spin[k]);
    pn.tangent = m.path.tangent(spin[k]);
    const PathSegment& seg = m.path.segments()[m.path.segmentAt(spin[k])];
    if (seg.isArc) {
      const RouteElement& e = route[seg.routeIndex];
      pn.center = seg.center;
      pn.radius = std::fabs(seg.signedRadius);
      if (e.sprocket) {
        pn.on = PinNominal::On::Sprocket;
        pn.rotor = m.sprockets[e.index].rotor;
      } else {
        pn.on = PinNominal::On::Guide;
        pn.rotor = m.guides[e.index].rotor;
      }
    } else {
      pn.on = PinNominal::On::Span;
    }
  }
  double maxGap = 0.0;
  for (int k = 0; k < n; ++k)
    maxGap = std::max(maxGap, std::fabs(norm(m.pins[(k + 1) % n].position - m.pins[k].position) - p));
  m.assembly.maxJointGap = maxGap;

  // ---- sprocket angles: a tooth gap at the pin nearest the middle of each wrap ----
  for (std::size_t r = 0; r < route.size(); ++r) {
    if (!route[r].sprocket) continue;
    SprocketModel& s = m.sprockets[route[r].index];
    const double mid = m.path.arcMiddle(static_cast<int>(r));
    int bestPin = -1;
    double bestD = 1e300;
    for (int k = 0; k < n; ++k) {
      if (m.pins[k].on != PinNominal::On::Sprocket || m.pins[k].rotor != s.rotor) continue;
      const double dd = norm(m.pins[k].position - m.path.point(mid));
      if (dd < bestD) { bestD = dd; bestPin = k; }
    }
    if (bestPin < 0) {
      problems.push_back("chain.route[" + std::to_string(r) + "]: the chain wraps sprocket '" + s.name +
                         "' by less than one pitch; no roller is seated on it");
      continue;
    }
    m.rotors[s.rotor].initialAngle = angleOf(m.pins[bestPin].position - s.center);
  }
  if (!problems.empty()) throw DescriptionError(problems);

  // ---- span probes ----
  auto probe = [&](const std::vector<std::string>& span, SpanProbe& pr) {
    if (span.size() != 2) return;
    for (std::size_t r = 0; r < route.size(); ++r) {
      if (d.chain.route[r] != span[0]) continue;
      const PathSegment& sg = m.path.segments()[2 * r + 1];
      pr.present = true;
      pr.point = 0.5 * (sg.from + sg.to);
      pr.direction = (1.0 / std::max(sg.length, 1e-12)) * (sg.to - sg.from);
    }
  };
  probe(d.measurement.tightSpan, m.tightSpan);
  probe(d.measurement.slackSpan, m.slackSpan);
  m.monitoredLink = d.measurement.monitoredLink;

  // ---- state layout ----
  int idx = 6 * n;
  for (auto& r : m.rotors) {
    r.stateAngle = idx++;
    r.stateRate = r.prescribed ? -1 : idx++;
  }
  m.stateInputWork = idx++;
  m.stateDissipated = idx++;
  m.nStates = idx;
  m.nGen = 3 * n + static_cast<int>(m.rotors.size());
  m.rotorOutputSign.assign(m.rotors.size(), 1.0);
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    if (m.rotors[r].isSprocket) {
      m.rotorOutputSign[r] = m.sense;
    } else if (m.tensioner.present && m.tensioner.rotor == static_cast<int>(r)) {
      m.rotorOutputSign[r] = cross(m.tensioner.pad - m.rotors[r].axis, m.tensioner.direction) >= 0.0 ? 1.0 : -1.0;
    }
  }
  return m;
}

}  // namespace chaindrive
