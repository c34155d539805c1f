// The comparison the fuzzer and the round-trip tests rely on: silent on a faithful round trip,
// and naming the body and the quantity when the reloaded world is not the saved one.
#include <gtest/gtest.h>

#include <string>

#include "scenes/scene.h"
#include "scenes/scene_writer.h"
#include "world_compare.h"

namespace {

const char* const kScene = R"(<scene name="t">
  <ground/>
  <box name="crate" pos="0 2 0" euler="10 20 30" velocity="1 0 0" angular-velocity="0 90 0"/>
  <capsule name="log" pos="2 1 0" radius="0.2" length="1" model="tetra"/>
  <particle name="p" pos="-1 3 0"/>
  <particle name="q" pos="-1 4 0" pinned="true"/>
  <stick a="p" b="q"/>
  <link a="crate" b="log" a-point="0.5 2 0" b-point="1.8 1 0" max="2"/>
  <no-collision a="crate" b="log"/>
</scene>)";

scenes::Scene reload(const scenes::Scene& scene) {
  return scenes::loadSceneText(scenes::writeSceneXml(scene), "saved.xml");
}

TEST(WorldCompare, AFaithfulRoundTripHasNoDifference) {
  scenes::Scene scene = scenes::loadSceneText(kScene, "t.xml");
  EXPECT_EQ(testsupport::compareScenes(scene, reload(scene)), "");
  for (int i = 0; i < 5; ++i) scene.world.step();
  EXPECT_EQ(testsupport::compareScenes(scene, reload(scene)), "");
}

TEST(WorldCompare, AMovedWorldIsReportedByBodyAndQuantity) {
  const scenes::Scene scene = scenes::loadSceneText(kScene, "t.xml");
  scenes::Scene moved = reload(scene);
  moved.world.step();
  const std::string difference = testsupport::compareScenes(scene, moved);
  // The first body in the world's order: the box, by index and name, then what differs.
  EXPECT_NE(difference.find("box #0 'crate': centre"), std::string::npos) << difference;
  EXPECT_NE(difference.find("> tolerance"), std::string::npos) << difference;
}

TEST(WorldCompare, ASettingIsComparedExactly) {
  const scenes::Scene scene = scenes::loadSceneText(kScene, "t.xml");
  scenes::Scene other = reload(scene);
  phys::SolverSettings solver = other.world.solverSettings();
  solver.iterations += 1;
  other.world.setSolverSettings(solver);
  EXPECT_EQ(testsupport::compareScenes(scene, other), "<solver> iterations: saved 3, reloaded 4");
}

TEST(WorldCompare, ALostNameIsReported) {
  const scenes::Scene scene = scenes::loadSceneText(kScene, "t.xml");
  scenes::Scene other = reload(scene);
  other.bodies.erase(other.bodies.begin());
  EXPECT_EQ(testsupport::compareScenes(scene, other), "the name 'crate' (box #0) is lost");
}

}  // namespace
