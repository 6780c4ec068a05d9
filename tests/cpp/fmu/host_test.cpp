#include "host.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace chaindrive::fmu
