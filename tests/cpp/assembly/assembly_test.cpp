// Assembly of the default drive: the chain closes at the initial pose, its length is n * p,
// the nominal pose puts rollers in the tooth gaps, and the preload converges.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "dynamics/contact_kinematics.h"
#include "dynamics/data.h"
#include "dynamics/dynamics.h"
#include "statics/preload.h"
#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

TEST(Assembly, ChainClosesWithAllJointGapsBelowOneNanometre) {
  const Model m = assemble(defaultDriveDescription());
  const std::vector<double> y = nominalState(m, 314.0);
  double worst = 0.0, length = 0.0;
  const int n = m.chain.links;
  for (int j = 0; j < n; ++j) {
    const LinkKin a = linkKinematics(m, y.data(), j);
    const LinkKin b = linkKinematics(m, y.data(), (j + 1) % n);
    worst = std::max(worst, norm(a.front - b.rear));
    length += norm(a.front - a.rear);
  }
  // tolerance: the closure solve stops at 1e-14 m; link angles pass through atan2 (1e-16 rad)
  EXPECT_LT(worst, 1e-9) << "largest joint gap " << worst << " m";
  EXPECT_NEAR(length, n * m.chain.pitch, 1e-9);
  EXPECT_LT(m.assembly.closureResidual, 1e-9);
  // the default drive is designed to close at the tension guide's drawn (nominal) pose
  EXPECT_LT(std::fabs(m.assembly.closureValue), 1e-6) << "tension guide closes at " << m.assembly.closureValue << " rad";
}

TEST(Assembly, PinsOnSprocketsSitInToothGapCentres) {
  const Model m = assemble(defaultDriveDescription());
  int checked = 0;
  for (const auto& p : m.pins) {
    if (p.on != PinNominal::On::Sprocket) continue;
    const RotorModel& r = m.rotors[p.rotor];
    const SprocketModel& s = m.sprockets[r.element];
    const Vec2 rel = p.position - s.center;
    EXPECT_NEAR(norm(rel), s.gap.pitchRadius, 1e-12);
    const double rel_angle = wrapAngle(angleOf(rel) - r.initialAngle);
    const double k = rel_angle / s.gap.gapAngle;
    EXPECT_NEAR(k, std::round(k), 1e-9) << "pin not at a gap centre on " << s.name;
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST(Assembly, NominalPoseHasNoPenetrationAndPreloadConverges) {
  const Model m = assemble(defaultDriveDescription());
  HeldInputs in(m);
  in.values.crankSpeed = 314.0;
  Data d(m);
  std::vector<double> y = nominalState(m, 314.0);
  std::vector<double> ydot(m.nStates);
  forwardCompliant(m, d, in, 0.0, y.data(), ydot.data());
  for (int i = 0; i < d.nContacts; ++i) EXPECT_GT(d.contacts[i].gap, -1e-7) << "contact " << i;
  InputValues v = in.values;
  v.loadTorque[m.rotorIndex("camshaftIntake")] = 3.0;
  v.loadTorque[m.rotorIndex("camshaftExhaust")] = 3.0;
  PreloadReport rep;
  y = initialState(m, v, PreloadOptions{}, rep);
  EXPECT_TRUE(rep.converged) << rep.message;
  EXPECT_LE(rep.residual, 1e-6);
  std::printf("preload: %s, %.3f s CPU\n", rep.message.c_str(), rep.cpuSeconds);
}

// A chain that does not close says what to change: the even link counts the path holds over the
// closure range, or, where none lies in it, how many pitches the path is from the nearest two.
TEST(Assembly, AChainThatDoesNotCloseNamesTheCountsThatWould) {
  auto closureError = [](const std::function<void(nlohmann::json&)>& edit) {
    try {
      assemble(modifiedDefault(edit));
    } catch (const DescriptionError& e) {
      return std::string(e.what());
    }
    return std::string("assembled");
  };
  const std::string shorter = closureError([](nlohmann::json& j) { j["chain"]["numberOfLinks"] = 110; });
  EXPECT_NE(shorter.find("110 links cannot close around the layout"), std::string::npos) << shorter;
  EXPECT_NE(shorter.find("; 120 links close it"), std::string::npos) << shorter;
  // the camshafts 4 mm higher: the path, about 0.8 links longer, lies between two even counts
  const std::string between = closureError([](nlohmann::json& j) {
    for (auto& s : j["sprockets"])
      if (s["motion"] == "free") s["center"][1] = s["center"][1].get<double>() + 0.004;
  });
  EXPECT_NE(between.find("no even count closes it: the path is "), std::string::npos) << between;
  EXPECT_NE(between.find(" links longer than 120 and "), std::string::npos) << between;
  EXPECT_NE(between.find(" shorter than 122 (change its length"), std::string::npos) << between;
}

// A sprocket inside the chain's loop, which the chain would wrap from outside (a back-side idler
// under the span between the camshafts), is refused by its name, with the link count that would
// have closed a crossed loop too: the model wraps every sprocket from inside the loop.
TEST(Assembly, ABackSideIdlerIsRefusedByName) {
  for (const int links : {120, 156}) {  // (156: the count a crossed path would have closed with)
    try {
      assemble(modifiedDefault([links](nlohmann::json& j) {
        nlohmann::json idler = j["sprockets"][2];
        idler["name"] = "backIdler";
        idler["teeth"] = 19;
        idler["motion"] = "idler";
        idler["inertia"] = 1e-4;
        idler["center"] = {0.0, 0.335140922 - 0.09};
        j["sprockets"].push_back(idler);
        auto& route = j["chain"]["route"];
        route.insert(route.begin() + 3, "backIdler");  // between the camshafts
        j["chain"]["numberOfLinks"] = links;
      }));
      ADD_FAILURE() << links << " links: assembled";
    } catch (const DescriptionError& e) {
      EXPECT_NE(std::string(e.what()).find("chain.route: 'backIdler' lies inside the chain's loop, where the chain "
                                           "would wrap it from outside (a back-side idler)"),
                std::string::npos)
          << e.what();
    }
  }
}
