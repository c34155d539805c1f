// Point gravity: a fixed-strength pull towards a point, switchable at run time.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "test_util.h"

namespace {

using phys::Vec3;

// A pull of constant strength s keeps a circle of radius r with speed sqrt(s r).
TEST(PointGravity, CircularOrbitKeepsItsRadiusWithin1PercentForOneOrbit) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.gravityMode = phys::GravityMode::Point;
  ws.gravityPoint = {1.0, 2.0, 3.0};
  ws.gravityStrength = 9.81;
  phys::World world(ws);
  const double r = 5.0;
  const double speed = std::sqrt(ws.gravityStrength * r);
  const auto id = world.addParticle({ws.gravityPoint + Vec3(r, 0.0, 0.0), Vec3(0.0, 0.0, speed), 1.0});
  const double period = 2.0 * M_PI * r / speed;  // 4.48 s
  double worst = 0.0;
  while (world.time() < period) {
    world.step();
    worst = std::max(worst, std::abs(glm::length(world.particles().position[id] - ws.gravityPoint) - r) / r);
  }
  EXPECT_LT(worst, 0.01);
  // And it came round: back near the start after one period.
  EXPECT_LT(glm::length(world.particles().position[id] - (ws.gravityPoint + Vec3(r, 0.0, 0.0))), 0.05 * r);
}

TEST(PointGravity, ModeSwitchesAtRunTime) {
  phys::World world = testing_phys::openSpace();
  const auto id = world.addParticle({Vec3(3.0, 0.0, 0.0), Vec3(0.0), 1.0});
  world.step();
  EXPECT_LT(world.velocity(id).y, 0.0);
  EXPECT_EQ(world.velocity(id).x, 0.0);
  phys::WorldSettings ws = world.worldSettings();
  ws.gravityMode = phys::GravityMode::Point;
  ws.gravityPoint = Vec3(0.0);
  world.setWorldSettings(ws);
  EXPECT_EQ(world.gravityAt(Vec3(3.0, 0.0, 0.0)), Vec3(-ws.gravityStrength, 0.0, 0.0));
  const double vx = world.velocity(id).x;
  world.step();
  EXPECT_LT(world.velocity(id).x, vx);                     // now pulled towards the origin along -x
  EXPECT_EQ(world.gravityAt(ws.gravityPoint), Vec3(0.0));  // no pull at the point itself
}

}  // namespace
