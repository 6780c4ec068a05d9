#include "dynamics/contact_kinematics.h"

#include <cmath>
#include <cstdio>

#include "sincos.h"

namespace chaindrive {

namespace {

// The link's pose and velocities from its state and its axis e = (cos, sin) of its angle.
LinkKin linkKinematics(const ChainModel& ch, const double* s, Vec2 e) {
  LinkKin k;
  k.c = Vec2{s[0], s[1]};
  k.e = e;
  k.v = Vec2{s[3], s[4]};
  k.w = s[5];
  const Vec2 half = (0.5 * ch.pitch) * k.e;
  k.rear = k.c - half;
  k.front = k.c + half;
  const Vec2 vHalf = crossWz(k.w, half);
  k.vRear = k.v - vHalf;
  k.vFront = k.v + vHalf;
  return k;
}

}  // namespace

LinkKin linkKinematics(const ChainModel& ch, const double* s) {
  Vec2 e;
  sinCos(s[2], e.y, e.x);
  return linkKinematics(ch, s, e);
}

void evaluateKinematics(const Model& m, Data& d, const double* y) {
  const int n = m.chain.links;
  // the link axes first, two at a time in a loop of their own (sinCos2: the same bits as one at
  // a time), then the rest of every link's kinematics
  int i = 0;
  for (; i + 2 <= n; i += 2) {
    const double angle[2] = {y[6 * i + 2], y[6 * i + 8]};
    double sine[2], cosine[2];
    sinCos2(angle, sine, cosine);
    d.links[i].e = Vec2{cosine[0], sine[0]};
    d.links[i + 1].e = Vec2{cosine[1], sine[1]};
  }
  if (i < n) sinCos(y[6 * i + 2], d.links[i].e.y, d.links[i].e.x);
  for (i = 0; i < n; ++i) d.links[i] = linkKinematics(m.chain, y + 6 * i, d.links[i].e);
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    const RotorModel& ro = m.rotors[r];
    const double a = y[ro.stateAngle];
    d.rotorAngle[r] = a;
    sinCos(a, d.rotorSin[r], d.rotorCos[r]);
    d.rotorRate[r] = ro.prescribed ? m.sense * d.inputs.crankSpeed : y[ro.stateRate];
  }
}

namespace {

// The tooth gap whose sector (from the tooth axis before it to the one after it) holds the
// direction `body` (sprocket frame), walked to from `guess`. The sectors partition the plane
// exactly (one cross product decides between two neighbours), so the gap found does not depend
// on the guess: a guess only saves the search (and the atan2 a first guess costs).
int gapOf(const SprocketModel& s, Vec2 body, int guess) {
  const int z = s.gap.teeth;
  int k = guess;
  if (k < 0 || k >= z) {
    k = static_cast<int>(std::lround(std::atan2(body.y, body.x) / s.gap.gapAngle)) % z;
    if (k < 0) k += z;
  }
  for (int i = 0; i < z; ++i) {
    if (cross(s.toothDirs[k], body) < 0.0) {
      k = k == 0 ? z - 1 : k - 1;
      continue;
    }
    const int next = k + 1 == z ? 0 : k + 1;
    if (cross(body, s.toothDirs[next]) <= 0.0) {
      k = next;
      continue;
    }
    break;
  }
  return k;
}

}  // namespace

namespace {

// The roller at p (rel = p - the sprocket's centre, within its reach) of link `link` at `end`
// against sprocket `sprocket`: the contact search's inner query, inlined there.
inline bool rollerContact(const Model& m, int sprocket, int link, int end, const LinkKin& lk, Vec2 p, Vec2 rel,
                          double cosA, double sinA, double rate, double margin, ContactPoint& cp, int* gapHint) {
  const SprocketModel& s = m.sprockets[sprocket];
  // roller centre in the sprocket frame, then in the frame of its tooth gap
  const Vec2 body = rotate(rel, cosA, -sinA);
  const int k = gapOf(s, body, gapHint ? *gapHint : -1);
  if (gapHint) *gapHint = k;
  const Vec2 gd = s.gapDirs[k];
  const Vec2 local = rotate(body, gd.x, -gd.y);
  const ProfileHit hit = s.gap.closest(local);
  const double gap = hit.distance - m.chain.rollerRadius;
  if (gap >= margin) return false;
  // back to the world frame: rotation by (rotor angle + k * gapAngle)
  const double c = cosA * gd.x - sinA * gd.y, sn = sinA * gd.x + cosA * gd.y;
  const Vec2 nW = rotate(hit.normal, c, sn);
  const Vec2 qW = s.center + rotate(hit.point, c, sn);
  cp.kind = ContactPoint::Kind::RollerSprocket;
  cp.link = link;
  cp.end = end;
  cp.element = sprocket;
  cp.face = -1;
  cp.rotor = s.rotor;
  cp.gap = gap;
  cp.normal = nW;
  cp.tangent = perp(nW);
  cp.rLink = p - lk.c;   // the roller turns on its bushing: the force acts at the roller centre
  cp.rRotor = qW - s.center;
  const Vec2 vChain = end == 0 ? lk.vRear : lk.vFront;
  const Vec2 vRel = vChain - crossWz(rate, cp.rRotor);
  cp.vN = dot(vRel, cp.normal);
  cp.vT = dot(vRel, cp.tangent);
  cp.fN = cp.fT = 0.0;
  return true;
}

}  // namespace

bool rollerSprocketKinematics(const Model& m, int sprocket, int link, int end, const LinkKin& lk, double /*angle*/,
                              double cosA, double sinA, double rate, double margin, ContactPoint& cp, int* gapHint) {
  const SprocketModel& s = m.sprockets[sprocket];
  const Vec2 p = end == 0 ? lk.rear : lk.front;
  const Vec2 rel = p - s.center;
  if (norm2(rel) > s.reach2) return false;
  return rollerContact(m, sprocket, link, end, lk, p, rel, cosA, sinA, rate, margin, cp, gapHint);
}

bool plateGuideKinematics(const Model& m, int guide, int face, int link, const LinkKin& lk, double cosA, double sinA,
                          double rate, double margin, ContactPoint& cp) {
  const GuideModel& g = m.guides[guide];
  return plateGuideKinematics(m, guide, face, placeFace(g.faces[face], g.pivot, cosA, sinA), link, lk, rate, margin, cp);
}

bool plateGuideKinematics(const Model& m, int guide, int face, const PlacedFace& pf, int link, const LinkKin& lk,
                          double rate, double margin, ContactPoint& cp) {
  const GuideModel& g = m.guides[guide];
  const Vec2 outward = faceOutwardNear(pf, lk.c);
  const Vec2 side = perp(lk.e);
  const double sgn = dot(side, outward) > 0.0 ? -1.0 : 1.0;  // the plate edge that faces the guide
  const Vec2 off = (sgn * m.chain.plateHalfHeight) * side;
  const FaceHit hit = plateEdgeFaceContact(pf, lk.rear + off, lk.front + off, sgn * side);
  if (!hit.valid || hit.gap >= margin) return false;
  cp.kind = ContactPoint::Kind::PlateGuide;
  cp.link = link;
  cp.end = 0;
  cp.element = guide;
  cp.face = face;
  cp.rotor = g.rotor;
  cp.gap = hit.gap;
  cp.normal = hit.normal;
  cp.tangent = perp(hit.normal);
  cp.rLink = hit.point - lk.c;
  cp.rRotor = hit.point - g.pivot;
  const Vec2 vChain = lk.v + crossWz(lk.w, cp.rLink);
  const Vec2 vRel = g.rotor >= 0 ? vChain - crossWz(rate, cp.rRotor) : vChain;
  cp.vN = dot(vRel, cp.normal);
  cp.vT = dot(vRel, cp.tangent);
  cp.fN = cp.fT = 0.0;
  return true;
}

void detectContacts(const Model& m, Data& d, double margin) {
  const int n = m.chain.links;
  const int cap = static_cast<int>(d.contacts.size());
  int count = 0;
  // rollers sit on the inner links (even index), one at each end; most are far from every
  // sprocket, which one distance test tells
  const std::size_t nSprockets = m.sprockets.size();
  for (int i = 0; i < n; i += 2) {
    const LinkKin& lk = d.links[i];
    for (int end = 0; end < 2; ++end) {
      const Vec2 roller = end == 0 ? lk.rear : lk.front;
      for (std::size_t s = 0; s < nSprockets; ++s) {
        const SprocketModel& sp = m.sprockets[s];
        const Vec2 rel = roller - sp.center;
        if (norm2(rel) > sp.reach2 || count >= cap) continue;
        const int r = sp.rotor;
        if (rollerContact(m, static_cast<int>(s), i, end, lk, roller, rel, d.rotorCos[r], d.rotorSin[r], d.rotorRate[r],
                          margin, d.contacts[count], &d.gapHints[(i + end) * nSprockets + s]))
          ++count;
      }
    }
  }
  // a plate edge lies within reachLink of its link's centre
  const double reachLink = std::hypot(0.5 * m.chain.pitch, m.chain.plateHalfHeight) + std::fabs(margin);
  for (std::size_t gi = 0; gi < m.guides.size(); ++gi) {
    const GuideModel& g = m.guides[gi];
    const double cosA = g.rotor >= 0 ? d.rotorCos[g.rotor] : 1.0;
    const double sinA = g.rotor >= 0 ? d.rotorSin[g.rotor] : 0.0;
    const double rate = g.rotor >= 0 ? d.rotorRate[g.rotor] : 0.0;
    const Vec2 bc = g.pivot + rotate(g.boundCenter - g.pivot, cosA, sinA);
    const double reach = g.boundRadius + 2.0 * reachLink;
    const std::size_t nFaces = g.faces.size();  // d.placedFaces holds the most faces of any guide
    for (std::size_t f = 0; f < nFaces; ++f) d.placedFaces[f] = placeFace(g.faces[f], g.pivot, cosA, sinA);
    for (int i = 0; i < n; ++i) {
      const LinkKin& lk = d.links[i];
      if (norm2(lk.c - bc) > reach * reach) continue;
      for (std::size_t f = 0; f < nFaces; ++f)
        if (count < cap && faceNear(d.placedFaces[f], lk.c, reachLink) &&
            plateGuideKinematics(m, static_cast<int>(gi), static_cast<int>(f), d.placedFaces[f], i, lk, rate, margin,
                                 d.contacts[count]))
          ++count;
    }
  }
  d.nContacts = count;
}

bool deepPenetration(const ContactPoint* contacts, int n, double limit, double t, Failure& why) {
  int worst = -1;
  for (int k = 0; k < n; ++k)
    if (contacts[k].gap < -limit && (worst < 0 || contacts[k].gap < contacts[worst].gap)) worst = k;
  if (worst < 0) return false;
  const ContactPoint& c = contacts[worst];
  char buf[256];
  std::snprintf(buf, sizeof buf, "tunnelling: %s contact of link %d penetrates by %.3f mm (limit %.3f mm) at t = %.6f s",
                c.kind == ContactPoint::Kind::RollerSprocket ? "roller-sprocket" : "plate-guide", c.link, -c.gap * 1e3,
                limit * 1e3, t);
  why = {FailureKind::Tunnelling, buf};
  return true;
}

}  // namespace chaindrive
