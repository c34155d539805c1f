// The real `lab` program, run as a user would through the shell: JSON, free fall against the
// closed form, determinism, overrides, the dump, and the exit codes.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "lab_test_util.h"
#include "output_files.h"

namespace {

using namespace lab_testing;

// Runs lab with --json and parses its stdout, failing the test when it is not one object.
FlatJson runJson(const std::string& args, const TempDir& dir) {
  const ProcessResult r = runLab(args + " --json", dir);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const std::optional<FlatJson> j = parseFlatJson(r.out);
  EXPECT_TRUE(j) << "not one flat JSON object: " << r.out;
  return j.value_or(FlatJson{});
}

// The rows of a dump, split at commas (the tests' names hold none unless quoted on purpose).
std::vector<std::vector<std::string>> csvRows(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(csv);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    rows.push_back(fields);
  }
  return rows;
}

// --model imposes a body model on every box: the same stack as rigid bodies has no particles, and
// the state differs from the file's corners boxes.
TEST(LabRun, ModelIsImposedOnEveryBox) {
  const TempDir dir;
  const auto scene = dir.write("s.xml",
                               "<scene name='s'>\n<stack name='st' pos='0 0 0' count='3' size='1'/>\n"
                               "<box name='b' pos='3 0.5 0'/>\n"
                               "<ragdoll name='r' pos='-3 1 0' model='lean'/>\n</scene>\n");
  const FlatJson asFile = runJson("run " + quoted(scene) + " --steps 30", dir);
  const FlatJson rigid = runJson("run " + quoted(scene) + " --steps 30 --model rigid", dir);
  EXPECT_EQ(number(asFile, "particles"), 32 + 40);  // corners boxes, a lean ragdoll
  EXPECT_EQ(number(rigid, "particles"), 0);         // the ragdoll is rigid too
  EXPECT_EQ(number(rigid, "bodies"), 4 + 10);
  EXPECT_NE(text(asFile, "hash"), text(rigid, "hash"));
  const ProcessResult bad = runLab("run " + quoted(scene) + " --model blob", dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--models: unknown model 'blob' (corners, tetra or rigid)"), std::string::npos)
      << bad.err;
}

// The summary does not let a method's name pass for what solved a world it changes nothing in.
TEST(LabRun, SaysWhenTheMethodChangesNothing) {
  const TempDir dir;
  const auto scene = dir.write("s.xml", "<scene name='s'>\n<box name='b' pos='0 0.5 0'/>\n</scene>\n");
  const ProcessResult asFile = runLab("run " + quoted(scene) + " --steps 5", dir);
  const ProcessResult rigid = runLab("run " + quoted(scene) + " --steps 5 --model rigid", dir);
  ASSERT_EQ(asFile.exitCode, 0) << asFile.err;
  ASSERT_EQ(rigid.exitCode, 0) << rigid.err;
  const std::string note = "(no stick to relax: every method steps this world alike, rigid bodies by XPBD)";
  EXPECT_EQ(asFile.out.find(note), std::string::npos) << asFile.out;  // a corners box has sticks
  EXPECT_NE(rigid.out.find("solver       gauss-seidel " + note), std::string::npos) << rigid.out;
}

TEST(LabRun, JsonHasEveryKeyWithFiniteNumbers) {
  const TempDir dir;
  const auto scene = dir.write("t.xml", freeFallScene());
  const FlatJson j = runJson("run " + quoted(scene) + " --steps 30", dir);
  EXPECT_EQ(j.keys, kRunJsonKeys);
  for (const std::string& key : kRunJsonKeys) {
    if (key == "scene" || key == "method" || key == "hash") continue;
    EXPECT_TRUE(std::isfinite(number(j, key))) << key << " = " << j.values.at(key);
  }
  EXPECT_EQ(text(j, "scene"), "t");
  EXPECT_EQ(text(j, "method"), "gauss-seidel");
  EXPECT_EQ(number(j, "steps"), 30);
  EXPECT_EQ(number(j, "particles"), 1);
  EXPECT_EQ(number(j, "constraints"), 0);
  EXPECT_EQ(number(j, "bodies"), 0);
  EXPECT_EQ(number(j, "contacts"), 0);
  EXPECT_EQ(number(j, "frozen"), 0);
  EXPECT_GT(number(j, "ms_per_step"), 0.0);
  const std::string hash = text(j, "hash");
  EXPECT_EQ(hash.size(), 16u);
  EXPECT_EQ(hash.find_first_not_of("0123456789abcdef"), std::string::npos) << hash;
}

// `largest_island` counts the bodies of the island with the most: two stacks apart are two islands
// of 3 and 2 boxes, and loose particles added before them (islands of no body, numbered first) are
// counted by `islands` alone.
TEST(LabRun, CountsTheBodiesOfTheLargestIsland) {
  const TempDir dir;
  const auto scene = dir.write("s.xml",
                               "<scene name=\"s\">\n"
                               "  <ground/>\n"
                               "  <particle name=\"p\" pos=\"9 1 0\"/>\n"
                               "  <particle name=\"q\" pos=\"9 1 2\"/>\n"
                               "  <stack name=\"a\" pos=\"0 0 0\" count=\"3\" size=\"1\" mass=\"1\"/>\n"
                               "  <stack name=\"b\" pos=\"5 0 0\" count=\"2\" size=\"1\" mass=\"1\"/>\n"
                               "</scene>\n");
  const FlatJson r = runJson("run " + quoted(scene) + " --steps 30", dir);
  EXPECT_EQ(number(r, "islands"), 4);
  EXPECT_EQ(number(r, "largest_island"), 3);
  const ProcessResult summary = runLab("run " + quoted(scene) + " --steps 30", dir);
  EXPECT_NE(summary.out.find("islands      4 at the end, the largest of 3 bodies,"), std::string::npos)
      << summary.out;
}

// The lab steps every body unless asked: a scene that says sleep="on" is stepped awake, and
// `--sleep on` lets the resting stack sleep, the JSON counting its bodies asleep.
TEST(LabRun, SleepsOnlyWhenAsked) {
  const TempDir dir;
  const auto scene = dir.write("s.xml",
                               "<scene name=\"s\">\n"
                               "  <solver sleep=\"on\" iterations=\"10\" substeps=\"4\"/>\n"
                               "  <ground/>\n"
                               "  <stack name=\"stack\" pos=\"0 0 0\" count=\"3\" size=\"1\" mass=\"1\"/>\n"
                               "</scene>\n");
  const FlatJson awake = runJson("run " + quoted(scene) + " --steps 180", dir);
  EXPECT_EQ(number(awake, "islands"), 1);
  EXPECT_EQ(number(awake, "awake_bodies"), 3);
  EXPECT_EQ(number(awake, "sleeping_bodies"), 0);
  const FlatJson asleep = runJson("run " + quoted(scene) + " --steps 180 --sleep on", dir);
  EXPECT_EQ(number(asleep, "islands"), 1);
  EXPECT_EQ(number(asleep, "awake_bodies"), 0);
  EXPECT_EQ(number(asleep, "sleeping_bodies"), 3);
  EXPECT_NE(text(awake, "hash"), text(asleep, "hash"));
  const ProcessResult bad = runLab("run " + quoted(scene) + " --sleep maybe", dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--sleep: 'maybe' is not on or off"), std::string::npos) << bad.err;
}

// --joint-projection on closes a rigid ragdoll's joints after every substep (docs/physics.md, "Joint
// projection"): at 1 x 1 its worst joint error over the fall comes down to the projection's
// tolerance, the summary says so, and --joint-projection off overrides a file that asks for it.
TEST(LabRun, ProjectsRigidJointsWhenAsked) {
  const TempDir dir;
  const std::string run = "run ragdoll --model rigid --iterations 1 --substeps 1 --steps 120";
  const FlatJson loose = runJson(run, dir);
  const FlatJson held = runJson(run + " --joint-projection on", dir);
  EXPECT_EQ(loose.values.at("joint_projection"), "false");
  EXPECT_EQ(held.values.at("joint_projection"), "true");
  EXPECT_GT(number(loose, "max_joint_error_over_run"), 1e-3);
  EXPECT_LT(number(held, "max_joint_error_over_run"), 2e-4);
  const ProcessResult summary = runLab(run + " --joint-projection on", dir);
  EXPECT_NE(summary.out.find("rigid joints projected"), std::string::npos) << summary.out;
  const auto scene = dir.write("p.xml",
                               "<scene name=\"p\">\n"
                               "  <solver joint-projection=\"on\"/>\n"
                               "  <ground/>\n"
                               "  <ragdoll name=\"r\" model=\"rigid\" pos=\"0 2 0\"/>\n"
                               "</scene>\n");
  EXPECT_EQ(runJson("run " + quoted(scene) + " --steps 10", dir).values.at("joint_projection"), "true");
  EXPECT_EQ(runJson("run " + quoted(scene) + " --steps 10 --joint-projection off", dir)
                .values.at("joint_projection"),
            "false");
  const ProcessResult bad = runLab("run ragdoll --joint-projection maybe", dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--joint-projection: 'maybe' is not on or off"), std::string::npos) << bad.err;
}

// Where the dropped particle "p" of freeFallScene() is in the dump of a run with these args.
double droppedHeight(const std::string& args, const TempDir& dir, double* dt) {
  const auto csv = dir.file("pose.csv");
  const FlatJson j = runJson(args + " --dump " + quoted(csv), dir);
  *dt = number(j, "dt");
  const auto rows = csvRows(readFile(csv));
  EXPECT_EQ(rows.size(), 2u) << args;
  if (rows.size() != 2 || rows[1].size() != 8) return std::nan("");
  EXPECT_EQ(rows[1][0], "p");
  EXPECT_EQ(std::strtod(rows[1][1].c_str(), nullptr), 0.0);
  EXPECT_EQ(std::strtod(rows[1][3].c_str(), nullptr), 0.0);
  EXPECT_EQ(rows[1][4] + rows[1][5] + rows[1][6] + rows[1][7], "1000")
      << "a particle's orientation is 1,0,0,0";
  return std::strtod(rows[1][2].c_str(), nullptr);
}

// y(t) = 5 - g t^2 / 2 for the particle dropped from rest: Verlet is exact for constant
// gravity up to round-off, with the scene's dt and whatever the method or iterations.
TEST(LabRun, FreeFallingParticleMatchesClosedForm) {
  const TempDir dir;
  const auto scene = dir.write("t.xml", freeFallScene());
  for (const std::string overrides : {"", " --method xpbd --iterations 7", " --method shake"}) {
    double dt = 0.0;
    const double y = droppedHeight("run " + quoted(scene) + " --steps 45" + overrides, dir, &dt);
    const double t = 45 * dt;
    const double expected = kDropHeight - 0.5 * kGravity * t * t;
    EXPECT_NEAR(y, expected, 1e-6 * std::abs(expected)) << overrides;
  }
}

// --dt and --substeps reach the built world through World::setSolverSettings, which must keep
// the free particle's velocity exact across the change of substep.
TEST(LabRun, FreeFallMatchesClosedFormWithDtAndSubstepOverrides) {
  const TempDir dir;
  const auto scene = dir.write("t.xml", freeFallScene());
  double dt = 0.0;
  const double y = droppedHeight("run " + quoted(scene) + " --steps 45 --dt 0.01 --substeps 3", dir, &dt);
  const double t = 45 * dt;
  const double expected = kDropHeight - 0.5 * kGravity * t * t;
  EXPECT_NEAR(y, expected, 1e-6 * std::abs(expected));
}

TEST(LabRun, SameRunTwiceSameHash) {
  const TempDir dir;
  const auto scene = dir.write("n.xml", namedBodiesScene());
  const std::string args = "run " + quoted(scene) + " --steps 30";
  const FlatJson a = runJson(args, dir);
  const FlatJson b = runJson(args, dir);
  EXPECT_EQ(text(a, "hash"), text(b, "hash"));
  EXPECT_EQ(text(a, "hash").size(), 16u);
  // One more step while a and b still fall: another state, another hash.
  EXPECT_NE(text(runJson("run " + quoted(scene) + " --steps 31", dir), "hash"), text(a, "hash"));
}

// The step on two threads gives the state it gives on one (docs/physics.md, "Threads").
TEST(LabRun, ThreadsChangeNothingButTheTime) {
  const TempDir dir;
  const std::string args = "run bullet-ragdolls --steps 20";
  const FlatJson two = runJson(args + " --threads 2", dir), one = runJson(args + " --threads 1", dir);
  EXPECT_EQ(text(two, "hash"), text(one, "hash"));
  // The run says what it ran on, as it says its other settings.
  EXPECT_EQ(number(two, "threads"), 2);
  EXPECT_EQ(number(one, "threads"), 1);
  EXPECT_EQ(one.values.at("sleep"), "false");  // the lab's default, whatever the scene says
  EXPECT_EQ(runJson(args + " --sleep on", dir).values.at("sleep"), "true");
  EXPECT_NE(runLab(args + " --threads 2", dir).out.find("on 2 threads"), std::string::npos);
  const ProcessResult bad = runLab(args + " --threads 0", dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--threads: '0' is not a whole number from 1 to 64"), std::string::npos) << bad.err;
}

TEST(LabRun, OverridesShowInTheJson) {
  const TempDir dir;
  const auto scene = dir.write("t.xml", freeFallScene());
  const FlatJson j = runJson(
      "run " + quoted(scene) + " --steps 7 --method shake --iterations 9 --substeps 4 --dt 0.004", dir);
  EXPECT_EQ(text(j, "method"), "shake");
  EXPECT_EQ(number(j, "iterations"), 9);
  EXPECT_EQ(number(j, "substeps"), 4);
  EXPECT_EQ(number(j, "dt"), 0.004);
  EXPECT_EQ(number(j, "steps"), 7);
}

TEST(LabRun, CountsBodiesConstraintsAndContacts) {
  const TempDir dir;
  const auto scene = dir.write("n.xml", namedBodiesScene());
  const FlatJson j = runJson("run " + quoted(scene) + " --steps 60", dir);
  EXPECT_EQ(number(j, "bodies"), 1);
  EXPECT_EQ(number(j, "particles"), 8 + 3);  // a corners box has 8
  EXPECT_EQ(number(j, "constraints"), 22 + 1);
  EXPECT_GT(number(j, "contacts"), 0);  // the crate sits on the ground
}

TEST(LabRun, DumpHasHeaderAndOneRowPerNamedBody) {
  const TempDir dir;
  const auto scene = dir.write("n.xml", namedBodiesScene());
  const auto csv = dir.file("out.csv");
  const ProcessResult r = runLab("run " + quoted(scene) + " --steps 10 --dump " + quoted(csv), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string text = readFile(csv);
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.csv.tmp")));
  const auto rows = csvRows(text);
  ASSERT_EQ(rows.size(), 4u) << text;  // header, crate, a, b,"odd"; not the unnamed particle
  EXPECT_EQ(text.substr(0, text.find('\n')), "name,x,y,z,qw,qx,qy,qz");
  EXPECT_EQ(rows[1][0], "crate");
  EXPECT_EQ(rows[2][0], "a");
  EXPECT_TRUE(text.find("\n\"b,\"\"odd\"\"\",") != std::string::npos) << text;
  for (std::size_t i = 1; i < 3; ++i) EXPECT_EQ(rows[i].size(), 8u) << i;
  // The crate rests on the ground, upright: centre near y = 0.5, orientation near identity.
  EXPECT_NEAR(std::strtod(rows[1][2].c_str(), nullptr), 0.5, 0.01);
  EXPECT_NEAR(std::abs(std::strtod(rows[1][4].c_str(), nullptr)), 1.0, 1e-3);
  EXPECT_NE(r.out.find("3 named bodies"), std::string::npos) << r.out;
}

// Under a gravity of 1e308 the guard freezes every part on the first step; the dump wrote -nan
// quaternions and the summary "error max inf" and "energy initial -nan". A frozen body keeps its
// last good pose, and a figure that overflowed reads n/a (summary), null (JSON) or nothing (CSV).
TEST(LabRun, AWorldThatOverflowsPrintsNoNonFiniteNumber) {
  const TempDir dir;
  const auto scene = dir.write("g.xml",
                               "<scene name=\"g\"><world gravity=\"1e308 1e308 -1e308\"/><ground/>"
                               "<ragdoll name=\"r\" shape=\"capsule\" pos=\"0 1 0\"/></scene>");
  const auto csv = dir.file("g.csv");
  const ProcessResult r = runLab("run " + quoted(scene) + " --steps 5 --dump " + quoted(csv), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("frozen       88 particles"), std::string::npos) << r.out;
  for (const char* bad : {"nan", "inf"}) {
    EXPECT_EQ(r.out.find(bad), std::string::npos) << bad << "\n" << r.out;
    EXPECT_EQ(readFile(csv).find(bad), std::string::npos) << bad << "\n" << readFile(csv);
  }
  const auto rows = csvRows(readFile(csv));
  ASSERT_EQ(rows.size(), 12u);  // the header and the 11 capsules
  for (std::size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 8u);
    for (std::size_t k = 1; k < 8; ++k) {
      char* end = nullptr;
      const double v = std::strtod(rows[i][k].c_str(), &end);
      EXPECT_TRUE(!rows[i][k].empty() && *end == '\0' && std::isfinite(v)) << rows[i][0] << " " << k;
    }
  }
  const ProcessResult json = runLab("run " + quoted(scene) + " --steps 5 --json", dir);
  ASSERT_EQ(json.exitCode, 0) << json.err;
  EXPECT_TRUE(parseFlatJson(json.out).has_value()) << json.out;
  EXPECT_EQ(json.out.find("nan"), std::string::npos) << json.out;
  EXPECT_EQ(json.out.find("inf"), std::string::npos) << json.out;
}

TEST(LabRun, SummaryReportsTimingPhasesFreezesAndHash) {
  const TempDir dir;
  const auto scene = dir.write("e.xml", escapingScene());
  const ProcessResult r = runLab("run " + quoted(scene) + " --steps 60", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* part : {"scene        escape", "ms/step", "median", "integrate", "narrow-phase", "sticks",
                           "contacts", "friction", "guard", "other", "energy", "runaway", "hash"}) {
    EXPECT_NE(r.out.find(part), std::string::npos) << part << "\n" << r.out;
  }
  EXPECT_NE(r.out.find("frozen       1 particle"), std::string::npos) << r.out;
}

TEST(LabRun, SceneByNameFromTheDataFolder) {
  const TempDir dir;
  std::filesystem::create_directories(dir.file("assets/scenes"));
  dir.write("assets/scenes/drop.xml", freeFallScene());
  const FlatJson j = runJson("run drop --steps 2 --data " + quoted(dir.file("")), dir);
  EXPECT_EQ(text(j, "scene"), "t");
}

TEST(LabRun, ProjectScenesRunByName) {
  const TempDir dir;
  const FlatJson j = runJson("run pendulum --steps 60", dir);  // DATA_DIR, the source tree
  EXPECT_EQ(text(j, "scene"), "pendulum");
  EXPECT_EQ(number(j, "constraints"), 1);
}

TEST(LabExit, BadSceneFileExitsOneWithFileAndLine) {
  const TempDir dir;
  const auto scene = dir.write("bad.xml", badSceneLine3());
  const ProcessResult r = runLab("run " + quoted(scene), dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find(scene.string() + ":3:"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("usage"), std::string::npos) << r.err;
}

TEST(LabExit, MissingSceneExitsOne) {
  const TempDir dir;
  const ProcessResult r = runLab("run no-such-scene --data " + quoted(dir.file("")), dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("no-such-scene.xml"), std::string::npos) << r.err;
}

// --data names the folder that holds assets/; a missing one, or a file, was said only when a run
// first read from it, and not at all by a run given its scene as a file. Every command that takes
// it refuses it first, with the system's reason, as lab report does, and runs nothing.
TEST(LabExit, ADataThatIsNotAFolderIsRefusedBeforeAnyRun) {
  const TempDir dir;
  const std::string scene = dir.write("fall.xml", freeFallScene()).string();
  const std::filesystem::path sweepOut = dir.file("sweep-out");
  const std::vector<std::vector<std::string>> commands = {
      {"run", scene, "--steps", "1"},
      {"sweep", scene, "--out", sweepOut.string()},
      {"stability"},
      {"tune", scene, "--target", "error=1e-3", "--repeat", "1"},
      {"compare", scene},
      {"converge", scene},
  };
  const std::pair<std::filesystem::path, std::string> folders[] = {
      {dir.file("missing"), "No such file or directory"},
      {dir.write("file", "not a folder\n"), "Not a directory"},
  };
  for (std::vector<std::string> args : commands) {
    for (const auto& [data, why] : folders) {
      args.insert(args.end(), {"--data", data.string()});
      const lab::CommandOutput o = lab::runCaptured(args);
      EXPECT_EQ(o.code, lab::kExitFailure) << args[0];
      EXPECT_EQ(o.err, "lab: --data: " + data.string() + ": " + why + "\n") << args[0];
      EXPECT_EQ(o.out, "") << args[0];
      args.resize(args.size() - 2);
    }
  }
  EXPECT_FALSE(std::filesystem::exists(sweepOut));
  EXPECT_FALSE(std::filesystem::exists(dir.file("missing")));
}

// The commands that write --out at the end checked only that the folder could be written: a folder
// standing where one of their files goes was found after all the runs. Each file is checked
// before the first run (output_files.h), lab report's and those of every command it runs too.
TEST(LabExit, AFolderInPlaceOfAnOutputFileIsRefusedBeforeAnyRun) {
  const TempDir dir;
  const std::string scene = dir.write("fall.xml", freeFallScene()).string();
  const std::string out = dir.file("out").string();
  struct Command {
    std::vector<std::string> args;
    std::vector<std::string> files;
  };
  const Command commands[] = {
      {{"sweep", scene, "--steps", "2", "--repeat", "1", "--no-peers", "--out", out}, lab::sweepFiles()},
      {{"stability", "--scene", "face-face", "--methods", "xpbd", "--iterations", "1", "--substeps", "1",
        "--no-peers", "--out", out},
       lab::stabilityFiles()},
      {{"scale", "--sizes", "1", "--steps", "2", "--out", out}, lab::scaleFiles()},
      {{"converge", "circular-orbit", "pendulum-exact", "--substeps", "1,2", "--out", out},
       lab::convergeFiles({"circular-orbit", "pendulum-exact"})},
  };
  for (const Command& c : commands) {
    ASSERT_FALSE(c.files.empty()) << c.args[0];
    for (const std::string& file : c.files) {
      const std::filesystem::path folder = dir.file("out/" + file);
      std::filesystem::create_directories(folder);
      const lab::CommandOutput o = lab::runCaptured(c.args);
      EXPECT_EQ(o.code, lab::kExitFailure) << c.args[0] << " " << file;
      EXPECT_EQ(o.err, "lab: --out: " + folder.string() + ": is a folder, not a file\n") << c.args[0];
      EXPECT_EQ(o.out, "") << c.args[0] << ": nothing ran";
      std::filesystem::remove(folder);
    }
  }
  const std::filesystem::path last = dir.file("report/results/converge/converge-circular-orbit.svg");
  std::filesystem::create_directories(last);
  const lab::CommandOutput report =
      lab::runCaptured({"report", "--quick", "--out", dir.file("report").string()});
  EXPECT_EQ(report.code, lab::kExitFailure);
  EXPECT_EQ(report.err, "lab: --out: " + last.string() + ": is a folder, not a file\n");
  EXPECT_EQ(report.out, "");
}

// The lists the commands check before their runs hold every file they then write: a file left out
// would again be found unwritable only after the work.
TEST(LabExit, EachCommandWritesOnlyTheFilesItChecksFirst) {
  const TempDir dir;
  const std::string scene = dir.write("fall.xml", freeFallScene()).string();
  struct Command {
    std::vector<std::string> args;
    std::vector<std::string> files;
  };
  const Command commands[] = {
      {{"sweep", scene, "--steps", "2", "--repeat", "1", "--no-peers"}, lab::sweepFiles()},
      {{"stability", "--scene", "face-face", "--methods", "xpbd", "--iterations", "1", "--substeps", "1",
        "--no-peers"},
       lab::stabilityFiles()},
      {{"scale", "--sizes", "1", "--steps", "2"}, lab::scaleFiles()},
      {{"converge", "circular-orbit", "--substeps", "1,2"}, lab::convergeFiles({"circular-orbit"})},
  };
  for (const Command& c : commands) {
    const std::filesystem::path out = dir.file(c.args[0]);
    std::vector<std::string> args = c.args;
    args.insert(args.end(), {"--out", out.string()});
    // Without gnuplot, stability fails for its heat maps, after writing the rest.
    const lab::CommandOutput o = lab::runCaptured(args);
    std::size_t written = 0;
    for (const auto& entry : std::filesystem::directory_iterator(out)) {
      const std::string name = entry.path().filename().string();
      EXPECT_NE(std::find(c.files.begin(), c.files.end(), name), c.files.end())
          << c.args[0] << " wrote " << name;
      ++written;
    }
    EXPECT_GT(written, 0u) << c.args[0] << ": " << o.err;
  }
}

// A dump whose folder is missing or is a file, that names a folder, a device or the scene itself
// (it was written over), or that lies in a folder no file can be created in, is refused before the
// run: it was found out after all the steps.
TEST(LabExit, UnwritableDumpExitsOneBeforeTheRun) {
  const TempDir dir;
  const auto scene = dir.write("t.xml", freeFallScene());
  const std::pair<std::filesystem::path, std::string> cases[] = {
      {dir.file("no/dir/x.csv"), "No such file or directory"},
      {dir.file(""), "a folder, not a file"},
      {scene / "x.csv", "Not a directory"},
      {scene, "is the scene " + scene.string() + " being run"},
      {"/dev/null", "/dev/null: is not a regular file"},
      {"/proc/x.csv", "/proc/x.csv: cannot create a temporary file in '/proc'"}};
  for (const auto& [dump, says] : cases) {
    const ProcessResult r = runLab("run " + quoted(scene) + " --steps 1 --dump " + quoted(dump), dir);
    EXPECT_EQ(r.exitCode, 1) << dump;
    EXPECT_NE(r.err.find("--dump"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "") << "nothing ran";
  }
  EXPECT_EQ(readFile(scene), freeFallScene()) << "the scene is as it was";
  for (const auto& entry : std::filesystem::directory_iterator(dir.file("")))
    EXPECT_FALSE(entry.path().string().ends_with(".tmp")) << "left behind: " << entry.path();
}

TEST(LabExit, BadArgumentsExitTwoNamingTheArgumentWithUsage) {
  const TempDir dir;
  const auto scene = quoted(dir.write("t.xml", freeFallScene()));
  const std::pair<std::string, std::string> cases[] = {
      {"", "command"},
      {"frobnicate", "'frobnicate'"},
      {"run", "SCENE"},
      {"run " + scene + " --bogus", "'--bogus'"},
      {"run " + scene + " --steps", "--steps"},
      {"run " + scene + " --steps 0", "--steps: '0'"},
      {"run " + scene + " --steps 10000001", "--steps"},
      {"run " + scene + " --dt 2", "--dt: '2'"},
      {"run " + scene + " --dt nan", "--dt: 'nan'"},
      {"run " + scene + " --iterations 0", "--iterations: '0'"},
      {"run " + scene + " --substeps 1001", "--substeps: '1001'"},
      {"run " + scene + " --method euler", "--method"},
  };
  for (const auto& [args, named] : cases) {
    const ProcessResult r = runLab(args, dir);
    EXPECT_EQ(r.exitCode, 2) << args;
    EXPECT_EQ(r.out, "") << args;
    EXPECT_TRUE(r.err.starts_with("lab: ")) << r.err;
    const std::string firstLine = r.err.substr(0, r.err.find('\n'));
    EXPECT_NE(firstLine.find(named), std::string::npos) << args << ": " << r.err;
    EXPECT_NE(r.err.find("\nusage: lab "), std::string::npos) << args;
  }
}

// A report that could not be written is a failure, with the system's reason: `lab run x --json >
// r.json` on a full disk ended in success with the file empty.
TEST(LabExit, AnOutputThatCannotBeWrittenExitsOne) {
  const TempDir dir;
  const auto scene = quoted(dir.write("t.xml", freeFallScene()));
  for (const std::string& args :
       {"run " + scene + " --steps 2 --json", "run " + scene + " --steps 2", std::string("help")}) {
    const ProcessResult r = runLab(args + " > /dev/full", dir);
    EXPECT_EQ(r.exitCode, 1) << args;
    EXPECT_NE(r.err.find("lab: the output could not be written: No space left on device"), std::string::npos)
        << args << ": " << r.err;
  }
}

TEST(LabExit, HelpExitsZero) {
  const TempDir dir;
  // The overview names every command; a command's help lists its options.
  for (const char* args : {"--help", "help", "run x --help"}) {
    const ProcessResult r = runLab(args, dir);
    EXPECT_EQ(r.exitCode, 0) << args;
    EXPECT_NE(r.out.find("run SCENE"), std::string::npos) << args;
    EXPECT_NE(r.out.find(args[0] == 'r' ? "--dump FILE" : "converge [SCENE...]"), std::string::npos) << args;
    EXPECT_EQ(r.err, "") << args;
  }
}

}  // namespace
