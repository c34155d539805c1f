// The sandbox's command line: what it accepts and what it says about what it does not.
#include <gtest/gtest.h>

#include "options.h"

namespace {

using sandbox::parseOptions;

TEST(Options, NoArgumentsOpenTheDefaultSceneInteractively) {
  const auto p = parseOptions({});
  EXPECT_EQ(p.error, "");
  EXPECT_EQ(p.options.scene, "");
  EXPECT_FALSE(p.options.screenshot.has_value());
}

TEST(Options, SceneScreenshotAndFrames) {
  const auto p = parseOptions({"falling-box", "--screenshot", "out.png", "--frames", "12"});
  EXPECT_EQ(p.error, "");
  EXPECT_EQ(p.options.scene, "falling-box");
  EXPECT_EQ(p.options.screenshot->string(), "out.png");
  EXPECT_EQ(p.options.frames, 12);
}

TEST(Options, BadFramesAreRefusedWithTheValue) {
  for (const char* bad : {"0", "-3", "abc", "12x", "99999999999"}) {
    const auto p = parseOptions({"--screenshot", "a.png", "--frames", bad});
    EXPECT_NE(p.error.find("--frames"), std::string::npos) << bad;
    EXPECT_NE(p.error.find(bad), std::string::npos) << bad;
  }
}

TEST(Options, MissingValuesUnknownOptionsAndTwoScenes) {
  EXPECT_NE(parseOptions({"--screenshot"}).error.find("--screenshot needs"), std::string::npos);
  EXPECT_NE(parseOptions({"--bogus"}).error.find("'--bogus'"), std::string::npos);
  EXPECT_NE(parseOptions({"a", "b"}).error.find("one scene only"), std::string::npos);
  EXPECT_NE(parseOptions({"--frames", "5"}).error.find("--frames needs --screenshot"), std::string::npos);
}

TEST(Options, DataDirDefaultsToTheBuildsAndCanBeOverridden) {
  EXPECT_FALSE(sandbox::dataDir(parseOptions({}).options).empty());
  EXPECT_EQ(sandbox::dataDir(parseOptions({"--data", "/x"}).options), "/x");
}

}  // namespace
