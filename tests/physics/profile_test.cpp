// The step's profile: each stage's time under its own name, and only the stages a world needs
// are timed at all (a stage with nothing to do reads exactly 0).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_util.h"

namespace {

using phys::Stage;
using phys::Vec3;

std::vector<Stage> allStages() {
  std::vector<Stage> stages;
  for (std::size_t i = 0; i < phys::kStageCount; ++i) stages.push_back(static_cast<Stage>(i));
  return stages;
}

// The profiles of `steps` steps summed: a clock that ticks in nanoseconds shows every stage that
// ran in one step, but ten make sure of it.
phys::Profile profileOf(phys::World& world, int steps) {
  phys::Profile sum;
  for (int i = 0; i < steps; ++i) {
    world.step();
    sum += world.profile();
  }
  return sum;
}

TEST(Profile, EveryStageHasItsOwnName) {
  std::vector<std::string> names;
  for (const Stage s : allStages()) {
    const std::string name(phys::toString(s));
    EXPECT_FALSE(name.empty());
    for (const std::string& other : names) EXPECT_NE(name, other);
    names.push_back(name);
  }
  EXPECT_EQ(phys::toString(Stage::Integrate), "integrate");
  EXPECT_EQ(phys::toString(Stage::BroadPhase), "broad-phase");
  EXPECT_EQ(phys::toString(Stage::Guard), "guard");
  EXPECT_EQ(phys::toString(Stage::Islands), "islands");
}

TEST(Profile, SumsAddStageByStage) {
  phys::Profile a, b;
  for (std::size_t i = 0; i < phys::kStageCount; ++i) {
    a.stage[i] = static_cast<double>(i);
    b.stage[i] = 100.0 * static_cast<double>(i);
  }
  a.total = 1.0;
  b.total = 2.0;
  a += b;
  EXPECT_EQ(a[Stage::Links], 808.0);
  EXPECT_EQ(a.total, 3.0);
  EXPECT_EQ(a.staged(), 101.0 * 120.0);  // 0 + 1 + ... + 15 = 120
}

// A pendulum, two particles and a stick in empty space: no bodies, contacts, restitution or body
// damping, so those stages are not timed at all; its stick is.
TEST(Profile, AWorldOfParticlesTimesOnlyItsStages) {
  phys::World world = testing_phys::openSpace();
  const phys::ParticleId pin = world.addParticle({Vec3(0.0), Vec3(0.0), 0.0, true});
  const phys::ParticleId bob = world.addParticle({Vec3(1.0, 0.0, 0.0)});
  world.addStick(pin, bob);
  const phys::Profile p = profileOf(world, 10);
  for (const Stage s : {Stage::Animate, Stage::Frames, Stage::BroadPhase, Stage::Sweep, Stage::NarrowPhase,
                        Stage::Parting, Stage::Links, Stage::Contacts, Stage::Friction, Stage::Velocities,
                        Stage::Restitution, Stage::BodyDamping,
                        Stage::Islands}) {  // sleeping off: the step leaves the islands to World::islands()
    EXPECT_EQ(p[s], 0.0) << phys::toString(s);
  }
  EXPECT_GT(p[Stage::Sticks], 0.0);
  EXPECT_LE(p.staged(), p.total);
}

// Two boxes, one on the other, on the ground, bouncy, damped and allowed to sleep: every stage but
// the links has work, and the two boxes' broad and narrow phases are timed. (Ten steps: they do
// not rest long enough to fall asleep, after which no stage would be timed.)
// Two unit boxes, one on the other (the top one `offset` m along x), bouncing a little and damped.
phys::World stackOfTwo(bool sleep, double offset) {
  phys::SolverSettings solver;
  solver.restitution = 0.5;
  solver.bodyDamping = 0.1;
  solver.sleep.enabled = sleep;
  phys::World world(phys::WorldSettings{}, solver);
  phys::BodyDesc box;
  box.center = {0.0, 0.5, 0.0};
  world.addBody(box);
  box.center = {offset, 1.5, 0.0};
  world.addBody(box);
  return world;
}

TEST(Profile, AStackTimesItsCollisionStages) {
  phys::World world = stackOfTwo(true, 0.0);
  const phys::Profile p = profileOf(world, 10);
  for (const Stage s : allStages()) {
    if (s == Stage::Animate || s == Stage::Links ||
        s == Stage::Velocities) {  // no characters, joints, rigid bodies
      EXPECT_EQ(p[s], 0.0);
    } else {
      EXPECT_GT(p[s], 0.0) << phys::toString(s);
    }
  }
  EXPECT_LE(p.staged(), p.total);
}

// With stage timing off (what `lab stability` asks for: it times whole steps itself) no stage reads
// the clock, so every stage reads exactly 0, the step still has its total, and the world moves as
// one timed does, bit for bit.
TEST(Profile, StageTimingOffTimesNoStageAndLeavesTheStateAlone) {
  phys::World timed = stackOfTwo(false, 0.1);
  phys::World untimed = stackOfTwo(false, 0.1);
  EXPECT_TRUE(untimed.stageTiming());
  untimed.setStageTiming(false);
  EXPECT_FALSE(untimed.stageTiming());
  const phys::Profile on = profileOf(timed, 10);
  const phys::Profile off = profileOf(untimed, 10);
  EXPECT_GT(on.staged(), 0.0);
  for (const Stage s : allStages()) EXPECT_EQ(off[s], 0.0) << phys::toString(s);
  EXPECT_GT(off.total, 0.0);
  EXPECT_EQ(untimed.stateHash(), timed.stateHash());
  untimed.setStageTiming(true);  // and back on, the stages are timed again
  EXPECT_GT(profileOf(untimed, 10).staged(), 0.0);
}

}  // namespace
