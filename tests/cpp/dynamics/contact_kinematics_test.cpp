// Contact kinematics (src/dynamics/contact_kinematics.h) on the default drive's pre-loaded start
// state at 3000 rpm: the relative velocities agree with the contact Jacobian columns and with
// the rate of change of the gaps, detection is complete and ordered, and the tunnelling check
// reports the deepest contact with its kind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "statics/preload.h"
#include "dynamics/contact_kinematics.h"
#include "dynamics/dynamics.h"
#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

namespace {

struct StartState {
  std::shared_ptr<const Model> m = defaultModel();
  std::unique_ptr<InputSignal> in = constantLoads(*m, 3000.0);
  std::vector<double> y;
  Data d{*m};
  StartState() {
    in->evaluate(0.0, d.inputs);
    PreloadReport report;
    y = initialState(*m, d.inputs, PreloadOptions{}, report);
    // velocities off the nominal motion (the seated rollers' normal velocities are near zero),
    // so that every term of the relative velocity counts: up to 0.5 m/s and 50 rad/s per link,
    // 20 rad/s per free rotor, from a fixed sequence
    unsigned seed = 12345u;
    auto next = [&seed] {
      seed = seed * 1103515245u + 12345u;
      return static_cast<double>((seed >> 8) & 0xffff) / 65535.0 - 0.5;
    };
    for (int i = 0; i < m->chain.links; ++i) {
      y[m->linkState(i, Model::kVx)] += next();
      y[m->linkState(i, Model::kVy)] += next();
      y[m->linkState(i, Model::kOmega)] += 100.0 * next();
    }
    for (const RotorModel& r : m->rotors)
      if (r.stateRate >= 0) y[r.stateRate] += 40.0 * next();
    std::vector<double> ydot(y.size());
    forwardCompliant(*m, d, *in, 0.0, y.data(), ydot.data());
  }
};

// The generalized velocity of contact c's link (x, y, gamma) and rotor at state y.
double projectedVelocity(const Model& m, const Data& d, const ContactPoint& c, Vec2 dir, const double* y) {
  double link[3], rotor;
  wColumn(c, dir, link, rotor);
  double v = 0.0;
  for (int k = 0; k < 3; ++k) v += link[k] * y[m.linkState(c.link, 3 + k)];
  return v + (c.rotor >= 0 ? rotor * d.rotorRate[c.rotor] : 0.0);
}

}  // namespace

// u = W^T v: the relative velocities of the kinematics are the Jacobian columns applied to the
// generalized velocities, to rounding (1e-9 m/s against link speeds of about 10 m/s).
TEST(ContactKinematics, RelativeVelocitiesAreTheJacobianColumnsTimesTheVelocities) {
  StartState s;
  ASSERT_GT(s.d.nContacts, 10);
  double largest = 0.0;
  for (int k = 0; k < s.d.nContacts; ++k) {
    largest = std::max(largest, std::fabs(s.d.contacts[k].vN));
    const ContactPoint& c = s.d.contacts[k];
    EXPECT_NEAR(c.vN, projectedVelocity(*s.m, s.d, c, c.normal, s.y.data()), 1e-9) << "contact " << k;
    EXPECT_NEAR(c.vT, projectedVelocity(*s.m, s.d, c, c.tangent, s.y.data()), 1e-9) << "contact " << k;
  }
  EXPECT_GT(largest, 0.1);  // the check is not on velocities that vanish
}

// The gap changes at the normal relative velocity: a central difference of the gap along the
// motion over +-1 ns agrees with vN to 1e-6 m/s (the difference error of the curved profiles
// and the rounding of gaps over 2 ns are about 1e-7 m/s; a wrong sign or a missing term is of the
// order of the velocities, 0.1-10 m/s).
TEST(ContactKinematics, GapRateIsTheNormalRelativeVelocity) {
  StartState s;
  const Model& m = *s.m;
  const double dt = 1e-9;
  auto gapsAt = [&](double t) {
    std::vector<double> y = s.y, ydot(s.y.size());
    forwardCompliant(m, s.d, *s.in, 0.0, s.y.data(), ydot.data());
    for (std::size_t i = 0; i < y.size(); ++i) y[i] += t * ydot[i];
    Data d(m);
    s.in->evaluate(t, d.inputs);
    evaluateKinematics(m, d, y.data());
    detectContacts(m, d, 1e-3);
    return d;
  };
  const Data ahead = gapsAt(dt), behind = gapsAt(-dt);
  forwardCompliant(m, s.d, *s.in, 0.0, s.y.data(), std::vector<double>(s.y.size()).data());
  int compared = 0;
  double worst = 0.0;
  for (int k = 0; k < s.d.nContacts; ++k) {
    const ContactPoint& c = s.d.contacts[k];
    auto same = [&](const ContactPoint& o) {
      return o.kind == c.kind && o.link == c.link && o.end == c.end && o.element == c.element && o.face == c.face;
    };
    const ContactPoint* a = std::find_if(ahead.contacts.data(), ahead.contacts.data() + ahead.nContacts, same);
    const ContactPoint* b = std::find_if(behind.contacts.data(), behind.contacts.data() + behind.nContacts, same);
    if (a == ahead.contacts.data() + ahead.nContacts || b == behind.contacts.data() + behind.nContacts) continue;
    EXPECT_NEAR((a->gap - b->gap) / (2.0 * dt), c.vN, 1e-6) << "contact " << k << " link " << c.link;
    worst = std::max(worst, std::fabs((a->gap - b->gap) / (2.0 * dt) - c.vN));
    ++compared;
  }
  EXPECT_EQ(compared, s.d.nContacts);
  std::printf("largest difference of gap rate and vN: %.3g m/s over %d contacts\n", worst, compared);
}

// Detection: every contact found lies within the margin, a wider margin finds a superset in the
// same order (rollers by link, end and sprocket; then plates by guide, link and face), and two
// detections give the same list.
TEST(ContactKinematics, DetectionIsCompleteAndOrdered) {
  StartState s;
  const Model& m = *s.m;
  Data narrow(m), wide(m);
  for (Data* d : {&narrow, &wide}) {
    d->inputs = s.d.inputs;
    evaluateKinematics(m, *d, s.y.data());
  }
  detectContacts(m, narrow, 0.0);
  detectContacts(m, wide, 1e-3);
  ASSERT_GT(narrow.nContacts, 0);
  ASSERT_GT(wide.nContacts, narrow.nContacts);
  for (int k = 0; k < narrow.nContacts; ++k) EXPECT_LT(narrow.contacts[k].gap, 0.0);
  for (int k = 0; k < wide.nContacts; ++k) EXPECT_LT(wide.contacts[k].gap, 1e-3);
  auto key = [](const ContactPoint& c) {
    return c.kind == ContactPoint::Kind::RollerSprocket ? std::vector<int>{0, c.element, c.link, c.end}
                                                         : std::vector<int>{1, c.link, c.element, c.face};
  };
  for (int k = 1; k < wide.nContacts; ++k) EXPECT_LT(key(wide.contacts[k - 1]), key(wide.contacts[k])) << k;
  int j = 0;  // the narrow list is a subsequence of the wide one
  for (int k = 0; k < wide.nContacts && j < narrow.nContacts; ++k)
    if (key(wide.contacts[k]) == key(narrow.contacts[j])) ++j;
  EXPECT_EQ(j, narrow.nContacts);
  // complete: every roller end against every sprocket and every link against every guide face,
  // one query at a time without the search's coarse tests, finds the same contacts with the same gaps
  for (const double margin : {0.0, 1e-3}) {
    Data& d = margin == 0.0 ? narrow : wide;
    std::vector<ContactPoint> all;
    for (std::size_t sp = 0; sp < m.sprockets.size(); ++sp)
      for (int i = 0; i < m.chain.links; i += 2)
        for (int end = 0; end < 2; ++end) {
          const int r = m.sprockets[sp].rotor;
          ContactPoint c;
          if (rollerSprocketKinematics(m, static_cast<int>(sp), i, end, d.links[i], d.rotorAngle[r], d.rotorCos[r],
                                       d.rotorSin[r], d.rotorRate[r], margin, c))
            all.push_back(c);
        }
    for (int i = 0; i < m.chain.links; ++i)
      for (std::size_t g = 0; g < m.guides.size(); ++g)
        for (std::size_t f = 0; f < m.guides[g].faces.size(); ++f) {
          const int r = m.guides[g].rotor;
          ContactPoint c;
          if (plateGuideKinematics(m, static_cast<int>(g), static_cast<int>(f), i, d.links[i], r >= 0 ? d.rotorCos[r] : 1.0,
                                   r >= 0 ? d.rotorSin[r] : 0.0, r >= 0 ? d.rotorRate[r] : 0.0, margin, c))
            all.push_back(c);
        }
    ASSERT_EQ(static_cast<int>(all.size()), d.nContacts) << "margin " << margin;
    for (int k = 0; k < d.nContacts; ++k) {
      EXPECT_EQ(key(all[k]), key(d.contacts[k])) << k;
      EXPECT_EQ(all[k].gap, d.contacts[k].gap) << k;
      EXPECT_EQ(all[k].vT, d.contacts[k].vT) << k;
      EXPECT_EQ(all[k].rRotor.x, d.contacts[k].rRotor.x) << k;
    }
  }
}

// Tunnelling: the deepest contact beyond the limit is reported, with its kind and link; a
// contact just within the limit is not.
TEST(ContactKinematics, DeepPenetrationNamesTheDeepestContact) {
  std::vector<ContactPoint> contacts(3);
  contacts[0].gap = -0.9e-3;
  contacts[1].gap = -1.5e-3;
  contacts[1].link = 7;
  contacts[1].kind = ContactPoint::Kind::PlateGuide;
  contacts[2].gap = -1.2e-3;
  Failure why;
  EXPECT_FALSE(deepPenetration(contacts.data(), 1, 1e-3, 0.5, why));
  ASSERT_TRUE(deepPenetration(contacts.data(), 3, 1e-3, 0.5, why));
  EXPECT_EQ(why.kind, FailureKind::Tunnelling);
  EXPECT_NE(why.reason.find("plate-guide contact of link 7 penetrates by 1.500 mm"), std::string::npos) << why.reason;
}

// The explicit schemes' evaluations (Data::listContacts off: nothing listed) sum the same forces
// with the same bits as listed ones, and keep the deepest gap: the contacts' most negative one.
TEST(ContactKinematics, UnlistedEvaluationSumsTheSameForces) {
  StartState s;
  const Model& m = *s.m;
  Data listed(m), unlisted(m);
  unlisted.listContacts = false;
  std::vector<double> a(s.y.size()), b(s.y.size());
  for (double t : {0.0, 1e-4}) {
    forwardCompliant(m, listed, *s.in, t, s.y.data(), a.data());
    forwardCompliant(m, unlisted, *s.in, t, s.y.data(), b.data());
    ASSERT_GT(listed.nContacts, 20);
    EXPECT_EQ(unlisted.nContacts, 0);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << "t = " << t;
    EXPECT_EQ(std::memcmp(listed.gen.data(), unlisted.gen.data(), listed.gen.size() * sizeof(double)), 0);
    double deepest = 0.0;
    for (int k = 0; k < listed.nContacts; ++k) deepest = std::min(deepest, listed.contacts[k].gap);
    EXPECT_LT(deepest, 0.0);
    EXPECT_EQ(listed.deepestGap, deepest);
    EXPECT_EQ(unlisted.deepestGap, deepest);
  }
}

// What the roller queries carry from one detection to the next (Data::rollerHints: the tooth
// gap found, the clearance of a roller that touched nothing) only saves work: along 2 ms of
// motion, in steps of the real-time step (where the clearance bound skips queries) and of 50 us,
// detection with carried hints, with scrambled tooth-gap guesses and with none (a fresh work
// area) finds the same contacts with the same bits.
TEST(ContactKinematics, CarriedHintsChangeNoBit) {
  StartState s;
  const Model& m = *s.m;
  std::vector<double> ydot(s.y.size());
  forwardCompliant(m, s.d, *s.in, 0.0, s.y.data(), ydot.data());
  for (const double dt : {2.5e-6, 5e-5}) {
    Data carried(m), scrambled(m);
    int checked = 0;
    for (int step = 0; step <= 40; ++step) {
      const double t = step * dt;
      std::vector<double> y = s.y;
      for (std::size_t i = 0; i < y.size(); ++i) y[i] += t * ydot[i];
      Data fresh(m);
      RollerHints& hints = scrambled.rollerHints;
      for (std::size_t h = 0; h < hints.gap.size(); ++h)
        hints.setGap(static_cast<int>(h), m.sprockets[h / hints.stride], static_cast<int>((h * 7919 + step) % 40));
      for (Data* d : {&fresh, &carried, &scrambled}) {
        d->inputs = s.d.inputs;
        evaluateKinematics(m, *d, y.data());
        detectContacts(m, *d, 0.0);
      }
      ASSERT_EQ(carried.nContacts, fresh.nContacts) << "t = " << t;
      ASSERT_EQ(scrambled.nContacts, fresh.nContacts) << "t = " << t;
      for (int k = 0; k < fresh.nContacts; ++k) {
        const ContactPoint &a = fresh.contacts[k], &b = carried.contacts[k], &c = scrambled.contacts[k];
        EXPECT_TRUE(a.link == b.link && a.end == b.end && a.element == b.element && a.gap == b.gap &&
                    a.normal.x == b.normal.x && a.normal.y == b.normal.y && a.vT == b.vT)
            << "t = " << t << " contact " << k;
        EXPECT_TRUE(a.link == c.link && a.gap == c.gap && a.normal.x == c.normal.x && a.vT == c.vT)
            << "t = " << t << " contact " << k;
        ++checked;
      }
    }
    EXPECT_GT(checked, 40 * 20);
    // the clearance bound did skip queries at the real-time step (and they changed nothing)
    std::printf("steps of %g s: %lld of %lld roller queries skipped by the clearance bound\n", dt,
                carried.rollerQueriesSkipped, carried.rollerQueries);
    if (dt < 1e-5) {
      EXPECT_GT(carried.rollerQueriesSkipped, carried.rollerQueries / 10);
    }
  }
}
