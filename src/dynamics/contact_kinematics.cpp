#include "dynamics/contact_kinematics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dynamics/pin_sheave.h"
#include "dynamics/contact_compliant.h"
#include "dynamics/contact_lanes.h"
#include "dynamics/link_loops.h"
#include "math/sincos.h"
#include "math/elementary.h"

namespace chaindrive {

namespace {

// The link's pose and velocities from its centre, velocities and its axis e = (cos, sin) of its angle.
LinkKin linkKinematics(const ChainModel& ch, Vec2 c, Vec2 v, double w, Vec2 e) {
  LinkKin k;
  k.c = c;
  k.e = e;
  k.v = v;
  k.w = w;
  const Vec2 half = (0.5 * ch.pitch) * k.e;
  k.rear = k.c - half;
  k.front = k.c + half;
  const Vec2 vHalf = crossWz(k.w, half);
  k.vRear = k.v - vHalf;
  k.vFront = k.v + vHalf;
  return k;
}

}  // namespace

LinkKin linkKinematics(const Model& m, const double* y, int link) {
  Vec2 e;
  sinCos(y[m.linkState(link, Model::kGamma)], e.y, e.x);
  return linkKinematics(m.chain, Vec2{y[m.linkState(link, Model::kX)], y[m.linkState(link, Model::kY)]},
                        Vec2{y[m.linkState(link, Model::kVx)], y[m.linkState(link, Model::kVy)]},
                        y[m.linkState(link, Model::kOmega)], e);
}

void evaluateKinematics(const Model& m, Data& d, const double* y) {
  linkKinematicsLoop(m, d, y);
  rotorKinematics(m, d, y);
}

void rotorKinematics(const Model& m, Data& d, const double* y) {
  for (std::size_t r = 0; r < m.rotors.size(); ++r) {
    const RotorModel& ro = m.rotors[r];
    const double a = y[ro.stateAngle];
    d.rotorAngle[r] = a;
    sinCos(a, d.rotorSin[r], d.rotorCos[r]);
    d.rotorRate[r] = ro.prescribed ? m.sense * d.inputs.crankSpeed : y[ro.stateRate];
  }
}

namespace roller {

int searchGap(const SprocketModel& s, Vec2 body, int guess) {
  const int z = s.gap.teeth;
  int k = guess;
  if (k < 0 || k >= z) {
    k = static_cast<int>(std::lround(math::atan2(body.y, body.x) / s.gap.gapAngle)) % z;
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

}  // namespace roller

bool rollerSprocketKinematics(const Model& m, int sprocket, int link, int end, const LinkKin& lk, double /*angle*/,
                              double cosA, double sinA, double rate, double margin, ContactPoint& cp) {
  const SprocketModel& s = m.sprockets[sprocket];
  const Vec2 p = end == 0 ? lk.rear : lk.front, v = end == 0 ? lk.vRear : lk.vFront;
  const Vec2 rel = p - s.center;
  if (norm2(rel) > s.reach2) return false;
  Vec2 body;
  roller::toSprocketFrame(rel.x, rel.y, cosA, sinA, body.x, body.y);
  // the roller centre in the frame of its tooth gap, its closest point on the outline there
  const int k = roller::gapOf(s, body, -1);
  const Vec2 gd = s.gapDirs[k];
  Vec2 local;
  roller::toGapFrame(body.x, body.y, gd.x, gd.y, local.x, local.y);
  const ProfileHit hit = s.gap.closest(local);
  const double gap = hit.distance - m.chain.rollerRadius;
  if (gap >= margin) return false;
  const roller::World<double> w = roller::toWorld(s.center, cosA, sinA, rate, gd.x, gd.y, hit.point.x, hit.point.y,
                                                  hit.normal.x, hit.normal.y, p.x, p.y, v.x, v.y, lk.c.x, lk.c.y);
  const roller::World<double[1]> one{{w.normalX}, {w.normalY}, {w.tangentX}, {w.tangentY}, {w.rLinkX},
                                     {w.rLinkY},  {w.rRotorX}, {w.rRotorY},  {w.vN},       {w.vT}};
  roller::setContact<1>(cp, link, end, sprocket, s.rotor, gap, one, 0);
  return true;
}

bool plateGuideKinematics(const Model& m, int guide, int face, int link, const LinkKin& lk, double cosA, double sinA,
                          double rate, double margin, ContactPoint& cp) {
  const GuideModel& g = m.guides[guide];
  return plateGuideKinematics(m, guide, face, placeFace(g.faces[face], g.pivot, cosA, sinA), link, lk, rate, margin, cp);
}

namespace {

// The edge of the link's plates that faces the placed face: -1 or +1 along perp(e).
double facingSide(const PlacedFace& pf, Vec2 c, Vec2 e) {
  return dot(perp(e), faceOutwardNear(pf, c)) > 0.0 ? -1.0 : 1.0;
}

// That edge's contact with the face (hit.valid false: none), the edge half the plate height
// from the pin line.
FaceHit plateEdgeHit(const Model& m, const PlacedFace& pf, const LinkKin& lk, double side) {
  const Vec2 normal = side * perp(lk.e);
  const Vec2 off = m.chain.plateHalfHeight * normal;
  return plateEdgeFaceContact(pf, lk.rear + off, lk.front + off, normal);
}


}  // namespace

void setPlateContact(const Model& m, int guide, int face, int link, Vec2 center, Vec2 velocity, double omega,
                     const FaceHit& hit, double rate, ContactPoint& cp) {
  const GuideModel& g = m.guides[guide];
  cp.kind = ContactPoint::Kind::PlateGuide;
  cp.link = link;
  cp.end = 0;
  cp.element = guide;
  cp.face = face;
  cp.rotor = g.rotor;
  cp.gap = hit.gap;
  cp.normal = hit.normal;
  cp.tangent = perp(hit.normal);
  cp.rLink = hit.point - center;
  cp.rRotor = hit.point - g.pivot;
  const Vec2 vChain = velocity + crossWz(omega, cp.rLink);
  const Vec2 vRel = g.rotor >= 0 ? vChain - crossWz(rate, cp.rRotor) : vChain;
  cp.vN = dot(vRel, cp.normal);
  cp.vT = dot(vRel, cp.tangent);
  cp.fN = cp.fT = 0.0;
}

bool plateGuideKinematics(const Model& m, int guide, int face, const PlacedFace& pf, int link, const LinkKin& lk,
                          double rate, double margin, ContactPoint& cp) {
  const FaceHit hit = plateEdgeHit(m, pf, lk, facingSide(pf, lk.c, lk.e));
  if (!hit.valid || hit.gap >= margin) return false;
  setPlateContact(m, guide, face, link, lk.c, lk.v, lk.w, hit, rate, cp);
  return true;
}

namespace {

// Calls f(i) for every link of the thread's part (all links without one), in increasing order.
template <class F>
void forEachOwnLink(const Model& m, const ThreadPart* part, F f) {
  if (!part) {
    for (int i = 0; i < m.chain.links; ++i) f(i);
    return;
  }
  for (const LinkRange& r : part->ranges)
    for (int i = r.first; i < r.last; ++i) f(i);
}

// The links near a guide against its faces (placed in d.placedFaces), in the order of guides, faces
// and links: arc faces several links at a time (contact_lanes.h), line faces one at a time. With a
// thread's part, its links only, the forces shared (sharePlateForce).
int detectPlateContacts(const Model& m, Data& d, double margin, double reachLink, bool forces, int count,
                        double& power, ThreadPart* part) {
  const int cap = static_cast<int>(d.contacts.size());
  const bool list = d.listsContacts(forces);
  int faceIndex = 0;  // in d.placedFaces
  for (std::size_t gi = 0; gi < m.guides.size(); ++gi) {
    const GuideModel& g = m.guides[gi];
    const double rate = g.rotor >= 0 ? d.rotorRate[g.rotor] : 0.0;
    const Vec2 bc{d.guideBoundX[gi], d.guideBoundY[gi]};
    const double reach2 = d.guideReach2[gi];
    for (std::size_t f = 0; f < g.faces.size(); ++f, ++faceIndex) {
      const PlacedFace& pf = d.placedFaces[faceIndex];
      if (g.faces[f].type != GuideFace::Type::Line) {
        const PlateFaceRef face{static_cast<int>(gi), static_cast<int>(f), pf, faceIndex, part};
        count = plateContactsLoop(m, d, face, margin, reachLink, forces, count, power);
        continue;
      }
      forEachOwnLink(m, part, [&](int i) {
        if (count >= cap && list) return;
        const LinkKin lk = d.links[i];
        if (norm2(lk.c - bc) > reach2 || !faceNear(pf, lk.c, reachLink)) return;
        const FaceHit hit = plateEdgeHit(m, pf, lk, facingSide(pf, lk.c, lk.e));
        if (!hit.valid || hit.gap >= margin) return;
        ContactPoint unlisted;
        ContactPoint& c = list ? d.contacts[count++] : unlisted;
        setPlateContact(m, static_cast<int>(gi), static_cast<int>(f), i, lk.c, lk.v, lk.w, hit, rate, c);
        if (!forces) return;
        if (part) sharePlateForce(m, c, d, *part, faceIndex);
        else power += addCompliantForce(m, m.plateGuide, c, d);
      });
    }
  }
  return count;
}

}  // namespace

double placeGuides(const Model& m, Data& d, double margin) {
  // a link is near a guide when its centre lies within the guide's bounding circle grown by twice
  // the reach of a plate edge from its link's centre
  const double reachLink = norm(Vec2{0.5 * m.chain.pitch, m.chain.plateHalfHeight}) + std::fabs(margin);
  std::size_t faceIndex = 0;
  for (std::size_t gi = 0; gi < m.guides.size(); ++gi) {
    const GuideModel& g = m.guides[gi];
    const double cosA = g.rotor >= 0 ? d.rotorCos[g.rotor] : 1.0;
    const double sinA = g.rotor >= 0 ? d.rotorSin[g.rotor] : 0.0;
    const Vec2 bc = g.pivot + rotate(g.boundCenter - g.pivot, cosA, sinA);
    const double reach = g.boundRadius + 2.0 * reachLink;
    d.guideBoundX[gi] = bc.x;
    d.guideBoundY[gi] = bc.y;
    d.guideReach2[gi] = reach * reach;
    for (const GuideFace& face : g.faces) d.placedFaces[faceIndex++] = placeFace(face, g.pivot, cosA, sinA);
  }
  return reachLink;
}

double detectContacts(const Model& m, Data& d, double margin, bool forces) {
  const double reachLink = placeGuides(m, d, margin);
  updateSearchWindows(m, d, margin);
  d.deepestGap = 0.0;
  // the rollers sprocket by sprocket, then the plates guide by guide, several at a time
  int count = 0;
  double power = 0.0;
  for (std::size_t s = 0; s < m.sprockets.size(); ++s)
    count = rollerContactsLoop(m, d, static_cast<int>(s), margin, forces, count, power);
  count = detectPlateContacts(m, d, margin, reachLink, forces, count, power, nullptr);
  // a CVT's rocker pins between its pulleys' sheaves
  d.nContacts = m.pulleys.empty() ? count : pinSheaveContacts(m, d, margin, forces, count, power);
  return power;
}

void shareContacts(const Model& m, Data& d, double reachLink, ThreadPart& part) {
  part.deepestGap = 0.0;
  part.rollerQueries = part.rollerQueriesSkipped = 0;
  std::fill(part.plateCount.begin(), part.plateCount.end(), 0);
  for (std::size_t s = 0; s < m.sprockets.size(); ++s) rollerContactsShare(m, d, static_cast<int>(s), part);
  double unused = 0.0;
  detectPlateContacts(m, d, 0.0, reachLink, true, 0, unused, &part);
}

double sumSharedContacts(const Model& m, Data& d) {
  double power = 0.0;
  for (std::size_t s = 0; s < m.sprockets.size(); ++s) rollerContactsSum(m, d, static_cast<int>(s), power);
  // the plates' shares face by face in link order (each part's are: merged)
  std::vector<ThreadPart>& parts = d.threads.parts;
  int faceIndex = 0;
  for (const GuideModel& g : m.guides)
    for (std::size_t f = 0; f < g.faces.size(); ++f, ++faceIndex) {
      const std::size_t base = static_cast<std::size_t>(faceIndex * m.chain.links);
      int next[StagePool::kMaxThreads] = {};
      for (;;) {
        const PlateShare* first = nullptr;
        int from = -1;
        for (std::size_t t = 0; t < parts.size(); ++t) {
          if (next[t] == parts[t].plateCount[faceIndex]) continue;
          const PlateShare& share = parts[t].plates[base + static_cast<std::size_t>(next[t])];
          if (!first || share.link < first->link) first = &share, from = static_cast<int>(t);
        }
        if (!first) break;
        ++next[from];
        if (g.rotor >= 0) d.gen[m.rotorGen(g.rotor)] -= first->moment;
        power += first->power;
      }
    }
  d.deepestGap = 0.0;
  for (const ThreadPart& part : parts) {
    d.deepestGap = std::min(d.deepestGap, part.deepestGap);
    d.rollerQueries += part.rollerQueries;
    d.rollerQueriesSkipped += part.rollerQueriesSkipped;
  }
  d.nContacts = 0;
  return power;
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
