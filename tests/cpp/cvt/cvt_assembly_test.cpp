#include "cvt/cvt_assembly.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

using namespace chaindrive;

TEST(CvtAssembly, RunningRadiiCloseTheChainAtTheRatio) {
  CvtDescription d = defaultCvtDescription();
  for (double ratio : {0.5, 1.0, 2.0}) {
    d.ratio = ratio;
    CvtLayout layout;
    const Model m = assembleCvt(d, &layout);
    EXPECT_NEAR(layout.runningRadius[1] / layout.runningRadius[0], ratio, 1e-12);
    EXPECT_LT(m.assembly.closureResidual, 1e-9) << "ratio " << ratio;
    EXPECT_LT(m.assembly.maxJointGap, 1e-9) << "ratio " << ratio;  // every chord the stretched pitch
    // the driven pulley's pins hold the described clamping force at the pre-tension
    EXPECT_NEAR(layout.clampingForce[1], d.clampingForce, 1e-9 * d.clampingForce);
    EXPECT_NEAR(layout.pretension, 2.0 * std::tan(d.wedgeHalfAngle) * d.clampingForce / layout.wrapAngle[1],
                1e-9 * layout.pretension);
    // the wraps and strands add up to the pins' polygon: the pulleys' free radii just outside the pins
    for (const PulleyModel& p : m.pulleys) EXPECT_GT(p.freeRadius, p.runningRadius);
  }
}

TEST(CvtAssembly, ChainThatDoesNotFitIsNamed) {
  CvtDescription d = defaultCvtDescription();
  d.centerDistance = 0.5;  // 63 links of 9.5 mm cannot reach around pulleys half a metre apart
  try {
    assembleCvt(d);
    FAIL() << "expected a DescriptionError";
  } catch (const DescriptionError& e) {
    EXPECT_NE(std::string(e.what()).find("chain.numberOfLinks"), std::string::npos) << e.what();
  }
}

TEST(CvtAssembly, NominalStateMovesWithThePulleys) {
  const Model m = assembleCvt(defaultCvtDescription());
  const double w = 200.0;
  const std::vector<double> y = cvtNominalState(m, w);
  const double r1 = m.pulleys[kDrivingPulley].runningRadius, r2 = m.pulleys[kDrivenPulley].runningRadius;
  EXPECT_NEAR(y[m.rotors[kDrivenPulley].stateRate], m.sense * w * r1 / r2, 1e-12);
  // every link centre moves at about the chain speed (chords on the wraps a little slower)
  for (int i = 0; i < m.chain.links; ++i) {
    const double v = std::hypot(y[m.linkState(i, Model::kVx)], y[m.linkState(i, Model::kVy)]);
    EXPECT_NEAR(v, w * r1, 0.01 * w * r1) << "link " << i;
  }
}

TEST(CvtAssembly, RatioTableGivesTheSheavesOfEveryRatioInTheRange) {
  const CvtDescription d = defaultCvtDescription();
  const Model m = assembleCvt(d);
  ASSERT_FALSE(m.ratioTable.empty());
  EXPECT_DOUBLE_EQ(m.ratioTable.lo, d.ratioMin);
  EXPECT_NEAR(m.ratioTable.hi(), d.ratioMax, 1e-12);
  // between the table's points: the layout assembled at that ratio, within a micrometre (0.24 um
  // measured; the pins' compression is 40-80 um)
  for (double ratio : {0.53, 0.8, 1.0, 1.37, 1.99}) {
    CvtDescription at = d;
    at.ratio = ratio;
    CvtLayout layout;
    assembleCvt(at, &layout);
    double running[2], free[2];
    m.ratioTable.at(ratio, running, free);
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(running[k], layout.runningRadius[k], 1e-6) << "ratio " << ratio << " pulley " << k;
      EXPECT_NEAR(free[k], layout.freeRadius[k], 1e-6) << "ratio " << ratio << " pulley " << k;
    }
    EXPECT_NEAR(running[1] / running[0], ratio, 1e-4);
  }
}

TEST(CvtAssembly, RatioRangeOutsideWhatTheChainReachesIsNamed) {
  CvtDescription d = defaultCvtDescription();
  d.centerDistance = 0.25;  // the chain closes at ratio 1 (radii 16 mm) ...
  EXPECT_NO_THROW(assembleCvt(d));
  d.ratioMax = 3.0;         // ... but at ratio 3 the small radius would fall below a pitch
  try {
    assembleCvt(d);
    FAIL() << "expected a DescriptionError";
  } catch (const DescriptionError& e) {
    EXPECT_NE(std::string(e.what()).find("pulleys.ratioRange"), std::string::npos) << e.what();
  }
}
