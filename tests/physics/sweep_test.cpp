// Stage::Sweep (docs/physics.md, "Fast bodies"): a body that would pass through another within a
// substep is stopped at its surface, whatever its model; what moves slower is left alone.
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "physics/collision.h"
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

// Open space without gravity at one substep of 3 Gauss-Seidel passes: a fast body's whole move in
// one substep, and nothing but the sweep and the contacts acting on it.
phys::World weightless() {
  return testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::GaussSeidel, 3, 1), Vec3(0.0));
}

// bullet-200's shot in open space: a 0.2 m box of 1 kg at 200 m/s (3.33 m a step at 1 substep) at
// a 0.1 m slab of 100 t, 2 m away. Without the sweep every model went through (the contact, found
// after the first substep's move, had the bullet on the far side); with it the bullet stops at the
// slab's face, 0.15 m from the slab's centre, within the 1e-3 m a contact's slop and stick play
// allow, and the two move on together with the bullet's momentum: 200 / 100001 m/s.
TEST(Sweep, ABulletStopsAtAThinWallForEveryModelAtOneSubstep) {
  for (const BodyModel model : kModels) {
    phys::World world = weightless();
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

// Two boxes of 1 and 3 kg shot at each other at 150 m/s each (5 m a step, more than their 4 m gap)
// meet where their masses say: the correction is shared by inverse mass, so the centre of mass
// goes on as before (from 1 * -2.5 + 3 * 2.5 = 5 kg m, moved by the momentum -300 kg m/s for a
// step, to 0); an equal share would leave it at 2.5 kg m.
TEST(Sweep, TwoFastBodiesMeetWhereTheirMassesSay) {
  for (const BodyModel model : kModels) {
    phys::World world = weightless();
    BodyDesc left = box({-2.5, 0.0, 0.0}, Vec3(1.0), 1.0, model),
             right = box({2.5, 0.0, 0.0}, Vec3(1.0), 3.0, model);
    left.velocity = {150.0, 0.0, 0.0};
    right.velocity = {-150.0, 0.0, 0.0};
    const BodyId a = world.addBody(left), b = world.addBody(right);
    world.step();
    EXPECT_EQ(world.sweptPairs(), 1) << phys::toString(model);
    EXPECT_LT(world.bodyPose(a).center.x, world.bodyPose(b).center.x) << phys::toString(model);
    EXPECT_NEAR(world.bodyPose(a).center.x + 3.0 * world.bodyPose(b).center.x, 0.0, 1e-9)
        << phys::toString(model);
  }
}

// A near miss is not a hit: a box at 120 m/s passing 5 cm above a wall's top edge (2 m a step,
// through the wall's span) keeps its speed. The sweep once looked along one axis only, the
// start's widest gap (here across the wall), found the move overlapping there and stopped it.
TEST(Sweep, ANearMissKeepsItsSpeed) {
  for (const BodyModel model : kModels) {
    phys::World world = weightless();
    world.addBody(box(Vec3(0.0), {0.1, 1.0, 3.0}, 1e5, model));
    BodyDesc fast = box({-1.0, 0.65, 0.0}, Vec3(0.2), 1.0, model);
    fast.velocity = {120.0, 0.0, 0.0};
    const BodyId id = world.addBody(fast);
    world.step();
    EXPECT_EQ(world.sweptPairs(), 0) << phys::toString(model);
    EXPECT_NEAR(world.bodyPose(id).center.x, 1.0, 1e-9) << phys::toString(model);
    EXPECT_NEAR(world.bodyVelocity(id).first.x, 120.0, 1e-6) << phys::toString(model);
  }
}

// A box coming in fast and low over a slab's edge (240 m/s along, 45 m/s down) is past the slab's
// side plane at 8% of the step and reaches its top at 27%: it lands on the top face, not the side.
// Taking the start's widest gap as the axis (the side) once put it back beside the slab, below
// the top, and it fell past.
TEST(Sweep, ADiagonalShotLandsOnTheFaceItReachesLast) {
  for (const BodyModel model : kModels) {
    phys::World world = weightless();
    world.addBody(box(Vec3(0.0), {4.0, 0.1, 3.0}, 1e5, model));
    BodyDesc fast = box({-2.4, 0.35, 0.0}, Vec3(0.2), 1.0, model);
    fast.velocity = {240.0, -45.0, 0.0};
    const BodyId id = world.addBody(fast);
    world.step();
    EXPECT_EQ(world.sweptPairs(), 1) << phys::toString(model);
    const phys::BodyPose pose = world.bodyPose(id);
    EXPECT_NEAR(pose.center.y, 0.15, 2e-3) << phys::toString(model);  // resting on the top face
    EXPECT_NEAR(pose.center.x, -2.4 + 4.0, 0.05) << phys::toString(model);
  }
}

// sweptSat on its own: the time and axis of the first touch, a graze, a miss past an edge.
TEST(Sweep, SweptSatFindsTheFirstTouch) {
  phys::Obb wall;
  wall.halfExtents = {0.05, 0.5, 1.5};
  phys::Obb shot;
  shot.halfExtents = Vec3(0.1);
  shot.center = {-1.0, 0.0, 0.0};
  const phys::SweptSat head = phys::sweptSat(wall, shot, {2.0, 0.0, 0.0});
  ASSERT_TRUE(head.hit);
  EXPECT_NEAR(head.time, 0.85 / 2.0, 1e-12);  // 0.85 m apart, 2 m moved
  EXPECT_NEAR(head.gap, 0.85, 1e-12);
  EXPECT_NEAR(glm::dot(head.normal, Vec3(-1.0, 0.0, 0.0)), 1.0, 1e-12);  // from the wall to the shot
  shot.center.y = 0.65;                                                  // 5 cm over the top: a miss
  EXPECT_FALSE(phys::sweptSat(wall, shot, {2.0, 0.0, 0.0}).hit);
  EXPECT_FALSE(phys::sweptSat(wall, shot, {0.5, 0.0, 0.0}).hit);  // short of it too
  shot.center = {-1.0, 0.0, 0.0};
  EXPECT_FALSE(phys::sweptSat(wall, shot, {0.5, 0.0, 0.0}).hit);   // stops short
  EXPECT_FALSE(phys::sweptSat(wall, shot, {-2.0, 0.0, 0.0}).hit);  // moves away
  shot.center = {0.1, 0.0, 0.0};                                   // overlapping at the start: hit, time < 0
  const phys::SweptSat inside = phys::sweptSat(wall, shot, {2.0, 0.0, 0.0});
  EXPECT_TRUE(inside.hit);
  EXPECT_LT(inside.time, 0.0);
}
// The sweep takes the approach, not the slide: a box skimming a slab's face at 100 m/s and closing
// on it at 20 m/s keeps its 100 m/s along the face.
TEST(Sweep, SlidingAlongASurfaceIsKept) {
  for (const BodyModel model : kModels) {
    phys::World world = weightless();
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
  phys::World world(phys::WorldSettings{}, testing_phys::solver(phys::SolverMethod::GaussSeidel, 3, 4));
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
