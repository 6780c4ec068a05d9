// Assembly: description -> immutable Model with the chain at its nominal polygonal pose.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "assembly/model.h"
#include "assembly/pin_placement.h"
#include "math/elementary.h"

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
  Layout(const DriveDescription& desc, const Model& m) : desc_(desc), m_(m) {
    for (const auto& name : desc.chain.route) {
      RouteElement e;
      e.sprocket = desc.sprocketIndex(name) >= 0;
      e.index = e.sprocket ? desc.sprocketIndex(name) : desc.guideIndex(name);
      route_.push_back(e);
    }
  }

  const std::vector<RouteElement>& route() const { return route_; }

  // Circles of the route at closure value x; picks the wrapped face of each guide. Returns an
  // empty string on success, else the reason.
  std::string circles(double x, std::vector<RouteCircle>& out) {
    const std::string why = placeCircles(x, out);
    if (!why.empty()) return why;
    // choose, for each guide, the arc whose tangent points lie inside its angle range; the
    // second pass sees the arcs the first one chose for the neighbouring guides
    for (int pass = 0; pass < 2; ++pass)
      for (std::size_t i = 0; i < route_.size(); ++i)
        if (!route_[i].sprocket && !pickFace(i, x, out) && pass == 1)
          return "guide '" + m_.guides[route_[i].index].name + "': the taut chain does not run along any of its arcs "
                 "(the tangent points fall outside every arc's angle range); move the guide or extend its arc";
    return "";
  }

  double rot(const RouteElement& e, double x) const { return (!e.sprocket && isClosure(e)) ? x : 0.0; }

  bool isClosure(const RouteElement& e) const {
    if (!desc_.closure) return false;
    const bool guide = desc_.closure->kind == ClosureDesc::Kind::Guide;
    if (e.sprocket == guide) return false;
    const std::string& nm = e.sprocket ? desc_.sprockets[e.index].name : desc_.guides[e.index].name;
    return nm == desc_.closure->element;
  }

 private:
  // Pitch circles of the sprockets (the closing one shifted by x), pin circles of the guides'
  // current faces (a guide without a face yet takes its first convex arc).
  std::string placeCircles(double x, std::vector<RouteCircle>& out) {
    const std::size_t n = route_.size();
    out.assign(n, RouteCircle{});
    for (std::size_t i = 0; i < n; ++i) {
      auto& e = route_[i];
      if (e.sprocket) {
        const SprocketModel& s = m_.sprockets[e.index];
        Vec2 c = s.center;
        if (isClosure(e)) c = c + x * desc_.closure->direction;
        out[i] = RouteCircle{c, m_.sense * s.gap.pitchRadius};
      } else {
        if (e.face < 0) e.face = firstArc(e.index);
        if (e.face < 0) return "guides '" + desc_.guides[e.index].name + "' has no convex arc (chainSide 'outside') to wrap";
        out[i] = guideCircle(e, x, e.face);
      }
    }
    return "";
  }
  // Makes the first convex arc of route element i (a guide) whose tangent points to its
  // neighbours lie inside the arc its wrapped face; false if there is none.
  bool pickFace(std::size_t i, double x, std::vector<RouteCircle>& out) {
    const std::size_t n = route_.size();
    auto& e = route_[i];
    const GuideModel& g = m_.guides[e.index];
    for (std::size_t f = 0; f < g.faces.size(); ++f) {
      if (g.faces[f].type != GuideFace::Type::ConvexArc) continue;
      const RouteCircle c = guideCircle(e, x, static_cast<int>(f));
      Vec2 m1, m2;
      if (!commonTangent(out[(i + n - 1) % n], c, m1) || !commonTangent(c, out[(i + 1) % n], m2)) continue;
      const double cg = math::cos(rot(e, x)), sg = math::sin(rot(e, x));
      const Vec2 d1 = rotate(c.signedRadius * m1, cg, -sg), d2 = rotate(c.signedRadius * m2, cg, -sg);
      if (g.faces[f].arc.contains(d1) && g.faces[f].arc.contains(d2)) {
        e.face = static_cast<int>(f);
        out[i] = c;
        return true;
      }
    }
    return false;
  }
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

  const DriveDescription& desc_;
  const Model& m_;
  std::vector<RouteElement> route_;
};

void throwIfAny(const std::vector<std::string>& problems) {
  if (!problems.empty()) throw DescriptionError(problems);
}

// ---- the steps of assemble(), in order ----

// The model's contact law as described: the force model by name, its parameters as given.
ContactLaw contactLawFromDescription(const ContactLawDesc& c) {
  ContactLaw l;
  l.huntCrossley = c.model == ContactLawModel::HuntCrossley;
  l.stiffness = c.stiffness;
  l.exponent = c.exponent;
  l.dampingFactor = c.dampingFactor;
  l.damping = c.damping;
  l.friction = c.friction;
  l.restitution = c.restitution;
  return l;
}

// The drive-wide constants, the chain's links and the contact laws, as described.
void setConstants(const DriveDescription& desc, Model& m) {
  m.description = desc;
  m.name = desc.name;
  m.sense = desc.rotationSense;
  m.gravity = desc.gravity;
  m.frictionRegularization = desc.contact.frictionRegularization;

  ChainModel& ch = m.chain;
  ch.links = desc.chain.numberOfLinks;
  ch.pitch = desc.chain.pitch;
  ch.mass = desc.chain.linkMass;
  ch.inertia = desc.chain.linkInertia;
  ch.rollerRadius = 0.5 * desc.chain.rollerDiameter;
  ch.depthScale = ch.rollerRadius;
  ch.plateHalfHeight = 0.5 * desc.chain.plateHeight;
  ch.jointStiffness = desc.chain.joint.stiffness;
  ch.jointDamping = desc.chain.joint.damping;
  ch.jointClearance = desc.chain.joint.clearance;

  m.rollerSprocket = contactLawFromDescription(desc.contact.rollerSprocket);
  m.plateGuide = contactLawFromDescription(desc.contact.plateGuide);
}

// A rotor (a sprocket or a pivoting guide, `element` in its list); returns its index.
int addRotor(Model& m, const std::string& name, bool isSprocket, std::size_t element, Vec2 axis, double inertia,
             bool prescribed) {
  RotorModel r;
  r.name = name;
  r.isSprocket = isSprocket;
  r.element = static_cast<int>(element);
  r.axis = axis;
  r.inertia = inertia;
  r.prescribed = prescribed;
  m.rotors.push_back(r);
  return static_cast<int>(m.rotors.size()) - 1;
}

// The ISO 606 tooth form of the sprocket's form, with the dimensions the description overrides.
Iso606ToothForm toothForm(const SprocketDesc& sd, const ChainDesc& chain) {
  Iso606ToothForm f = iso606ToothForm(sd.teeth, chain.pitch, chain.rollerDiameter, sd.toothProfile.form);
  if (sd.toothProfile.seatRadius) f.seatRadius = *sd.toothProfile.seatRadius;
  if (sd.toothProfile.seatAngle) f.seatAngle = *sd.toothProfile.seatAngle;
  if (sd.toothProfile.flankRadius) f.flankRadius = *sd.toothProfile.flankRadius;
  if (sd.toothProfile.tipDiameter) f.tipDiameter = *sd.toothProfile.tipDiameter;
  return f;
}

// Sprockets with their tooth gaps and rotors; a tooth profile that cannot be built is a problem
// of that sprocket's toothProfile.
void buildSprockets(const DriveDescription& desc, Model& m, std::vector<std::string>& problems) {
  for (std::size_t i = 0; i < desc.sprockets.size(); ++i) {
    const SprocketDesc& sd = desc.sprockets[i];
    SprocketModel s;
    s.name = sd.name;
    s.center = sd.center;
    const Iso606ToothForm f = toothForm(sd, desc.chain);
    try {
      s.gap = ToothGap::build(sd.teeth, desc.chain.pitch, desc.chain.rollerDiameter, f.seatRadius, f.seatAngle,
                              f.flankRadius, f.tipDiameter);
    } catch (const std::invalid_argument& e) {
      problems.push_back("sprockets[" + std::to_string(i) + "].toothProfile: " + e.what());
      continue;
    }
    const double reach = s.gap.tipRadius + m.chain.rollerRadius;
    s.reach2 = reach * reach;
    for (int k = 0; k < sd.teeth; ++k) s.gapDirs.push_back(unit(k * s.gap.gapAngle));
    for (int k = 0; k < sd.teeth; ++k) s.toothDirs.push_back(unit((k - 0.5) * s.gap.gapAngle));
    s.rotor = addRotor(m, sd.name, true, i, sd.center, sd.inertia, sd.prescribed);
    if (sd.prescribed) m.drivenRotor = s.rotor;
    m.sprockets.push_back(s);
  }
}

// Two sprockets must be farther apart than their tip radii plus a roller diameter.
void checkSprocketOverlaps(const Model& m, std::vector<std::string>& problems) {
  for (std::size_t i = 0; i < m.sprockets.size(); ++i)
    for (std::size_t j = i + 1; j < m.sprockets.size(); ++j) {
      const double dist = norm(m.sprockets[i].center - m.sprockets[j].center);
      const double need = m.sprockets[i].gap.tipRadius + m.sprockets[j].gap.tipRadius + 2.0 * m.chain.rollerRadius;
      if (dist < need)
        problems.push_back("sprockets[" + std::to_string(j) + "].center: sprocket '" + m.sprockets[j].name +
                           "' overlaps '" + m.sprockets[i].name + "': centre distance " + fmt(dist) +
                           " m is less than the tip radii plus a roller diameter, " + fmt(need) + " m");
    }
}

// One face of a guide profile; adds points of its outline to `pts` (for the bounding circle).
// False for an arc of 180 deg or more, which the face queries cannot handle.
bool guideFace(const GuideFeatureDesc& fd, GuideFace& f, std::vector<Vec2>& pts) {
  if (fd.type == GuideFeatureDesc::Type::Arc) {
    if (fd.endAngle - fd.startAngle >= kPi) return false;
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
  return true;
}

// The bounding circle of a guide's outline points: centred at their mean.
void setBoundingCircle(const std::vector<Vec2>& pts, GuideModel& g) {
  Vec2 c;
  for (const auto& p : pts) c += p;
  if (!pts.empty()) c = (1.0 / static_cast<double>(pts.size())) * c;
  double r = 0.0;
  for (const auto& p : pts) r = std::max(r, norm(p - c));
  g.boundCenter = c;
  g.boundRadius = r;
}

// Guides with their faces, bounding circles and (pivoting ones) rotors.
void buildGuides(const DriveDescription& desc, Model& m, std::vector<std::string>& problems) {
  for (std::size_t i = 0; i < desc.guides.size(); ++i) {
    const GuideDesc& gd = desc.guides[i];
    GuideModel g;
    g.name = gd.name;
    g.pivot = gd.pivoting ? gd.pivot : Vec2{};
    g.mass = gd.mass;
    g.centerOfMass = gd.centerOfMass;
    g.pivotDamping = gd.pivotDamping;
    std::vector<Vec2> pts;
    for (std::size_t k = 0; k < gd.profile.size(); ++k) {
      GuideFace f;
      if (!guideFace(gd.profile[k], f, pts)) {
        problems.push_back("guides[" + std::to_string(i) + "].profile[" + std::to_string(k) +
                           "]: arcs must span less than 180 deg; split it into several arcs");
        continue;
      }
      g.faces.push_back(f);
    }
    setBoundingCircle(pts, g);
    if (gd.pivoting) g.rotor = addRotor(m, gd.name, false, i, gd.pivot, gd.inertia, false);
    m.guides.push_back(g);
  }
}

// The tensioner on its guide's rotor; the pad must lie ahead of the housing along the plunger.
void buildTensioner(const DriveDescription& desc, Model& m, std::vector<std::string>& problems) {
  if (!desc.tensioner.present) return;
  TensionerModel& t = m.tensioner;
  t.present = true;
  t.rotor = m.rotorIndex(desc.tensioner.guide);
  t.housing = desc.tensioner.housing;
  t.direction = desc.tensioner.direction;
  t.pad = desc.tensioner.contactPoint;
  t.preload = desc.tensioner.preload;
  t.stiffness = desc.tensioner.stiffness;
  t.dampingRetract = desc.tensioner.damping;
  t.dampingExtend = desc.tensioner.dampingExtension;
  t.kind = desc.tensioner.kind;
  t.hydraulic = desc.tensioner.hydraulic;
  if (t.hydraulicChamber()) t.chamberOil = ChamberOilLaw(t.hydraulic.oil);
  t.nominalStroke = dot(t.pad - t.housing, t.direction);
  if (t.kind == TensionerKind::Hydraulic && t.rotor >= 0) {
    // the plunger rides on the guide's pad (its spring and oil push it there): its mass moves
    // with the guide, about the pivot at the lever of the plunger's axis (at the drawn pose)
    RotorModel& guide = m.rotors[t.rotor];
    const double lever = cross(t.pad - guide.axis, t.direction);
    guide.inertia += t.hydraulic.plungerMass * lever * lever;
  }
  if (t.nominalStroke <= 0.0)
    problems.push_back("tensioner.contactPoint: the pad lies behind the housing along 'direction' (stroke " +
                       fmt(t.nominalStroke) + " m); the plunger extends from the housing towards the guide");
}

// The closure gap at closure value x: how far the last of n chords of one pitch, walked from the
// middle of the first wrap, ends beyond the start (NaN where the route has no valid path).
class ClosureGap {
 public:
  ClosureGap(Layout& layout, int links, double pitch) : layout_(layout), n_(links), p_(pitch) {}

  double operator()(double x, double& fitLinks) {
    const std::string why = layout_.circles(x, circles_);
    if (!why.empty()) return std::nan("");
    ChainPath path;
    try {
      path = ChainPath::through(circles_);
    } catch (const std::invalid_argument&) {
      return std::nan("");
    }
    // a guide bends the chain by less than 90 degrees; a larger sweep means the taut chain
    // does not touch it (the tangents wrap around its far side)
    for (const PathSegment& seg : path.segments())
      if (seg.isArc && !layout_.route()[seg.routeIndex].sprocket && std::fabs(seg.sweep) > 0.5 * kPi) return std::nan("");
    const double s0 = path.arcMiddle(0);
    const double g = walkChords(path, s0, n_, p_, nullptr) - s0 - path.length();
    fitLinks = n_ - g / p_;
    return g;
  }

 private:
  Layout& layout_;
  const int n_;
  const double p_;
  std::vector<RouteCircle> circles_;
};

// The gap at nScan + 1 points over the closure range, and the links the path holds there.
struct ClosureScan {
  static constexpr int nScan = 64;
  std::vector<double> xs = std::vector<double>(nScan + 1), gs = std::vector<double>(nScan + 1),
                      fits = std::vector<double>(nScan + 1, std::nan(""));
};

ClosureScan scanClosure(const ClosureDesc& cl, ClosureGap& gap) {
  const int nScan = ClosureScan::nScan;
  ClosureScan sc;
  for (int k = 0; k <= nScan; ++k) {
    sc.xs[k] = cl.rangeMin + (cl.rangeMax - cl.rangeMin) * k / nScan;
    sc.gs[k] = gap(sc.xs[k], sc.fits[k]);
  }
  return sc;
}

// The scan interval with a sign change of the gap nearest the drawn pose (x = 0); -1 if none.
int nearestBracket(const ClosureScan& sc) {
  int best = -1;
  for (int k = 0; k < ClosureScan::nScan; ++k) {
    if (std::isnan(sc.gs[k]) || std::isnan(sc.gs[k + 1])) continue;
    if ((sc.gs[k] <= 0.0) != (sc.gs[k + 1] <= 0.0)) {
      if (best < 0 || std::fabs(sc.xs[k]) < std::fabs(sc.xs[best])) best = k;
    }
  }
  return best;
}

// What to change where the links do not fit: the even link counts (a roller chain's inner and outer
// links alternate) the path holds over the closure range, or how far the path is from the nearest.
std::string closingCounts(double lo, double hi) {
  const long long first = 2 * static_cast<long long>(std::ceil(lo / 2.0)), last = 2 * static_cast<long long>(std::floor(hi / 2.0));
  if (first <= last)
    return "; " + std::to_string(first) + (last > first ? " to " + std::to_string(last) : "") + " links close it";
  const long long below = last, above = first;  // the even counts either side of the range
  return "; no even count closes it: the path is " + fmt(lo - static_cast<double>(below), 3) + " links longer than " +
         std::to_string(below) + " and " + fmt(static_cast<double>(above) - hi, 3) + " shorter than " +
         std::to_string(above) + " (change its length by that many pitches: move a sprocket or the closure's element)";
}

// Why the chain cannot close: the route has no path at the drawn pose, or the number of links
// does not fit (with the range of links the path holds), or no path over the whole range.
DescriptionError noClosure(const ClosureDesc& cl, Layout& layout, const ClosureScan& sc, int n) {
  const std::string unitName = cl.kind == ClosureDesc::Kind::Guide ? "rad" : "m";
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
  for (double f : sc.fits)
    if (!std::isnan(f)) { lo = std::min(lo, f); hi = std::max(hi, f); }
  if (!why.empty()) return DescriptionError({"chain.route: " + why});
  if (lo <= hi)
    return DescriptionError({"chain.numberOfLinks: " + std::to_string(n) + " links cannot close around the layout; "
                             "over the closure range [" + fmt(cl.rangeMin) + ", " + fmt(cl.rangeMax) + "] " +
                             unitName + " of '" + cl.element + "' the path holds between " + fmt(lo, 5) + " and " +
                             fmt(hi, 5) + " links" + closingCounts(lo, hi)});
  return DescriptionError({"chain.route: no valid chain path over the closure range of '" + cl.element + "'"});
}

// Refines the bracket [best, best + 1] (bisection with a secant guess); returns the root.
double refineClosure(ClosureGap& gap, const ClosureScan& sc, int best) {
  double a = sc.xs[best], b = sc.xs[best + 1], ga = sc.gs[best], gb = sc.gs[best + 1];
  double x = a, fit = 0.0;
  for (int it = 0; it < 200; ++it) {
    double c = (ga * b - gb * a) / (ga - gb);
    if (!(c > std::min(a, b) && c < std::max(a, b)) || it % 3 == 2) c = 0.5 * (a + b);
    const double gc = gap(c, fit);
    x = c;
    if (std::fabs(gc) < 1e-14 || std::fabs(b - a) < 1e-16) break;
    if ((gc <= 0.0) == (ga <= 0.0)) { a = c; ga = gc; }
    else { b = c; gb = gc; }
  }
  return x;
}

// Whether the open segments a-b and c-d cross (each one's ends strictly on both sides of the other).
bool segmentsCross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double abc = cross(b - a, c - a), abd = cross(b - a, d - a);
  const double cda = cross(d - c, a - c), cdb = cross(d - c, b - c);
  return ((abc > 0.0 && abd < 0.0) || (abc < 0.0 && abd > 0.0)) && ((cda > 0.0 && cdb < 0.0) || (cda < 0.0 && cdb > 0.0));
}

// The taut path must be one loop. Every sprocket is wrapped from inside the loop (the path turns
// around it in the drive's sense); one that lies inside it, where the chain would wrap it from
// outside (a back-side idler), makes the spans to and from it cross: refused by name, where the
// link count alone would have read as a chain too short.
void checkOneLoop(const DriveDescription& desc, const ChainPath& path) {
  const auto& segs = path.segments();
  const std::size_t n = desc.chain.route.size();
  for (std::size_t i = 0; i < segs.size(); ++i)
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      if (segs[i].isArc || segs[j].isArc || !segmentsCross(segs[i].from, segs[i].to, segs[j].from, segs[j].to)) continue;
      const std::size_t a = static_cast<std::size_t>(segs[i].routeIndex), b = static_cast<std::size_t>(segs[j].routeIndex);
      const auto& route = desc.chain.route;
      if ((a + 1) % n == b || (b + 1) % n == a) {  // the spans to and from one element
        const std::string& e = route[(a + 1) % n == b ? b : a];
        throw DescriptionError({"chain.route: '" + e + "' lies inside the chain's loop, where the chain would wrap it "
                                "from outside (a back-side idler): the spans to and from it cross; the model wraps every "
                                "sprocket from inside the loop: move it outside the loop or leave it out"});
      }
      throw DescriptionError({"chain.route: the spans leaving '" + route[a] + "' and '" + route[b] +
                              "' cross: the route's order does not make one loop"});
    }
}

// The closure value: the root of the gap nearest the drawn pose over the closure range.
double solveClosure(const ClosureDesc& cl, const Model& m, Layout& layout) {
  {  // (at the drawn pose: a route that is no loop is named before its length is)
    std::vector<RouteCircle> drawn;
    if (layout.circles(0.0, drawn).empty()) {
      try {
        checkOneLoop(m.description, ChainPath::through(drawn));
      } catch (const std::invalid_argument&) {  // (no path at the drawn pose: the scan says why)
      }
    }
  }
  ClosureGap gap(layout, m.chain.links, m.chain.pitch);
  const ClosureScan sc = scanClosure(cl, gap);
  const int best = nearestBracket(sc);
  if (best < 0) throw noClosure(cl, layout, sc, m.chain.links);
  return refineClosure(gap, sc, best);
}

// The path at closure value x, and the closing element moved there (sprocket shifted or guide
// rotated), with a note saying so.
void applyClosure(const ClosureDesc& cl, Model& m, Layout& layout, double x) {
  std::vector<RouteCircle> circles;
  if (layout.circles(x, circles) != "") throw DescriptionError({"chain.route: internal: lost the path at the closure"});
  m.path = ChainPath::through(circles);
  checkOneLoop(m.description, m.path);
  m.assembly.closureElement = cl.element;
  m.assembly.closureValue = x;
  m.assembly.pathLength = m.path.length();

  if (cl.kind == ClosureDesc::Kind::Sprocket) {
    SprocketModel& s = m.sprockets[m.description.sprocketIndex(cl.element)];
    s.center = s.center + x * cl.direction;
    m.rotors[s.rotor].axis = s.center;
    m.assembly.notes.push_back("sprocket '" + s.name + "' shifted by " + fmt(x * 1e3) + " mm to close the chain");
  } else {
    m.rotors[m.rotorIndex(cl.element)].initialAngle = x;
    m.assembly.notes.push_back("guide '" + cl.element + "' at " + fmt(x * 180.0 / kPi) +
                               " deg from its drawn pose closes the chain");
  }
}

// What carries the pins on each wrap of the route: a sprocket's rotor, or a guide (with its
// rotor if it pivots).
std::vector<WrapCarrier> wrapCarriers(const Model& m, const std::vector<RouteElement>& route) {
  std::vector<WrapCarrier> carriers(route.size());
  for (std::size_t r = 0; r < route.size(); ++r) {
    const RouteElement& e = route[r];
    carriers[r] = e.sprocket ? WrapCarrier{PinNominal::On::Sprocket, m.sprockets[e.index].rotor}
                             : WrapCarrier{PinNominal::On::Guide, m.guides[e.index].rotor};
  }
  return carriers;
}

// The pin on sprocket rotor `rotor` nearest the point at arc length `mid`; -1 if none.
int pinNearest(const Model& m, int rotor, double mid) {
  int bestPin = -1;
  double bestD = 1e300;
  for (int k = 0; k < m.chain.links; ++k) {
    if (m.pins[k].on != PinNominal::On::Sprocket || m.pins[k].rotor != rotor) continue;
    const double dd = norm(m.pins[k].position - m.path.point(mid));
    if (dd < bestD) { bestD = dd; bestPin = k; }
  }
  return bestPin;
}

// Sprocket angles: a tooth gap at the pin nearest the middle of each wrap; a wrap shorter than
// one pitch seats no roller and is a problem.
void alignSprockets(Model& m, const std::vector<RouteElement>& route, std::vector<std::string>& problems) {
  for (std::size_t r = 0; r < route.size(); ++r) {
    if (!route[r].sprocket) continue;
    SprocketModel& s = m.sprockets[route[r].index];
    const int bestPin = pinNearest(m, s.rotor, m.path.arcMiddle(static_cast<int>(r)));
    if (bestPin < 0) {
      problems.push_back("chain.route[" + std::to_string(r) + "]: the chain wraps sprocket '" + s.name +
                         "' by less than one pitch; no roller is seated on it");
      continue;
    }
    m.rotors[s.rotor].initialAngle = angleOf(m.pins[bestPin].position - s.center);
  }
}

// A span probe at the middle of the free part of the span that leaves route element r.
SpanProbe probeLeaving(const Model& m, std::size_t r) {
  const PathSegment& sg = m.path.segments()[2 * r + 1];
  SpanProbe pr;
  pr.present = true;
  pr.point = 0.5 * (sg.from + sg.to);
  pr.direction = (1.0 / std::max(sg.length, 1e-12)) * (sg.to - sg.from);
  return pr;
}

// The probes of every span, and the measured spans' (span[0] to span[1]) among them.
void placeSpanProbes(Model& m, const DriveDescription& desc) {
  const std::vector<std::string>& route = desc.chain.route;
  for (std::size_t r = 0; r < route.size(); ++r) {
    m.spanProbes.push_back(probeLeaving(m, r));
    if (desc.measurement.tightSpan.size() == 2 && route[r] == desc.measurement.tightSpan[0]) m.tightSpan = m.spanProbes[r];
    if (desc.measurement.slackSpan.size() == 2 && route[r] == desc.measurement.slackSpan[0]) m.slackSpan = m.spanProbes[r];
  }
}

// Output signs: sprockets in the running sense, the tensioner's guide towards the chain.
void setRotorOutputSigns(Model& m) {
  m.rotorOutputSign.assign(m.rotors.size(), 1.0);
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    if (m.rotors[r].isSprocket) {
      m.rotorOutputSign[r] = m.sense;
    } else if (m.tensioner.present && m.tensioner.rotor == static_cast<int>(r)) {
      m.rotorOutputSign[r] = cross(m.tensioner.pad - m.rotors[r].axis, m.tensioner.direction) >= 0.0 ? 1.0 : -1.0;
    }
  }
}

}  // namespace

// The state vector (model.h): the 6 link components over all links, each rotor's angle (and rate
// unless prescribed), then the two energy accumulators and a hydraulic tensioner's chamber oil content.
void layOutState(Model& m) {
  int idx = 6 * m.chain.links;
  for (auto& r : m.rotors) {
    r.stateAngle = idx++;
    r.stateRate = r.prescribed ? -1 : idx++;
  }
  m.stateInputWork = idx++;
  m.stateDissipated = idx++;
  m.stateChamberOil = m.tensioner.hydraulicChamber() ? idx++ : -1;
  m.chainImpulse = layOutImpulseStates(idx, static_cast<int>(m.rotors.size()));
  m.nStates = idx;
  m.nGen = 3 * m.chain.links + static_cast<int>(m.rotors.size());
}

namespace {

// The pin at arc length s and what carries it there: a wrap's carrier, or a span.
PinNominal nominalPin(const ChainPath& path, const std::vector<WrapCarrier>& wrapCarriers, double s) {
  PinNominal pn;
  pn.position = path.point(s);
  pn.tangent = path.tangent(s);
  const PathSegment& seg = path.segments()[path.segmentAt(s)];
  if (seg.isArc) {
    const WrapCarrier& carrier = wrapCarriers[seg.routeIndex];
    pn.on = carrier.on;
    pn.rotor = carrier.rotor;
    pn.center = seg.center;
    pn.radius = std::fabs(seg.signedRadius);
  } else {
    pn.on = PinNominal::On::Span;
  }
  return pn;
}

}  // namespace

void placePins(Model& m, double chord, const std::vector<WrapCarrier>& wrapCarriers) {
  const int n = m.chain.links;
  std::vector<double> spin;
  const double s0 = m.path.arcMiddle(0);
  const double sEnd = walkChords(m.path, s0, n, chord, &spin);
  m.assembly.closureResidual = norm(m.path.point(sEnd) - m.path.point(s0));
  m.pins.resize(n);
  for (int k = 0; k < n; ++k) m.pins[k] = nominalPin(m.path, wrapCarriers, spin[k]);
  m.assembly.maxJointGap = largestChordError(m.pins, chord);
}

double largestChordError(const std::vector<PinNominal>& pins, double chord) {
  const std::size_t n = pins.size();
  double largest = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    largest = std::max(largest, std::fabs(norm(pins[(k + 1) % n].position - pins[k].position) - chord));
  return largest;
}

int Model::rotorIndex(const std::string& n) const {
  for (std::size_t i = 0; i < rotors.size(); ++i)
    if (rotors[i].name == n) return static_cast<int>(i);
  return -1;
}

// A table of contents of the steps above. Problems are collected per stage and thrown together;
// a later stage needs the earlier ones valid.
Model assemble(const DriveDescription& desc) {
  // constants, chain and contact laws: copied from the description
  Model m;
  setConstants(desc, m);

  // the elements: sprockets first (their overlap check needs valid tooth gaps), guides, tensioner
  std::vector<std::string> problems;
  buildSprockets(desc, m, problems);
  throwIfAny(problems);
  checkSprocketOverlaps(m, problems);
  buildGuides(desc, m, problems);
  buildTensioner(desc, m, problems);
  throwIfAny(problems);

  // closure: the closing element placed so that the links close around the route
  Layout layout(desc, m);
  const ClosureDesc& cl = *desc.closure;
  applyClosure(cl, m, layout, solveClosure(cl, m, layout));

  // the rigid pose: pins on the path, each sprocket turned to seat a roller in a tooth gap
  placePins(m, m.chain.pitch, wrapCarriers(m, layout.route()));
  alignSprockets(m, layout.route(), problems);
  throwIfAny(problems);

  // what is measured, and where each quantity lives in the state vector
  placeSpanProbes(m, desc);
  m.monitoredLink = desc.measurement.monitoredLink;
  layOutState(m);
  setRotorOutputSigns(m);
  return m;
}

}  // namespace chaindrive
