// Stage::Sweep (docs/physics.md, "Fast bodies"): a body that would pass through another within a
// substep is stopped at its surface, whatever its model; what moves slower is left alone.
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "physics/world.h"
#include "test_util.h"

namespace {

using phys::BodyDesc;
using phys::BodyId;
using phys::BodyModel;
using phys::Vec3;

constexpr BodyModel kModels[] = {BodyModel::Corners, BodyModel::Tetra, BodyModel::Rigid};

BodyDesc box(const Vec3& centre, const Vec3& size, double mass, BodyModel model) {
  BodyDesc d;
  d.center = centre;
  d.size = size;
  d.mass = mass;
  d.model = model;
  return d;
}

// bullet-200's shot in open space: a 0.2 m box of 1 kg at 200 m/s (3.33 m a step at 1 substep) at
// a 0.1 m slab of 100 t, 2 m away. Without the sweep every model went through (the contact, found
// after the first substep's move, had the bullet on the far side); with it the bullet stops at the
// slab's face, 0.15 m from the slab's centre, within the 1e-3 m a contact's slop and stick play
// allow, and the two move on together with the bullet's momentum: 200 / 100001 m/s.
TEST(Sweep, ABulletStopsAtAThinWallForEveryModelAtOneSubstep) {
  for (const BodyModel model : kModels) {
    phys::World world =
        testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::GaussSeidel, 1, 3), Vec3(0.0));
    const BodyId wall = world.addBody(box(Vec3(0.0), {0.1, 3.0, 3.0}, 1e5, model));
    BodyDesc bullet = box({-2.0, 0.0, 0.0}, Vec3(0.2), 1.0, model);
    bullet.velocity = {200.0, 0.0, 0.0};
    const BodyId id = world.addBody(bullet);
    for (int i = 0; i < 60; ++i) {
      world.step();
      ASSERT_LT(world.bodyPose(id).center.x, world.bodyPose(wall).center.x)
          << phys::toString(model) << " step " << i;
      if (i == 0) {
        EXPECT_EQ(world.sweptPairs(), 1) << phys::toString(model);
      }
    }
    EXPECT_NEAR(world.bodyPose(id).center.x - world.bodyPose(wall).center.x, -0.15, 1e-3)
        << phys::toString(model);
    EXPECT_NEAR(world.bodyVelocity(id).first.x, 200.0 / 100001.0, 1e-4) << phys::toString(model);
    EXPECT_NEAR(world.bodyVelocity(wall).first.x, 200.0 / 100001.0, 1e-4) << phys::toString(model);
  }
}

// Two equal boxes shot at each other at 150 m/s each (5 m a step, more than their 4 m gap) meet
// in the middle: the correction is shared by inverse mass, so momentum (zero) is kept.
TEST(Sweep, TwoFastBodiesMeetWhereTheirMassesSay) {
  for (const BodyModel model : kModels) {
    phys::World world =
        testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::GaussSeidel, 1, 3), Vec3(0.0));
    BodyDesc left = box({-2.5, 0.0, 0.0}, Vec3(1.0), 2.0, model),
             right = box({2.5, 0.0, 0.0}, Vec3(1.0), 2.0, model);
    left.velocity = {150.0, 0.0, 0.0};
    right.velocity = {-150.0, 0.0, 0.0};
    const BodyId a = world.addBody(left), b = world.addBody(right);
    world.step();
    EXPECT_LT(world.bodyPose(a).center.x, world.bodyPose(b).center.x) << phys::toString(model);
    EXPECT_NEAR(world.bodyPose(a).center.x + world.bodyPose(b).center.x, 0.0, 1e-9) << phys::toString(model);
  }
}

// The sweep takes the approach, not the slide: a box skimming a slab's face at 100 m/s and closing
// on it at 20 m/s keeps its 100 m/s along the face.
TEST(Sweep, SlidingAlongASurfaceIsKept) {
  for (const BodyModel model : kModels) {
    phys::World world =
        testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::GaussSeidel, 1, 3), Vec3(0.0));
    world.addBody(box(Vec3(0.0), {40.0, 0.1, 40.0}, 1e5, model));
    BodyDesc fast = box({-10.0, 0.2, 0.0}, Vec3(0.2), 1.0, model);
    fast.velocity = {100.0, -20.0, 0.0};  // 0.33 m down a step: more than the slab's 0.05 half
    const BodyId id = world.addBody(fast);
    world.step();
    const phys::BodyPose pose = world.bodyPose(id);
    EXPECT_GT(pose.center.y, 0.0) << phys::toString(model);  // on the slab's upper side
    EXPECT_NEAR(pose.center.x, -10.0 + 100.0 / 60.0, 0.01) << phys::toString(model);
  }
}

// What does not move past another's half thickness in a substep is left to the contacts: a box
// falling onto another at 10 m/s and 4 substeps (4 cm a substep against half extents of 0.5 m)
// is never swept, though the stage runs and looks.
TEST(Sweep, ASlowBodyIsLeftToTheContacts) {
  phys::World world(phys::WorldSettings{}, testing_phys::solver(phys::SolverMethod::GaussSeidel, 4, 3));
  world.addBody(box({0.0, 0.5, 0.0}, Vec3(1.0), 1.0, BodyModel::Corners));
  BodyDesc falling = box({0.0, 2.5, 0.0}, Vec3(1.0), 1.0, BodyModel::Corners);
  falling.velocity = {0.0, -10.0, 0.0};
  const BodyId id = world.addBody(falling);
  double sweepMs = 0.0;
  for (int i = 0; i < 60; ++i) {
    world.step();
    EXPECT_EQ(world.sweptPairs(), 0) << "step " << i;
    sweepMs += world.profile()[phys::Stage::Sweep];
  }
  EXPECT_GT(sweepMs, 0.0);
  EXPECT_NEAR(world.bodyPose(id).center.y, 1.5, 0.01);  // landed and resting on the other
}

}  // namespace
