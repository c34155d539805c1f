// The peer engines (app/lab/peers/) and `lab compare` (app/lab/compare.cpp). Each physical
// check runs in every engine built in, so a machine without Bullet, ODE or MuJoCo still runs
// the rest; the lab built for CI has all three (scripts/install-deps).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "commands.h"
#include "csv.h"
#include "gnuplot.h"
#include "lab.h"
#include "lab_test_util.h"
#include "peer.h"
#include "peers/peer_scene.h"
#include "run_metrics.h"
#include "runner.h"
#include "scenes/scene.h"

namespace {

using lab_testing::TempDir;

constexpr double kDt = 1.0 / 60.0;
constexpr int kTwoSeconds = 120;

scenes::Scene load(const std::string& xml) {
  return scenes::loadSceneText(xml, "compare_test");
}

// Three 1 m boxes of 1 kg on the ground: centres at 0.5, 1.5 and 2.5 m.
const char* kStack =
    "<scene name=\"stack3\">\n"
    "  <ground friction=\"0.6\"/>\n"
    "  <stack name=\"s\" pos=\"0 0 0\" count=\"3\" size=\"1\" mass=\"1\"/>\n"
    "</scene>\n";

// A flat box 0.8 x 0.4 x 0.6 m dropped from 2 m: it comes to rest with its centre at 0.2 m.
const char* kFall =
    "<scene name=\"fall\">\n"
    "  <ground/>\n"
    "  <box name=\"b\" pos=\"0.3 2 -0.2\" size=\"0.8 0.4 0.6\" mass=\"2\"/>\n"
    "</scene>\n";

// Five 0.2 m links hanging from a pinned particle at 3 m: the end hangs 1 m below it.
const char* kChain =
    "<scene name=\"chain\">\n"
    "  <ground/>\n"
    "  <chain name=\"c\" pos=\"0 3 0\" links=\"5\" length=\"0.2\" mass=\"1\"/>\n"
    "</scene>\n";

std::vector<std::string> engines() {
  std::vector<std::string> e = lab::peerEngines();
  if (e.empty())
    std::cout << "[ note     ] no peer engines built in; the physical checks have nothing to run\n";
  return e;
}

// An engine is stepped by the lab's one step loop as it is, with no wrapper: the poses the runner
// records at the last step are the engine's own, body for body in the description's order.
TEST(PeerEngines, StepThroughTheRunnerAsTheyAre) {
  const lab::peers::Description d = lab::peers::describe(load(kStack));
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const auto built = lab::peers::makeEngine(engine, d, kDt);
    ASSERT_NE(built, nullptr);
    lab::RunSpec spec;
    spec.steps = 30;
    spec.checkpoints = {10, 30};
    spec.orientations = true;
    const lab::RunRecord run = lab::runSteps(*built, spec);
    EXPECT_EQ(run.stepsRun, 30);
    ASSERT_EQ(run.positions.size(), 2u);
    ASSERT_EQ(run.orientations.size(), 2u);
    ASSERT_EQ(run.positions[1].size(), d.bodies.size());
    for (int i = 0; i < static_cast<int>(d.bodies.size()); ++i) {
      const auto k = static_cast<std::size_t>(i);
      EXPECT_TRUE(run.positions[1][k] == built->position(i)) << "body " << i;
      EXPECT_TRUE(run.orientations[1][k] == built->orientation(i)) << "body " << i;
      EXPECT_NEAR(run.positions[1][k].y, 0.5 + static_cast<double>(i), 0.05) << "body " << i;  // resting
    }
  }
}

// A run of ODE is the same whatever ran before it in the process. ODE's solver shuffles its rows
// from a random state that lived on between worlds, so a second run of one scene differed from
// the first (a sweep's ODE row at one dt moved with the dts listed before it).
TEST(PeerEngines, AnOdeRunDoesNotDependOnTheRunsBefore) {
  const std::vector<std::string> e = lab::peerEngines();
  if (std::find(e.begin(), e.end(), "ode") == e.end()) GTEST_SKIP() << "ODE is not built in";
  const lab::peers::Description d = lab::peers::describe(load(kStack));
  lab::RunSpec spec;
  spec.steps = 60;
  spec.checkpoints = {60};
  spec.orientations = true;
  std::vector<lab::RunRecord> runs;
  for (int k = 0; k < 2; ++k) {
    const auto built = lab::peers::makeEngine("ode", d, kDt);
    ASSERT_NE(built, nullptr);
    runs.push_back(lab::runSteps(*built, spec));
  }
  ASSERT_EQ(runs[0].positions.size(), 1u);
  ASSERT_EQ(runs[1].positions.size(), 1u);
  for (std::size_t i = 0; i < d.bodies.size(); ++i) {
    EXPECT_TRUE(runs[0].positions[0][i] == runs[1].positions[0][i]) << "body " << i;
    EXPECT_TRUE(runs[0].orientations[0][i] == runs[1].orientations[0][i]) << "body " << i;
  }
}

// MuJoCo meets bad numbers by putting the bodies back where they began and going on: the run
// read as sound (a sweep row not blown up, on the front; compare gave it an error). A box thrown
// at 1e12 m/s makes it reset: the poses after read not finite, and the sweep calls it blown up.
TEST(PeerEngines, AMujocoRunThatResetItselfHasBlownUp) {
  const std::vector<std::string> e = lab::peerEngines();
  if (std::find(e.begin(), e.end(), "mujoco") == e.end()) GTEST_SKIP() << "MuJoCo is not built in";
  TempDir dir;
  const std::filesystem::path fly =
      dir.write("fly.xml",
                "<scene name=\"fly\">\n  <ground/>\n"
                "  <box name=\"b\" pos=\"0 3 0\" velocity=\"1e12 0 0\" size=\"1\" mass=\"8\"/>\n</scene>\n");
  const lab::PeerResult r = lab::runPeer("mujoco", scenes::loadSceneFile(fly), kDt, 60, {1, 60});
  ASSERT_TRUE(r.ran) << r.unsupported;
  EXPECT_NE(r.unsupported.find("MuJoCo reset the run after bad numbers"), std::string::npos) << r.unsupported;
  ASSERT_EQ(r.positions.size(), 2u);
  EXPECT_FALSE(std::isfinite(r.positions[1][0].x)) << r.positions[1][0].x;

  const lab::CommandOutput s = lab::runCaptured(
      {"sweep", fly.string(), "--iterations", "1", "--repeat", "1", "--out", dir.file("out").string()});
  ASSERT_EQ(s.code, 0) << s.err;
  const lab::CsvTable csv = lab::readCsv(dir.file("out/results.csv"));
  int seen = 0;
  for (const lab::CsvRow& row : csv.rows) {
    if (row.at("method") != "mujoco") continue;
    ++seen;
    EXPECT_EQ(row.at("blew_up"), "1");
    EXPECT_EQ(row.at("pareto"), "0");
    EXPECT_EQ(row.at("error"), "");
  }
  EXPECT_EQ(seen, 1);
}

TEST(PeerEngines, ListedInTheFixedOrder) {
  const std::vector<std::string> e = lab::peerEngines();
  const std::vector<std::string> order = {"bullet", "ode", "mujoco"};
  std::size_t at = 0;
  for (const std::string& name : e) {
    while (at < order.size() && order[at] != name) ++at;
    ASSERT_LT(at, order.size()) << name << " is not one of bullet, ode, mujoco in that order";
    ++at;
  }
}

TEST(PeerEngines, AnUnknownEngineIsNotRun) {
  const scenes::Scene scene = load(kFall);
  const lab::PeerResult r = lab::runPeer("havok", scene, kDt, 10, {});
  EXPECT_FALSE(r.ran);
  EXPECT_EQ(r.engine, "havok");
  EXPECT_NE(r.unsupported.find("not built"), std::string::npos) << r.unsupported;
}

TEST(PeerScene, ReadsMassInertiaVelocityAndOrder) {
  const scenes::Scene scene = load(
      "<scene name=\"d\">\n"
      "  <ground friction=\"0.4\"/>\n"
      "  <particle name=\"p\" pos=\"0 3 0\" velocity=\"1 0 0\" mass=\"0.5\"/>\n"
      "  <particle name=\"q\" pos=\"0 4 0\" pinned=\"true\"/>\n"
      "  <box name=\"b\" pos=\"1 2 3\" size=\"2 1 0.5\" mass=\"8\" velocity=\"0 1 2\" angular-velocity=\"0 "
      "90 0\"\n"
      "       friction=\"0.9\"/>\n"
      "  <box name=\"t\" pos=\"5 2 3\" size=\"1\" mass=\"4\" model=\"tetra\"/>\n"
      "</scene>\n");
  const lab::peers::Description d = lab::peers::describe(scene);
  ASSERT_EQ(d.bodies.size(), 4u);  // boxes first, then loose particles in id order
  const auto& box = d.bodies[0];
  EXPECT_EQ(box.shape, lab::peers::Body::Shape::Box);
  EXPECT_NEAR(box.mass, 8.0, 1e-12);
  EXPECT_NEAR(box.halfExtents.x, 1.0, 1e-9);
  EXPECT_NEAR(box.halfExtents.z, 0.25, 1e-9);
  // The corners model's inertia: m (hy^2 + hz^2) about x, three times a solid box's.
  EXPECT_NEAR(box.inertia.x, 8.0 * (0.25 + 0.0625), 1e-9);
  EXPECT_NEAR(box.inertia.y, 8.0 * (1.0 + 0.0625), 1e-9);
  EXPECT_NEAR(box.velocity.y, 1.0, 1e-9);
  EXPECT_NEAR(box.velocity.z, 2.0, 1e-9);
  EXPECT_NEAR(box.angularVelocity.y, std::numbers::pi / 2.0, 1e-9);
  EXPECT_NEAR(box.friction, 0.9, 1e-12);
  EXPECT_NEAR(d.bodies[1].mass, 4.0, 1e-12);  // the tetra box: four particles of 1 kg
  EXPECT_NEAR(d.bodies[1].inertia.x, 4.0 * 0.5, 1e-9);
  const auto& p = d.bodies[2];
  EXPECT_EQ(p.shape, lab::peers::Body::Shape::Sphere);
  EXPECT_NEAR(p.mass, 0.5, 1e-12);
  EXPECT_NEAR(p.velocity.x, 1.0, 1e-9);
  EXPECT_NEAR(p.velocity.y, 0.0, 1e-9);  // the Verlet start corrected back to the given velocity
  // A loose particle slides as its ground contact says: the ground's material, not the default.
  const double groundDynamic = scene.world.worldSettings().groundMaterial.dynamicFriction;
  ASSERT_NE(groundDynamic, phys::Material{}.dynamicFriction);
  EXPECT_NEAR(p.friction, groundDynamic, 1e-12);
  EXPECT_TRUE(d.bodies[3].fixed);
  EXPECT_NEAR(d.groundFriction, 0.4, 1e-12);
  EXPECT_TRUE(d.refused.empty());
}

TEST(PeerStack, ThreeBoxesStandInEveryEngine) {
  const scenes::Scene scene = load(kStack);
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, kTwoSeconds, {1, kTwoSeconds});
    ASSERT_TRUE(r.ran) << r.unsupported;
    // Notes may say how the run went (Bullet's bodies fall asleep), never that part is missing.
    EXPECT_EQ(r.unsupported.find("not"), std::string::npos) << r.unsupported;
    ASSERT_EQ(r.positions.size(), 2u);
    const phys::Vec3 top = r.positions[1][2];
    EXPECT_LT(std::hypot(top.x, top.z), 0.05) << "top box drifted to " << top.x << ", " << top.z;
    EXPECT_NEAR(top.y, 2.5, 0.05);
    EXPECT_GT(r.meanMsPerStep, 0.0);
    EXPECT_LT(r.maxPenetration, 0.05);
  }
}

// Allowed to, Bullet puts the resting stack to sleep within four seconds, as it ships; by default
// (as ours, unless asked) it keeps every body awake, so its time is that of a world that steps
// everything.
TEST(PeerStack, BulletSleepsOnlyWhenAllowed) {
  const std::vector<std::string> built = engines();
  if (std::find(built.begin(), built.end(), "bullet") == built.end()) GTEST_SKIP() << "no Bullet in this lab";
  const scenes::Scene scene = load(kStack);
  const lab::PeerResult asleep = lab::runPeer("bullet", scene, kDt, 2 * kTwoSeconds, {2 * kTwoSeconds}, true);
  EXPECT_NE(asleep.unsupported.find("asleep"), std::string::npos) << asleep.unsupported;
  const lab::PeerResult awake = lab::runPeer("bullet", scene, kDt, 2 * kTwoSeconds, {2 * kTwoSeconds});
  ASSERT_TRUE(awake.ran) << awake.unsupported;
  EXPECT_EQ(awake.unsupported.find("asleep"), std::string::npos) << awake.unsupported;
  EXPECT_NE(awake.settings.find("no sleeping"), std::string::npos) << awake.settings;
  EXPECT_NEAR(awake.positions[0][2].y, 2.5, 0.05);  // and the stack stands
}

TEST(PeerFall, ABoxComesToRestAtItsHalfHeight) {
  const scenes::Scene scene = load(kFall);
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, kTwoSeconds, {kTwoSeconds});
    ASSERT_TRUE(r.ran) << r.unsupported;
    const phys::Vec3 c = r.positions.at(0).at(0);
    EXPECT_NEAR(c.y, 0.2, 0.02);
    // Straight down. Bullet's box-plane contact adds one point a step (its default collision
    // configuration), so its flat landing pivots on the first corner and slides some 7 cm.
    EXPECT_LT(std::hypot(c.x - 0.3, c.z + 0.2), 0.1);
  }
}

TEST(PeerFall, FreeFallMatchesTheFormula) {
  // Before it lands (0.5 s, 1.23 m of its 1.8 m), every engine's box is where g t^2 / 2 puts it.
  const scenes::Scene scene = load(kFall);
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, 30, {30});
    ASSERT_TRUE(r.ran) << r.unsupported;
    // Semi-implicit Euler (all three) falls g dt^2 / 2 per step further than the formula.
    EXPECT_NEAR(r.positions.at(0).at(0).y, 2.0 - 0.5 * 9.81 * 0.25, 0.05);
  }
}

TEST(PeerFall, EachEngineReportsThePoseAfterItsLastStep) {
  // All three step semi-implicit Euler, so after n steps from rest a body has fallen exactly
  // g dt^2 n (n + 1) / 2: 1.2736 m after 30 steps. A pose one step old (MuJoCo's xpos after
  // mj_step, before the adapter brings it up to date) would read g dt^2 n = 8 cm less.
  const scenes::Scene scene = load(kFall);
  const double fallen = 9.81 * kDt * kDt * 30.0 * 31.0 / 2.0;
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, 30, {30});
    ASSERT_TRUE(r.ran) << r.unsupported;
    EXPECT_NEAR(r.positions.at(0).at(0).y, 2.0 - fallen, 1e-3);
  }
}

TEST(PeerChain, APinnedChainHangsAtItsLength) {
  const scenes::Scene scene = load(kChain);
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, kTwoSeconds, {kTwoSeconds});
    ASSERT_TRUE(r.ran) << r.unsupported;
    const std::vector<phys::Vec3>& p = r.positions.at(0);
    ASSERT_EQ(p.size(), 6u);
    EXPECT_NEAR(p[0].y, 3.0, 1e-9);  // the pinned particle stays
    EXPECT_NEAR(glm::length(p[5] - p[0]), 1.0, 0.05);
    for (std::size_t k = 0; k + 1 < p.size(); ++k)
      EXPECT_NEAR(glm::length(p[k + 1] - p[k]), 0.2, 0.01) << "link " << k;
  }
}

TEST(PeerRange, ARangeStickHoldsItsBounds) {
  // Two particles under pinned ones: "over" starts 0.6 m above its anchor and falls on a
  // stick that only pushes apart below 0.5 m; "under" starts 0.1 m below its anchor and
  // falls on one that only pulls together beyond 1 m.
  const scenes::Scene scene = load(
      "<scene name=\"range\">\n"
      "  <particle name=\"a\" pos=\"0 3 0\" pinned=\"true\"/>\n"
      "  <particle name=\"over\" pos=\"0 3.6 0\"/>\n"
      "  <stick a=\"a\" b=\"over\" min=\"0.5\"/>\n"
      "  <particle name=\"b\" pos=\"2 3 0\" pinned=\"true\"/>\n"
      "  <particle name=\"under\" pos=\"2 2.9 0\"/>\n"
      "  <stick a=\"b\" b=\"under\" max=\"1\"/>\n"
      "</scene>\n");
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, kTwoSeconds, {kTwoSeconds});
    ASSERT_TRUE(r.ran) << r.unsupported;
    const std::vector<phys::Vec3>& p = r.positions.at(0);
    EXPECT_NEAR(p[1].y - p[0].y, 0.5, 0.02);
    EXPECT_NEAR(p[2].y - p[3].y, 1.0, 0.03);
  }
}

TEST(PeerDamping, VelocityDecaysAsOurWindResistance) {
  // No gravity, damping 1/s: a particle and a box launched at 10 m/s cover 10 (1 - 1/e) m in
  // 1 s (ours exactly); each engine's damping is set to the same decay, up to its own stepping.
  const scenes::Scene scene = load(
      "<scene name=\"damp\">\n"
      "  <world gravity=\"0 0 0\" damping=\"1\"/>\n"
      "  <box pos=\"0 1 0\" size=\"0.5 0.3 0.2\" velocity=\"10 0 0\"/>\n"
      "  <particle pos=\"0 3 0\" velocity=\"10 0 0\"/>\n"
      "</scene>\n");
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, 60, {60});
    ASSERT_TRUE(r.ran) << r.unsupported;
    for (const phys::Vec3& p : r.positions.at(0)) EXPECT_NEAR(p.x, 10.0 * (1.0 - std::exp(-1.0)), 0.2);
  }
}

TEST(PeerRestitution, ABallBouncesWhereTheEngineCanSayIt) {
  // Dropped 2 m onto the ground at restitution 0.5, a ball rises again to 0.25 x 2 = 0.5 m;
  // MuJoCo has no restitution coefficient and says so.
  const scenes::Scene scene = load(
      "<scene name=\"bounce\">\n"
      "  <solver restitution=\"0.5\"/>\n"
      "  <ground/>\n"
      "  <particle pos=\"0 2.05 0\"/>\n"
      "</scene>\n");
  std::vector<int> every(100);
  for (int s = 0; s < 100; ++s) every[static_cast<std::size_t>(s)] = s + 1;
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, 100, every);
    ASSERT_TRUE(r.ran) << r.unsupported;
    if (r.unsupported.find("restitution not expressed") != std::string::npos) continue;
    // The first peak after the ball turns upwards, measured at its bottom.
    std::size_t k = 1;
    while (k < r.positions.size() && r.positions[k][0].y <= r.positions[k - 1][0].y) ++k;
    while (k < r.positions.size() && r.positions[k][0].y > r.positions[k - 1][0].y) ++k;
    ASSERT_LT(k, r.positions.size()) << "no bounce";
    EXPECT_NEAR(r.positions[k - 1][0].y - lab::peers::kParticleRadius, 0.5, 0.1);
  }
}

TEST(PeerRagdoll, PinsAndStopsHoldInEveryEngine) {
  // One ragdoll dropped on its back from 1 m: its 18 pins (the hinges) and 18 stops (range
  // links) go through ball joints and distance limits in each engine.
  const scenes::Scene scene = load(
      "<scene name=\"doll\">\n"
      "  <ground/>\n"
      "  <ragdoll name=\"r\" pos=\"0 1 0\" euler=\"80 0 0\"/>\n"
      "</scene>\n");
  const lab::peers::Description d = lab::peers::describe(scene);
  ASSERT_EQ(d.pins.size(), 18u);
  ASSERT_EQ(d.distances.size(), 18u);
  ASSERT_EQ(d.ignored.size(), 9u);
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    auto built = lab::peers::makeEngine(engine, d, kDt);
    ASSERT_NE(built, nullptr);
    double worstGap = 0.0, worstStop = 0.0;
    for (int s = 0; s < kTwoSeconds; ++s) {
      built->step();
      if (s < 60) continue;  // after the landing
      auto point = [&](int body, const phys::Vec3& local) {
        return lab::peers::toWorld(built->position(body), built->orientation(body), local);
      };
      for (const auto& p : d.pins)
        worstGap = std::max(worstGap, glm::length(point(p.a, p.localA) - point(p.b, p.localB)));
      for (const auto& r : d.distances) {
        const double length = glm::length(point(r.a, r.localA) - point(r.b, r.localB));
        worstStop = std::max({worstStop, r.min - length, length - r.max});
      }
    }
    built->finish();
    EXPECT_TRUE(built->notes.empty()) << built->notes.front();
    EXPECT_LT(worstGap, 0.02);
    EXPECT_LT(worstStop, 0.02);
    std::cout << "[ " << engine << " ] ragdoll at rest: pin gap up to " << worstGap
              << " m, stops exceeded by up to " << worstStop << " m\n";
  }
}

TEST(PeerUnsupported, PointGravityIsReportedInWords) {
  const scenes::Scene scene = scenes::loadSceneFile(scenes::sceneDirectory(DATA_DIR) / "orbit.xml");
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, 10, {10});
    EXPECT_FALSE(r.ran);
    EXPECT_TRUE(r.positions.empty());
    EXPECT_NE(r.unsupported.find("point gravity"), std::string::npos) << r.unsupported;
  }
}

// Scenes the loader takes whose bodies get where ODE aborts the program (an assertion in its hash
// space beyond 2.7e8 m, or in normalising a quaternion that overflowed): every engine either runs
// them or says why not, and the process lives. ODE stops before the step that would abort.
TEST(PeerReach, ABodyBeyondWhatAnEngineReachesStopsItsRunWithAReason) {
  struct Case {
    const char* what;
    const char* body;  // the <box> element's attributes
    const char* world;
    const char* odeSays;
  };
  const Case cases[] = {
      {"thrown at 1e12 m/s", "pos=\"0 5 0\" velocity=\"1e12 0 0\"", "", "after step 1, body 'b' is at ("},
      {"under a gravity of 1e20", "pos=\"0 5 0\"", "<world gravity=\"0 -1e20 0\"/>",
       "after step 1, body 'b' is at ("},
      {"spun at 1e160 degrees a second", "pos=\"0 5 0\" angular-velocity=\"1e160 0 0\"", "",
       "body 'b' spins at (1.74533e+158, 0, 0) rad/s"},
      {"placed at 5e8 m", "pos=\"5e8 5 0\"", "<world bound=\"1e9\"/>", "body 'b' is at (5e+08, 5, 0) m"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const scenes::Scene scene = load(std::string("<scene name=\"far\">") + c.world +
                                     "<ground/><box name=\"b\" " + c.body + "/></scene>");
    for (const std::string& engine : engines()) {
      SCOPED_TRACE(engine);
      const lab::PeerResult r = lab::runPeer(engine, scene, kDt, 3, {3});
      if (!r.ran) {
        EXPECT_FALSE(r.unsupported.empty());
      }
      if (engine != "ode") continue;
      EXPECT_FALSE(r.ran);
      EXPECT_NE(r.unsupported.find(c.odeSays), std::string::npos) << r.unsupported;
      EXPECT_EQ(r.unsupported.find("inf"), std::string::npos) << r.unsupported;
    }
  }
}

// `lab compare` in-process, on a scene file in a temporary folder.
using Output = lab::CommandOutput;
Output compare(const std::vector<std::string>& args) {
  return lab::runCaptured(args);
}

// A box and a loose particle falling onto the ground: something for every column.
const char* kSmall =
    "<scene name=\"small\">\n"
    "  <ground/>\n"
    "  <box name=\"b\" pos=\"0 1.5 0\" size=\"0.5\" euler=\"10 20 30\"/>\n"
    "  <particle name=\"p\" pos=\"1 1 0\"/>\n"
    "</scene>\n";

TEST(Compare, PrintsARowForEachOfOurMethodsAndEachPeer) {
  TempDir dir;
  const auto file = dir.write("small.xml", kSmall);
  const Output o = compare({"compare", file.string(), "--steps", "60"});
  ASSERT_EQ(o.code, 0) << o.err;
  // Nothing on stderr but the progress bar's lines.
  std::istringstream errLines(o.err);
  for (std::string line; std::getline(errLines, line);)
    EXPECT_TRUE(line.empty() || line.rfind("compare [", 0) == 0) << line;
  for (const char* method : {"gauss-seidel", "jacobi", "xpbd", "shake"}) {
    EXPECT_NE(o.out.find(std::string("| ours | ") + method + " |"), std::string::npos) << method << "\n"
                                                                                       << o.out;
  }
  for (const std::string& engine : lab::peerEngines()) {
    EXPECT_NE(o.out.find("| " + engine + " |"), std::string::npos) << engine << "\n" << o.out;
  }
  EXPECT_NE(o.out.find("| engine | method | settings | ms/step |"), std::string::npos) << o.out;
  EXPECT_EQ(o.out.find("not run"), std::string::npos) << o.out;
}

// Rigid bodies and no stick step alike under the four methods (lab::xpbdWhateverTheMethod): one row of ours,
// xpbd, for how its rigid bodies are solved, and its settings say so.
TEST(Compare, AWorldWithNoStickIsOneRowOfOurs) {
  TempDir dir;
  const auto file = dir.write("rigid.xml",
                              "<scene name=\"r\"><box name=\"a\" pos=\"0 0.5 0\" model=\"rigid\"/>"
                              "<box name=\"b\" pos=\"0.1 1.5 0\" model=\"rigid\"/></scene>");
  const Output o = compare({"compare", file.string(), "--steps", "20"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("| ours | xpbd | rigid bodies, "), std::string::npos) << o.out;
  for (const char* method : {"gauss-seidel", "jacobi", "shake"})
    EXPECT_EQ(o.out.find(std::string("| ours | ") + method + " |"), std::string::npos) << method << "\n"
                                                                                       << o.out;
}

// --model, --iterations and --substeps reach our runs: the corners box made rigid leaves no
// stick, so ours is one xpbd row, at the iterations and substeps asked.
TEST(Compare, ModelIterationsAndSubstepsAreImposed) {
  TempDir dir;
  const auto file = dir.write("small.xml", kSmall);
  const Output o = compare({"compare", file.string(), "--steps", "20", "--model", "rigid", "--iterations",
                            "1", "--substeps", "3"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("| ours | xpbd | Verlet and rigid bodies, 1 iteration x 3 substeps |"),
            std::string::npos)
      << o.out;
  const Output json = compare({"compare", file.string(), "--steps", "20", "--json", "--model", "rigid"});
  ASSERT_EQ(json.code, 0) << json.err;
  EXPECT_NE(json.out.find("\"settings\":\"Verlet and rigid bodies, "), std::string::npos) << json.out;
}

// Compare is a preset of the sweep: its rows are the sweep's rows of the four methods at the
// scene's iterations and substeps, then the peers', ours figure for figure (the timings apart).
TEST(Compare, OurRowsAreTheSweepsRows) {
  TempDir dir;
  // A ragdoll, so the joint gap is something, at settings of neither the scene nor the defaults.
  const Output o = compare({"compare", "ragdoll", "--steps", "30", "--dt", "0.01", "--iterations", "2",
                            "--substeps", "3", "--json"});
  ASSERT_EQ(o.code, 0) << o.err;
  // The sweep's --steps count at the scene's dt (1/60 s): 0.3 s, the compare's 30 steps of 0.01 s.
  const Output s = lab::runCaptured({"sweep", "ragdoll", "--steps", "18", "--dt", "0.01", "--iterations", "2",
                                     "--substeps", "3", "--methods", "gauss-seidel,jacobi,xpbd,shake",
                                     "--repeat", "1", "--out", dir.file("sweep").string()});
  ASSERT_EQ(s.code, 0) << s.err;
  const lab::CsvTable csv = lab::readCsv(dir.file("sweep/results.csv"));
  std::istringstream lines(o.out);
  std::string line;
  std::size_t i = 0;
  while (std::getline(lines, line)) {
    const auto j = lab_testing::parseFlatJson(line);
    ASSERT_TRUE(j.has_value()) << line;
    ASSERT_LT(i, csv.rows.size());
    const lab::CsvRow& row = csv.rows[i++];
    const std::string engine = lab_testing::text(*j, "engine");
    EXPECT_EQ(engine == "ours" ? lab_testing::text(*j, "method") : engine, row.at("method"));
    EXPECT_EQ(lab_testing::number(*j, "steps"), 30.0);
    EXPECT_EQ(row.at("steps"), "30");
    // A peer's second run in one process repeats its first too (ODE's random state is seeded
    // at the start of each run): its figures are compared as ours are. The JSON's %.17g against
    // the CSV's %.10g.
    for (const auto& [key, column] :
         std::vector<std::pair<const char*, const char*>>{{"error", "error"},
                                                          {"error_first", "error_first"},
                                                          {"max_penetration", "pose_penetration"},
                                                          {"max_joint_gap", "pose_joint_gap"}}) {
      const double a = lab_testing::number(*j, key), b = lab::fieldNumber(row, column);
      EXPECT_NEAR(a, b, 1e-9 * std::max(1.0, std::abs(b))) << engine << " " << key;
    }
    if (engine == "ours") {
      EXPECT_GT(lab_testing::number(*j, "max_joint_gap"), 0.0) << engine;
    }
  }
  EXPECT_EQ(i, csv.rows.size());
}

// --steps counts steps of the dt asked; an analytic answer later than that makes every run go
// on to it; --repeat times ours that many times (a peer once).
TEST(Compare, StepsDtAndRepeatsAreWhatWasAsked) {
  const Output o = compare({"compare", "falling-box", "--steps", "25", "--dt", "0.004", "--repeat", "2",
                            "--json", "--data", DATA_DIR});
  ASSERT_EQ(o.code, 0) << o.err;
  std::istringstream lines(o.out);
  int rows = 0;
  for (std::string line; std::getline(lines, line); ++rows) {
    const auto j = lab_testing::parseFlatJson(line);
    ASSERT_TRUE(j.has_value()) << line;
    EXPECT_EQ(lab_testing::number(*j, "steps"), 25.0) << line;
    EXPECT_EQ(lab_testing::number(*j, "dt"), 0.004) << line;
    EXPECT_EQ(lab_testing::number(*j, "repeats"), lab_testing::text(*j, "engine") == "ours" ? 2.0 : 1.0)
        << line;
  }
  EXPECT_GT(rows, 0);
  // pendulum-exact's answers go to t = 2 s: 120 steps of its 1/60 s, whatever --steps says.
  const Output analytic =
      compare({"compare", "pendulum-exact", "--steps", "10", "--json", "--data", DATA_DIR});
  ASSERT_EQ(analytic.code, 0) << analytic.err;
  const auto first = lab_testing::parseFlatJson(analytic.out.substr(0, analytic.out.find('\n')));
  ASSERT_TRUE(first.has_value()) << analytic.out;
  EXPECT_EQ(lab_testing::number(*first, "steps"), 120.0);
  EXPECT_EQ(lab_testing::text(*first, "accuracy"), "analytic");
}

// A run the guard froze has no error to report (the table says inf; JSON, which has no
// infinity, null), and its note says why.
TEST(Compare, AFrozenRunHasNoErrorAndSaysWhy) {
  TempDir dir;
  const auto file = dir.write("escape.xml", lab_testing::escapingScene());
  const Output o = compare({"compare", file.string(), "--steps", "30"});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::size_t at = o.out.find("| ours | ");
  ASSERT_NE(at, std::string::npos) << o.out;
  const std::string row = o.out.substr(at, o.out.find('\n', at) - at);
  EXPECT_NE(row.find(" | blew up | blew up | "), std::string::npos) << row;
  EXPECT_NE(row.find("blew up: the guard froze 1 particle |"), std::string::npos) << row;
  // Nor any other figure: the penetration, joint gap and every-step figures read "blew up" (they read 0).
  std::string blewUp = " | blew up | blew up | blew up | blew up";
  for (std::size_t i = 0; i < lab::kRunMetricCount; ++i) blewUp += " | blew up";
  EXPECT_NE(row.find(blewUp + " | blew up: the guard"), std::string::npos) << row;
  const Output json = compare({"compare", file.string(), "--steps", "30", "--json"});
  ASSERT_EQ(json.code, 0) << json.err;
  const auto first = lab_testing::parseFlatJson(json.out.substr(0, json.out.find('\n')));
  ASSERT_TRUE(first.has_value()) << json.out;
  EXPECT_EQ(first->values.at("error"), "null") << json.out;
  EXPECT_EQ(first->values.at("error_first"), "null") << json.out;
  EXPECT_EQ(first->values.at("max_penetration"), "null") << json.out;
  EXPECT_EQ(first->values.at("max_joint_gap"), "null") << json.out;
  for (const lab::RunMetric& m : lab::kRunMetrics)
    EXPECT_EQ(first->values.at(std::string(m.column) + "_every_step"), "null") << m.column;
}

TEST(Compare, NamesAProjectSceneFromTheDataFolderAndAnyOtherAsGiven) {
  const Output project = compare({"compare", "falling-box", "--steps", "5", "--data", DATA_DIR});
  ASSERT_EQ(project.code, 0) << project.err;
  EXPECT_NE(project.out.find("(assets/scenes/falling-box.xml)"), std::string::npos) << project.out;
  TempDir dir;
  const auto file = dir.write("small.xml", kSmall);
  const Output other = compare({"compare", file.string(), "--steps", "5"});
  ASSERT_EQ(other.code, 0) << other.err;
  std::string shown("(");  // built by append: "(" + path trips GCC 12's -Wrestrict (bug 105329)
  shown.append(file.string()).append(")");
  EXPECT_NE(other.out.find(shown), std::string::npos) << other.out;
}

TEST(Compare, JsonRowsHoldFiniteNumbers) {
  TempDir dir;
  const auto file = dir.write("small.xml", kSmall);
  const Output o = compare({"compare", file.string(), "--steps", "60", "--json"});
  ASSERT_EQ(o.code, 0) << o.err;
  std::istringstream lines(o.out);
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(lines, line)) {
    const auto j = lab_testing::parseFlatJson(line);
    ASSERT_TRUE(j.has_value()) << line;
    rows.push_back(lab_testing::text(*j, "engine") + "/" + lab_testing::text(*j, "method"));
    EXPECT_EQ(j->values.at("ran"), "true") << line;
    for (const char* key :
         {"ms_per_step", "ratio", "error_first", "error", "max_penetration", "max_joint_gap", "dt"}) {
      EXPECT_TRUE(std::isfinite(lab_testing::number(*j, key))) << key << " in " << line;
    }
    EXPECT_GT(lab_testing::number(*j, "ms_per_step"), 0.0) << line;
    EXPECT_EQ(lab_testing::number(*j, "steps"), 60.0);
  }
  EXPECT_EQ(rows.size(), 4u + lab::peerEngines().size());
  EXPECT_EQ(rows.at(0), "ours/gauss-seidel");
  EXPECT_EQ(rows.at(3), "ours/shake");
}

// Every engine's penetration and joint gap come from its bodies' poses, by our code: a falling
// ragdoll's joints hold within centimetres in every engine, and never exactly; no engine lets a
// body sink or overlap by 10 cm.
TEST(Compare, EveryEngineHasAJointGapAndPenetrationFromItsPoses) {
  const Output o = compare({"compare", "ragdoll", "--steps", "60", "--json"});
  ASSERT_EQ(o.code, 0) << o.err;
  std::istringstream lines(o.out);
  std::string line;
  int rows = 0;
  while (std::getline(lines, line)) {
    const auto j = lab_testing::parseFlatJson(line);
    ASSERT_TRUE(j.has_value()) << line;
    ++rows;
    const double gap = lab_testing::number(*j, "max_joint_gap");
    EXPECT_GT(gap, 0.0) << line;
    EXPECT_LT(gap, 0.1) << line;
    const double depth = lab_testing::number(*j, "max_penetration");
    EXPECT_GE(depth, 0.0) << line;
    EXPECT_LT(depth, 0.1) << line;
  }
  EXPECT_EQ(rows, 4 + static_cast<int>(lab::peerEngines().size()));
}

TEST(Compare, APointGravitySceneSaysWhatThePeersCannotExpress) {
  const Output o = compare({"compare", "orbit", "--steps", "30"});
  ASSERT_EQ(o.code, 0) << o.err;
  for (const std::string& engine : lab::peerEngines()) {
    const std::size_t row = o.out.find("| " + engine + " |");
    ASSERT_NE(row, std::string::npos) << o.out;
    const std::string text = o.out.substr(row, o.out.find('\n', row) - row);
    EXPECT_NE(text.find("not run"), std::string::npos) << text;
    EXPECT_NE(text.find("point gravity"), std::string::npos) << text;
  }
}

TEST(Compare, BadArgumentsExitWithUsage) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"compare"},
                                             {"compare", "a", "b"},
                                             {"compare", "x", "--steps", "0"},
                                             {"compare", "x", "--steps", "1e3"},
                                             {"compare", "x", "--dt", "2"},
                                             {"compare", "x", "--dt"},
                                             {"compare", "x", "--peer-sleep", "maybe"},
                                             {"compare", "x", "--model", "lean"},
                                             {"compare", "x", "--iterations", "0"},
                                             {"compare", "x", "--substeps", "1001"},
                                             {"compare", "x", "--frobnicate"}}) {
    const Output o = compare(args);
    EXPECT_EQ(o.code, lab::kExitUsage) << args.back();
    EXPECT_NE(o.err.find("usage: lab compare"), std::string::npos) << o.err;
  }
  const Output help = compare({"compare", "--help"});
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.out.find("usage: lab compare"), std::string::npos);
}

TEST(Compare, AMissingSceneExitsOne) {
  const Output o = compare({"compare", "/nonexistent/scene.xml"});
  EXPECT_EQ(o.code, lab::kExitFailure);
  EXPECT_NE(o.err.find("scene.xml"), std::string::npos) << o.err;
}

}  // namespace

#include <filesystem>

#include <unistd.h>

#include "commands.h"
#include "gnuplot.h"

namespace {

// lab report --quick: every part runs through its own command and results.md holds each
// part's section, its charts and the computed sentences.
TEST(Report, QuickReportWritesEveryPart) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / ("lab-report-" + std::to_string(::getpid()));
  std::filesystem::remove_all(out);
  const Output r = lab::runCaptured("report", {"--quick", "--out", out.string(), "--data", DATA_DIR});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string md = lab_testing::readFile(out / "results.md");
  for (const char* part : {"## Speed against accuracy",
                           "### ragdoll",
                           "### pendulum-exact",
                           "Pareto front, cheapest first:",
                           "**Winner here:",
                           "## Where methods fail",
                           "### The rigid model on the same suite",
                           "| face-face |",
                           "xpbd rigid",
                           "## Beside Bullet, ODE and MuJoCo",
                           "## Cost against size",
                           "us/body-step",
                           "## Error against substep size",
                           "converge    circular-orbit",
                           "## Pose tracking",
                           "### run-cycle\n",
                           "### run-cycle-capsule",
                           "### run-cycle-lean",
                           "each method's cheapest setting within the bar",
                           "(root: hand of god)"}) {
    EXPECT_NE(md.find(part), std::string::npos) << part;
  }
  EXPECT_TRUE(std::filesystem::exists(out / "results" / "pyramid" / "results.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "results" / "stability" / "stability.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "results" / "stability-rigid" / "stability.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "results" / "scale" / "scale.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "results" / "converge" / "converge.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "results" / "tracking" / "results.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "results" / "tracking-capsule" / "results.csv"));
  // Each tracking scene has its table of what its joints needed, the particle ragdoll's too.
  std::size_t tables = 0;
  for (std::size_t at = md.find("What each part's drive needed"); at != std::string::npos;
       at = md.find("What each part's drive needed", at + 1))
    ++tables;
  EXPECT_EQ(tables, 3u);
  EXPECT_NE(md.find("`lab run run-cycle-lean --json`'s `drives`"), std::string::npos);
  // The particle ragdoll is swept under every method, the rigid ones under their own alone.
  const std::string lean = lab_testing::readFile(out / "results" / "tracking-lean" / "results.csv");
  for (const char* method : {",gauss-seidel,", ",jacobi,", ",xpbd,", ",shake,"})
    EXPECT_NE(lean.find(method), std::string::npos) << method;
  EXPECT_EQ(lab_testing::readFile(out / "results" / "tracking" / "results.csv").find(",shake,"),
            std::string::npos);
  if (!lab::findGnuplot().empty()) {
    EXPECT_TRUE(std::filesystem::exists(out / "results" / "converge" / "converge-circular-orbit.png"));
    EXPECT_TRUE(std::filesystem::exists(out / "results" / "chain" / "error-vs-cost.png"));
    EXPECT_TRUE(std::filesystem::exists(out / "results" / "scale" / "scale.png"));
  }
  std::filesystem::remove_all(out);
}

// Every part would fail on a --data that is no folder, after writing a results.md of failures
// (and, as root, creating the folder for the default --out inside it): it is refused first,
// with the system's reason, and nothing is written.
TEST(Report, ADataThatIsNotAFolderIsRefusedBeforeAnythingRuns) {
  TempDir dir;
  const std::filesystem::path missing = dir.file("missing");
  const Output gone = lab::runCaptured("report", {"--quick", "--data", missing.string()});
  EXPECT_EQ(gone.code, lab::kExitFailure);
  EXPECT_EQ(gone.err, "lab: --data: " + missing.string() + ": No such file or directory\n");
  EXPECT_TRUE(gone.out.empty()) << gone.out;
  EXPECT_FALSE(std::filesystem::exists(missing));

  const std::filesystem::path file = dir.write("file", "not a folder\n");
  const std::filesystem::path out = dir.file("out");
  const Output notFolder =
      lab::runCaptured("report", {"--quick", "--data", file.string(), "--out", out.string()});
  EXPECT_EQ(notFolder.code, lab::kExitFailure);
  EXPECT_EQ(notFolder.err, "lab: --data: " + file.string() + ": Not a directory\n");
  EXPECT_FALSE(std::filesystem::exists(out));
}

// Without --out the report writes <data>/docs/results.md, the checked-in results: a quick report,
// whose figures only check the pipeline, wrote over them. It is refused before anything runs.
TEST(Report, AQuickReportWithoutOutIsRefusedAndWritesNothing) {
  TempDir dir;
  const std::filesystem::path data = dir.file("data");
  std::filesystem::create_directories(data);
  const Output r = lab::runCaptured("report", {"--quick", "--data", data.string()});
  EXPECT_EQ(r.code, lab::kExitUsage) << r.err;
  EXPECT_EQ(r.err.rfind("lab: --quick needs --out DIR: its tiny figures would replace the checked-in " +
                            (data / "docs" / "results.md").string() + "\n",
                        0),
            0u)
      << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(std::filesystem::exists(data / "docs")) << "nothing written";
}

// results.md linked each converge chart by the name the report gave the scene, but converge names
// its charts after the scene's own <scene name> (unique within the folder): a scene whose name is
// not its file's had its chart drawn and not linked. Here circular-orbit.xml is named "orbit-renamed".
TEST(Report, LinksEachConvergeChartByTheNameConvergeGaveIt) {
  if (lab::findGnuplot().empty()) GTEST_SKIP() << "no chart is linked without gnuplot";
  TempDir dir;
  const std::filesystem::path assets = std::filesystem::path(DATA_DIR) / "assets";
  const std::filesystem::path data = dir.file("data");
  std::filesystem::create_directories(data / "assets" / "scenes");
  for (const auto& entry : std::filesystem::directory_iterator(assets)) {
    if (entry.path().filename() != "scenes")
      std::filesystem::create_directory_symlink(entry.path(), data / "assets" / entry.path().filename());
  }
  for (const auto& entry : std::filesystem::directory_iterator(assets / "scenes")) {
    const std::filesystem::path to = data / "assets" / "scenes" / entry.path().filename();
    if (entry.path().filename() != "circular-orbit.xml") std::filesystem::create_symlink(entry.path(), to);
  }
  std::string orbit = lab_testing::readFile(assets / "scenes" / "circular-orbit.xml");
  const std::string name = "<scene name=\"circular-orbit\"";
  ASSERT_NE(orbit.find(name), std::string::npos);
  orbit.replace(orbit.find(name), name.size(), "<scene name=\"orbit-renamed\"");
  dir.write("data/assets/scenes/circular-orbit.xml", orbit);

  const std::filesystem::path out = dir.file("out");
  const Output r = lab::runCaptured("report", {"--quick", "--out", out.string(), "--data", data.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(out / "results" / "converge" / "converge-orbit-renamed.png"));
  EXPECT_NE(lab_testing::readFile(out / "results.md").find("(results/converge/converge-orbit-renamed.png)"),
            std::string::npos);
}

// results.md is written last, after minutes of runs: a folder or a device in its place is refused
// before the first run, with the option and the file (it was found out at the end).
TEST(Report, AResultsFileThatCannotBeWrittenIsRefusedBeforeAnythingRuns) {
  TempDir dir;
  const std::filesystem::path out = dir.file("out");
  std::filesystem::create_directories(out / "results.md");
  const Output r = lab::runCaptured("report", {"--quick", "--out", out.string(), "--data", DATA_DIR});
  EXPECT_EQ(r.code, lab::kExitFailure);
  EXPECT_EQ(r.err, "lab: --out: " + (out / "results.md").string() + ": is a folder, not a file\n");
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_TRUE(std::filesystem::is_empty(out / "results")) << "no part ran";
}

// Without gnuplot each command said so on its stderr, which the report dropped (a command that
// succeeds), and results.md linked charts that were never drawn. The report says it once, links
// no chart, and still writes every part's data.
TEST(Report, WithoutGnuplotItSaysSoOnceAndLinksNoChart) {
  TempDir dir;
  std::filesystem::create_directories(dir.file("empty-bin"));
  const char* path = std::getenv("PATH");
  const std::string old = path != nullptr ? path : "";
  ::setenv("PATH", dir.file("empty-bin").c_str(), 1);
  const Output r =
      lab::runCaptured("report", {"--quick", "--out", dir.file("out").string(), "--data", DATA_DIR});
  ::setenv("PATH", old.c_str(), 1);
  EXPECT_EQ(r.code, lab::kExitFailure) << "the stability suite fails without its heat maps: " << r.err;
  std::size_t said = 0;
  for (std::size_t at = r.err.find("gnuplot is not installed"); at != std::string::npos;
       at = r.err.find("gnuplot is not installed", at + 1))
    ++said;
  EXPECT_EQ(said, 1u) << r.err;
  const std::string md = lab_testing::readFile(dir.file("out/results.md"));
  EXPECT_EQ(md.find(".png)"), std::string::npos) << md;
  EXPECT_NE(md.find("gnuplot was not installed"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/results/chain/sweep.gp")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/results/converge/converge.csv")));
}

TEST(Report, BadArgumentsExitWithUsage) {
  const Output r = lab::runCaptured("report", {"--frobnicate"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown option '--frobnicate'"), std::string::npos);
}

}  // namespace
