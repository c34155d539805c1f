// World::raycast, the sandbox's picking: boxes as their fitted oriented boxes, loose particles as
// spheres of kPickRadius, the nearest hit within the distance wins. And bodies added to a world
// that has already stepped, as picking, throwing and scene edits do.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "physics/ragdoll.h"
#include "test_util.h"

namespace {

using phys::Vec3;

constexpr double kExact = 1e-9;  // m

phys::BodyId addBody(phys::World& world, const Vec3& centre, const Vec3& size,
                     const phys::Quat& orientation = {1.0, 0.0, 0.0, 0.0}, double mass = 1.0) {
  phys::BodyDesc desc;
  desc.center = centre;
  desc.size = size;
  desc.orientation = orientation;
  desc.mass = mass;
  return world.addBody(desc);
}

// The far box is added first, so the nearer one wins on distance, not order. The direction need
// not be a unit vector: distances are in metres along the ray.
TEST(Raycast, HitsTheNearerOfTwoBoxesAtTheAnalyticDistance) {
  phys::World world = testing_phys::openSpace();
  const phys::BodyId far = addBody(world, {6.0, 0.0, 0.0}, Vec3(2.0));
  const phys::BodyId near = addBody(world, {3.0, 0.0, 0.0}, Vec3(1.0));
  const Vec3 origin(0.0, 0.1, 0.2);
  const auto hit = world.raycast(origin, Vec3(2.0, 0.0, 0.0), 100.0);
  ASSERT_TRUE(hit.has_value());
  ASSERT_TRUE(hit->box.has_value());
  EXPECT_FALSE(hit->particle.has_value());
  EXPECT_EQ(*hit->box, near);
  EXPECT_NEAR(hit->distance, 2.5, kExact);
  EXPECT_LT(glm::length(hit->point - Vec3(2.5, 0.1, 0.2)), kExact);

  // From between the two, the far one: its face at x = 5.
  const auto beyond = world.raycast(Vec3(4.0, 0.1, 0.2), Vec3(1.0, 0.0, 0.0), 100.0);
  ASSERT_TRUE(beyond.has_value() && beyond->box.has_value());
  EXPECT_EQ(*beyond->box, far);
  EXPECT_NEAR(beyond->distance, 1.0, kExact);
}

// A ray built in a turned box's own frame, from (-3, 0.1, 0.2) along +x, meets the face x = -0.5
// at 2.5 m; the same ray in world coordinates must too. And a cube turned 45 degrees about y shows
// a ray along x its vertical edge, half a diagonal from its centre.
TEST(Raycast, RotatedBox) {
  phys::World world = testing_phys::openSpace();
  const phys::Quat q = glm::angleAxis(0.7, glm::normalize(Vec3(1.0, 2.0, -0.5)));
  const Vec3 centre(1.0, 2.0, -3.0), size(1.0, 0.6, 0.8);
  const phys::BodyId turned = addBody(world, centre, size, q);
  const auto hit = world.raycast(centre + q * Vec3(-3.0, 0.1, 0.2), q * Vec3(1.0, 0.0, 0.0), 10.0);
  ASSERT_TRUE(hit.has_value() && hit->box.has_value());
  EXPECT_EQ(*hit->box, turned);
  EXPECT_NEAR(hit->distance, 2.5, kExact);
  EXPECT_LT(glm::length(hit->point - (centre + q * Vec3(-0.5, 0.1, 0.2))), kExact);

  phys::World diamond = testing_phys::openSpace();
  addBody(diamond, Vec3(0.0), Vec3(1.0), glm::angleAxis(glm::radians(45.0), Vec3(0.0, 1.0, 0.0)));
  const auto edge = diamond.raycast(Vec3(-5.0, 0.2, 0.0), Vec3(1.0, 0.0, 0.0), 10.0);
  ASSERT_TRUE(edge.has_value());
  EXPECT_NEAR(edge->distance, 5.0 - std::sqrt(0.5), kExact);
  // At z = 0.6 the diamond spans x from -(0.707 - 0.6) to +(0.707 - 0.6).
  const auto side = diamond.raycast(Vec3(-5.0, 0.2, 0.6), Vec3(1.0, 0.0, 0.0), 10.0);
  ASSERT_TRUE(side.has_value());
  EXPECT_NEAR(side->distance, 5.0 - (std::sqrt(0.5) - 0.6), kExact);
}

TEST(Raycast, MissReturnsNothing) {
  phys::World world = testing_phys::openSpace();
  addBody(world, {3.0, 0.0, 0.0}, Vec3(1.0));
  world.addParticle({Vec3(0.0, 3.0, 0.0)});
  EXPECT_FALSE(world.raycast(Vec3(0.0), Vec3(-1.0, 0.0, 0.0), 100.0).has_value());           // pointing away
  EXPECT_FALSE(world.raycast(Vec3(0.0, 0.6, 0.0), Vec3(1.0, 0.0, 0.0), 100.0).has_value());  // passes above
  EXPECT_FALSE(world.raycast(Vec3(0.0), Vec3(1.0, 0.0, 0.0), 2.4).has_value());              // too short
  EXPECT_TRUE(world.raycast(Vec3(0.0), Vec3(1.0, 0.0, 0.0), 2.5).has_value());  // just long enough
  EXPECT_FALSE(
      world.raycast(Vec3(0.0, 0.0, 0.0), Vec3(0.0, 1.0, 0.0), 2.85).has_value());  // short of the particle
  EXPECT_FALSE(phys::World().raycast(Vec3(0.0), Vec3(1.0, 0.0, 0.0), 100.0).has_value());  // empty world
}

// A loose particle is a sphere of kPickRadius: a ray 5 cm off its centre enters the sphere
// sqrt(r^2 - 0.05^2) before the point of closest approach. A box's own particles are never
// reported: the box is.
TEST(Raycast, ParticleHit) {
  phys::World world = testing_phys::openSpace();
  const auto loose = world.addParticle({Vec3(0.0, 1.0, 0.0)});
  const phys::BodyId box = addBody(world, {0.0, 1.0, 3.0}, Vec3(1.0));
  const auto hit = world.raycast(Vec3(-2.0, 1.05, 0.0), Vec3(1.0, 0.0, 0.0), 10.0);
  ASSERT_TRUE(hit.has_value() && hit->particle.has_value());
  EXPECT_FALSE(hit->box.has_value());
  EXPECT_EQ(*hit->particle, loose);
  const double entry = 2.0 - std::sqrt(phys::kPickRadius * phys::kPickRadius - 0.05 * 0.05);
  EXPECT_NEAR(hit->distance, entry, kExact);
  EXPECT_LT(glm::length(hit->point - Vec3(-2.0 + entry, 1.05, 0.0)), kExact);
  // Aimed at a corner particle of the box, from outside: the box.
  const auto corner = world.raycast(Vec3(-2.0, 1.5, 2.5), Vec3(1.0, 0.0, 0.0), 10.0);
  ASSERT_TRUE(corner.has_value());
  ASSERT_TRUE(corner->box.has_value());
  EXPECT_EQ(*corner->box, box);
  EXPECT_NEAR(corner->distance, 1.5, kExact);
}

// A ray that starts inside a box (or a particle's sphere) hits it where it starts.
TEST(Raycast, StartingInsideABoxHitsItAtDistanceZero) {
  phys::World world = testing_phys::openSpace();
  const phys::BodyId big = addBody(world, Vec3(0.0), Vec3(4.0));
  addBody(world, {1.0, 0.0, 0.0}, Vec3(0.5));  // inside the big one, ahead of the origin
  const Vec3 origin(-1.0, 0.3, 0.2);
  const auto hit = world.raycast(origin, Vec3(1.0, 0.0, 0.0), 10.0);
  ASSERT_TRUE(hit.has_value() && hit->box.has_value());
  EXPECT_EQ(*hit->box, big);
  EXPECT_EQ(hit->distance, 0.0);
  EXPECT_EQ(hit->point, origin);
  const auto particle = world.addParticle({Vec3(5.0, 0.0, 0.0)});
  const auto inSphere = world.raycast(Vec3(5.05, 0.0, 0.0), Vec3(0.0, 1.0, 0.0), 1.0);
  ASSERT_TRUE(inSphere.has_value() && inSphere->particle.has_value());
  EXPECT_EQ(*inSphere->particle, particle);
  EXPECT_EQ(inSphere->distance, 0.0);
}

TEST(Raycast, BadInputThrows) {
  phys::World world = testing_phys::openSpace();
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(world.raycast(Vec3(nan, 0.0, 0.0), Vec3(1.0, 0.0, 0.0), 1.0), std::invalid_argument);
  EXPECT_THROW(world.raycast(Vec3(0.0), Vec3(0.0), 1.0), std::invalid_argument);
  EXPECT_THROW(world.raycast(Vec3(0.0), Vec3(inf, 0.0, 0.0), 1.0), std::invalid_argument);
  EXPECT_THROW(world.raycast(Vec3(0.0), Vec3(1.0, 0.0, 0.0), -1.0), std::invalid_argument);
  EXPECT_THROW(world.raycast(Vec3(0.0), Vec3(1.0, 0.0, 0.0), nan), std::invalid_argument);
  EXPECT_NO_THROW(world.raycast(Vec3(0.0), Vec3(1.0, 0.0, 0.0), inf));
}

// A box and a ragdoll added to a world that has stepped 100 times with three crates (1 m, 200 kg)
// resting on the ground: the new box falls exactly as in free flight until it lands, then rests on the old
// box it was dropped on; the ragdoll lands on another old box and touches it; the old boxes stay put, nothing
// freezes, and a ray from above picks the new box.
TEST(LateBodies, BoxAndRagdollAddedAfterSteppingCollideWithTheOldOnes) {
  phys::SolverSettings s;
  s.substeps = 4;
  s.iterations = 2;
  s.bodyDamping = 1.0;  // as the ragdoll scenes
  phys::World world({}, s);
  std::vector<phys::BodyId> old;
  for (int i = 0; i < 3; ++i)
    old.push_back(addBody(world, {3.0 * i, 0.5, 0.0}, Vec3(1.0), {1.0, 0.0, 0.0, 0.0}, 200.0));
  for (int i = 0; i < 100; ++i) world.step();
  std::vector<Vec3> oldCentres;
  for (phys::BodyId id : old) oldCentres.push_back(world.bodyPose(id).center);

  const Vec3 dropAt(0.0, 4.0, 0.0);
  const phys::BodyId added = addBody(world, dropAt, Vec3(1.0));
  phys::RagdollDesc ragdoll;
  ragdoll.hips = {3.0, 2.5, 0.0};
  ragdoll.model = phys::RagdollModel::Lean;
  const phys::Ragdoll doll = phys::addRagdoll(world, ragdoll);

  const double start = world.time();
  for (int i = 0; i < 30; ++i) world.step();  // 0.5 s: still 1.3 m above the old box
  const double t = world.time() - start;
  EXPECT_NEAR(world.bodyPose(added).center.y, dropAt.y - 0.5 * 9.81 * t * t, kExact);

  auto isPart = [&doll](phys::BodyId body) {
    return std::find(doll.parts.begin(), doll.parts.end(), body) != doll.parts.end();
  };
  const phys::BodyId crate = old[1];
  bool ragdollTouchedTheCrate = false;
  while (world.time() < start + 4.0) {
    world.step();
    for (const phys::BodyContact& c : world.bodyContacts()) {
      if ((c.bodyA == crate && isPart(c.bodyB)) || (c.bodyB == crate && isPart(c.bodyA)))
        ragdollTouchedTheCrate = true;
    }
  }
  EXPECT_TRUE(ragdollTouchedTheCrate);
  std::printf("new box at rest %.4f m up (1.5 on the crate); crates moved", world.bodyPose(added).center.y);
  for (std::size_t i = 0; i < old.size(); ++i) {
    const double moved = glm::length(world.bodyPose(old[i]).center - oldCentres[i]);
    std::printf(" %.4f", moved);
    EXPECT_LT(moved, 0.01) << "crate " << i;
  }
  std::printf(" m\n");
  EXPECT_NEAR(world.bodyPose(added).center.y, 1.5, 5e-3);
  EXPECT_TRUE(world.freezes().empty());
  EXPECT_LT(world.metrics().maxPenetration, 0.01);

  const auto hit = world.raycast(Vec3(0.0, 10.0, 0.0), Vec3(0.0, -1.0, 0.0), 100.0);
  ASSERT_TRUE(hit.has_value() && hit->box.has_value());
  EXPECT_EQ(*hit->box, added);
  EXPECT_NEAR(hit->distance, 8.0, 0.01);
}

}  // namespace
