// Draw > trails: one point per step of each loose particle and of the followed body, the last
// kTrailPoints of them, started over when the world goes back in time.
#include <filesystem>

#include <gtest/gtest.h>

#include "scenes/scene.h"
#include "trails.h"

namespace {

scenes::Scene open(const char* name) {
  return scenes::loadSceneFile(scenes::resolveScene(name, scenes::sceneDirectory(DATA_DIR)));
}

TEST(Trails, OnePointPerStepOfEachLooseParticle) {
  scenes::Scene s = open("pendulum");  // a pinned pivot and a bob: two loose particles
  sandbox::Trails t;
  t.record(s.world, std::nullopt);
  t.record(s.world, std::nullopt);  // the same step again: nothing added
  ASSERT_EQ(t.pathCount(), 2u);
  EXPECT_EQ(t.pointCount(1), 1u);
  for (int i = 0; i < 700; ++i) {
    s.world.step();
    t.record(s.world, std::nullopt);
  }
  EXPECT_EQ(t.pointCount(1), sandbox::kTrailPoints);
  EXPECT_EQ(t.pointCount(0), sandbox::kTrailPoints);  // the pivot's, pinned: all one point
}

TEST(Trails, TheFollowedBodyHasOneAndGoingBackStartsOver) {
  scenes::Scene s = open("ragdoll");
  sandbox::Trails t;
  for (int i = 0; i < 10; ++i) {
    s.world.step();
    t.record(s.world, phys::BodyId(0));
  }
  ASSERT_EQ(t.pathCount(), 1u);  // no loose particles: the followed body's path alone
  EXPECT_EQ(t.pointCount(0), 10u);
  scenes::Scene again = open("ragdoll");
  again.world.step();
  t.record(again.world, phys::BodyId(0));  // step 1 after step 10: a new world
  EXPECT_EQ(t.pointCount(0), 1u);
  t.record(again.world, std::nullopt);  // following stopped
  EXPECT_EQ(t.pathCount(), 0u);
}

}  // namespace
