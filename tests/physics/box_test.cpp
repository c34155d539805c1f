// Boxes of 8 corner particles: pose read-back, rest on the ground, and a drop that settles.
#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "physics/world.h"

namespace {

using phys::Vec3;

double maxSpeed(const phys::World& world) {
  double v = 0.0;
  for (phys::ParticleId i = 0; i < world.particles().size(); ++i) v = std::max(v, glm::length(world.velocity(i)));
  return v;
}

double maxStickError(const phys::World& world) {
  double e = 0.0;
  const auto& p = world.particles().position;
  for (const phys::Stick& s : world.sticks()) {
    e = std::max(e, std::abs(glm::length(p[s.b] - p[s.a]) - s.length) / s.length);
  }
  return e;
}

// Angle between two orientations, in radians.
double angleBetween(const phys::Quat& a, const phys::Quat& b) {
  const double d = std::min(1.0, std::abs(glm::dot(glm::normalize(a), glm::normalize(b))));
  return 2.0 * std::acos(d);
}

TEST(Box, PoseReadsBackWhatWasCreated) {
  phys::World world;
  phys::BoxDesc desc;
  desc.center = {1.0, 2.0, -3.0};
  desc.size = {0.5, 1.0, 2.0};
  desc.orientation = glm::dquat(glm::radians(glm::dvec3(30.0, -50.0, 75.0)));
  const phys::BoxId id = world.addBox(desc);
  const phys::BoxPose pose = world.boxPose(id);
  EXPECT_LE(glm::length(pose.center - desc.center), 1e-12);
  EXPECT_LE(angleBetween(pose.orientation, desc.orientation), 1e-7);
  EXPECT_EQ(world.particles().size(), 8u);
  EXPECT_EQ(world.sticks().size(), static_cast<std::size_t>(phys::kBoxStickCount));
}

// A box resting on the ground sags a little under its own weight, because a few relaxation
// passes cannot undo all of one step of gravity; the sag must be small, settle within a few
// steps, shrink with more iterations, and never turn into drift.
TEST(Box, AtRestOnTheGroundStaysAtRest) {
  for (const auto& [iterations, maxSag] : {std::pair{3, 1e-3}, std::pair{10, 1e-5}}) {
    phys::SolverSettings solver;
    solver.iterations = iterations;
    phys::World world({}, solver);
    phys::BoxDesc desc;
    desc.center = {0.0, 0.5, 0.0};
    const phys::BoxId id = world.addBox(desc);
    for (int i = 0; i < 60; ++i) world.step();  // 1 s to settle into its sag
    const phys::BoxPose settled = world.boxPose(id);
    for (int i = 0; i < 540; ++i) world.step();  // 9 s more
    const phys::BoxPose pose = world.boxPose(id);
    EXPECT_LE(glm::length(pose.center - settled.center), 1e-9) << "drift at " << iterations << " iterations";
    EXPECT_LE(glm::length(pose.center - desc.center), maxSag) << "sag at " << iterations << " iterations";
    EXPECT_LE(angleBetween(pose.orientation, desc.orientation), 1e-9);
    EXPECT_LE(maxSpeed(world), 1e-9);
  }
}

TEST(Box, DroppedTiltedSettlesOnAFaceWithoutSliding) {
  phys::World world;
  phys::BoxDesc desc;
  desc.center = {0.0, 3.0, 0.0};
  desc.orientation = glm::dquat(glm::radians(glm::dvec3(20.0, 35.0, 10.0)));
  const phys::BoxId id = world.addBox(desc);
  // Fall until the first contact, then remember where the box was.
  int steps = 0;
  auto lowestCorner = [&] {
    double y = 1e9;
    for (const Vec3& p : world.particles().position) y = std::min(y, p.y);
    return y;
  };
  while (lowestCorner() > 1e-9 && steps < 600) {
    world.step();
    ++steps;
  }
  ASSERT_LT(steps, 600) << "the box never reached the ground";
  for (int i = 0; i < 300; ++i) world.step();  // 5 s after touching down
  const phys::BoxPose pose = world.boxPose(id);
  for (const Vec3& p : world.particles().position) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
  EXPECT_LT(maxSpeed(world), 0.01) << "still moving after 5 s";
  EXPECT_NEAR(pose.center.y, 0.5, 0.02) << "not lying on a face";
  EXPECT_LT(std::hypot(pose.center.x, pose.center.z), 0.5) << "slid or rolled away";
  EXPECT_LT(maxStickError(world), 0.01);
  EXPECT_GE(lowestCorner(), -1e-9);
}

}  // namespace
