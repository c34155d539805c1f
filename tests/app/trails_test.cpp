// Draw > trails: one point per step of each loose particle and of the followed body, the last
// kTrailPoints of them; going back in time keeps the path up to the step shown, and a jump forward
// is not joined.
#include <algorithm>
#include <filesystem>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "project_session.h"
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

std::size_t linesOf(const sandbox::Trails& t, std::size_t path) {
  std::size_t n = 0;
  t.forEachLine(path, [&n](const glm::vec3&, const glm::vec3&, float) { ++n; });
  return n;
}

float longestLineOf(const sandbox::Trails& t, std::size_t path) {
  float longest = 0.0f;
  t.forEachLine(path, [&longest](const glm::vec3& a, const glm::vec3& b, float) {
    longest = std::max(longest, glm::length(b - a));
  });
  return longest;
}

// A trail is the path the body took. Scrubbing the timeline forward from step 20 to 80 drew a
// straight line from the bob at 20 to the bob at 80, through where it never went; the jump now
// leaves the two unjoined. Going back (B, the timeline) keeps the path up to the step shown, where
// it started the trail over. Steps a frame of the clock or of Play takes at once are joined.
TEST(Trails, AJumpOnTheTimelineIsNotJoinedAndGoingBackKeepsThePathTaken) {
  sandbox::Session s = testing_app::openSession("pendulum");
  sandbox::Trails t;
  auto show = [&](long step) {
    ASSERT_EQ(s.rewindTo(step), "");
    t.record(s.scene().world, std::nullopt);
  };
  for (int i = 0; i < 100; ++i) {
    s.step();
    t.record(s.scene().world, std::nullopt);
  }
  constexpr std::size_t kBob = 1;
  ASSERT_EQ(linesOf(t, kBob), 99u);
  const float perStep = longestLineOf(t, kBob);

  show(20);
  EXPECT_EQ(t.pointCount(kBob), 20u);  // steps 1 to 20, as they were drawn
  EXPECT_EQ(linesOf(t, kBob), 19u);

  show(80);  // the timeline dragged forward: a jump
  EXPECT_EQ(t.pointCount(kBob), 21u);
  EXPECT_EQ(linesOf(t, kBob), 19u);
  EXPECT_LE(longestLineOf(t, kBob), perStep);

  show(80 + sandbox::kMaxStepsPerFrame);  // Play's most in one frame: the path, at the frame's grain
  EXPECT_EQ(linesOf(t, kBob), 20u);
  show(84);  // back, past none of the first piece: it stays; 84 joins 80
  EXPECT_EQ(t.pointCount(kBob), 22u);
  EXPECT_EQ(linesOf(t, kBob), 20u);
  show(10);
  EXPECT_EQ(t.pointCount(kBob), 10u);
  EXPECT_EQ(linesOf(t, kBob), 9u);
}

}  // namespace
