// The mouse spring (World::setDrag): a damped spring from a point of a body to a target, applied
// implicitly once per substep. Its stiffness is in N/m: at rest under gravity the point hangs
// m g / k below the target.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "test_util.h"

namespace {

using phys::BodyModel;
using phys::Vec3;

constexpr double kG = 9.81;  // m/s^2

phys::Drag dragOf(const phys::Embedding& point, const Vec3& target) {
  phys::Drag drag;
  drag.point = point;
  drag.target = target;
  return drag;
}

// With no gravity, a 1 kg particle 2.3 m from the target at the default stiffness and damping
// (ratio 1.1 of critical) is within 1 mm of it after 2 s, never having passed it by more than a
// millimetre.
TEST(Drag, FreeParticleConvergesToTheTarget) {
  phys::World world = testing_phys::openSpace({}, Vec3(0.0));
  const auto id = world.addParticle({Vec3(0.0), Vec3(0.0), 1.0});
  const Vec3 target(1.0, 2.0, -0.5);
  world.setDrag(dragOf(phys::embedParticle(id), target));
  double overshoot = 0.0;
  const Vec3 towards = glm::normalize(target);
  while (world.time() < 2.0) {
    world.step();
    overshoot = std::max(overshoot, glm::dot(world.particles().position[id] - target, towards));
  }
  const double distance = glm::length(world.particles().position[id] - target);
  std::printf("after 2 s: %.3g m from the target, overshoot %.3g m\n", distance, overshoot);
  EXPECT_LT(distance, 1e-3);
  EXPECT_LT(overshoot, 1e-3);
}

// The spring is implicit: from 1 N/m to 1e15 N/m on a 1 g or a 1 kg particle, with or without
// damping, the particle never ends a step farther from the target than it started, and a stiff
// enough spring holds it on the target.
TEST(Drag, StableAtAnyStiffness) {
  for (double stiffness : {1.0, 2000.0, 1e6, 1e15}) {
    for (double mass : {1e-3, 1.0}) {
      for (double damping : {0.0, 100.0}) {
        phys::World world = testing_phys::openSpace({}, Vec3(0.0));
        const auto id = world.addParticle({Vec3(0.0), Vec3(0.0), mass});
        phys::Drag drag = dragOf(phys::embedParticle(id), Vec3(1.0, 0.0, 0.0));
        drag.stiffness = stiffness;
        drag.damping = damping;
        world.setDrag(drag);
        double farthest = 0.0;
        for (int i = 0; i < 120; ++i) {
          world.step();
          farthest = std::max(farthest, glm::length(world.particles().position[id] - drag.target));
        }
        EXPECT_LE(farthest, 1.0 + 1e-12) << stiffness << " N/m, " << mass << " kg, " << damping << " N s/m";
        if (stiffness * 1e-3 / mass >= 1e6) {
          EXPECT_LT(glm::length(world.particles().position[id] - drag.target), 1e-6) << stiffness << " N/m";
        }
      }
    }
  }
}

// At rest under gravity the spring holds the weight: the point hangs m g / k below the target,
// exactly in the implicit step's fixed point (asserted to 1e-9 m; 9.81 mm for 2 kg at 2000 N/m).
TEST(Drag, ParticleHangsMgOverKBelowTheTarget) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.damping = 1.0;  // 1/s
  phys::World world(ws);
  const double mass = 2.0;
  const auto id = world.addParticle({Vec3(0.3, 1.0, 0.0), Vec3(0.0), mass});
  const Vec3 target(0.0, 1.0, 0.0);
  world.setDrag(dragOf(phys::embedParticle(id), target));
  while (world.time() < 10.0) world.step();
  const Vec3 expected = target - Vec3(0.0, mass * kG / phys::kDragStiffness, 0.0);
  EXPECT_LT(glm::length(world.particles().position[id] - expected), 1e-9);
}

class DragBoxes : public ::testing::TestWithParam<BodyModel> {};

// A 1 kg box held by its corner hangs with the diagonal through that corner vertical, its centre
// half a diagonal (0.866 m) plus M g / k (4.9 mm) below the target: asserted within 0.1 mm after
// 10 s (world damping 2/s lets the swing die). The box answers the spring as a rigid body; pulled
// through the corner's carrier particles alone, it hung 7.6 cm lower (corners) or 3.3 cm (tetra).
TEST_P(DragBoxes, BoxHeldByACornerHangsBelowTheTarget) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.damping = 2.0;  // 1/s
  phys::World world(ws);
  phys::BodyDesc desc;
  desc.model = GetParam();
  desc.center = {0.0, 2.0, 0.0};
  const phys::BodyId id = world.addBody(desc);
  const Vec3 corner = desc.center + Vec3(0.5);
  world.setDrag(dragOf(world.anchor(id, corner), corner));
  bool finite = true;
  while (world.time() < 10.0) {
    world.step();
    for (const Vec3& x : world.particles().position) finite = finite && phys::finite(x);
  }
  const Vec3 centre = world.bodyPose(id).center;
  const double drop = corner.y - centre.y,
               side = glm::length(Vec3(centre.x - corner.x, 0.0, centre.z - corner.z));
  std::printf("%s box: centre %.6f m below the target (%.6f expected), %.2g m to the side\n",
              std::string(toString(GetParam())).c_str(), drop, std::sqrt(3.0) / 2 + kG / phys::kDragStiffness,
              side);
  EXPECT_TRUE(finite);
  EXPECT_TRUE(world.freezes().empty());
  EXPECT_NEAR(drop, std::sqrt(3.0) / 2 + kG / phys::kDragStiffness, 1e-4);
  EXPECT_LT(side, 1e-4);
}

// A spring of 1e15 N/m yanks a box's corner 3 m sideways in one step (180 m/s): the box stays
// finite and whole (stick error under 1% after a second; measured 0.008%) and spins about its
// corner, held within 2 cm of the target (measured 8 mm, and shrinking as the spin slows).
TEST_P(DragBoxes, StiffestSpringYanksABoxWithoutBreakingIt) {
  phys::World world = testing_phys::openSpace({}, Vec3(0.0));
  phys::BodyDesc desc;
  desc.model = GetParam();
  const phys::BodyId id = world.addBody(desc);
  phys::Drag drag = dragOf(world.anchor(id, Vec3(0.5)), Vec3(3.5, 0.5, 0.5));
  drag.stiffness = 1e15;
  world.setDrag(drag);
  while (world.time() < 1.0) world.step();
  EXPECT_TRUE(world.freezes().empty());
  EXPECT_LT(world.metrics().maxConstraintError, 0.01);
  EXPECT_LT(glm::length(world.position(drag.point) - drag.target), 0.02);
}

INSTANTIATE_TEST_SUITE_P(Models, DragBoxes, ::testing::Values(BodyModel::Corners, BodyModel::Tetra),
                         [](const auto& param) { return std::string(toString(param.param)); });

// After clearDrag the particle flies on at the velocity it had: no force is left.
TEST(Drag, ClearDragStopsThePull) {
  phys::World world = testing_phys::openSpace({}, Vec3(0.0));
  const auto id = world.addParticle({Vec3(0.0), Vec3(0.0), 1.0});
  world.setDrag(dragOf(phys::embedParticle(id), Vec3(5.0, 0.0, 0.0)));
  for (int i = 0; i < 6; ++i) world.step();
  world.clearDrag();
  EXPECT_FALSE(world.drag().has_value());
  const Vec3 velocity = world.velocity(id), start = world.particles().position[id];
  ASSERT_GT(velocity.x, 1.0);  // m/s: it was being pulled
  const double t0 = world.time();
  for (int i = 0; i < 60; ++i) world.step();
  EXPECT_LT(glm::length(world.velocity(id) - velocity), 1e-9);
  EXPECT_LT(glm::length(world.particles().position[id] - (start + velocity * (world.time() - t0))), 1e-9);
}

// setDragTarget moves the target and nothing else; a pinned particle is never moved, alone or as
// one carrier of an embedded point.
TEST(Drag, PinnedParticlesDoNotMove) {
  phys::World world = testing_phys::openSpace({}, Vec3(0.0));
  const auto pinned = world.addParticle({Vec3(0.0), Vec3(0.0), 0.0, true});
  const auto loose = world.addParticle({Vec3(1.0, 0.0, 0.0), Vec3(0.0), 1.0});
  world.setDrag(dragOf(phys::embedParticle(pinned), Vec3(0.0, 3.0, 0.0)));
  for (int i = 0; i < 30; ++i) world.step();
  EXPECT_EQ(world.particles().position[pinned], Vec3(0.0));
  phys::Embedding both;
  both.particle = {pinned, loose, phys::ParticleId{}, phys::ParticleId{}};
  both.weight = {0.5, 0.5, 0.0, 0.0};
  both.count = 2;
  world.setDrag(dragOf(both, Vec3(0.5, 0.0, 0.0)));
  world.setDragTarget(Vec3(0.5, 2.0, 0.0));
  EXPECT_EQ(world.drag()->target, Vec3(0.5, 2.0, 0.0));
  for (int i = 0; i < 120; ++i) world.step();
  EXPECT_EQ(world.particles().position[pinned], Vec3(0.0));
  EXPECT_GT(world.particles().position[loose].y, 1.0);  // the free carrier went up
}

TEST(Drag, BadInputThrowsAndKeepsTheOldDrag) {
  phys::World world = testing_phys::openSpace();
  const auto id = world.addParticle({Vec3(0.0), Vec3(0.0), 1.0});
  EXPECT_THROW(world.setDragTarget(Vec3(1.0)), std::invalid_argument);  // no drag yet
  const phys::Drag good = dragOf(phys::embedParticle(id), Vec3(1.0));
  world.setDrag(good);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();

  phys::Drag bad = good;
  bad.target = Vec3(nan, 0.0, 0.0);
  EXPECT_THROW(world.setDrag(bad), std::invalid_argument);
  bad = good;
  bad.point.count = 0;
  EXPECT_THROW(world.setDrag(bad), std::invalid_argument);
  bad = good;
  bad.point.count = 5;
  EXPECT_THROW(world.setDrag(bad), std::invalid_argument);
  bad = good;
  bad.point.particle[0] = phys::ParticleId{7};  // no such particle
  EXPECT_THROW(world.setDrag(bad), std::invalid_argument);
  bad = good;
  bad.point.weight[0] = 0.5;  // weights must sum to 1
  EXPECT_THROW(world.setDrag(bad), std::invalid_argument);
  bad = good;
  bad.point.weight[0] = nan;
  EXPECT_THROW(world.setDrag(bad), std::invalid_argument);
  bad = good;
  bad.stiffness = -1.0;
  EXPECT_THROW(world.setDrag(bad), std::invalid_argument);
  bad = good;
  bad.stiffness = inf;
  EXPECT_THROW(world.setDrag(bad), std::invalid_argument);
  bad = good;
  bad.damping = nan;
  EXPECT_THROW(world.setDrag(bad), std::invalid_argument);
  EXPECT_THROW(world.setDragTarget(Vec3(0.0, inf, 0.0)), std::invalid_argument);

  ASSERT_TRUE(world.drag().has_value());
  EXPECT_EQ(world.drag()->target, good.target);
  EXPECT_EQ(world.drag()->point.count, 1);
  world.clearDrag();
  world.clearDrag();  // twice is fine
  EXPECT_FALSE(world.drag().has_value());
}

}  // namespace
