// Free flight against the closed form x(t) = x0 + v0 t + g t^2 / 2. Verlet is exact for
// constant acceleration when x* is set from v0 consistently (World::addParticle), so the only
// error left is round-off: asserted to 1e-9 relative (measured up to 4e-11; the issue asks
// for 1e-5).
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "physics/world.h"
#include "test_util.h"

namespace {

using phys::Vec3;
using testing_phys::openSpace;

struct FlightCase {
  Vec3 x0, v0, gravity;
  int substeps;
};

class FreeFall : public ::testing::TestWithParam<FlightCase> {};

TEST_P(FreeFall, MatchesClosedFormAfter600Steps) {
  const FlightCase c = GetParam();
  phys::SolverSettings ss;
  ss.substeps = c.substeps;
  phys::World world = openSpace(ss, c.gravity);
  const phys::ParticleId id = world.addParticle({c.x0, c.v0, 2.0});

  for (int i = 0; i < 600; ++i) world.step();

  const double t = 600 * ss.dt;
  ASSERT_NEAR(world.time(), t, 1e-9);
  const Vec3 expected = c.x0 + c.v0 * t + 0.5 * c.gravity * t * t;
  const Vec3 got = world.particles().position[id];
  EXPECT_LE(glm::length(got - expected) / glm::length(expected), 1e-9)
      << "got (" << got.x << ", " << got.y << ", " << got.z << "), expected (" << expected.x << ", "
      << expected.y << ", " << expected.z << ")";
  // Verlet's velocity (x - x*) / h is the one half a substep back.
  const double h = ss.dt / c.substeps;
  const Vec3 expectedVelocity = c.v0 + c.gravity * (t - h / 2);
  EXPECT_LE(glm::length(world.velocity(id) - expectedVelocity), 1e-6 * glm::length(expectedVelocity));
}

INSTANTIATE_TEST_SUITE_P(
    FreeFallAndProjectiles, FreeFall,
    ::testing::Values(FlightCase{{0, 10, 0}, {0, 0, 0}, {0, -9.81, 0}, 1},         // dropped
                      FlightCase{{1, 10, -2}, {3, 5, 1}, {0, -9.81, 0}, 1},        // projectile
                      FlightCase{{0, 100, 0}, {20, 20, 0}, {0, -9.81, 0}, 4},      // projectile, substeps
                      FlightCase{{-3, 0, 4}, {0, 0, 0}, {2, -20, 1}, 8},           // slanted gravity
                      FlightCase{{1e3, 1e3, 1e3}, {1, 2, 3}, {0, -9.81, 0}, 1}));  // far out

TEST(Damping, VelocityDecaysExponentiallyWhateverTheSubsteps) {
  for (int substeps : {1, 3, 10}) {
    phys::WorldSettings ws;
    ws.gravity = Vec3(0.0);
    ws.damping = 0.5;  // 1/s
    ws.ground = false;
    phys::SolverSettings ss;
    ss.substeps = substeps;
    phys::World world(ws, ss);
    const phys::ParticleId id = world.addParticle({Vec3(0.0), Vec3(4.0, 0.0, 0.0), 1.0});
    for (int i = 0; i < 120; ++i) world.step();
    EXPECT_NEAR(world.velocity(id).x, 4.0 * std::exp(-0.5 * 2.0), 1e-9) << substeps << " substeps";
  }
}

TEST(Damping, RestingParticleFarFromOriginStaysPut) {
  // REFERENCES.md: the literal "1.99" form moves x = 500 to 470.25 in 3 steps.
  phys::WorldSettings ws;
  ws.gravity = Vec3(0.0);
  ws.damping = 3.0;
  ws.ground = false;
  phys::World world(ws);
  const phys::ParticleId id = world.addParticle({Vec3(1000.0, -1000.0, 1000.0), Vec3(0.0), 1.0});
  for (int i = 0; i < 600; ++i) world.step();
  EXPECT_EQ(world.particles().position[id], Vec3(1000.0, -1000.0, 1000.0));
}

// Changing the step mid-flight keeps the trajectory: 0.5 s at 1/60, then 0.5 s at 1/240 in 3
// substeps, lands where the closed form says.
TEST(StepChange, FreeFlightStaysOnTheClosedForm) {
  phys::World world = openSpace();
  const Vec3 x0(0.0, 10.0, 0.0), v0(2.0, 3.0, 0.0), g(0.0, -9.81, 0.0);
  const phys::ParticleId id = world.addParticle({x0, v0, 1.0});
  for (int i = 0; i < 30; ++i) world.step();
  phys::SolverSettings s = world.solverSettings();
  s.dt = 1.0 / 240.0;
  s.substeps = 3;
  world.setSolverSettings(s);
  for (int i = 0; i < 120; ++i) world.step();
  const double t = 1.0;
  const Vec3 expected = x0 + v0 * t + 0.5 * g * t * t;
  EXPECT_LE(glm::length(world.particles().position[id] - expected), 1e-9 * glm::length(expected));
}

// A 1 m box settled on the ground for 1 s, then given new solver settings and stepped `steps`
// more times. Returns its height before the change and the highest it reached after.
struct StepChangeRun {
  double before;
  double highest;
  double after;
  double speed;
};

StepChangeRun restingBoxThenChange(phys::SolverSettings (*change)(phys::SolverSettings), int steps) {
  phys::World world;
  phys::BodyDesc box;
  box.center = {0.0, 0.5, 0.0};
  world.addBody(box);
  for (int i = 0; i < 60; ++i) world.step();
  StepChangeRun r{world.bodyPose(phys::BodyId{0}).center.y, 0.0, 0.0, 0.0};
  world.setSolverSettings(change(world.solverSettings()));
  for (int i = 0; i < steps; ++i) {
    world.step();
    r.highest = std::max(r.highest, world.bodyPose(phys::BodyId{0}).center.y);
  }
  r.after = world.bodyPose(phys::BodyId{0}).center.y;
  r.speed = world.metrics().maxSpeed;
  return r;
}

// A box resting on the ground does not hop when the step grows; it only sags a little deeper,
// as a longer step lets gravity push further between relaxations, and rests again.
TEST(StepChange, RestingBoxDoesNotHopWhenTheStepGrows) {
  const StepChangeRun r = restingBoxThenChange(
      [](phys::SolverSettings s) {
        s.dt = 1.0 / 30.0;
        return s;
      },
      30);
  EXPECT_LE(r.highest, r.before + 1e-6);
  EXPECT_NEAR(r.after, r.before, 3e-3);
  EXPECT_LT(r.speed, 1e-3);
}

// Nor when it shrinks: from 1 to 16 substeps. Adding free-flight gravity's term to a body the
// ground holds would drive it into the ground, and the sag the coarser step left, relaxed in
// one go by the finer one, would throw it up by 5 mm. It settles to its full height instead.
TEST(StepChange, RestingBoxDoesNotHopWhenTheStepShrinks) {
  const StepChangeRun r = restingBoxThenChange(
      [](phys::SolverSettings s) {
        s.substeps = 16;
        return s;
      },
      60);
  EXPECT_GE(r.before, 0.499);        // it had sagged
  EXPECT_LE(r.highest, 0.5 + 1e-5);  // and now rests at its full height, no higher
  EXPECT_LT(r.speed, 1e-3);
}

TEST(Pinned, NeverMoves) {
  phys::World world;
  const phys::ParticleId id = world.addParticle({Vec3(0.0, 5.0, 0.0), Vec3(0.0), 0.0, true});
  for (int i = 0; i < 60; ++i) world.step();
  EXPECT_EQ(world.particles().position[id], Vec3(0.0, 5.0, 0.0));
  EXPECT_EQ(world.particles().inverseMass[id], 0.0);
}

}  // namespace
