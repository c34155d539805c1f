// The sandbox's command line: what it accepts and what it says about what it does not.
#include <array>

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

// An option where a value goes is a value forgotten: `--screenshot --hide-panels` wrote a PNG
// named "--hide-panels", `--data --sweep` looked for the shaders in "--sweep/".
TEST(Options, AnOptionIsNotTakenAsTheValueBeforeIt) {
  EXPECT_EQ(parseOptions({"pendulum", "--screenshot", "--hide-panels", "--frames", "5"}).error,
            "--screenshot needs a file name, and '--hide-panels' is an option (one of that name is "
            "./--hide-panels)");
  EXPECT_EQ(parseOptions({"--data", "--sweep"}).error,
            "--data needs a folder, and '--sweep' is an option (one of that name is ./--sweep)");
  EXPECT_EQ(parseOptions({"--draw", "--markers"}).error,
            "--draw needs filled, wireframe or constraints, and '--markers' is an option");
  EXPECT_EQ(parseOptions({"--threads", "--sweep"}).error,
            "--threads needs a whole number from 1 to 64, and '--sweep' is an option");
  EXPECT_EQ(parseOptions({"--data", ""}).error, "--data: the folder name is empty");
  // A name that only looks like one is written as a path.
  const auto p = parseOptions({"--screenshot", "./--hide-panels", "--data", "-d"});
  EXPECT_EQ(p.error, "");
  EXPECT_EQ(p.options.screenshot->string(), "./--hide-panels");
  EXPECT_EQ(p.options.dataDir, "-d");
}

TEST(Options, DataDirDefaultsToTheBuildsAndCanBeOverridden) {
  EXPECT_FALSE(sandbox::dataDir(parseOptions({}).options).empty());
  EXPECT_EQ(sandbox::dataDir(parseOptions({"--data", "/x"}).options), "/x");
}

}  // namespace

namespace {

TEST(Options, DrawMarkersOverlayAndPauseAt) {
  const auto p =
      sandbox::parseOptions({"pyramid", "--draw", "wireframe", "--markers", "--targets", "--overlay",
                             "iterations=3", "substeps=8,iterations=1", "method=xpbd", "--pause-at", "40"});
  ASSERT_EQ(p.error, "");
  EXPECT_EQ(p.options.scene, "pyramid");
  EXPECT_EQ(p.options.draw, sandbox::DrawMode::Wireframe);
  EXPECT_TRUE(p.options.markers);
  EXPECT_TRUE(p.options.targets);
  EXPECT_FALSE(sandbox::parseOptions({"pyramid"}).options.targets);
  ASSERT_EQ(p.options.overlay.size(), 3u);
  EXPECT_EQ(p.options.overlay[1].text, "substeps=8,iterations=1");
  EXPECT_EQ(p.options.pauseAt, 40);
}

TEST(Options, BadDrawOverlayAndPauseAtSayWhat) {
  EXPECT_EQ(sandbox::parseOptions({"--draw", "shaded"}).error,
            "--draw: 'shaded' must be filled, wireframe or constraints");
  EXPECT_EQ(sandbox::parseOptions({"--overlay", "iterations=3"}).error,
            "--overlay needs 2 to 4 settings, got 1");
  EXPECT_EQ(sandbox::parseOptions({"--overlay", "iterations=3", "substeps=2", "pendulum"}).error,
            "--overlay: 'pendulum' is not key=value (a scene goes before --overlay)");
  EXPECT_EQ(sandbox::parseOptions({"chain", "--overlay", "iterations=3", "substeps=2", "pendulum"}).error,
            "--overlay: 'pendulum' is not key=value");  // a scene was given: no such guess
  EXPECT_EQ(sandbox::parseOptions({"--overlay", "a=1", "b=2", "c=3", "d=4", "e=5"}).error.substr(0, 19),
            "--overlay: unknown ");
  EXPECT_EQ(sandbox::parseOptions({"--overlay", "iterations=0", "iterations=2"}).error.substr(0, 25),
            "--overlay: 'iterations=0'");
  EXPECT_EQ(sandbox::parseOptions({"--pause-at", "-1"}).error,
            "--pause-at: '-1' is not a whole number from 0 to 1000000");
}

TEST(Options, ThreadsAndColourBy) {
  const sandbox::ParsedOptions p = sandbox::parseOptions({"stack", "--threads", "2", "--color-by", "island"});
  ASSERT_EQ(p.error, "");
  EXPECT_EQ(p.options.threads, 2);
  EXPECT_EQ(p.options.coloring, sandbox::BodyColoring::Island);
  EXPECT_FALSE(sandbox::parseOptions({}).options.threads);
  EXPECT_EQ(sandbox::parseOptions({"--threads", "0"}).error,
            "--threads: '0' is not a whole number from 1 to 64");
  EXPECT_EQ(sandbox::parseOptions({"--threads", "65"}).error,
            "--threads: '65' is not a whole number from 1 to 64");
  EXPECT_EQ(sandbox::parseOptions({"--color-by", "mass"}).error,
            "--color-by: 'mass' must be kind, body, island or sleep");
}

}  // namespace

namespace {

TEST(Options, HidePanelsAndUnfold) {
  const auto p = sandbox::parseOptions({"chain", "--hide-panels", "--unfold", "world,stats"});
  ASSERT_EQ(p.error, "");
  EXPECT_TRUE(p.options.hidePanels);
  EXPECT_EQ(p.options.unfold, (sandbox::SectionFlags{false, false, true, false, true, false}));
  EXPECT_EQ(sandbox::parseOptions({"--unfold", "all"}).options.unfold,
            (sandbox::SectionFlags{true, true, true, true, true, true}));
  EXPECT_FALSE(sandbox::parseOptions({}).options.unfold.has_value());
  EXPECT_FALSE(sandbox::parseOptions({}).options.hidePanels);
  for (const char* bad : {"", "stat", "world,", "world,,draw", "All"}) {
    const auto b = sandbox::parseOptions({"--unfold", bad});
    EXPECT_EQ(b.error, std::string("--unfold: '") + bad +
                           "' must be all, or sections among simulation, rewind, world, draw, stats, lab")
        << bad;
  }
  EXPECT_NE(sandbox::parseOptions({"--unfold"}).error.find("--unfold needs"), std::string::npos);
}

}  // namespace
