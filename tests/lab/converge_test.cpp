// lab converge: the free-body reference against an analytic answer, the fitted order, each
// method's measured order on the scenes with exact answers, the command's outputs and its errors.
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <sys/inotify.h>
#include <unistd.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "commands.h"
#include "converge.h"
#include "csv.h"
#include "free_body.h"
#include "gnuplot.h"
#include "lab_test_util.h"
#include "output_files.h"
#include "scenes/scene.h"

namespace {

using lab::ConvergeRow;
using lab_testing::TempDir;
using phys::Quat;
using phys::Vec3;

lab::CommandOutput converge(std::vector<std::string> args) {
  args.insert(args.end(), {"--data", DATA_DIR});
  return lab::runCaptured("converge", args);
}

std::filesystem::path sceneFile(const std::string& name) {
  return scenes::resolveScene(name, scenes::sceneDirectory(DATA_DIR));
}

// A symmetric top (I1 = I2) precesses regularly: its symmetry axis turns about the fixed angular
// momentum L at |L| / I1 (Landau and Lifshitz, Mechanics, section 33). The RK4 reference must
// follow it to well under the 1e-8 m floor it is used at.
TEST(FreeBody, ASymmetricTopPrecessesAboutItsMomentumAtLOverI1) {
  lab::FreeBodyStart start;
  start.inertia = Vec3(2.0, 2.0, 0.5);
  start.orientation = glm::angleAxis(0.3, glm::normalize(Vec3(1.0, 2.0, 3.0)));
  start.angularVelocity = start.orientation * Vec3(0.7, -0.4, 6.0);  // body (0.7, -0.4, 6) rad/s
  const Vec3 L = start.orientation * (start.inertia * Vec3(0.7, -0.4, 6.0));
  const double rate = glm::length(L) / start.inertia.x;
  const std::vector<double> times{0.5, 1.0, 2.0, 4.0};
  const std::vector<lab::FreeBodyPose> poses = lab::freeBodyPoses(start, times, lab::kFreeBodyStep);
  const Vec3 axis0 = start.orientation * Vec3(0.0, 0.0, 1.0);
  for (std::size_t i = 0; i < times.size(); ++i) {
    const Vec3 expected = glm::angleAxis(rate * times[i], glm::normalize(L)) * axis0;
    const Vec3 got = poses[i].orientation * Vec3(0.0, 0.0, 1.0);
    EXPECT_LT(glm::length(got - expected), 1e-11) << "t = " << times[i];
  }
  EXPECT_LT(lab::freeBodyUncertainty(start, times, Vec3(0.5, 0.5, 1.0)), 1e-11);
}

TEST(FreeBody, BadInputIsRefused) {
  lab::FreeBodyStart start;
  start.inertia = Vec3(1.0, 0.0, 1.0);
  EXPECT_THROW(lab::freeBodyPoses(start, {1.0}, 1e-3), std::invalid_argument);
  start.inertia = Vec3(1.0);
  EXPECT_THROW(lab::freeBodyPoses(start, {1.0, 0.5}, 1e-3), std::invalid_argument);
  EXPECT_THROW(lab::freeBodyPoses(start, {1.0}, 0.0), std::invalid_argument);
}

// The physics keeps a rigid body's spin half a substep back (shifted by Euler's dw/dt, as gravity
// shifts a velocity); the reference undoes that and gets the scene's spin back.
TEST(FreeBody, TheSpinAtTheStartIsTheScenesAngularVelocity) {
  scenes::LoadOptions rigid;
  rigid.boxModel = phys::BodyModel::Rigid;
  const scenes::Scene s = scenes::loadSceneFile(sceneFile("tumbling-box"), rigid);
  const phys::BodyId id(0u);
  const Vec3 kept = s.world.bodyVelocity(id).second;
  const Vec3 inertia = Vec3(1.0) / s.world.rigidBodies().inverseInertia[0];
  const double h = s.world.solverSettings().dt / s.world.solverSettings().substeps;
  const Vec3 declared = Vec3(30.0, 45.0, 360.0) * (std::numbers::pi / 180.0);  // tumbling-box.xml
  EXPECT_GT(glm::length(kept - declared), 1e-3);
  const std::optional<Vec3> spin = lab::spinAtStart(kept, s.world.bodyPose(id).orientation, inertia, h);
  ASSERT_TRUE(spin.has_value());
  EXPECT_LT(glm::length(*spin - declared), 1e-12);
  // A spin the substep cannot resolve (h |w| = 5 about no principal axis) has no start to recover.
  EXPECT_FALSE(lab::spinAtStart(kept * 200.0, s.world.bodyPose(id).orientation, inertia, h).has_value());
}

std::vector<ConvergeRow> line(const std::vector<double>& hs, double c, double p) {
  std::vector<ConvergeRow> rows;
  for (const double h : hs) {
    ConvergeRow r;
    r.h = h;
    r.error = c * std::pow(h, p);
    rows.push_back(r);
  }
  return rows;
}

TEST(ConvergeOrder, IsTheSlopeOverTheFinestPointsAboveTheFloor) {
  EXPECT_NEAR(*lab::fittedOrder(line({0.1, 0.05, 0.025, 0.0125}, 3.0, 2.0)), 2.0, 1e-12);
  // A coarse point off the line (not yet asymptotic) is not among the finest three.
  std::vector<ConvergeRow> rows = line({0.1, 0.05, 0.025, 0.0125}, 1.0, 1.0);
  rows.front().error = 5.0;
  EXPECT_NEAR(*lab::fittedOrder(rows), 1.0, 1e-12);
  // Points below the floor are round-off: left out, and with one point left there is no order.
  rows = line({0.1, 0.01, 0.001}, 1e-6, 1.0);  // 1e-7, 1e-8, 1e-9
  EXPECT_FALSE(lab::fittedOrder(rows).has_value());
  rows = line({0.1, 0.05, 0.025}, 1.0, 2.0);
  rows.back().error = std::numeric_limits<double>::infinity();
  EXPECT_NEAR(*lab::fittedOrder(rows), 2.0, 1e-12);  // the blown-up run is left out too
}

// A run that blew up has error infinity: the CSV writes it blank, never inf, and says so in blew_up.
TEST(ConvergeCsv, ABlowUpIsSaidInItsColumnNotAsInf) {
  std::vector<ConvergeRow> rows = line({0.1, 0.05}, 1.0, 2.0);
  rows.back().error = std::numeric_limits<double>::infinity();
  const std::string csv = lab::convergeCsv(rows);
  EXPECT_EQ(csv.find("inf"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",0.01,0\n"), std::string::npos) << csv;   // h 0.1: 1 x 0.1^2
  EXPECT_NE(csv.find(",0.05,,1\n"), std::string::npos) << csv;  // h 0.05: blew up
}

// The order each method has, measured: Verlet is second order on the orbit whatever relaxes the
// (absent) sticks; Jakobsen's projection along the stick's current direction is first order on the
// pendulum (it drains energy at O(h)), SHAKE second. A free box's rotation is second order under
// SHAKE and under the rigid model; under projection it is at most first (0.85 measured from 16 to
// 64 substeps, still approaching 1 from below). Tolerance 0.1 on an order: the finest points
// measured within 0.01 of 1 and 2.
TEST(Converge, EachMethodHasTheOrderItShould) {
  lab::ConvergeOptions o;
  o.substeps = {4, 8, 16, 32};
  auto orders = [&](const std::string& scene) {
    lab::ConvergeTarget target;
    std::map<std::string, double> out;
    for (const auto& l : lab::convergeLines(lab::runConverge(sceneFile(scene), o, target))) {
      const std::optional<double> p = lab::fittedOrder(l);
      out[l.front().method + " " + l.front().model] = p ? *p : -1.0;
    }
    return out;
  };
  for (const auto& [name, p] : orders("circular-orbit")) EXPECT_NEAR(p, 2.0, 0.1) << name;
  const auto pendulum = orders("pendulum-exact");
  EXPECT_NEAR(pendulum.at("gauss-seidel particle"), 1.0, 0.1);
  EXPECT_NEAR(pendulum.at("xpbd particle"), 1.0, 0.1);
  EXPECT_NEAR(pendulum.at("shake particle"), 2.0, 0.1);
  const auto box = orders("tumbling-box");
  EXPECT_NEAR(box.at("xpbd rigid"), 2.0, 0.1);
  EXPECT_NEAR(box.at("shake corners"), 2.0, 0.1);
  EXPECT_NEAR(box.at("shake tetra"), 2.0, 0.1);
  EXPECT_LT(box.at("gauss-seidel corners"), 1.1);
}

// Free flight under uniform gravity is exact for Verlet and for the rigid model: every error is
// round-off, under the floor, and the table says "exact" instead of fitting noise.
TEST(Converge, FreeFlightIsExactForEveryMethodAndModel) {
  lab::ConvergeOptions o;
  o.substeps = {1, 4, 16};
  lab::ConvergeTarget target;
  const std::vector<ConvergeRow> rows = lab::runConverge(sceneFile("projectile"), o, target);
  EXPECT_EQ(target.kind, "analytic");
  EXPECT_EQ(rows.size(), 9u * 3u);  // 4 methods x corners, tetra; rigid once; 3 substep counts
  for (const ConvergeRow& r : rows) EXPECT_LT(r.error, lab::kConvergeFloor) << r.method << " " << r.model;
  const std::string table = lab::convergeTable(rows, target);
  EXPECT_NE(table.find("exact"), std::string::npos) << table;
}

// The orbit named twice runs once (its rows and chart were written twice).
TEST(Converge, WritesItsCsvAndOneChartPerScene) {
  TempDir dir;
  const auto o = converge({"circular-orbit", "tumbling-box", "circular-orbit", "--methods", "shake",
                           "--models", "rigid", "--substeps", "2,4", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const lab::CsvTable csv = lab::readCsv(dir.file("out") / "converge.csv");
  EXPECT_EQ(csv.header,
            (std::vector<std::string>{"scene", "method", "model", "substeps", "h", "error", "blew_up"}));
  ASSERT_EQ(csv.rows.size(), 4u);  // the orbit's particle at 2 and 4, the rigid box at 2 and 4
  EXPECT_NE(o.err.find("circular-orbit has no boxes or ragdolls: --models does not apply"), std::string::npos)
      << o.err;
  EXPECT_EQ(lab::fieldText(csv.rows[0], "model"), "particle");
  EXPECT_EQ(lab::fieldText(csv.rows[2], "method"), "xpbd");  // rigid bodies are XPBD's
  EXPECT_EQ(lab::fieldText(csv.rows[2], "model"), "rigid");
  EXPECT_NEAR(lab::fieldNumber(csv.rows[1], "h"), 1.0 / 240.0, 1e-12);
  EXPECT_TRUE(std::filesystem::exists(dir.file("out") / "converge-circular-orbit.gp"));
  if (!lab::findGnuplot().empty()) {
    EXPECT_TRUE(std::filesystem::exists(dir.file("out") / "converge-tumbling-box.png"));
    EXPECT_TRUE(std::filesystem::exists(dir.file("out") / "converge-tumbling-box.svg"));
  }
}

// Two files may give their scenes one name, and a name may hold a '/': each chart has files of its
// own in the folder (the second overwrote the first; a '/' failed after all the runs).
TEST(Converge, ScenesOfOneNameGetChartsOfTheirOwn) {
  TempDir dir;
  std::string orbit =
      lab_testing::readFile(std::filesystem::path(DATA_DIR) / "assets/scenes/circular-orbit.xml");
  const std::filesystem::path a = dir.write("a.xml", orbit);
  const std::filesystem::path b = dir.write("b.xml", orbit);
  orbit.replace(orbit.find("name=\"circular-orbit\""), 21, "name=\"orbit/slash\"");
  const std::filesystem::path c = dir.write("c.xml", orbit);
  const auto o = converge({a.string(), b.string(), c.string(), "--methods", "shake", "--substeps", "1,2",
                           "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  for (const char* gp :
       {"converge-circular-orbit.gp", "converge-circular-orbit-2.gp", "converge-orbit-slash.gp"})
    EXPECT_TRUE(std::filesystem::exists(dir.file("out") / gp)) << gp;
}

// A scene's name reaches the chart's title, its key and its file name. A line break in it ended
// the script's comment line and its title's string, and what followed ran as gnuplot commands
// (system() among them); it made a file name with a line break in it.
TEST(Converge, AControlCharacterInASceneNameStaysText) {
  const std::vector<std::string> names = lab::convergeChartNames({"fb\nsystem('touch x')\r\t"});
  ASSERT_EQ(names.size(), 1u);
  EXPECT_EQ(names[0], "converge-fb-system('touch x')--");
  std::vector<ConvergeRow> rows = line({0.1, 0.05}, 1.0, 1.0);
  for (ConvergeRow& r : rows)
    r.scene = "fb\nsystem('touch x')\n", r.method = "shake\r\nreplot", r.model = "rigid";
  lab::Chart chart = lab::convergeChart(rows);
  chart.output = "out\nsystem('touch y')";
  const std::string script = lab::gnuplotScript(chart);
  std::istringstream lines(script);
  for (std::string l; std::getline(lines, l);) {
    EXPECT_FALSE(l.starts_with("system")) << script;
    EXPECT_FALSE(l.starts_with("replot'")) << script;
    EXPECT_EQ(l.find('\r'), std::string::npos) << script;
  }
  EXPECT_NE(script.find("fb system(''touch x'')"), std::string::npos) << script;
}

// Several lines on one chart are told apart: each in its own colour and point type, not the single
// black line of a front.
TEST(Converge, TheChartDrawsEachLineInItsOwnStyle) {
  std::vector<ConvergeRow> rows = line({0.1, 0.05}, 1.0, 1.0);
  for (ConvergeRow& r : rows) r.scene = "s", r.method = "gauss-seidel", r.model = "corners";
  std::vector<ConvergeRow> second = line({0.1, 0.05}, 1.0, 2.0);
  for (ConvergeRow& r : second) r.scene = "s", r.method = "shake", r.model = "corners";
  rows.insert(rows.end(), second.begin(), second.end());
  const std::string script = lab::gnuplotScript(lab::convergeChart(rows));
  EXPECT_NE(script.find("with linespoints lw 1.5 pt 7 ps 1.2 lc 1 title 'gauss-seidel corners: order 1'"),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("with linespoints lw 1.5 pt 5 ps 1.2 lc 2 title 'shake corners: order 2'"),
            std::string::npos)
      << script;
  EXPECT_EQ(script.find("lc 'black'"), std::string::npos) << script;
  EXPECT_NE(script.find("set logscale x"), std::string::npos);
  EXPECT_NE(script.find("set logscale y"), std::string::npos);
}

// A scene file where converge writes its results was overwritten by them; it is refused before
// any run, as lab run --dump refuses the scene it runs.
TEST(Converge, RefusesToWriteOverASceneItRuns) {
  TempDir dir;
  const std::string scene =
      lab_testing::readFile(std::filesystem::path(DATA_DIR) / "assets/scenes/circular-orbit.xml");
  const std::filesystem::path file = dir.write("converge.csv", scene);
  const auto o = converge({"pendulum-exact", file.string(), "--methods", "shake", "--substeps", "1,2",
                           "--out", dir.file("").string()});
  EXPECT_EQ(o.code, lab::kExitFailure) << o.err;
  EXPECT_NE(o.err.find("converge.csv: is the scene " + file.string() + " being run"), std::string::npos)
      << o.err;
  EXPECT_EQ(lab_testing::readFile(file), scene);
}

// With --out each scene file was read and loaded three times (for its name, the check before the
// runs, the runs), and a file saved over between them gave a chart named after one text and runs of
// another. It is opened once (inotify counts the opens; watching the closes too keeps two opens
// from being merged into one event, as inotify merges identical events in a row).
TEST(Converge, ReadsEachSceneFileOnce) {
  TempDir dir;
  const std::filesystem::path file =
      dir.write("orbit.xml",
                lab_testing::readFile(std::filesystem::path(DATA_DIR) / "assets/scenes/circular-orbit.xml"));
  const int watch = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  ASSERT_GE(watch, 0);
  ASSERT_GE(::inotify_add_watch(watch, file.c_str(), IN_OPEN | IN_CLOSE), 0);
  const auto o =
      converge({file.string(), "--methods", "shake", "--substeps", "1,2", "--out", dir.file("out").string()});
  EXPECT_EQ(o.code, 0) << o.err;
  int opens = 0;
  alignas(inotify_event) char buffer[4096];
  for (ssize_t n; (n = ::read(watch, buffer, sizeof buffer)) > 0;) {
    for (ssize_t at = 0; at < n;) {
      const auto* event = reinterpret_cast<const inotify_event*>(buffer + at);
      opens += (event->mask & IN_OPEN) != 0 ? 1 : 0;
      at += static_cast<ssize_t>(sizeof(inotify_event) + event->len);
    }
  }
  ::close(watch);
  EXPECT_EQ(opens, 1);
}

TEST(Converge, ASceneWithoutAnExactAnswerIsAClearError) {
  const auto o = converge({"pyramid"});
  EXPECT_EQ(o.code, lab::kExitFailure);
  EXPECT_NE(o.err.find("pyramid has no exact answer"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("it has gravity"), std::string::npos) << o.err;
}

// Every scene is checked before the first run: a scene without an exact answer after others was
// found only once they had run (56 s for tumbling-box before pyramid), with nothing written.
TEST(Converge, ASceneWithoutAnExactAnswerIsSaidBeforeAnyRun) {
  TempDir dir;
  const auto o = converge({"pendulum-exact", "pyramid", "--methods", "shake", "--substeps", "1,2", "--out",
                           dir.file("out").string()});
  EXPECT_EQ(o.code, lab::kExitFailure);
  EXPECT_NE(o.err.find("pyramid has no exact answer"), std::string::npos) << o.err;
  EXPECT_EQ(o.out, "") << "pendulum-exact ran first";
  // A --time no free-body scene can take is said before the runs too.
  const auto time = converge(
      {"pendulum-exact", "tumbling-box", "--time", "0.001", "--methods", "shake", "--substeps", "1,2"});
  EXPECT_EQ(time.code, lab::kExitUsage) << time.err;
  EXPECT_NE(time.err.find("--time: '0.001' s is shorter than one step"), std::string::npos) << time.err;
  EXPECT_EQ(time.out, "");
}

// --time is for free-body scenes: a scene with exact answers measures at their times, and says
// that it does not use --time (it was taken and ignored in silence).
TEST(Converge, TimeGivenToAnAnalyticSceneIsSaid) {
  const auto o = converge({"pendulum-exact", "--time", "2", "--methods", "shake", "--substeps", "1,2"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("pendulum-exact has exact answers at their own times: --time does not apply to it"),
            std::string::npos)
      << o.err;
  const auto quiet = converge({"pendulum-exact", "--methods", "shake", "--substeps", "1,2"});
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("--time"), std::string::npos) << quiet.err;
}

TEST(Converge, FreeBodiesThatTouchAreAClearError) {
  TempDir dir;
  const auto file = dir.write("touch.xml",
                              "<scene name=\"touch\">\n  <world gravity=\"0 0 0\"/>\n  <solver/>\n"
                              "  <box name=\"a\" pos=\"0 0 0\" velocity=\"1 0 0\"/>\n"
                              "  <box name=\"b\" pos=\"1.5 0 0\"/>\n</scene>\n");
  const auto o = converge({file.string(), "--substeps", "1"});
  EXPECT_EQ(o.code, lab::kExitFailure);
  EXPECT_NE(o.err.find("touch: a body touched something"), std::string::npos) << o.err;
}

// A capsule of a particle model turns as its box's corners make it, not as a solid capsule: the
// reference for it has the box's moments. With the solid capsule's, SHAKE's error stopped falling
// at 0.3 m (its order read near 0); with the box's it is second order as on the box.
TEST(Converge, AParticleCapsuleIsMeasuredAgainstItsOwnInertia) {
  TempDir dir;
  const auto file = dir.write("capsule.xml",
                              "<scene name=\"spinning-capsule\">\n  <world gravity=\"0 0 0\"/>\n  <solver/>\n"
                              "  <capsule name=\"c\" pos=\"0 0 0\" radius=\"0.3\" length=\"2\" "
                              "angular-velocity=\"45 360 30\"/>\n</scene>\n");
  lab::ConvergeOptions o;
  o.methods = {phys::SolverMethod::Shake};
  o.models = {"corners", "rigid"};
  o.substeps = {8, 16, 32};
  lab::ConvergeTarget target;
  for (const auto& l : lab::convergeLines(lab::runConverge(file, o, target))) {
    const std::optional<double> p = lab::fittedOrder(l);
    ASSERT_TRUE(p.has_value()) << l.front().model;
    EXPECT_NEAR(*p, 2.0, 0.1) << l.front().model;  // measured 2.00 for both at 8, 16, 32
  }
}

// A spin its substep cannot resolve has no reference: a clear error naming the scene and the body.
TEST(Converge, ASpinTooFastForTheSubstepIsAClearError) {
  TempDir dir;
  const auto file = dir.write(
      "fast.xml",
      "<scene name=\"fast\">\n  <world gravity=\"0 0 0\"/>\n  <solver/>\n"
      "  <box name=\"spinner\" pos=\"0 0 0\" size=\"0.4 1 2\" angular-velocity=\"3000 6000 20000\"/>\n"
      "</scene>\n");
  const auto o = converge({file.string(), "--substeps", "1"});
  EXPECT_EQ(o.code, lab::kExitFailure);
  EXPECT_NE(o.err.find("fast: body 'spinner' spins too fast for its substep"), std::string::npos) << o.err;
  // A spin whose length no double holds is said in words, not as inf.
  const auto huge = converge({dir.write("huge.xml",
                                        "<scene name=\"huge\">\n  <world gravity=\"0 0 0\"/>\n"
                                        "  <box name=\"b\" pos=\"0 0 0\" size=\"0.4 1 2\" "
                                        "angular-velocity=\"1e300 1e300 1e300\"/>\n</scene>\n")
                                  .string(),
                              "--substeps", "1"});
  EXPECT_EQ(huge.code, lab::kExitFailure);
  EXPECT_NE(huge.err.find("h |w| = more than 1e308 rad"), std::string::npos) << huge.err;
}

TEST(Converge, BadOptionsAreUsageErrors) {
  lab_testing::expectUsageError(converge({"--methods", "verlet"}), "converge", "verlet");
  lab_testing::expectUsageError(converge({"--models", "seed"}), "converge", "seed");
  lab_testing::expectUsageError(converge({"--substeps", "0"}), "converge", "--substeps");
  lab_testing::expectUsageError(converge({"--time", "0"}), "converge", "--time");
  lab_testing::expectUsageError(converge({"--iterations"}), "converge", "--iterations");
  lab_testing::expectUsageError(converge({"--bogus"}), "converge", "--bogus");
  // Options the scene cannot take are usage errors too, as in sweep: a model it has nothing for,
  // and a --time of more steps than a run may take at its dt (3.6e9 steps ran as one, "exact").
  TempDir dir;
  const auto rag = dir.write("rag.xml",
                             "<scene name=\"rag\">\n  <world gravity=\"0 0 0\"/>\n"
                             "  <ragdoll name=\"r\" pos=\"0 2 0\"/>\n</scene>\n");
  lab_testing::expectUsageError(converge({rag.string(), "--models", "corners"}), "converge",
                                "--models: 'corners' is a box model and the scene has no boxes");
  std::string tumbling = lab_testing::readFile(sceneFile("tumbling-box"));
  const std::string dt = "dt=\"0.0166666666666667\"";
  ASSERT_NE(tumbling.find(dt), std::string::npos);
  tumbling.replace(tumbling.find(dt), dt.size(), "dt=\"1e-6\"");
  lab_testing::expectUsageError(
      converge({dir.write("tiny-dt.xml", tumbling).string(), "--time", "3600", "--substeps", "1,2"}),
      "converge", "--time: at the scene's dt 1e-06 s the 3600 s asked take more than 10000000 steps");
}

// A --time under half the scene's dt rounds to no step; it ran one, and the header said
// "t = 0.01667 to 0.01667 s". Refused like any option out of its range, naming the option and
// the step.
TEST(Converge, ATimeShorterThanOneStepIsAUsageError) {
  lab_testing::expectUsageError(converge({"tumbling-box", "--time", "0.001", "--substeps", "1"}), "converge",
                                "--time: '0.001' s is shorter than one step of the scene's dt 0.0166667 s");
  // One step's time is one step, measured.
  const auto one = converge({"tumbling-box", "--time", "0.0166666666666667", "--substeps", "1"});
  EXPECT_EQ(one.code, lab::kExitOk) << one.err;
}

TEST(Converge, AMissingSceneNamesTheFile) {
  const auto o = converge({"no-such-scene"});
  EXPECT_EQ(o.code, lab::kExitFailure);
  EXPECT_NE(o.err.find("no-such-scene"), std::string::npos) << o.err;
}

}  // namespace
