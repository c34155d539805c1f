// The sandbox's command line: what it accepts and what it says about what it does not.
#include <array>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "open_scene.h"
#include "options.h"
#include "scenes/scene.h"
#include "session.h"
#include "temp_folder.h"

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

namespace {

// A second value would silently win over the first (`--threads 2 ... --threads 8` ran with 8), and
// a second --overlay added its runs to the first's.
TEST(Options, AnOptionWithAValueIsRefusedWhenGivenTwice) {
  EXPECT_EQ(parseOptions({"--threads", "2", "--threads", "3"}).error,
            "--threads is given twice; give it once");
  EXPECT_EQ(
      parseOptions({"--overlay", "iterations=2", "substeps=2", "--overlay", "iterations=3", "substeps=3"})
          .error,
      "--overlay is given twice; give it once");
  EXPECT_EQ(parseOptions({"--screenshot", "a.png", "--screenshot", "b.png"}).error,
            "--screenshot is given twice; give it once");
  // A flag given twice says the same thing twice.
  EXPECT_EQ(parseOptions({"--markers", "--sweep", "--markers"}).error, "");
}

// "--" ends the options, as for most command-line programs: what follows is the scene, whatever it
// starts with.
TEST(Options, DoubleDashEndsTheOptions) {
  const auto p = parseOptions({"--sweep", "--", "--hide-panels"});
  ASSERT_EQ(p.error, "");
  EXPECT_EQ(p.options.scene, "--hide-panels");
  EXPECT_TRUE(p.options.sweep);
  EXPECT_FALSE(p.options.hidePanels);
  EXPECT_EQ(parseOptions({"--", "-x"}).options.scene, "-x");
  EXPECT_EQ(parseOptions({"--", "a", "b"}).error, "one scene only; got 'a' and 'b'");
  EXPECT_EQ(parseOptions({"--screenshot", "--"}).error,
            "--screenshot needs a file name, and '--' ends the options (one of that name is ./--)");
}

// An empty scene name opened the default scene as if none had been given.
TEST(Options, AnEmptySceneNameIsRefused) {
  EXPECT_EQ(parseOptions({""}).error, "the scene's name is empty");
  EXPECT_EQ(parseOptions({"--", ""}).error, "the scene's name is empty");
  EXPECT_EQ(parseOptions({"pendulum", ""}).error, "the scene's name is empty");
}

// A value is quoted in the message as the terminal can show it: an escape sequence must not clear
// the screen, and a 100 kB value pasted by mistake must not bury what is wrong with it.
TEST(Options, ValuesAreQuotedPrintableAndShort) {
  EXPECT_EQ(parseOptions({"--draw", "\x1b[2Jx"}).error,
            "--draw: '\\x1b[2Jx' must be filled, wireframe or constraints");
  EXPECT_EQ(parseOptions({"--color-by", "a\nb\tc"}).error,
            "--color-by: 'a\\x0ab\\x09c' must be kind, body, island or sleep");
  EXPECT_EQ(parseOptions({"--bogus\x07"}).error, "unknown option '--bogus\\x07'");
  const std::string huge(100000, '9');
  EXPECT_EQ(parseOptions({"--threads", huge}).error,
            "--threads: '" + std::string(60, '9') + "... (100000 bytes)' is not a whole number from 1 to 64");
  // The overlay's own messages quote a part of a setting: one that long is refused as that.
  const std::string longSetting = "iterations=" + std::string(100000, '1');
  EXPECT_EQ(parseOptions({"--overlay", longSetting, "substeps=2"}).error,
            "--overlay: '" + longSetting.substr(0, 60) +
                "... (100011 bytes)' is longer than a setting can be (1024 bytes)");
  // A multi-byte character is not cut in half.
  std::string accents = "a";
  for (int k = 0; k < 600; ++k) accents += "\xc3\xa9";  // byte 60 is the second of one
  const std::string shown = parseOptions({"--unfold", accents}).error;
  EXPECT_NE(shown.find("'" + accents.substr(0, 59) + "... (1201 bytes)'"), std::string::npos) << shown;
}

TEST(Options, NumbersOutsideTheirRangeOrNotWholeAreRefused) {
  for (const char* bad : {"nan", "inf", "-inf", "1e999", "1e3", "2.0", "+3", " 3", "0x10", "-0", "",
                          "99999999999999999999999"}) {
    EXPECT_EQ(parseOptions({"--threads", bad}).error,
              std::string("--threads: '") + bad + "' is not a whole number from 1 to 64")
        << bad;
  }
  EXPECT_EQ(parseOptions({"--pause-at", "-0"}).options.pauseAt, 0);  // -0 is 0, which is allowed
}

using testing_app::TempFolder;

// Files named on the command line are checked before a window opens (sandbox.cpp), so a mistyped
// name is said without a display; each message names the argument and gives the OS's reason.
TEST(Options, FilesThatCannotBeUsedAreSaidWithTheOsReason) {
  const TempFolder temp;
  const std::string dir = temp.path.string();
  temp.touch("file");
  auto problem = [](const std::vector<std::string>& args) {
    const auto p = parseOptions(args);
    EXPECT_EQ(p.error, "");
    sandbox::CheckedFiles checked = sandbox::checkFiles(p.options);
    EXPECT_EQ(checked.scene != nullptr, checked.error.empty() && !p.options.scene.empty()) << checked.error;
    return checked.error;
  };
  EXPECT_EQ(problem({"pendulum"}), "");
  EXPECT_EQ(problem({dir + "/none.xml"}),
            "scene: " + dir + "/none.xml: cannot open scene file: No such file or directory");
  EXPECT_EQ(problem({dir}), "scene: " + dir + ": is a folder, not a scene file");
  std::ofstream(temp.path / "bad.xml") << "<scene name=\"x\">\n  <box size=\"1 nan 1\"/>\n</scene>\n";
  EXPECT_EQ(problem({dir + "/bad.xml"}),
            "scene: " + dir +
                "/bad.xml:2: <box> attribute 'size': '1 nan 1' must be one or three finite numbers (m)");
  // Opened as the sandbox opens it: an analytic answer that is no place is refused before a window
  // does (it was said only once the window had opened).
  std::ofstream(temp.path / "answer.xml")
      << "<scene name=\"x\">\n  <particle name=\"p\" pos=\"0 1 0\"/>\n"
         "  <expect kind=\"position\" body=\"p\" at=\"1\" pos=\"1 2\"/>\n</scene>\n";
  EXPECT_EQ(problem({dir + "/answer.xml"}), "scene: " + dir +
                                                "/answer.xml:3: <expect kind=\"position\"> attribute 'pos': "
                                                "'1 2' must be three finite numbers (m)");
  EXPECT_EQ(problem({"--data", dir + "/none"}), "--data '" + dir + "/none': No such file or directory");
  EXPECT_EQ(problem({"--data", dir + "/file"}), "--data '" + dir + "/file': Not a directory");
  EXPECT_EQ(problem({"--data", dir}), "--data '" + dir + "': its shaders/ folder: No such file or directory");
  EXPECT_EQ(problem({"--screenshot", dir}), "--screenshot '" + dir + "': is a folder");
  EXPECT_EQ(
      problem({"--screenshot", dir + "/none/a.png"}),
      "--screenshot '" + dir + "/none/a.png': its folder '" + dir + "/none': No such file or directory");
  EXPECT_EQ(problem({"--screenshot", dir + "/file/a.png"}),
            "--screenshot '" + dir + "/file/a.png': its folder '" + dir + "/file': Not a directory");
  EXPECT_EQ(problem({"--screenshot", dir + "/a.png"}), "");
  // A name too long for the OS: its reason, the name shortened.
  const std::string huge = problem({"--screenshot", std::string(100000, 'x') + ".png"});
  EXPECT_LT(huge.size(), 300u);
  EXPECT_NE(huge.find("File name too long"), std::string::npos) << huge;
}

// The scene checkFiles opens is the one the sandbox starts with: opened as every scene of the
// session is (sleeping unless it says, --threads imposed, which the loader's defaults are not), and
// taken by the session as it is, not read again.
TEST(Options, TheSceneCheckedIsOpenedAsTheSandboxOpensIt) {
  const auto p = parseOptions({"pendulum", "--threads", "2"});
  ASSERT_EQ(p.error, "");
  sandbox::CheckedFiles checked = sandbox::checkFiles(p.options);
  ASSERT_EQ(checked.error, "");
  ASSERT_NE(checked.scene, nullptr);
  const phys::SolverSettings byDefault =
      scenes::loadSceneFile(sandbox::scenePath(p.options)).world.solverSettings();
  ASSERT_FALSE(byDefault.sleep.enabled);
  ASSERT_NE(byDefault.threads, 2);
  EXPECT_TRUE(checked.scene->world.solverSettings().sleep.enabled);
  EXPECT_EQ(checked.scene->world.solverSettings().threads, 2);
  const std::unique_ptr<scenes::Scene> asSession =
      sandbox::loadCheckedScene(sandbox::scenePath(p.options), sandbox::sceneLoadOptions(2));
  EXPECT_EQ(checked.scene->world.solverSettings(), asSession->world.solverSettings());
  const scenes::Scene* given = checked.scene.get();
  sandbox::Session session(std::move(checked.scene), sandbox::scenePath(p.options),
                           scenes::sceneDirectory(sandbox::dataDir(p.options)), 2);
  EXPECT_EQ(&session.scene(), given);
  EXPECT_EQ(session.file(), sandbox::scenePath(p.options));
}

}  // namespace
