// Input time series (src/run/inputs.h): besides the crankshaft's speed and the sprockets' loads, a
// pivoting guide's torque and a hydraulic tensioner's supply pressure (the modes study's
// excitations), interpolated like the others; the guide's torque reaches its generalized force in
// its output sense; a column that sets nothing is refused naming what is allowed.
#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>
#include <string>

#include "test_util.h"
#include "dynamics/dynamics.h"
#include "run/inputs.h"
#include "statics/preload.h"

using namespace chaindrive;
using namespace chaindrive::test;

namespace {

std::string table(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "inputs_test_" + name;
  std::ofstream(path) << text;
  return path;
}

std::string refusal(const Model& m, const std::string& path) {
  try {
    TableInputs in(m, path);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(TableInputs, GuideTorqueAndSupplyPressureAreInterpolated) {
  const Model& m = *defaultModel();
  ASSERT_TRUE(m.tensioner.hydraulicChamber());
  const std::string path = table("guide.csv",
                                 "time,crankshaft.w,tensionGuide.tau,tensioner.supplyPressure\n"
                                 "0,314,0,300000\n"
                                 "0.01,314,10,400000\n");
  const TableInputs in(m, path);
  InputValues v;
  v.loadTorque.assign(m.rotors.size(), 0.0);
  in.evaluate(0.0025, v);
  EXPECT_DOUBLE_EQ(v.loadTorque[m.rotorIndex("tensionGuide")], 2.5);
  EXPECT_DOUBLE_EQ(v.supplyPressure, 325000.0);
  EXPECT_DOUBLE_EQ(v.loadTorque[m.rotorIndex("camshaftIntake")], 0.0);
}

TEST(TableInputs, TheGuideTorqueActsInTheGuidesOutputSense) {
  const Model& m = *defaultModel();
  const int guide = m.rotorIndex("tensionGuide");
  const std::string none = table("none.csv", "time,crankshaft.w,tensionGuide.tau\n0,314,0\n1,314,0\n");
  const std::string some = table("some.csv", "time,crankshaft.w,tensionGuide.tau\n0,314,7\n1,314,7\n");
  const TableInputs without(m, none), with(m, some);
  const std::vector<double> y = nominalState(m, 314.0);
  Data a(m), b(m);
  generalizedForces(m, a, without, 0.5, y.data());
  generalizedForces(m, b, with, 0.5, y.data());
  EXPECT_NEAR(b.gen[m.rotorGen(guide)] - a.gen[m.rotorGen(guide)], 7.0 * m.rotorOutputSign[guide], 1e-9);
  EXPECT_EQ(b.rotorChainTorque[guide], a.rotorChainTorque[guide]);  // (not the chain's)
}

TEST(TableInputs, AColumnThatSetsNothingIsRefused) {
  const Model& m = *defaultModel();
  const std::string unknown = refusal(m, table("unknown.csv", "time,crankshaft.w,fixedGuide.tauu\n0,314,0\n"));
  EXPECT_NE(unknown.find("column 'fixedGuide.tauu' is unknown; allowed: crankshaft.w, <free sprocket>.tau, "
                         "<pivoting guide>.tau, tensioner.supplyPressure"), std::string::npos) << unknown;
  const Model spring = assemble(modifiedDefault(useSpringDamperTensioner));
  const std::string supply =
      refusal(spring, table("supply.csv", "time,crankshaft.w,tensioner.supplyPressure\n0,314,300000\n"));
  EXPECT_NE(supply.find("tensioner.supplyPressure: a hydraulic tensioner's only"), std::string::npos) << supply;
}
