// The per-link loops (src/dynamics/link_loops.h) give, bit for bit, what the formulas of one link
// at a time give, and they and the contact search's loops (contact_lanes.h) the same bits with 2
// lanes (SSE2) and with 4 (AVX2, where this CPU has it): on the default drive, on a drive of 122
// links (a last vector of 4 lanes only partly filled) and with joint clearance (the other branch
// of the joint law). (The contact search against one query at a time: contact_kinematics_test.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "dynamics/contact_kinematics.h"
#include "dynamics/dynamics.h"
#include "dynamics/joint_forces.h"
#include "dynamics/link_loops.h"
#include "test_util.h"

using namespace chaindrive;
using chaindrive::test::modifiedDefault;
using chaindrive::test::runningState;

namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Everything the loops write, in one list of doubles.
std::vector<double> loopOutputs(const Model& m, const Data& d, double power) {
  const LinkArrays& L = d.links;
  std::vector<double> out;
  for (const std::vector<double>* a : {&L.cx, &L.cy, &L.vx, &L.vy, &L.w, &L.ex, &L.ey, &L.rearX, &L.rearY, &L.frontX,
                                       &L.frontY, &L.vRearX, &L.vRearY, &L.vFrontX, &L.vFrontY})
    out.insert(out.end(), a->begin(), a->end());  // (with the padding: it must stay as it was)
  for (int j = -1; j < m.chain.links; ++j) {
    out.push_back(d.joints.forceX()[j]);
    out.push_back(d.joints.forceY()[j]);
  }
  out.insert(out.end(), d.gen.begin(), d.gen.end());
  out.push_back(d.nContacts);
  for (int k = 0; k < d.nContacts; ++k) {
    const ContactPoint& c = d.contacts[k];
    for (double v : {double(c.link), double(c.end), double(c.element), c.gap, c.normal.x, c.normal.y, c.tangent.x,
                     c.tangent.y, c.rLink.x, c.rLink.y, c.rRotor.x, c.rRotor.y, c.vN, c.vT, c.fN, c.fT})
      out.push_back(v);
  }
  out.push_back(power);
  out.push_back(d.jointOpening2);
  out.insert(out.end(), d.joints.tension.begin(), d.joints.tension.end());
  out.insert(out.end(), d.joints.deformation.begin(), d.joints.deformation.end());
  out.push_back(jointEnergy(m, d));
  return out;
}

// Kinematics, joints and the contacts with their forces (the contact search's loops) with the
// given lanes.
std::vector<double> runLoops(const Model& m, const InputSignal& in, const std::vector<double>& y, int lanes) {
  Data d(m);
  d.vectorLanes = lanes;
  in.evaluate(0.0, d.inputs);
  evaluateKinematics(m, d, y.data());
  std::fill(d.gen.begin() + m.rotorGen(0), d.gen.end(), 0.0);
  double power = evaluateJoints(m, d);
  power += detectContacts(m, d, 0.0, true);
  measureJoints(m, d);
  std::vector<double> out = loopOutputs(m, d, power);
  // the joints' damping off its diagonal, applied to the link velocities as a field
  const auto velocities = y.begin() + m.linkState(0, Model::kVx);
  std::vector<double> field(velocities, velocities + 3 * m.chain.links);
  jointDampingOffDiagonalLoop(m, d, 1.7e-6, field.data());
  out.insert(out.end(), field.begin(), field.end());
  return out;
}

// The loops against the formulas of one link and one joint at a time, and 2 lanes against 4.
void checkLoops(const Model& m) {
  HeldInputs in(m);
  in.values.crankSpeed = 314.159;
  const std::vector<double> y = runningState(m, in);
  const int n = m.chain.links;
  Data d(m);
  d.vectorLanes = 2;
  in.evaluate(0.0, d.inputs);
  evaluateKinematics(m, d, y.data());
  const double power = evaluateJoints(m, d);
  measureJoints(m, d);
  double expectedPower = 0.0, expectedEnergy = 0.0, widest = 0.0;
  for (int i = 0; i < n; ++i) {
    const LinkKin one = linkKinematics(m, y.data(), i), loop = d.links[i];
    for (auto [a, b] : {std::pair{one.c, loop.c}, {one.v, loop.v}, {one.e, loop.e}, {one.rear, loop.rear},
                        {one.front, loop.front}, {one.vRear, loop.vRear}, {one.vFront, loop.vFront}})
      ASSERT_TRUE(sameBits(a.x, b.x) && sameBits(a.y, b.y)) << "link " << i;
    const int k = (i + 1) % n;
    const JointResult jr = jointForce(m.chain, one, linkKinematics(m, y.data(), k));
    ASSERT_TRUE(sameBits(jr.force.x, d.joints.force(i).x) && sameBits(jr.force.y, d.joints.force(i).y)) << "joint " << i;
    ASSERT_TRUE(sameBits(d.joints.tension[i], jointTension(one, linkKinematics(m, y.data(), k), jr.force))) << i;
    ASSERT_TRUE(sameBits(d.joints.deformation[i], jointDeformation(m.chain, one, linkKinematics(m, y.data(), k))))
        << i;
    expectedPower += jr.power;
    expectedEnergy += jr.energy;
    widest = std::max(widest, norm2(one.front - linkKinematics(m, y.data(), k).rear));
  }
  // the links' forces: the front joint's force at the front pin, the rear joint's opposite one at the rear pin
  for (int i = 0; i < n; ++i) {
    const LinkKin lk = d.links[i];
    const Vec2 front = d.joints.force(i), rear = d.joints.force((i + n - 1) % n);
    ASSERT_TRUE(sameBits(d.gen[m.linkGen(i, Model::kX)], front.x - rear.x)) << i;
    ASSERT_TRUE(sameBits(d.gen[m.linkGen(i, Model::kY)], front.y - rear.y)) << i;
    ASSERT_TRUE(sameBits(d.gen[m.linkGen(i, Model::kGamma)], cross(lk.front - lk.c, front) - cross(lk.rear - lk.c, rear)))
        << i;
  }
  EXPECT_NEAR(power, expectedPower, 1e-12 * std::fabs(expectedPower));  // (summed in another order)
  EXPECT_NEAR(jointEnergy(m, d), expectedEnergy, 1e-12 * expectedEnergy);
  EXPECT_EQ(d.jointOpening2, widest);
  // 2 lanes against 4, every output and the padding
  const std::vector<double> two = runLoops(m, in, y, 2);
  if (supportedVectorLanes() < 4) GTEST_SKIP() << "this CPU has no AVX2: the 4-lane loops are not run";
  const std::vector<double> four = runLoops(m, in, y, 4);
  ASSERT_EQ(two.size(), four.size());
  for (std::size_t k = 0; k < two.size(); ++k) ASSERT_TRUE(sameBits(two[k], four[k])) << "output " << k;
}

}  // namespace

TEST(LinkLoops, DefaultDriveSameBitsAsOneLinkAtATimeWithTwoAndFourLanes) {
  checkLoops(assemble(defaultDriveDescription()));
}

TEST(LinkLoops, PartlyFilledLastVectorSameBits) {
  // 122 links (the camshafts 10 mm further up to make room): the last vector of 4 holds 2 links
  const Model m = assemble(modifiedDefault([](nlohmann::json& j) {
    j["chain"]["numberOfLinks"] = 122;
    for (auto& s : j["sprockets"])
      if (s["name"] != "crankshaft") s["center"][1] = s["center"][1].get<double>() + 0.010;
  }));
  ASSERT_EQ(m.chain.links % 4, 2);
  checkLoops(m);
}

TEST(LinkLoops, JointClearanceSameBits) {
  const Model m = assemble(modifiedDefault([](nlohmann::json& j) { j["chain"]["joint"]["clearance"] = 2e-6; }));
  checkLoops(m);
}
