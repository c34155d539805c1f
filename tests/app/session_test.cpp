// The sandbox's command layer (session.h), driven as the keys, menus and panels drive it, with
// no window: loading and its failures, clear, the seed's world keys, spawning, picking and
// dragging, the method overlay, and Save As.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>

#include <unistd.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "body_colors.h"
#include "history.h"
#include "panels.h"
#include "physics/character.h"
#include "physics/motion.h"
#include "real_time.h"
#include "session.h"
#include "stats_text.h"
#include "temp_folder.h"

namespace {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(DATA_DIR) / "assets" / "scenes";

using TempDir = testing_app::TempFolder;

sandbox::Session open(const char* name) {
  return sandbox::Session(kScenes / (std::string(name) + ".xml"), kScenes);
}

TEST(Session, ABadSceneKeepsTheCurrentWorldAndSaysWhereTheErrorIs) {
  sandbox::Session s = open("pyramid");
  for (int i = 0; i < 10; ++i) s.step();
  const std::uint64_t before = s.scene().world.stateHash();
  const TempDir dir;
  const fs::path bad = dir.path / "bad.xml";
  std::ofstream(bad) << "<scene name=\"bad\">\n  <box pos=\"0 1 0\" mass=\"-2\"/>\n</scene>\n";
  const std::string error = s.open(bad);
  EXPECT_EQ(error, bad.string() + ":2: <box> attribute 'mass': '-2' must be from 1e-06 to 1e+09 (kg)");
  EXPECT_EQ(s.scene().name, "pyramid");
  EXPECT_EQ(s.scene().world.stateHash(), before);  // not even restarted
  EXPECT_EQ(s.scene().world.stepCount(), 10);
  EXPECT_EQ(s.file(), kScenes / "pyramid.xml");
  EXPECT_NE(s.status().find("the current world is kept"), std::string::npos);
  EXPECT_NE(s.open(dir.path / "missing.xml"), "");
  EXPECT_EQ(s.scene().name, "pyramid");
}

// The sandbox draws a scene's analytic answers: one that is no place or no time is refused at
// load, as the lab refuses it, with its line and attribute.
TEST(Session, AWrongAnalyticAnswerIsRefusedWithItsLine) {
  sandbox::Session s = open("pyramid");
  const TempDir dir;
  const fs::path bad = dir.path / "answer.xml";
  const char* cases[][2] = {
      {"at=\"1\" pos=\"nan 1 0\"", "attribute 'pos': 'nan 1 0' must be three finite numbers (m)"},
      {"at=\"1\" pos=\"1 2\"", "attribute 'pos': '1 2' must be three finite numbers (m)"},
      {"at=\"soon\" pos=\"0 1 0\"", "attribute 'at': 'soon' must be a finite number > 0 (s)"}};
  for (const auto& c : cases) {
    std::ofstream(bad) << "<scene name=\"answer\">\n  <particle name=\"p\" pos=\"0 1 0\"/>\n"
                       << "  <expect kind=\"position\" body=\"p\" " << c[0] << "/>\n</scene>\n";
    const std::string error = s.open(bad);
    EXPECT_EQ(error, bad.string() + ":3: <expect kind=\"position\"> " + c[1]) << c[0];
    EXPECT_EQ(s.scene().name, "pyramid");
  }
}

TEST(Session, ReloadRestartsFromTheFileAndBuiltinsOpenTheSeedsScenes) {
  sandbox::Session s = open("ragdoll");
  const std::uint64_t start = s.scene().world.stateHash();
  for (int i = 0; i < 5; ++i) s.step();
  ASSERT_NE(s.scene().world.stateHash(), start);
  EXPECT_EQ(s.reload(), "");
  EXPECT_EQ(s.scene().world.stateHash(), start);
  EXPECT_EQ(s.openBuiltin("box-of-boxes"), "");
  EXPECT_EQ(s.scene().world.bodies().size(), 27u);  // three 3x3 layers
}

TEST(Session, ClearRemovesEveryBodyAndKeepsTheSettings) {
  sandbox::Session s = open("pyramid");
  const phys::SolverSettings solver = s.scene().world.solverSettings();
  s.clear();
  EXPECT_EQ(s.scene().world.bodies().size(), 0u);
  EXPECT_EQ(s.scene().world.particles().size(), 0u);
  EXPECT_EQ(s.scene().world.solverSettings().iterations, solver.iterations);
  s.step();  // an empty world steps
  EXPECT_EQ(s.reload(), "");
  EXPECT_GT(s.scene().world.bodies().size(), 0u);
}

TEST(Session, GravityKeysChangeStrengthAndModeAndKeepTheStrengthAcrossModes) {
  sandbox::Session s = open("ragdoll");
  s.changeGravity(1.0);
  EXPECT_NEAR(glm::length(s.scene().world.worldSettings().gravity), 10.81, 1e-12);
  EXPECT_NEAR(s.scene().world.worldSettings().gravity.y, -10.81, 1e-12);  // still down
  s.toggleGravityMode();
  EXPECT_EQ(s.scene().world.worldSettings().gravityMode, phys::GravityMode::Point);
  EXPECT_NEAR(s.scene().world.worldSettings().gravityStrength, 10.81, 1e-12);
  s.changeGravity(-20.0);  // never below zero
  EXPECT_EQ(s.scene().world.worldSettings().gravityStrength, 0.0);
  s.toggleGravityMode();
  EXPECT_EQ(s.scene().world.worldSettings().gravityMode, phys::GravityMode::Uniform);
}

// Found by the soak test: uniform gravity brought to 0 lost the strength later given in point
// mode (it came back as 0 0 0), and a gravity over 1.3e154 overflowed glm::length, so G said
// "towards the point" and changed nothing, or set gravity to 0.
TEST(Session, GravityKeepsItsStrengthThroughZeroAndHugeValues) {
  sandbox::Session s = open("falling-box");
  for (int i = 0; i < 10; ++i) s.changeGravity(-1.0);
  EXPECT_EQ(glm::length(s.scene().world.worldSettings().gravity), 0.0);
  EXPECT_EQ(s.toggleGravityMode(), "");
  for (int i = 0; i < 5; ++i) s.changeGravity(1.0);
  EXPECT_EQ(s.toggleGravityMode(), "");
  EXPECT_EQ(s.scene().world.worldSettings().gravity, phys::Vec3(0.0, -5.0, 0.0));  // down, as by default

  phys::WorldSettings w = s.scene().world.worldSettings();
  w.gravity = phys::Vec3(0.0, -1e200, 0.0);
  ASSERT_EQ(s.setWorldSettings(w), "");
  EXPECT_EQ(s.toggleGravityMode(), "");
  EXPECT_EQ(s.status(), "gravity: towards the point");
  EXPECT_EQ(s.scene().world.worldSettings().gravityMode, phys::GravityMode::Point);
  EXPECT_EQ(s.scene().world.worldSettings().gravityStrength, 1e200);
  EXPECT_EQ(s.toggleGravityMode(), "");
  EXPECT_EQ(s.scene().world.worldSettings().gravity, phys::Vec3(0.0, -1e200, 0.0));
  EXPECT_EQ(s.changeGravity(-1e200), "");
  EXPECT_EQ(s.scene().world.worldSettings().gravity, phys::Vec3(0.0, 0.0, 0.0));
}

// Y used to raise gravity without bound (1009 m/s^2 after a held key, where the slider ends at 30):
// it stops at the slider's top, and a scene's stronger gravity is only ever lowered by the keys.
TEST(Session, GravityKeyStopsAtTheSlidersTop) {
  sandbox::Session s = open("ragdoll");
  for (int i = 0; i < 100; ++i) ASSERT_EQ(s.changeGravity(1.0), "");
  EXPECT_EQ(glm::length(s.scene().world.worldSettings().gravity), sandbox::kMaxRaisedGravity);
  EXPECT_NE(s.status().find("the most Y gives"), std::string::npos) << s.status();
  phys::WorldSettings w = s.scene().world.worldSettings();
  w.gravity = phys::Vec3(0.0, -50.0, 0.0);
  ASSERT_EQ(s.setWorldSettings(w), "");
  ASSERT_EQ(s.changeGravity(1.0), "");
  EXPECT_EQ(s.scene().world.worldSettings().gravity.y, -50.0);
  ASSERT_EQ(s.changeGravity(-1.0), "");
  EXPECT_EQ(s.scene().world.worldSettings().gravity.y, -49.0);
}

// The status line's figure after Y/H and U/J is the setting's value: it was the first five
// characters of std::to_string's, so 123455 m/s^2 read "12345" and 0.0004 read "0.000".
TEST(Session, TheWorldKeysSayTheValueTheySet) {
  sandbox::Session s = open("ragdoll");
  phys::WorldSettings w = s.scene().world.worldSettings();
  w.gravity = phys::Vec3(0.0, -123456.0, 0.0);
  w.damping = 123456.7;
  ASSERT_EQ(s.setWorldSettings(w), "");
  ASSERT_EQ(s.changeGravity(-1.0), "");
  EXPECT_EQ(s.status(), "gravity 123455 m/s^2");
  ASSERT_EQ(s.changeDamping(0.1), "");
  EXPECT_EQ(s.status(), "wind resistance 123456.8 1/s");
  w.gravity = phys::Vec3(0.0, -1.0004, 0.0);
  w.damping = 0.0;
  ASSERT_EQ(s.setWorldSettings(w), "");
  ASSERT_EQ(s.changeGravity(-1.0), "");
  EXPECT_EQ(s.status(), "gravity 0.0004 m/s^2");
  ASSERT_EQ(s.changeGravity(1.0), "");
  EXPECT_EQ(s.status(), "gravity 1.0004 m/s^2");
  ASSERT_EQ(s.changeDamping(0.1), "");
  EXPECT_EQ(s.status(), "wind resistance 0.1 1/s");
}

// Found by the soak test (seed 11): a gravity whose length is one ulp under the largest double.
// Each press of H rounded it a little longer, until its length and then a component overflowed and
// the key was refused ("gravity must be finite"). The keys now keep it finite and its direction.
TEST(Session, GravityKeysWorkAtTheLargestStrengthADoubleHolds) {
  sandbox::Session s = open("falling-box");
  phys::WorldSettings w = s.scene().world.worldSettings();
  w.gravity = phys::Vec3(-9.14659982763921e+307, 6.108253608622828e+307, 1.4219669832977364e+308);
  ASSERT_EQ(s.setWorldSettings(w), "");
  const phys::Vec3 direction = w.gravity / w.gravity.z;
  auto expectSameWay = [&](const std::string& when) {
    const phys::Vec3 g = s.scene().world.worldSettings().gravity;
    ASSERT_TRUE(std::isfinite(g.x) && std::isfinite(g.y) && std::isfinite(g.z)) << when;
    EXPECT_NEAR(g.z / w.gravity.z, 1.0, 1e-6) << when;  // as strong as a double allows
    EXPECT_NEAR(g.x / g.z, direction.x, 1e-12) << when;
    EXPECT_NEAR(g.y / g.z, direction.y, 1e-12) << when;
  };
  for (int i = 0; i < 100; ++i) {
    ASSERT_EQ(s.changeGravity(-1.0), "") << "H, press " << i + 1;
    expectSameWay("H, press " + std::to_string(i + 1));
  }
  for (int i = 0; i < 100; ++i) {
    ASSERT_EQ(s.changeGravity(1.0), "") << "Y, press " << i + 1;
    expectSameWay("Y, press " + std::to_string(i + 1));
  }
  EXPECT_EQ(s.toggleGravityMode(), "");
  EXPECT_NEAR(s.scene().world.worldSettings().gravityStrength / 1.7976931348623157e308, 1.0, 1e-15);
  EXPECT_EQ(s.toggleGravityMode(), "");
  expectSameWay("G twice");
}

TEST(Session, DampingKeysStepByATenthAndComeBackExactly) {
  sandbox::Session s = open("ragdoll");
  const double start = s.scene().world.worldSettings().damping;
  for (int i = 0; i < 10; ++i) s.changeDamping(0.1);
  EXPECT_NEAR(s.scene().world.worldSettings().damping, start + 1.0, 1e-12);
  for (int i = 0; i < 10; ++i) s.changeDamping(-0.1);
  EXPECT_EQ(s.scene().world.worldSettings().damping, start);
  for (int i = 0; i < 10; ++i) s.changeDamping(-0.1);
  EXPECT_EQ(s.scene().world.worldSettings().damping, 0.0);
}

TEST(Session, ThrownBoxesAndRagdollsFlyAlongTheViewAndLand) {
  sandbox::Session s = open("pyramid");
  const std::size_t boxes = s.scene().world.bodies().size();
  s.spawnBox(phys::Vec3(0, 3, 6), phys::Vec3(0, 0, -sandbox::kThrowSpeed));
  s.spawnRagdoll(phys::Vec3(4, 3, 0), phys::Vec3(sandbox::kThrowSpeed, 0, 0));
  ASSERT_EQ(s.scene().world.bodies().size(), boxes + 11);
  s.step();
  EXPECT_LT(s.scene().world.bodyPose(static_cast<phys::BodyId>(boxes)).center.z, 6.0);  // flies towards -z
  EXPECT_GT(s.scene().world.bodyPose(static_cast<phys::BodyId>(boxes + 1)).center.x, 4.0);  // towards +x
  for (int i = 0; i < 240; ++i) s.step();
  const phys::Metrics m = s.scene().world.metrics();
  EXPECT_EQ(m.frozen, 0);
  EXPECT_LT(m.maxPenetration, 0.05);
}

// 100 presses of R used to stack ragdolls inside each other at the crosshair. A throw goes from
// higher up when a body is in the way, says so, and gives up once every try is taken.
TEST(Session, AThrowNeverGoesIntoABody) {
  sandbox::Session s = open("ragdoll");
  s.clear();
  const phys::Vec3 at(0.0, 3.0, 0.0), still(0.0);
  std::vector<phys::Vec3> thrown;
  for (int i = 0; i < sandbox::kThrowTries; ++i) {
    ASSERT_EQ(s.spawnBox(at, still), "") << "throw " << i + 1;
    thrown.push_back(s.scene().world.bodyPose(phys::BodyId(i)).center);
    EXPECT_NEAR(thrown.back().y, at.y + 2.0 * sandbox::kBoxThrowRoom * i, 1e-9);
    if (i > 0) {
      EXPECT_NE(s.status().find("m higher: a body was in the way"), std::string::npos) << s.status();
    }
  }
  EXPECT_EQ(s.status(), "threw a box, 3.6 m higher: a body was in the way");
  EXPECT_EQ(s.spawnBox(at, still), "nothing thrown: bodies in the way at the crosshair and above it");
  EXPECT_EQ(s.scene().world.bodies().size(), static_cast<std::size_t>(sandbox::kThrowTries));
  // A ragdoll needs more room: beside the boxes' column it goes where nothing reaches.
  ASSERT_EQ(s.spawnRagdoll(at + phys::Vec3(3.0, 0.0, 0.0), still), "");
  EXPECT_EQ(s.status(), "threw a ragdoll");
  // 1 m from both: it goes above them.
  ASSERT_EQ(s.spawnRagdoll(at + phys::Vec3(1.0, 0.0, 0.0), still), "");
  EXPECT_NE(s.status().find("m higher: a body was in the way"), std::string::npos) << s.status();
}

TEST(Session, ThrownCapsuleRagdollHasBulletsElevenCapsules) {
  sandbox::Session s = open("pyramid");
  const std::size_t boxes = s.scene().world.bodies().size();
  s.spawnRagdoll(phys::Vec3(-4, 3, 0), phys::Vec3(-sandbox::kThrowSpeed, 0, 0), true);
  const phys::World& w = s.scene().world;
  ASSERT_EQ(w.bodies().size(), boxes + 11);
  for (std::size_t i = boxes; i < w.bodies().size(); ++i)
    EXPECT_EQ(w.bodies()[i].shape, phys::Shape::Capsule);
  EXPECT_EQ(s.status(), "threw a capsule ragdoll");
  for (int i = 0; i < 240; ++i) s.step();
  EXPECT_EQ(w.metrics().frozen, 0);
  EXPECT_LT(w.bodyPose(static_cast<phys::BodyId>(boxes)).center.x, -4.0);  // flew towards -x
}

TEST(Session, ThrownBodiesTakeTheChosenModel) {
  sandbox::Session s = open("pyramid");
  const phys::World& w = s.scene().world;
  const std::size_t boxes = w.bodies().size(), particles = w.particles().size();
  s.setThrowModel(phys::BodyModel::Rigid);
  s.spawnBox(phys::Vec3(0, 3, 6), phys::Vec3(0, 0, -sandbox::kThrowSpeed));
  s.spawnRagdoll(phys::Vec3(4, 3, 0), phys::Vec3(sandbox::kThrowSpeed, 0, 0));
  s.spawnRagdoll(phys::Vec3(-4, 3, 0), phys::Vec3(-sandbox::kThrowSpeed, 0, 0), true);
  ASSERT_EQ(w.bodies().size(), boxes + 1 + 10 + 11);
  for (std::size_t i = boxes; i < w.bodies().size(); ++i)
    EXPECT_EQ(w.bodies()[i].model, phys::BodyModel::Rigid);
  EXPECT_EQ(w.particles().size(), particles);
  EXPECT_EQ(w.rigidJoints().size(), 9u + 10u);
  s.setThrowModel(phys::BodyModel::Tetra);
  s.spawnRagdoll(phys::Vec3(0, 3, -4), phys::Vec3(0, 0, sandbox::kThrowSpeed));
  EXPECT_EQ(w.particles().size(), particles + 40);  // a lean ragdoll
  for (int i = 0; i < 120; ++i) s.step();
  EXPECT_EQ(w.metrics().frozen, 0);
}

TEST(Session, PickingHitsTheBodyUnderTheRayAndTheSpringPullsIt) {
  sandbox::Session s = open("falling-box");
  for (int i = 0; i < 120; ++i) s.step();  // landed
  const phys::World& w = s.scene().world;
  const phys::Vec3 centre = w.bodyPose(phys::BodyId{0}).center;
  EXPECT_FALSE(s.pick(phys::Vec3(0, 10, 0), phys::Vec3(0, 1, 0)));  // straight up: nothing
  const phys::Vec3 eye = centre + phys::Vec3(0, 0, 5);
  const phys::Vec3 view = glm::normalize(centre - eye);
  const std::optional<phys::RayHit> hit = w.raycast(eye, view, 100.0);
  ASSERT_TRUE(hit.has_value());
  ASSERT_TRUE(s.pick(eye, view));
  ASSERT_TRUE(s.dragging());
  // Pull the cursor up 1 m: the ray through a point 1 m above the picked one.
  s.dragAlong(eye, glm::normalize(centre + phys::Vec3(0, 1, 0) - eye));
  for (int i = 0; i < 120; ++i) s.step();
  EXPECT_GT(w.bodyPose(phys::BodyId{0}).center.y, centre.y + 0.15);  // lifted off the ground
  const auto line = s.dragLine();
  ASSERT_TRUE(line.has_value());
  // An 8 kg box on the 2000 N/m spring hangs 4 cm below it, plus what is left of the swing.
  EXPECT_LT(glm::length(line->first - line->second), 0.1);
  // The target lies on the plane through the picked point facing the view, under the ray.
  EXPECT_NEAR(glm::dot(line->second - hit->point, view), 0.0, 1e-9);
  EXPECT_GT(line->second.y, hit->point.y + 0.5);
  s.release();
  EXPECT_FALSE(s.dragging());
  EXPECT_FALSE(w.drag().has_value());
}

// A rigid body is picked and pulled the same way (World::dragAt holds its point in its frame).
TEST(Session, PickingARigidBodyPullsItToo) {
  sandbox::Session s = open("rigid");
  const phys::World& w = s.scene().world;
  const phys::BodyId top{9};  // the stack's top box
  ASSERT_EQ(w.bodies()[top].name, "stack[9]");
  ASSERT_EQ(w.bodies()[top].model, phys::BodyModel::Rigid);
  for (int i = 0; i < 30; ++i) s.step();
  const phys::Vec3 centre = w.bodyPose(top).center;
  const phys::Vec3 eye = centre + phys::Vec3(0, 0, 5);
  ASSERT_TRUE(s.pick(eye, phys::Vec3(0, 0, -1)));
  ASSERT_TRUE(w.drag().has_value());
  EXPECT_EQ(w.drag()->body, top);
  s.dragAlong(eye, glm::normalize(centre + phys::Vec3(0, 1, 0) - eye));
  for (int i = 0; i < 120; ++i) s.step();
  EXPECT_GT(w.bodyPose(top).center.y, centre.y + 0.5);  // lifted off the stack
  const auto line = s.dragLine();
  ASSERT_TRUE(line.has_value());
  EXPECT_LT(glm::length(line->first - line->second), 0.1);  // 1 kg on 2000 N/m: 5 mm, and the swing
  s.release();
  EXPECT_FALSE(w.drag().has_value());
}

// An active ragdoll picked and pulled: a short pull at about the Animation block's push (200 N) makes
// it stagger and it stands again; a long hard one knocks it past its threshold, limp.
TEST(Session, DraggingAStandingCharacterStaggersItOrKnocksItOver) {
  const TempDir dir;
  std::ofstream(dir.path / "player.xml")
      << "<scene name=\"player\"><world gravity=\"0 -9.81 0\"/><solver method=\"xpbd\" iterations=\"2\" "
         "substeps=\"8\"/><ground/><ragdoll name=\"p\" pos=\"0 0.85 0\" euler=\"0 90 0\" model=\"rigid\"/>"
         "<character ragdoll=\"p\" clip=\""
      << (fs::path(DATA_DIR) / "assets" / "clips" / "stand.bvh").string()
      << "\" balance=\"0.2\" react=\"1.5\"/></scene>\n";
  const auto pull = [&](double how_far, int steps, double& moved, double& headLowest) {
    sandbox::Session s(dir.path / "player.xml", dir.path);
    const phys::World& w = s.scene().world;
    const phys::Character& c = w.characters()[0];
    for (int i = 0; i < 30; ++i) s.step();
    const phys::Vec3 torso = w.bodyPose(c.bones[0].body).center;
    const double head = w.bodyPose(c.bones[1].body).center.y;
    // From in front (it faces +x), at the torso, between the arms; pulled sideways.
    const phys::Vec3 eye = torso + phys::Vec3(4, 0, 0);
    EXPECT_TRUE(s.pick(eye, phys::Vec3(-1, 0, 0)));
    EXPECT_TRUE(w.drag().has_value() && w.drag()->body == c.bones[0].body);
    s.dragAlong(eye, glm::normalize(torso + phys::Vec3(0, 0, how_far) - eye));
    moved = 0.0, headLowest = head;
    for (int i = 0; i < 240; ++i) {
      if (i == steps) s.release();
      s.step();
      moved = std::max(moved, glm::length(w.bodyPose(c.bones[0].body).center - torso));
      headLowest = std::min(headLowest, w.bodyPose(c.bones[1].body).center.y);
    }
    headLowest = head - headLowest;
    return c.state;
  };
  double moved = 0.0, dropped = 0.0;
  // 0.1 m on the 2000 N/m spring: 200 N, for 0.2 s.
  EXPECT_EQ(pull(0.1, 12, moved, dropped), phys::CharacterState::Active);
  std::printf("a 0.1 m pull for 0.2 s: the torso moved up to %.3f m, the head dropped %.3f m\n", moved,
              dropped);
  EXPECT_GT(moved, 0.01);   // it staggered
  EXPECT_LT(dropped, 0.1);  // and stood
  // 2 m: 4000 N at first, for half a second. (1 m, 2000 N, knocks it over too, but its largest blow
  // is then 1.4 m/s, under the threshold: it passed it only while the balance turned the body the
  // drag had lifted off its feet, a torque from the world the balance no longer gives in the air.)
  EXPECT_NE(pull(2.0, 30, moved, dropped), phys::CharacterState::Active);
  std::printf("a 2 m pull for 0.5 s: the torso moved up to %.3f m, the head dropped %.3f m\n", moved,
              dropped);
  EXPECT_GT(dropped, 0.5);  // down
}

TEST(Session, TheOverlayRunsEachSettingFromTheSameStateAndRefusesBadCounts) {
  sandbox::Session s = open("chain");
  for (int i = 0; i < 10; ++i) s.step();
  auto spec = [](const char* text) { return sandbox::parseOverlaySpec(text).spec; };
  const std::vector<sandbox::OverlaySpec> one{spec("iterations=3")};
  EXPECT_EQ(s.startOverlay(one), "the overlay needs 2 to 4 settings, got 1");
  EXPECT_FALSE(s.overlayActive());
  const std::vector<sandbox::OverlaySpec> three{spec("iterations=3"), spec("substeps=8,iterations=1"),
                                                spec("method=xpbd")};
  ASSERT_EQ(s.startOverlay(three), "");
  ASSERT_EQ(s.runs().size(), 3u);
  for (const sandbox::Run& run : s.runs()) EXPECT_EQ(run.scene->world.stepCount(), 10);
  EXPECT_EQ(s.runs()[1].scene->world.solverSettings().substeps, 8);
  EXPECT_EQ(s.runs()[2].scene->world.solverSettings().method, phys::SolverMethod::Xpbd);
  EXPECT_EQ(s.runs()[0].label, "iterations=3");
  for (int i = 0; i < 60; ++i) s.step();
  // Same start, different methods: the chain's end parts ways.
  const auto end = [&](int run) {
    const phys::World& w = s.runs()[static_cast<std::size_t>(run)].scene->world;
    return w.particles().position.back();
  };
  EXPECT_GT(glm::length(end(0) - end(1)), 1e-3);
  for (const sandbox::Run& run : s.runs()) {
    EXPECT_GT(run.stepMs, 0.0);
    EXPECT_GT(run.medianMs(), 0.0);
  }
  // A restart applies each setting to the settings from before the overlay, not on top of
  // run 0's: run 2 is xpbd with the scene's own iteration count, not run 0's 3.
  const int sceneIterations = 1;  // chain.xml's
  ASSERT_EQ(s.startOverlay(three), "");
  EXPECT_EQ(s.runs()[2].scene->world.solverSettings().iterations, sceneIterations);
  s.stopOverlay();
  EXPECT_EQ(s.runs().size(), 1u);
  EXPECT_EQ(s.scene().world.solverSettings().iterations, sceneIterations);
  EXPECT_EQ(s.scene().world.solverSettings().substeps, 8);
}

// Starting the overlay once threw the recording away, and Stop started an empty one: minutes of
// history lost to a comparison. Run 0 is recorded through the overlay instead.
TEST(Session, TheOverlayKeepsTheRecordingAndRecordsRunZero) {
  sandbox::Session s = open("chain");
  std::map<long, std::uint64_t> hashes;  // the main run's state after each step
  auto stepAndKeep = [&](int steps) {
    for (int i = 0; i < steps; ++i) {
      s.step();
      hashes[s.scene().world.stepCount()] = s.scene().world.stateHash();
    }
  };
  stepAndKeep(20);
  auto spec = [](const char* text) { return sandbox::parseOverlaySpec(text).spec; };
  const std::vector<sandbox::OverlaySpec> specs{spec("iterations=4"), spec("method=xpbd")};
  ASSERT_EQ(s.startOverlay(specs), "");
  // A step's state is the one after a command at it: more iterations settle the chain at once.
  hashes[20] = s.scene().world.stateHash();
  stepAndKeep(20);                // run 0, under iterations=4
  EXPECT_NE(s.rewindTo(10), "");  // the other runs are not recorded: not while they run
  s.stopOverlay();
  hashes[40] = s.scene().world.stateHash();
  stepAndKeep(10);
  const sandbox::Recording& r = s.recording();
  EXPECT_EQ(r.first(), 0);
  EXPECT_EQ(r.last(), 50);
  for (const long step : {5L, 20L, 21L, 35L, 40L, 41L, 50L}) {
    ASSERT_EQ(s.rewindTo(step), "") << "step " << step;
    EXPECT_EQ(s.scene().world.stateHash(), hashes[step]) << "step " << step;
  }
  // A step of the overlay's shows run 0's setting; one after it, the setting from before.
  ASSERT_EQ(s.rewindTo(30), "");
  EXPECT_EQ(s.scene().world.solverSettings().iterations, 4);
  ASSERT_EQ(s.rewindTo(45), "");
  EXPECT_EQ(s.scene().world.solverSettings().iterations, 1);  // chain.xml's
}

TEST(Session, OverlayRunsWithAnotherDtKeepTheMainRunsClock) {
  sandbox::Session s = open("falling-box");
  auto spec = [](const char* text) { return sandbox::parseOverlaySpec(text).spec; };
  const std::vector<sandbox::OverlaySpec> specs{spec("dt=0.02"), spec("dt=0.005"), spec("dt=0.03")};
  ASSERT_EQ(s.startOverlay(specs), "");
  for (int i = 0; i < 30; ++i) s.step();
  const double now = s.runs()[0].scene->world.time();
  EXPECT_NEAR(now, 0.6, 1e-9);
  EXPECT_EQ(s.runs()[1].scene->world.stepCount(), 120);  // four steps for each of the main run's
  for (const sandbox::Run& run : s.runs()) {
    // Each within half its own step of the main run's time.
    EXPECT_LE(std::abs(run.scene->world.time() - now), 0.5 * run.scene->world.solverSettings().dt + 1e-9);
    EXPECT_EQ(run.behind(now), 0.0);
  }
}

// A run whose dt is under a thousandth of run 0's takes kMaxCatchUpSteps a step and falls behind;
// the legend shows by how much (its picture is of an earlier moment), rather than nothing.
TEST(Session, AnOverlayRunThatCannotKeepUpSaysHowFarBehindItIs) {
  sandbox::Session s = open("falling-box");
  auto spec = [](const char* text) { return sandbox::parseOverlaySpec(text).spec; };
  const std::vector<sandbox::OverlaySpec> specs{spec("dt=0.01"), spec("dt=0.000005")};
  ASSERT_EQ(s.startOverlay(specs), "");
  for (int i = 0; i < 3; ++i) s.step();
  const double now = s.runs()[0].scene->world.time();
  EXPECT_EQ(s.runs()[1].scene->world.stepCount(), 3 * sandbox::kMaxCatchUpSteps);
  EXPECT_NEAR(s.runs()[1].behind(now), 3 * (0.01 - sandbox::kMaxCatchUpSteps * 0.000005), 1e-9);
  EXPECT_EQ(s.runs()[0].behind(now), 0.0);
}

TEST(Session, StartingTheOverlayLetsGoOfADrag) {
  sandbox::Session s = open("falling-box");
  const phys::Vec3 centre = s.scene().world.bodyPose(phys::BodyId{0}).center;
  ASSERT_TRUE(s.pick(centre + phys::Vec3(0, 0, 5), phys::Vec3(0, 0, -1)));
  const std::vector<sandbox::OverlaySpec> specs{sandbox::parseOverlaySpec("iterations=2").spec,
                                                sandbox::parseOverlaySpec("iterations=4").spec};
  ASSERT_EQ(s.startOverlay(specs), "");
  EXPECT_FALSE(s.dragging());
  for (const sandbox::Run& run : s.runs()) EXPECT_FALSE(run.scene->world.drag().has_value());
  // And a ray that is no ray picks nothing rather than throwing.
  EXPECT_FALSE(s.pick(centre, phys::Vec3(0.0)));
  EXPECT_FALSE(s.pick(centre, phys::Vec3(std::nan(""), 0, 0)));
}

// Found by the soak test: a refused overlay let go of the drag before it refused.
TEST(Session, ARefusedOverlayChangesNothingNotEvenTheDrag) {
  sandbox::Session s = open("falling-box");
  for (int i = 0; i < 60; ++i) s.step();
  const phys::Vec3 centre = s.scene().world.bodyPose(phys::BodyId{0}).center;
  ASSERT_TRUE(s.pick(centre + phys::Vec3(0, 0, 5), phys::Vec3(0, 0, -1)));
  std::vector<sandbox::OverlaySpec> specs{sandbox::parseOverlaySpec("iterations=2").spec,
                                          sandbox::parseOverlaySpec("iterations=4").spec};
  specs[1].iterations = 0;  // the panel's parser would refuse it; the API must too
  EXPECT_NE(s.startOverlay(specs).find("overlay run 2 'iterations=4': SolverSettings: "), std::string::npos);
  EXPECT_FALSE(s.overlayActive());
  EXPECT_TRUE(s.dragging());
  EXPECT_TRUE(s.scene().world.drag().has_value());
}

// Found by the soak test: a throw from beyond about 1e15 m let addBody's exception out. Beyond the
// world's bound nothing is thrown, and whatever the world refuses is a message.
TEST(Session, AThrowFromBeyondTheWorldIsRefusedWithAMessage) {
  sandbox::Session s = open("falling-box");
  const std::size_t boxes = s.scene().world.bodies().size();
  const std::uint64_t before = s.scene().world.stateHash();
  EXPECT_NE(s.spawnBox(phys::Vec3(1e17, 1, 0), phys::Vec3(0, 0, -8)).find("beyond the world's bound"),
            std::string::npos);
  EXPECT_NE(
      s.spawnRagdoll(phys::Vec3(0, 2e6, 0), phys::Vec3(0, 0, -8), true).find("beyond the world's bound"),
      std::string::npos);
  EXPECT_EQ(s.status().rfind("nothing thrown: ", 0), 0u) << s.status();
  EXPECT_EQ(s.scene().world.bodies().size(), boxes);
  EXPECT_EQ(s.scene().world.stateHash(), before);
  EXPECT_EQ(s.spawnBox(phys::Vec3(0, 3, 0), phys::Vec3(0, 0, -8)), "");
  EXPECT_EQ(s.scene().world.bodies().size(), boxes + 1);
  EXPECT_EQ(s.scene().world.bodies().back().name, "thrown box 1");
}

TEST(Session, BadWorldSettingsAreRefusedWithTheReason) {
  sandbox::Session s = open("ragdoll");
  phys::WorldSettings w = s.scene().world.worldSettings();
  w.gravityPoint.x = std::numeric_limits<double>::infinity();
  EXPECT_EQ(s.setWorldSettings(w), "world settings: gravityPoint must be finite");
  EXPECT_TRUE(phys::finite(s.scene().world.worldSettings().gravityPoint));
}

TEST(Session, SaveAsWritesAWorldThatOpensAgainAndABadPathKeepsEverything) {
  const TempDir dir;
  sandbox::Session s = open("ragdoll");
  for (int i = 0; i < 30; ++i) s.step();
  const fs::path file = dir.path / "saved.xml";
  scenes::CameraStart camera;
  camera.eye = {1, 2, 3};
  ASSERT_EQ(s.saveAs(file, camera), "");
  EXPECT_EQ(s.file(), file);  // the saved file is the current one: Reload reads it
  const phys::Vec3 torso = s.scene().world.bodyPose(phys::BodyId{1}).center;
  ASSERT_EQ(s.reload(), "");
  EXPECT_NEAR(glm::length(s.scene().world.bodyPose(phys::BodyId{1}).center - torso), 0.0, 1e-3);
  EXPECT_EQ(s.scene().camera.eye, glm::vec3(1, 2, 3));

  // A folder that does not exist: the message says why, nothing is written, the file stays.
  const std::string error = s.saveAs(dir.path / "no such folder" / "x.xml", camera);
  EXPECT_NE(error.find("No such file or directory"), std::string::npos) << error;
  EXPECT_EQ(s.file(), file);
  // Over a file that cannot be replaced (a folder of that name): the old one is untouched.
  fs::create_directories(dir.path / "taken.xml" / "inside");
  EXPECT_NE(s.saveAs(dir.path / "taken.xml", camera), "");
  EXPECT_TRUE(fs::is_directory(dir.path / "taken.xml" / "inside"));
  for (const auto& entry : fs::directory_iterator(dir.path)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "saved.xml" || name == "taken.xml") << "left behind: " << name;
  }
}

}  // namespace

namespace {

TEST(Run, StepTimeIsTheMedianOfTheLastSecondOfSteps) {
  sandbox::Run run;
  EXPECT_EQ(run.medianMs(), 0.0);
  for (double ms : {5.0, 1.0, 3.0}) run.recentMs[static_cast<std::size_t>(run.timed++)] = ms;
  EXPECT_EQ(run.medianMs(), 3.0);
  // One slow step (a page fault, another process) does not move it.
  for (int i = 0; i < sandbox::Run::kTimedSteps; ++i) {
    run.recentMs[static_cast<std::size_t>(run.timed++ % sandbox::Run::kTimedSteps)] = i == 7 ? 50.0 : 0.2;
  }
  EXPECT_EQ(run.medianMs(), 0.2);
}

TEST(History, KeepsOneSampleASixtiethOfASecondForTenSeconds) {
  sandbox::History h;
  EXPECT_EQ(h.filled(), 0);
  h.add(1.0f, 0.5);  // half a second of frames at this value
  EXPECT_EQ(h.filled(), 30);
  EXPECT_EQ(h.last(), 1.0f);
  h.add(2.0f, 1.0 / 120.0);  // a fast frame: no sample yet
  EXPECT_EQ(h.filled(), 30);
  h.add(2.0f, 1.0 / 120.0);
  EXPECT_EQ(h.filled(), 31);
  EXPECT_EQ(h.last(), 2.0f);
  EXPECT_EQ(h.max(), 2.0f);
  h.add(3.0f, 60.0);  // a stall longer than the ring: it holds only that value
  EXPECT_EQ(h.filled(), sandbox::History::kSamples);
  EXPECT_EQ(h.max(), 3.0f);
  // The oldest sample is where PlotLines starts.
  EXPECT_GE(h.offset(), 0);
  EXPECT_LT(h.offset(), h.size());
}

}  // namespace

namespace {

// A setting longer than the panel's old 128-byte field was cut short and restarted as another.
TEST(Remembered, ALongOverlaySettingComesIntoThePanelWhole) {
  const std::string longSpec = "iterations=2,compliance=0.00012345" + std::string(280, '0');
  const auto parsed = sandbox::parseOptions({"--overlay", "iterations=3", longSpec});
  ASSERT_EQ(parsed.error, "");
  sandbox::UiState ui;
  sandbox::applyRemembered(sandbox::UserSettings{}, parsed.options, ui);
  EXPECT_EQ(ui.overlayText[1], longSpec);
}

// The Lab section's close button hid it for good: the View menu and Reset layout knew five sections.
TEST(Remembered, ResetLayoutShowsEverySectionTheLabToo) {
  sandbox::UiState ui;
  for (bool* shown : sandbox::sectionsShown(ui)) *shown = false;
  ui.panelsHidden = true;
  ui.unfolded = {};
  sandbox::resetLayout(ui);
  EXPECT_TRUE(ui.showLab);
  for (bool* shown : sandbox::sectionsShown(ui)) EXPECT_TRUE(*shown);
  EXPECT_FALSE(ui.panelsHidden);
  EXPECT_EQ(ui.unfolded, sandbox::kDefaultUnfolded);
  EXPECT_TRUE(ui.resetLayout);
}

// What the sandbox remembers between runs goes into the panels, and back out.
TEST(Remembered, PanelsAndDrawModeComeBackAndTheCommandLineWins) {
  sandbox::UserSettings user;
  user.showStats = false;
  user.drawMode = "constraints";
  user.markers = true;
  sandbox::UiState ui;
  sandbox::applyRemembered(user, sandbox::Options{}, ui);
  EXPECT_FALSE(ui.showStats);
  EXPECT_TRUE(ui.showSimulation);
  EXPECT_EQ(ui.draw.mode, sandbox::DrawMode::Constraints);
  EXPECT_TRUE(ui.draw.markers);
  EXPECT_EQ(ui.overlayText[0], "iterations=3");  // an example to start from

  const auto parsed =
      sandbox::parseOptions({"--draw", "wireframe", "--overlay", "method=xpbd", "iterations=9"});
  ASSERT_EQ(parsed.error, "");
  sandbox::applyRemembered(user, parsed.options, ui);
  EXPECT_EQ(ui.draw.mode, sandbox::DrawMode::Wireframe);
  // The command line's overlay, and no example after it: Restart runs what was started.
  EXPECT_EQ(ui.overlayText[0], "method=xpbd");
  EXPECT_EQ(ui.overlayText[1], "iterations=9");
  EXPECT_EQ(ui.overlayText[2], "");
  EXPECT_EQ(ui.overlayText[3], "");

  ui.showWorld = false;
  ui.draw.mode = sandbox::DrawMode::Filled;
  sandbox::UserSettings next;
  sandbox::remember(ui, next);
  EXPECT_FALSE(next.showWorld);
  EXPECT_FALSE(next.showStats);
  EXPECT_EQ(next.drawMode, "filled");
  EXPECT_TRUE(next.markers);
}

// The Rewind and Lab sections, the colouring, the throw speed and the recording's budget too; the
// panels' own defaults until a run has remembered them, and --color-by wins.
TEST(Remembered, SectionsColouringThrowSpeedAndBudget) {
  sandbox::UiState fresh;
  sandbox::applyRemembered(sandbox::UserSettings{}, sandbox::Options{}, fresh);
  EXPECT_EQ(fresh.draw.coloring, sandbox::BodyColoring::Body);
  EXPECT_EQ(fresh.throwSpeed, static_cast<float>(sandbox::kThrowSpeed));
  EXPECT_EQ(fresh.recordingBudgetMb, static_cast<int>(sandbox::kDefaultRecordingBudget >> 20));

  fresh.showRewind = false;
  fresh.draw.coloring = sandbox::BodyColoring::Sleep;
  fresh.throwSpeed = 3.0f;
  fresh.recordingBudgetMb = 100;
  sandbox::UserSettings user;
  sandbox::remember(fresh, user);
  sandbox::UiState next;
  sandbox::applyRemembered(user, sandbox::Options{}, next);
  EXPECT_FALSE(next.showRewind);
  EXPECT_TRUE(next.showLab);
  EXPECT_EQ(next.draw.coloring, sandbox::BodyColoring::Sleep);
  EXPECT_EQ(next.throwSpeed, 3.0f);
  EXPECT_EQ(next.recordingBudgetMb, 100);

  const auto parsed = sandbox::parseOptions({"--color-by", "kind"});
  ASSERT_EQ(parsed.error, "");
  sandbox::applyRemembered(user, parsed.options, next);
  EXPECT_EQ(next.draw.coloring, sandbox::BodyColoring::Kind);
}

// A section the last run hid (its close button) is shown when the command line unfolds it, or
// starts the Lab's sweep: `--sweep` swept behind a Lab section the user had closed, out of sight.
TEST(Remembered, ASectionTheCommandLineUnfoldsIsShown) {
  sandbox::UserSettings user;
  user.showWorld = user.showLab = user.showStats = false;
  const auto parsed = sandbox::parseOptions({"--unfold", "world,draw", "--sweep"});
  ASSERT_EQ(parsed.error, "");
  sandbox::UiState ui;
  sandbox::applyRemembered(user, parsed.options, ui);
  EXPECT_TRUE(ui.showWorld);
  EXPECT_TRUE(ui.unfolded[2]);
  EXPECT_TRUE(ui.showLab);
  EXPECT_TRUE(ui.unfolded[5]);
  EXPECT_FALSE(ui.showStats);  // not named: as the last run left it
  EXPECT_FALSE(ui.unfolded[4]);

  sandbox::UiState sweeping;
  sandbox::applyRemembered(user, sandbox::parseOptions({"--sweep"}).options, sweeping);
  EXPECT_TRUE(sweeping.showLab);
  EXPECT_TRUE(sweeping.unfolded[5]);
  EXPECT_FALSE(sweeping.showWorld);
  EXPECT_TRUE(sweeping.unfolded[0]);  // the other sections as they start
}

}  // namespace

namespace {

// Under a gravity of -1.8e308 m/s^2 the energies overflow before the first step (m g . x over
// bodies above and below the origin is inf - inf): the Stats panel said "energy nan J". Found
// by the soak test.
TEST(StatsText, AFigureThatOverflowsReadsOverflow) {
  EXPECT_EQ(sandbox::figure("%.3f", 1.5), "1.500");
  EXPECT_EQ(sandbox::figure("%.3f", std::numeric_limits<double>::quiet_NaN()), "overflow");
  EXPECT_EQ(sandbox::figure("%.2e", -std::numeric_limits<double>::infinity()), "overflow");

  sandbox::Session s = open("ragdoll");
  phys::WorldSettings w = s.scene().world.worldSettings();
  w.gravityMode = phys::GravityMode::Uniform;
  w.gravity = phys::Vec3(0.0, -std::numeric_limits<double>::max(), 0.0);
  w.ground = false;
  phys::World& world = s.scene().world;
  world.setWorldSettings(w);
  world.addParticle({.position = phys::Vec3(0.0, -1.0, 0.0), .name = "below"});
  ASSERT_TRUE(std::isnan(world.metrics().energy()));  // what the panel must not print
  bool sawEnergy = false;
  for (const sandbox::StatsLine& line : sandbox::statsLines(world)) {
    EXPECT_EQ(line.text.find("nan"), std::string::npos) << line.text;
    EXPECT_EQ(line.text.find("inf"), std::string::npos) << line.text;
    if (line.text.rfind("energy ", 0) == 0) {
      sawEnergy = true;
      EXPECT_NE(line.text.find("energy overflow J"), std::string::npos) << line.text;
    }
  }
  EXPECT_TRUE(sawEnergy);
}

}  // namespace

namespace {

// The sandbox sleeps unless the scene says otherwise (the lab does not: LabRun.SleepsOnlyWhenAsked):
// the stack comes to rest, falls asleep and says so in Stats; the checkbox turned off wakes it.
TEST(SessionSleep, TheStackFallsAsleepAndStatsSaysSo) {
  sandbox::Session s = open("stack");
  const phys::World& world = s.scene().world;
  ASSERT_TRUE(world.solverSettings().sleep.enabled);
  for (int i = 0; i < 600 && world.islands().awakeBodies() > 0; ++i) s.step();
  ASSERT_EQ(world.islands().sleepingBodies(), world.bodies().size()) << "t = " << world.time();
  bool said = false;
  for (const sandbox::StatsLine& line : sandbox::statsLines(world)) {
    said = said || line.text == "1 island (1 asleep), bodies 0 awake, " +
                                    std::to_string(world.bodies().size()) + " asleep";
  }
  EXPECT_TRUE(said);
  EXPECT_EQ(sandbox::bodyColor(world, phys::BodyId(0), sandbox::BodyColoring::Sleep),
            sandbox::kSleepingColor);
  EXPECT_EQ(sandbox::bodyColor(world, phys::BodyId(0), sandbox::BodyColoring::Kind), sandbox::kBoxColor);
  phys::SolverSettings off = world.solverSettings();
  off.sleep.enabled = false;
  EXPECT_EQ(s.setSolverSettings(off), "");
  EXPECT_EQ(world.islands().sleepingBodies(), 0u);
  EXPECT_EQ(sandbox::bodyColor(world, phys::BodyId(0), sandbox::BodyColoring::Sleep), sandbox::kBoxColor);
}

// Colour by island: the bodies of one island share a colour, and islands' colours differ and
// differ from the sleeping colour, so that neither reading is ambiguous.
// "Every body is the same orange": by body, each ragdoll is one colour (its parts share a joint
// group) and ragdolls next to each other differ; loose boxes each have their own.
TEST(BodyColours, EachRagdollAndEachBoxHasAColourOfItsOwn) {
  sandbox::Session s = open("ragdolls");
  const phys::World& world = s.scene().world;
  const std::vector<std::uint32_t> groups = sandbox::jointGroups(world);
  ASSERT_EQ(groups.size(), 160u);
  for (std::size_t i = 0; i < groups.size(); ++i)
    EXPECT_EQ(groups[i], i / 10) << "body " << i;  // 16 ragdolls
  for (phys::BodyId id{}; id + 10 < world.bodies().size(); ++id) {
    EXPECT_NE(sandbox::bodyColor(world, id, sandbox::BodyColoring::Body),
              sandbox::bodyColor(world, phys::BodyId(id + 10), sandbox::BodyColoring::Body));
  }
  EXPECT_EQ(sandbox::bodyColor(world, phys::BodyId(0), sandbox::BodyColoring::Body, groups),
            sandbox::kBoxColor);
  sandbox::Session p = open("pyramid");
  const std::vector<std::uint32_t> boxes = sandbox::jointGroups(p.scene().world);
  for (std::size_t i = 0; i < boxes.size(); ++i) EXPECT_EQ(boxes[i], i);
  EXPECT_NE(sandbox::paletteColor(0), sandbox::paletteColor(1));
  EXPECT_EQ(sandbox::paletteColor(10), sandbox::paletteColor(0));
}

TEST(SessionSleep, EachIslandHasAColourOfItsOwn) {
  sandbox::Session s = open("box-models");
  phys::World& world = s.scene().world;
  for (int i = 0; i < 30; ++i) s.step();
  const auto island = world.islands().bodyIsland();
  ASSERT_GE(world.islands().islandCount(), 2u);
  for (phys::BodyId a{}; a < world.bodies().size(); ++a) {
    for (phys::BodyId b{}; b < world.bodies().size(); ++b) {
      const glm::vec3 ca = sandbox::bodyColor(world, a, sandbox::BodyColoring::Island);
      const glm::vec3 cb = sandbox::bodyColor(world, b, sandbox::BodyColoring::Island);
      if (island[a] == island[b])
        EXPECT_EQ(ca, cb);
      else
        EXPECT_GT(glm::length(ca - cb), 0.1f) << "islands " << island[a] << " and " << island[b];
    }
    EXPECT_GT(
        glm::length(sandbox::bodyColor(world, a, sandbox::BodyColoring::Island) - sandbox::kSleepingColor),
        0.1f);
  }
}

}  // namespace

namespace {

// The real-time factor over the last second of frames: 1 when each frame steps its own time, a
// quarter when the steps of a frame take four frames' time, and nothing while paused.
TEST(RealTimeMeter, SimulatedSecondsPerWallSecondOverTheLastSecond) {
  sandbox::RealTimeMeter meter;
  EXPECT_FALSE(meter.factor());
  for (int i = 0; i < 120; ++i) meter.add(1.0 / 60.0, 1.0 / 60.0, true);
  ASSERT_TRUE(meter.factor());
  EXPECT_NEAR(*meter.factor(), 1.0, 1e-12);
  EXPECT_FALSE(meter.fallingBehind(1.0));
  // Slow frames: 8 steps of 1/60 s each frame, each frame a whole second of wall time.
  meter.add(8.0 / 60.0, 1.0, true);
  EXPECT_NEAR(*meter.factor(), 8.0 / 60.0, 1e-12);  // the last second is that one frame
  EXPECT_TRUE(meter.fallingBehind(1.0));
  EXPECT_TRUE(meter.fallingBehind(0.5));
  EXPECT_FALSE(meter.fallingBehind(0.1));  // slower than real time by choice: not behind
  meter.add(0.0, 1.0 / 60.0, false);
  EXPECT_FALSE(meter.factor());
}

}  // namespace

namespace {

// The World panel's drive strength: every rigid and particle joint of every run takes it, each
// keeping its own stiffness and target, and so does every character; a bad strength, or a scene
// without joints with drives, changes nothing and says why.
TEST(Session, DriveStrengthReachesEveryRigidJointAndBadOnesAreRefused) {
  sandbox::Session s = open("rigid-ragdolls");
  const phys::World& world = s.scene().world;
  ASSERT_EQ(world.rigidJoints().size(), 19u);  // a box ragdoll's 9 and a capsule ragdoll's 10
  const phys::Quat target = world.jointDrive(3).target;
  const double stiffness = world.jointDrive(3).stiffness;
  EXPECT_EQ(s.setDriveStrength(0.8), "");
  for (std::size_t k = 0; k < world.rigidJoints().size(); ++k) EXPECT_EQ(world.jointDrive(k).strength, 0.8);
  EXPECT_EQ(world.jointDrive(3).stiffness, stiffness);
  EXPECT_EQ(world.jointDrive(3).target, target);
  EXPECT_EQ(s.setDriveStrength(1.5), "drives: strength must be from 0 to 1");
  EXPECT_EQ(s.setDriveStrength(std::nan("")), "drives: strength must be from 0 to 1");
  EXPECT_EQ(world.jointDrive(0).strength, 0.8);
  // A particle ragdoll's joints take it through their particle joints.
  sandbox::Session lean = open("run-cycle-lean");
  ASSERT_EQ(lean.scene().world.particleJoints().size(), 9u);
  EXPECT_EQ(lean.setDriveStrength(0.3), "");
  for (std::size_t k = 0; k < 9; ++k) EXPECT_EQ(lean.scene().world.particleJointDrive(k).strength, 0.3);
  // Its character takes it too (a character sets its joints' drives every substep from its own
  // strength), so the joints keep it through a step.
  ASSERT_EQ(lean.scene().world.characters().size(), 1u);
  EXPECT_EQ(lean.scene().world.characters()[0].strength, 0.3);
  lean.step();
  for (std::size_t k = 0; k < 9; ++k)
    EXPECT_NEAR(lean.scene().world.particleJointDrive(k).strength, 0.3, 1e-12);
  sandbox::Session pyramid = open("pyramid");
  EXPECT_EQ(pyramid.setDriveStrength(0.5),
            "drives: the scene has no joints with drives (rigid joints, or particle joints of ragdolls)");
}

// The Animation block: a character's strength, balance and threshold reach the world, a bad value
// changes nothing and says why, and the shoves push its root part the way it faces.
TEST(Session, CharacterControlsReachTheWorldAndBadOnesAreRefused) {
  sandbox::Session s = open("line-up");
  const phys::World& world = s.scene().world;
  ASSERT_EQ(world.characters().size(), 5u);
  EXPECT_EQ(s.setCharacterStrength(1, 0.6), "");
  EXPECT_EQ(world.characters()[1].strength, 0.6);
  EXPECT_EQ(s.setCharacterBalance(1, 0.3), "");
  EXPECT_EQ(world.characters()[1].goalBalance, 0.3);
  EXPECT_EQ(s.setReactionThreshold(1, 4.0), "");
  EXPECT_EQ(world.characters()[1].reaction.threshold, 4.0);
  EXPECT_NE(s.setReactionThreshold(1, -1.0), "");
  EXPECT_NE(s.setCharacterBalance(1, 2.0), "");
  EXPECT_NE(s.setCharacterStrength(9, 0.5), "");
  EXPECT_EQ(world.characters()[1].reaction.threshold, 4.0);
  EXPECT_EQ(world.characters()[1].goalBalance, 0.3);
  EXPECT_EQ(s.setPartStrength(1, "lower-arm-left", 0.2), "");
  EXPECT_EQ(world.characters()[1].partStrength[3], 0.2);  // the box skeleton's fourth bone
  EXPECT_NE(s.setPartStrength(1, "torso", 0.2), "");
  EXPECT_EQ(s.pushCharacter(2, sandbox::kPushForce), "");
  ASSERT_EQ(world.pushes().size(), 1u);
  EXPECT_EQ(world.pushes()[0].body, world.characters()[2].bones[0].body);
  // line-up.xml's players face +x (euler 0 90 0)
  EXPECT_NEAR(world.pushes()[0].force.x, sandbox::kPushForce, 1e-9);
  EXPECT_NEAR(world.pushes()[0].remaining, sandbox::kPushTime, 1e-12);
}

// A push goes the way the player faces now, not the way its clip's path was laid (its clip frame):
// turned away from the frame (limp, fallen, dragged round, or on a clip that turns) it was pushed
// along the frame, sideways or from behind. Here the frame is turned to +z under a player that still
// faces +x, and the push goes along +x; tipped onto its back it still goes along +x.
TEST(Session, APushGoesTheWayThePlayerFacesNotItsClipFrame) {
  sandbox::Session s = open("line-up");
  phys::World& world = s.scene().world;
  phys::CharacterMotion m = world.characterMotion(2);
  m.frame = phys::Quat(1.0, 0.0, 0.0, 0.0);  // the clip's path along +z
  world.setCharacterMotion(2, m);
  EXPECT_EQ(s.pushCharacter(2, sandbox::kPushForce), "");
  ASSERT_EQ(world.pushes().size(), 1u);
  EXPECT_NEAR(world.pushes()[0].force.x, sandbox::kPushForce, 1e-9);
  EXPECT_NEAR(world.pushes()[0].force.z, 0.0, 1e-9);
  // Lying on its back, face up: its forward points at the sky, its heading still along +x.
  const phys::Quat lying = glm::angleAxis(glm::radians(90.0), phys::Vec3(0.0, 1.0, 0.0)) *
                           glm::angleAxis(glm::radians(-90.0), phys::Vec3(1.0, 0.0, 0.0));
  const phys::Vec3 forward = phys::facing(world, 2);
  EXPECT_NEAR(forward.x, 1.0, 1e-9);
  phys::Motion motion = world.motion();  // the world has not stepped: its motion can be given back
  motion.rigidOrientation[world.bodies()[world.characters()[2].bones[0].body].rigid] = lying;
  world.setMotion(motion);
  const phys::Vec3 up =
      world.bodyPose(world.characters()[2].bones[0].body).orientation * phys::Vec3(0.0, 0.0, 1.0);
  ASSERT_GT(up.y, 0.99);  // face up
  EXPECT_NEAR(phys::facing(world, 2).x, 1.0, 1e-9);
}

// The Animation block's clip controls: a clip chosen from a file fades in from its start; the scrub
// cuts to a time on the clip playing; a file that is no clip, or whose bones are not the
// character's, is refused with the file named and the clip kept.
TEST(Session, CharacterClipsAreChosenFromFilesAndScrubbed) {
  sandbox::Session s = open("line-up");
  const phys::World& world = s.scene().world;
  const std::filesystem::path clips = std::filesystem::path(DATA_DIR) / "assets" / "clips";
  EXPECT_EQ(s.playCharacterClip(0, clips / "run.bvh", true), "");
  const phys::Character& c = world.characters()[0];
  EXPECT_EQ(std::filesystem::path(c.now.clip->name).filename(), "run.bvh");
  EXPECT_EQ(c.now.time, 0.0);
  EXPECT_TRUE(c.now.loop);
  EXPECT_EQ(c.blendTime, sandbox::kClipBlendTime);
  EXPECT_EQ(std::filesystem::path(c.before.clip->name).filename(), "stand.bvh");
  phys::Playback scrubbed = c.now;
  scrubbed.time = 0.5;
  EXPECT_EQ(s.setCharacterPlayback(0, scrubbed, 0.0), "");
  EXPECT_EQ(c.now.time, 0.5);
  EXPECT_EQ(c.blend, 1.0);  // a cut
  const std::string missing = s.playCharacterClip(0, clips / "nonexistent.bvh", true);
  EXPECT_NE(missing.find("nonexistent.bvh"), std::string::npos) << missing;
  EXPECT_NE(missing.find("No such file or directory"), std::string::npos) << missing;
  scrubbed.time = 2e9;  // beyond any clip's clock
  EXPECT_NE(s.setCharacterPlayback(0, scrubbed, 0.0), "");
  EXPECT_EQ(std::filesystem::path(c.now.clip->name).filename(), "run.bvh");
  EXPECT_EQ(c.now.time, 0.5);
}

// Save As during the overlay wrote run 0's overlay setting, and the saved file, now the current
// one, reloaded with it without a word.
TEST(Session, SaveAsDuringTheOverlayWritesTheSettingsFromBeforeIt) {
  const TempDir dir;
  sandbox::Session s = open("chain");
  const int sceneIterations = s.scene().world.solverSettings().iterations;
  ASSERT_NE(sceneIterations, 7);
  for (int i = 0; i < 10; ++i) s.step();
  const std::vector<sandbox::OverlaySpec> specs{sandbox::parseOverlaySpec("iterations=7").spec,
                                                sandbox::parseOverlaySpec("method=xpbd").spec};
  ASSERT_EQ(s.startOverlay(specs), "");
  for (int i = 0; i < 10; ++i) s.step();
  const fs::path file = dir.path / "during-overlay.xml";
  ASSERT_EQ(s.saveAs(file, scenes::CameraStart{}), "");
  EXPECT_EQ(s.scene().world.solverSettings().iterations, 7);  // the overlay runs on
  s.stopOverlay();
  ASSERT_EQ(s.reload(), "");
  EXPECT_EQ(s.scene().world.solverSettings().iterations, sceneIterations);
}

}  // namespace
