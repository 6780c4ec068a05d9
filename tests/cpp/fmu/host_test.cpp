#include "host.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace chaindrive::fmu {
namespace {

TEST(ResourceDirectory, PosixForms) {
  const auto posix = [](const char* uri) { return resourceDirectory(uri, PathStyle::Posix); };
  EXPECT_EQ(posix("file:///tmp/fmu/resources"), "/tmp/fmu/resources");
  EXPECT_EQ(posix("file:///tmp/fmu/resources/"), "/tmp/fmu/resources");
  EXPECT_EQ(posix("file:////tmp/fmu/resources"), "/tmp/fmu/resources");
  EXPECT_EQ(posix("file://localhost/tmp/fmu/resources"), "/tmp/fmu/resources");
  EXPECT_EQ(posix("file:/tmp/fmu/resources"), "/tmp/fmu/resources");
  EXPECT_EQ(posix("file:///tmp/my%20fmu/r%C3%A9sources"), "/tmp/my fmu/r\xC3\xA9sources");
  EXPECT_EQ(posix(nullptr), "");
  EXPECT_EQ(posix(""), "");
  EXPECT_EQ(posix("http://example.com/resources"), "");
}

// Windows importers (and fmpy's remoting server under wine, which gives file:///Z:/...) name a
// drive after the root's slash: the path is C:/..., not /C:/... (which would miss the resources).
TEST(ResourceDirectory, WindowsForms) {
  const auto windows = [](const char* uri) { return resourceDirectory(uri, PathStyle::Windows); };
  EXPECT_EQ(windows("file:///Z:/tmp/fmu/resources"), "Z:/tmp/fmu/resources");
  EXPECT_EQ(windows("file:///C:/Users/J%C3%BCrgen/AppData/Local/Temp/fmu/resources/"),
            "C:/Users/J\xC3\xBCrgen/AppData/Local/Temp/fmu/resources");
  EXPECT_EQ(windows("file://localhost/C:/fmu/resources"), "C:/fmu/resources");
  EXPECT_EQ(windows("file:/C:/fmu/resources"), "C:/fmu/resources");
  EXPECT_EQ(windows("file:///C|/fmu/resources"), "C:/fmu/resources");
  EXPECT_EQ(windows("file:///C:/"), "C:/");
  EXPECT_EQ(windows("file://server/share/fmu/resources"), "//server/share/fmu/resources");
  EXPECT_EQ(windows("file:////server/share/fmu/resources"), "//server/share/fmu/resources");
}

// ---- the protocol state: every transition of the FMI 2.0 state machine and of the
// communication times is one of Host's methods, made by the protocol (fmu/instance.h) ----

// Keeps a host's messages, in order.
void collect(fmi2ComponentEnvironment env, fmi2String, fmi2Status, fmi2String, fmi2String message, ...) {
  static_cast<std::vector<std::string>*>(env)->emplace_back(message);
}

// What a host passed to the environment.
struct Environment {
  std::vector<std::string> messages;
  fmi2CallbackFunctions callbacks{collect, nullptr, nullptr, nullptr, &messages};
};

// A host with its transitions in reach, as Instance has them.
class ProtocolHost : public Environment, public Host {
 public:
  ProtocolHost() : Host("test", &callbacks, nullptr, false) {}

  using Host::enterErrorState;
  using Host::getRealStatus;
  using Host::getStatus;
  using Host::protocolSnapshot;
  using Host::resetProtocol;
  using Host::restoreProtocol;
  using Host::setExperiment;
  using Host::startStepping;
  using Host::stepAcceptable;
  using Host::stepCompleted;
  using Host::stepDiscarded;

  double lastSuccessfulTime() {
    double t = NAN;
    EXPECT_EQ(getRealStatus(fmi2LastSuccessfulTime, &t), fmi2OK);
    return t;
  }
};

TEST(ProtocolState, AnExperimentSetsTheTimesOrIsRefusedWithoutChangingThem) {
  ProtocolHost host;
  EXPECT_FALSE(host.setExperiment(NAN, false, 0.0));
  EXPECT_FALSE(host.setExperiment(1.0, true, 0.5));
  EXPECT_EQ(host.messages.size(), 2u);
  EXPECT_EQ(host.time(), 0.0);
  ASSERT_TRUE(host.setExperiment(0.25, true, 1.0));
  EXPECT_EQ(host.time(), 0.25);
  EXPECT_EQ(host.lastSuccessfulTime(), 0.25);
  EXPECT_EQ(host.state(), kInstantiated);
}

TEST(ProtocolState, AStepIsCheckedAgainstTheTimeAndTheStopTime) {
  ProtocolHost host;
  ASSERT_TRUE(host.setExperiment(0.0, true, 1e-3));
  host.startStepping();
  double tEnd = 0.0;
  EXPECT_FALSE(host.stepAcceptable(0.0, 0.0, tEnd));      // not positive
  EXPECT_FALSE(host.stepAcceptable(1e-4, 1e-4, tEnd));    // not from the FMU's time
  EXPECT_FALSE(host.stepAcceptable(0.0, 2e-3, tEnd));     // past the stop time
  EXPECT_EQ(host.messages.size(), 3u);
  ASSERT_TRUE(host.stepAcceptable(0.0, 1e-4, tEnd));
  EXPECT_EQ(tEnd, 1e-4);
  host.stepCompleted(tEnd);
  EXPECT_EQ(host.time(), 1e-4);
  EXPECT_EQ(host.lastSuccessfulTime(), 1e-4);
  EXPECT_EQ(host.state(), kStepComplete);
}

TEST(ProtocolState, ADiscardedStepKeepsTheTimeAndIsRestoredReadyForTheNextStep) {
  ProtocolHost host;
  ASSERT_TRUE(host.setExperiment(0.0, false, 0.0));
  host.startStepping();
  host.stepCompleted(1e-4);
  const ProtocolSnapshot before = host.protocolSnapshot();
  host.stepDiscarded();
  EXPECT_EQ(host.state(), kStepFailed);
  EXPECT_EQ(host.lastSuccessfulTime(), 1e-4);
  fmi2Status status = fmi2OK;
  ASSERT_EQ(host.getStatus(fmi2DoStepStatus, &status), fmi2OK);
  EXPECT_EQ(status, fmi2Discard);
  const ProtocolSnapshot failed = host.protocolSnapshot();
  host.restoreProtocol(before);
  EXPECT_EQ(host.state(), kStepComplete);
  host.restoreProtocol(failed);  // (a state taken after the failure)
  EXPECT_EQ(host.state(), kStepComplete);
  EXPECT_EQ(host.time(), 1e-4);
}

TEST(ProtocolState, AResetReturnsToTheInstantiatedState) {
  ProtocolHost host;
  ASSERT_TRUE(host.setExperiment(2.0, true, 3.0));
  host.enterErrorState();
  EXPECT_EQ(host.state(), kError);
  host.resetProtocol();
  EXPECT_EQ(host.state(), kInstantiated);
  EXPECT_EQ(host.time(), 0.0);
  EXPECT_EQ(host.lastSuccessfulTime(), 0.0);
  EXPECT_TRUE(host.initializing());
}

}  // namespace
}  // namespace chaindrive::fmu
