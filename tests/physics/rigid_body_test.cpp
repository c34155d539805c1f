// The rigid body model (docs/physics.md, "Rigid bodies"): free motion against the exact answers
// (free fall, Euler's equations), resting and stacking, friction and restitution against their
// analytic answers, contacts with particle bodies, the guard, and bad input.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "physics/rigid_contacts.h"
#include "physics/world.h"
#include "test_util.h"

namespace {

using phys::BodyDesc;
using phys::BodyId;
using phys::BodyModel;
using phys::Real;
using phys::Vec3;

phys::SolverSettings xpbd(int substeps, int iterations = 1) {
  phys::SolverSettings s;
  s.method = phys::SolverMethod::Xpbd;
  s.substeps = substeps;
  s.iterations = iterations;
  return s;
}

using testing_phys::rigidBox;

phys::WorldSettings noGravity() {
  phys::WorldSettings w;
  w.gravity = Vec3(0.0);
  w.ground = false;
  return w;
}

TEST(RigidBody, HasNoParticlesAndASolidShapesInertia) {
  phys::World world;
  const BodyId id = world.addBody(rigidBox({0.0, 3.0, 0.0}, {0.4, 1.0, 2.0}, 2.0));
  EXPECT_EQ(world.particles().size(), 0u);
  EXPECT_EQ(world.sticks().size(), 0u);
  const phys::Body& body = world.bodies()[id];
  EXPECT_EQ(body.model, BodyModel::Rigid);
  const Vec3 inverse = world.rigidBodies().inverseInertia[body.rigid];
  // A solid box: I = m (b^2 + c^2) / 12 about each axis.
  EXPECT_NEAR(1.0 / inverse.x, 2.0 * (1.0 + 4.0) / 12.0, 1e-12);
  EXPECT_NEAR(1.0 / inverse.y, 2.0 * (0.16 + 4.0) / 12.0, 1e-12);
  EXPECT_NEAR(1.0 / inverse.z, 2.0 * (0.16 + 1.0) / 12.0, 1e-12);
  EXPECT_EQ(phys::toString(BodyModel::Rigid), "rigid");
  EXPECT_EQ(phys::parseBodyModel("rigid"), BodyModel::Rigid);
}

TEST(RigidBody, CapsuleInertiaMatchesItsLimits) {
  // No core: a solid sphere, 2/5 m r^2 about every axis.
  const Vec3 sphere = phys::solidCapsuleInertia(0.5, 0.0, 3.0);
  EXPECT_NEAR(sphere.x, 0.4 * 3.0 * 0.25, 1e-12);
  EXPECT_NEAR(sphere.y, 0.4 * 3.0 * 0.25, 1e-12);
  // A core far longer than the radius: a thin rod, m L^2 / 12 across, m r^2 / 2 along.
  const Real r = 0.01, half = 50.0;
  const Vec3 rod = phys::solidCapsuleInertia(r, half, 1.0);
  EXPECT_NEAR(rod.x, 1.0 * (2.0 * half) * (2.0 * half) / 12.0, 1e-3 * rod.x);
  EXPECT_NEAR(rod.y, 0.5 * r * r, 1e-3 * rod.y);
}

// The inertia floor raises each principal moment to at least its fraction of the largest and leaves
// the others as they are; 0 (every body's default) keeps the solid shape's, and values outside 0 to
// 1 are refused with nothing added.
TEST(RigidBody, InertiaFloorRaisesOnlyTheSmallMoments) {
  phys::World world;
  BodyDesc thin = rigidBox({0.0, 3.0, 0.0}, {0.1, 1.0, 0.1}, 2.0);  // a limb: small about its length
  const Vec3 solid = phys::solidBoxInertia(thin.size * 0.5, thin.mass);
  thin.inertiaFloor = 0.5;
  const BodyId id = world.addBody(thin);
  const phys::Body& body = world.bodies()[id];
  EXPECT_EQ(body.inertiaFloor, 0.5);
  const Vec3 floored = 1.0 / world.rigidBodies().inverseInertia[body.rigid];
  EXPECT_NEAR(floored.x, solid.x, 1e-15);
  EXPECT_NEAR(floored.z, solid.z, 1e-15);
  EXPECT_LT(solid.y, 0.02 * solid.x);
  EXPECT_NEAR(floored.y, 0.5 * solid.x, 1e-15);
  EXPECT_EQ(phys::flooredInertia(solid, 0.0), solid);
  EXPECT_EQ(phys::flooredInertia(solid, 1.0), Vec3(solid.x));
  for (const Real bad : {-0.1, 1.5, std::numeric_limits<Real>::quiet_NaN()}) {
    thin.inertiaFloor = bad;
    EXPECT_THROW(world.addBody(thin), std::invalid_argument) << bad;
  }
  EXPECT_EQ(world.bodies().size(), 1u);
  EXPECT_EQ(world.rigidBodies().size(), 1u);
}

// Free fall with a throw: the velocity kept is the substep's middle's, so the trajectory is exact to
// round-off at any substep, as for particles.
TEST(RigidBody, FreeFallIsExact) {
  phys::WorldSettings w;
  w.ground = false;
  phys::World world(w, xpbd(3));
  BodyDesc d = rigidBox({1.0, 2.0, 3.0});
  d.velocity = {2.0, 5.0, -1.0};
  const BodyId id = world.addBody(d);
  for (int i = 0; i < 120; ++i) world.step();
  const Real t = world.time();
  const Vec3 expected = d.center + d.velocity * t + 0.5 * w.gravity * t * t;
  EXPECT_LT(glm::length(world.bodyPose(id).center - expected), 1e-9);
}

// Counts how often the middle axis (y) turns from along its start direction to against it, or back.
int countFlips(phys::World& world, BodyId id, int steps) {
  const Vec3 start = world.bodyPose(id).orientation * Vec3(0.0, 1.0, 0.0);
  bool along = true;
  int flips = 0;
  for (int i = 0; i < steps; ++i) {
    world.step();
    const bool now = glm::dot(world.bodyPose(id).orientation * Vec3(0.0, 1.0, 0.0), start) > 0.0;
    if (now != along) ++flips;
    along = now;
  }
  return flips;
}

// The stability suite's Dzhanibekov scene: a 0.4 x 1 x 2 m box spun about its middle axis. A rigid
// body flips at 1.93, 6.25 and 10.58 s (Euler's equations, RK4 at 1 ms), so 3 times in 12 s. The
// implicit midpoint rule keeps the kinetic energy to the Newton solve's round-off: 1e-12 measured.
TEST(RigidBody, DzhanibekovFlipsThreeTimesAndKeepsItsEnergy) {
  for (const int substeps : {1, 4}) {
    phys::World world(noGravity(), xpbd(substeps));
    BodyDesc d = rigidBox(Vec3(0.0), {0.4, 1.0, 2.0});
    d.angularVelocity = {0.36 * std::numbers::pi / 180.0, 2.0 * std::numbers::pi,
                         0.36 * std::numbers::pi / 180.0};
    const BodyId id = world.addBody(d);
    const Real before = world.metrics().energy();
    EXPECT_EQ(countFlips(world, id, 720), 3) << substeps << " substeps";
    EXPECT_NEAR(world.metrics().energy(), before, 1e-9 * before) << substeps << " substeps";
  }
}

TEST(RigidBody, AngularVelocityComesBackFromThePoseUnchanged) {
  // The exact exponential and logarithm: a spin of 50 rad/s over a substep of 1/60 s (0.83 rad)
  // is read back to round-off, where the paper's linearised update loses 8% of it.
  phys::World world(noGravity(), xpbd(1));
  BodyDesc d = rigidBox(Vec3(0.0));
  d.angularVelocity = {0.0, 50.0, 0.0};  // about a principal axis of a cube: no precession
  const BodyId id = world.addBody(d);
  world.step();
  EXPECT_NEAR(world.bodyVelocity(id).second.y, 50.0, 1e-9);
}

// A tumbling box (a spin about its long axis with a wobble) turns the same way at any substep to
// second order in h: the kept spin is that of the substep's middle, so the load and every change
// of substep shift it by Euler's dw/dt, as gravity shifts a velocity. Without the shift the turn is
// a constant O(h) out of phase (first order: the error halved with h). Measured against 512
// substeps, the unit long axis's end is 5.6e-5, 1.4e-5 and 3.5e-6 m off at 4, 8 and 16 substeps:
// ratios of 4.0; a first-order turn would read ratios of 2 and fail.
TEST(RigidBody, RotationConvergesAtSecondOrder) {
  auto tip = [](int substeps) {
    phys::World world(noGravity(), xpbd(1));
    BodyDesc d = rigidBox(Vec3(0.0), {0.4, 1.0, 2.0});
    d.angularVelocity = {0.5, 0.8, 6.0};
    const BodyId id = world.addBody(d);
    world.setSolverSettings(xpbd(substeps));  // from the load's substep, as the lab does
    for (int i = 0; i < 60; ++i) world.step();
    return world.bodyPose(id).orientation * Vec3(0.0, 0.0, 1.0);  // the long axis's far end
  };
  const Vec3 converged = tip(512);
  const Real e4 = glm::length(tip(4) - converged), e8 = glm::length(tip(8) - converged),
             e16 = glm::length(tip(16) - converged);
  std::printf("tip error at 4, 8, 16 substeps: %.3g %.3g %.3g m\n", e4, e8, e16);
  EXPECT_NEAR(std::log2(e4 / e8), 2.0, 0.15);
  EXPECT_NEAR(std::log2(e8 / e16), 2.0, 0.15);
}

// Changing the substep and changing it back gives the spin back: both shifts read Euler's dw/dt at
// the same spin, that of the start of the substep.
TEST(RigidBody, ChangingTheSubstepAndBackKeepsTheSpin) {
  phys::World world(noGravity(), xpbd(1));
  BodyDesc d = rigidBox(Vec3(0.0), {0.4, 1.0, 2.0});
  d.angularVelocity = {0.5, 0.8, 6.0};
  const BodyId id = world.addBody(d);
  const Vec3 before = world.bodyVelocity(id).second;
  world.setSolverSettings(xpbd(64));
  const Vec3 fine = world.bodyVelocity(id).second;
  EXPECT_GT(glm::length(fine - before), 1e-3);  // the shift is there: w' h / 2 at 1 substep
  world.setSolverSettings(xpbd(1));
  EXPECT_NEAR(glm::length(world.bodyVelocity(id).second - before), 0.0, 1e-13);
}

// A body saved and reloaded goes on as it would have: rigidDescVelocity is the exact inverse of
// addBody's half-substep shift, so the reloaded body keeps the spin (and velocity) it had to
// round-off. Reading bodyVelocity instead shifted the spin once more at every reload: by
// 1.4e-7 rad/s on a rolling capsule, found by the scene fuzzer's round trip.
TEST(RigidBody, DescVelocityReloadsToTheSameState) {
  // 0.03 rad a substep, shifted; 1.3 rad a substep, past kMostShiftedTurn: kept as it is.
  for (const Vec3 spin0 : {Vec3(0.5, 0.8, 6.0), Vec3(50.0, 80.0, 300.0)}) {
    phys::World world({}, xpbd(4));
    BodyDesc d = rigidBox({0.0, 5.0, 0.0}, {0.4, 1.0, 2.0});
    d.velocity = {1.0, 2.0, 0.0};
    d.angularVelocity = spin0;
    const BodyId id = world.addBody(d);
    for (int i = 0; i < 5; ++i) world.step();
    phys::World reloaded({}, xpbd(4));
    BodyDesc again = d;
    again.center = world.bodyPose(id).center;
    again.orientation = world.bodyPose(id).orientation;
    std::tie(again.velocity, again.angularVelocity) = world.rigidDescVelocity(id);
    const BodyId copy = reloaded.addBody(again);
    const auto [velocity, spin] = world.bodyVelocity(id);
    EXPECT_LT(glm::length(reloaded.bodyVelocity(copy).first - velocity), 1e-13);
    EXPECT_LT(glm::length(reloaded.bodyVelocity(copy).second - spin), 1e-13 * glm::length(spin));
    if (spin0.z < 10.0) {
      EXPECT_GT(glm::length(again.angularVelocity - spin), 1e-3);  // a shift undone
    }
  }
  phys::World world({}, xpbd(4));
  EXPECT_THROW((void)world.rigidDescVelocity(world.addBody(BodyDesc{})), std::invalid_argument);
}

// The velocity the peers are given with a body's pose is the spin at the pose's time, as a
// particle body's is: a rigid body's, kept half a substep back, moved on (it was handed over as
// kept, off by about h |w|^2 / 2 about an axis it precesses about).
TEST(RigidBody, PoseVelocityIsTheSpinAtThePosesTime) {
  phys::World world({}, xpbd(1));
  BodyDesc d = rigidBox({0.0, 5.0, 0.0}, {0.4, 1.0, 2.0});
  d.velocity = {1.0, 2.0, 0.0};
  d.angularVelocity = {0.5, 0.8, 6.0};
  const BodyId id = world.addBody(d);
  const auto [velocity, spin] = world.poseVelocity(id);
  EXPECT_LT(glm::length(spin - d.angularVelocity), 1e-13 * glm::length(d.angularVelocity));
  EXPECT_LT(glm::length(velocity - d.velocity), 1e-13);
  world.step();
  const auto [laterVelocity, laterSpin] = world.poseVelocity(id);
  const auto [descVelocity, descSpin] = world.rigidDescVelocity(id);
  EXPECT_EQ(laterSpin, descSpin);
  EXPECT_EQ(laterVelocity, descVelocity);
}

TEST(RigidBody, RestsOnTheGroundWithoutDrift) {
  for (const int substeps : {1, 4}) {
    phys::World world({}, xpbd(substeps));
    const BodyId box = world.addBody(rigidBox({0.0, 0.5, 0.0}));
    for (int i = 0; i < 600; ++i) world.step();
    const phys::BodyPose pose = world.bodyPose(box);
    // It sinks by what gravity adds in a substep, g h^2 (2.7 mm at 1 substep), at most.
    EXPECT_NEAR(pose.center.y, 0.5, 9.81 / (3600.0 * substeps * substeps)) << substeps;
    // Measured: 0.5 mm at 1 substep, 0.03 mm at 4, in 10 s.
    EXPECT_LT(std::hypot(pose.center.x, pose.center.z), 1e-3) << substeps;
    EXPECT_LT(2.0 * std::acos(std::min(1.0, std::abs(pose.orientation.w))), 1e-3) << substeps;
  }
}

// A slab 0.1 m thick, 3 m tall and 3 m long, of 100 t (the wall of stability/bullet-100.xml),
// standing on its thin edge. Its centre is over its base, so it is at rest, and tipped from rest by
// a rocking spin of kinetic energy K0 about one long bottom edge, it can rise only until its
// potential energy has taken K0: by m g (b/2) theta for a tilt theta (b = 0.1 m; 2.0e-3 rad for
// K0 = 100 J), far short of the 0.033 rad past which it falls. Its energy over rest, kinetic plus
// m g (y - y_rest), never passes K0, and the contacts, inelastic, take it all. The block's sweeps
// alone did not settle how the weight splits between the two long edges (docs/physics.md, "A
// slender body on its edge"): stood still, the wall rocked and fell over within 15 s at 1 x 1, and
// at 1 x 4 rocked by up to 0.13 degrees, 109 J over rest, and was still rocking after 20 s. Measured with the
// direct solve: still, below 1e-19 J and no tilt; kicked, at most 101.14 J over rest at 1 x 1 and 100.36 at 1
// x 4 (100.1 at 1 x 16: the position solve's pivoting about the edge gains O(h) over a swing, and the landing
// takes it back), a tilt of 2.13e-3 rad, and at rest (below 1e-18 J) by 2.5 s.
TEST(RigidBody, ASlabStandingOnItsEdgeStaysStandingAndComesToRest) {
  const Real mass = 1e5, g = 9.81, halfThickness = 0.05, halfHeight = 1.5;
  const Real edgeInertia =
      mass * (4.0 * halfThickness * halfThickness + 4.0 * halfHeight * halfHeight) / 12.0 +
      mass * (halfThickness * halfThickness + halfHeight * halfHeight);
  const Real kick = 100.0;  // unit: J
  for (const int substeps : {1, 4}) {
    for (const bool kicked : {false, true}) {
      phys::World world({}, xpbd(substeps));
      BodyDesc slab = rigidBox({0.0, halfHeight, 0.0}, {2.0 * halfThickness, 2.0 * halfHeight, 3.0}, mass);
      if (kicked) {
        // Turning about its bottom edge at x = +b/2: w about -z, the centre moving as w x r.
        const Real w = std::sqrt(2.0 * kick / edgeInertia);
        slab.angularVelocity = Vec3(0.0, 0.0, -w);
        slab.velocity = glm::cross(slab.angularVelocity, Vec3(-halfThickness, halfHeight, 0.0));
      }
      const BodyId id = world.addBody(slab);
      const Real start = kicked ? kick : 0.0;
      // Tilt at which the potential energy has taken the kick (the height rises by (b/2) theta).
      const Real mostTilt = start / (mass * g * halfThickness);
      Real mostEnergy = 0.0, worstTilt = 0.0;
      for (int i = 0; i < 1200; ++i) {
        world.step();
        const phys::Metrics m = world.metrics();
        mostEnergy = std::max(mostEnergy, m.kineticEnergy + m.potentialEnergy - mass * g * halfHeight);
        const Vec3 up = world.bodyPose(id).orientation * Vec3(0.0, 1.0, 0.0);
        worstTilt = std::max(worstTilt, std::acos(std::min(1.0, up.y)));
      }
      const Real last = world.metrics().kineticEnergy;
      std::printf(
          "slab on its edge at 1 x %d, %s: most energy over rest %.5g J, most tilt %.3g rad, "
          "kinetic energy after 20 s %.3g J\n",
          substeps, kicked ? "kicked" : "still", mostEnergy, worstTilt, last);
      // Tolerances: 2 J over the kick (2%; still, over nothing), its tilt 10% past the analytic
      // bound plus 1e-5 rad, and at rest within 1 mJ.
      EXPECT_LT(mostEnergy, start + 2.0) << substeps << (kicked ? " kicked" : " still");
      EXPECT_LT(worstTilt, 1.1 * mostTilt + 1e-5) << substeps << (kicked ? " kicked" : " still");
      EXPECT_LT(last, 1e-3) << substeps << (kicked ? " kicked" : " still");
      EXPECT_EQ(world.metrics().frozen, 0);
    }
  }
}

// A stack of 10 unit boxes stands 10 s at 1/60 s with 4 substeps of one iteration (docs/physics.md:
// the patches from the ground up, shock propagation for resting ones). Measured: the top box moves
// 4 mm.
TEST(RigidBody, StackOfTenStands) {
  phys::World world({}, xpbd(4));
  BodyId top{};
  for (int k = 0; k < 10; ++k) top = world.addBody(rigidBox({0.0, 0.5 + k, 0.0}));
  const Vec3 start = world.bodyPose(top).center;
  for (int i = 0; i < 600; ++i) world.step();
  EXPECT_LT(glm::length(world.bodyPose(top).center - start), 0.02);
  EXPECT_EQ(world.metrics().frozen, 0);
}

// The stability suite's stack of 40 stands a minute at one substep of one iteration, as the issue
// asks (each patch one block, held at its anchor: docs/physics.md, "Standing for a minute").
// Measured: the top box moves under 0.1 mm (1.4 cm, 0.9 cm of it in the first 10 steps, before a
// face's block was solved directly); before the blocks and anchors it needed 2 x 12 to stand 4 s.
TEST(RigidBody, StackOfFortyStandsAMinuteAtOneSubstep) {
  phys::World world({}, xpbd(1));
  std::vector<BodyId> boxes;
  boxes.reserve(40);
  for (int k = 0; k < 40; ++k)
    boxes.push_back(world.addBody(rigidBox({k % 2 == 1 ? 0.01 : 0.0, 0.5 + k, 0.0})));
  const Vec3 start = world.bodyPose(boxes.back()).center;
  Real afterTenSteps = 0.0;
  for (int i = 1; i <= 3600; ++i) {
    world.step();
    if (i == 10) afterTenSteps = glm::length(world.bodyPose(boxes.back()).center - start);
  }
  const Real moved = glm::length(world.bodyPose(boxes.back()).center - start);
  std::printf("stack of 40 at 1 x 1: top box moved %.4f m in 10 steps, %.4f m in 60 s\n", afterTenSteps,
              moved);
  EXPECT_LT(moved, 0.03);
  EXPECT_EQ(world.metrics().frozen, 0);
}

// A pyramid of 10 rows, each box across the seam of two below, stands 20 s at one substep: a box's
// two patches are one block, so pushing on one does not tip it on the other. Measured: no box moves
// more than 1e-12 m (2e-11 m before a face's block was solved directly, 0.1 mm before the blocks started
// where the last substep ended); pushed patch by patch (and held only against each substep's slip) the top of
// the pyramid of 20 crept 0.57 m in a minute even at 8 substeps.
TEST(RigidBody, PyramidStandsAtOneSubstep) {
  phys::World world({}, xpbd(1));
  std::vector<std::pair<BodyId, Vec3>> boxes;
  const int rows = 10;
  for (int row = 0; row < rows; ++row) {
    for (int i = 0; i < rows - row; ++i) {
      const Vec3 at(-0.5 * (rows - row - 1) + i, 0.5 + row, 0.0);
      boxes.emplace_back(world.addBody(rigidBox(at)), at);
    }
  }
  for (int i = 0; i < 1200; ++i) world.step();
  Real worst = 0.0;
  for (const auto& [box, at] : boxes) worst = std::max(worst, glm::length(world.bodyPose(box).center - at));
  std::printf("pyramid of 10 rows at 1 x 1: worst box moved %.3g m in 20 s\n", worst);
  EXPECT_LT(worst, 1e-3);
  EXPECT_EQ(world.metrics().frozen, 0);
}

// Gravity tilted by theta from the ground's normal is a slope of theta. Below the friction angle
// (tan 25 deg = 0.47 < mu_s = 0.6) the box stays; above it (40 deg) it slides with
// a = g (sin - mu_d cos), 2.55 m/s^2, and covers a t^2 / 2 = 1.27 m in 1 s.
TEST(RigidBody, FrictionHoldsBelowTheFrictionAngleAndSlidesAtTheDynamicRateAbove) {
  const Real g = 9.81;
  for (const Real degrees : {25.0, 40.0}) {
    const Real theta = degrees * std::numbers::pi / 180.0;
    phys::WorldSettings w;
    w.gravity = {g * std::sin(theta), -g * std::cos(theta), 0.0};
    phys::World world(w, xpbd(8));
    const BodyId box = world.addBody(rigidBox({0.0, 0.5, 0.0}));
    for (int i = 0; i < 60; ++i) world.step();
    const Real slid = world.bodyPose(box).center.x;
    if (degrees < 30.0) {
      EXPECT_LT(std::abs(slid), 1e-3);
    } else {
      const Real a = g * (std::sin(theta) - 0.5 * std::cos(theta));
      EXPECT_NEAR(slid, 0.5 * a * world.time() * world.time(), 0.03);
    }
  }
}

// A solid ball (a capsule with no core) thrown sliding along the ground: friction turns slipping
// into rolling, and momentum about the contact point is kept, so it rolls on at 5/7 of the speed
// it was thrown at, with w r = v (Coulomb's and Euler's answer for a sphere).
TEST(RigidBody, ASlidingBallRollsOnAtFiveSeventhsOfItsSpeed) {
  phys::World world({}, xpbd(8));
  BodyDesc d = rigidBox({0.0, 0.25, 0.0}, Vec3(0.5));
  d.shape = phys::Shape::Capsule;
  d.velocity = {2.0, 0.0, 0.0};
  const BodyId ball = world.addBody(d);
  for (int i = 0; i < 120; ++i) world.step();
  const auto [v, w] = world.bodyVelocity(ball);
  EXPECT_NEAR(v.x, 2.0 * 5.0 / 7.0, 0.02);
  EXPECT_NEAR(-w.z * 0.25, v.x, 0.01);  // rolling: the contact point at rest
  EXPECT_NEAR(world.bodyPose(ball).center.y, 0.25, 1e-3);
}

// XPBD at one pass a substep and one substep of dt.
phys::SolverSettings xpbdAt(Real dt) {
  phys::SolverSettings s = xpbd(1);
  s.dt = dt;
  return s;
}

// A rigid capsule of `radius`, 0.4 m long, lying along x with its centre at `centre`.
BodyDesc lyingCapsule(const Vec3& centre, Real radius) {
  BodyDesc d = rigidBox(centre, {2.0 * radius, 0.4, 2.0 * radius});
  d.shape = phys::Shape::Capsule;
  d.orientation = glm::angleAxis(std::numbers::pi / 2.0, Vec3(0.0, 0.0, 1.0));
  return d;
}

// A rigid capsule (radius 0.05 m, 0.4 m long) lying on the ground rests with its core at its
// radius at any step: gravity takes it g h^2 into the ground each substep (0.88 m at dt 0.3), and
// its two ground points, the lowest points of its end spheres, must lift it back level. Pushed one
// after the other, each push tipped it on the other end: at one pass a substep it lay tilted, its
// low end 1.2 mm under the ground at 1/60 s and 2.2 cm at 0.1 s, and at 0.3 s it stood 65 degrees
// from level with its centre 0.25 m under the ground. Solved together, as a face's points are, it
// rises level. Tolerance: 1 micrometre (measured: 1.4e-9 m at 0.3 s), for the block's
// regularisation and round-off.
TEST(RigidBody, ALyingCapsuleRestsAtItsRadiusAtAnyStep) {
  const Real radius = 0.05;
  for (const Real dt : {1.0 / 60.0, 0.1, 0.3}) {
    phys::World world({}, xpbdAt(dt));
    const BodyId id = world.addBody(lyingCapsule({0.0, radius, 0.0}, radius));
    for (int i = 0; i < 60; ++i) world.step();
    const phys::BodyPose pose = world.bodyPose(id);
    const Vec3 along = pose.orientation * Vec3(0.0, 1.0, 0.0);
    EXPECT_NEAR(pose.center.y, radius, 1e-6) << dt;
    EXPECT_LT(world.metrics().maxPenetration, 1e-6) << dt;
    EXPECT_LT(std::abs(along.y), 1e-6) << dt;  // level
  }
}

// A rigid box lying on a rigid slab (1000 kg, 1 m thick) resting on the ground: neither moves, at
// any step and any number of passes. Shock propagation holds the lower body of a resting patch
// still and moves the upper one; which is lower was read from the two centres as a pass found
// them, after the slab's ground patch had already lifted the slab back from its fall of g h^2, and
// once that fall passed the 0.55 m between the centres (dt 0.25 s and over, from the second step,
// whose fall is a full g h^2) the box read as the lower: held there, it pushed the slab down to it,
// every pass, and both ended g h^2 into the ground (0.61 m at 0.25 s, 0.88 m at 0.3 s) for good.
// Which side is lower is now the patch's normal's. Tolerance: 1 micrometre, for the block's
// regularisation and round-off (`lab run` of the same scene after the fix: at most 1.1e-9 m deep, at
// 0.3 s and 1 pass).
TEST(RigidBody, ABoxOnARigidSlabKeepsItUpAtAnyStep) {
  for (const Real dt : {1.0 / 60.0, 0.1, 0.2, 0.25, 0.3}) {
    for (const int passes : {1, 2, 3}) {
      phys::SolverSettings s = xpbd(1, passes);
      s.dt = dt;
      phys::World world({}, s);
      const BodyId slab = world.addBody(rigidBox({0.0, 0.5, 0.0}, {4.0, 1.0, 4.0}, 1000.0));
      const BodyId box = world.addBody(rigidBox({0.0, 1.05, 0.0}, {0.4, 0.1, 0.1}));
      Real slabWorst = 0.0, boxWorst = 0.0, deepest = 0.0;
      for (int i = 0; i < 60; ++i) {
        world.step();
        slabWorst = std::max(slabWorst, std::abs(world.bodyPose(slab).center.y - 0.5));
        boxWorst = std::max(boxWorst, std::abs(world.bodyPose(box).center.y - 1.05));
        deepest = std::max(deepest, world.metrics().maxPenetration);
      }
      EXPECT_LT(slabWorst, 1e-6) << dt << " x " << passes;
      EXPECT_LT(boxWorst, 1e-6) << dt << " x " << passes;
      EXPECT_LT(deepest, 1e-6) << dt << " x " << passes;
    }
  }
}

// The same capsule lying on a rigid box (a 1000 kg slab 1 m thick resting on the ground) instead of
// the ground: its two points on the box come from the narrow phase, not the ground's capsule ends,
// and pushed one after the other each push tipped it on the other end, as on the ground. Measured
// after 60 steps at one pass a substep, point by point: its centre 0.59 mm under its resting height
// at 1/60 s and 7.9 mm at 0.1 s, 5.3 degrees from level. Solved as one block it rises level.
// Tolerance: 1 micrometre, as on the ground. At 0.25 and 0.3 s the slab itself fell g h^2 into the
// ground with the capsule in the second step, for another cause
// (RigidBody.ABoxOnARigidSlabKeepsItUpAtAnyStep).
TEST(RigidBody, ACapsuleLyingOnABoxRestsAtItsRadiusAtAnyStep) {
  const Real radius = 0.05;
  for (const Real dt : {1.0 / 60.0, 0.1, 0.2, 0.25, 0.3}) {
    phys::World world({}, xpbdAt(dt));
    const BodyId slab = world.addBody(rigidBox({0.0, 0.5, 0.0}, {4.0, 1.0, 4.0}, 1000.0));
    const BodyId id = world.addBody(lyingCapsule({0.0, 1.0 + radius, 0.0}, radius));
    for (int i = 0; i < 60; ++i) world.step();
    const phys::BodyPose pose = world.bodyPose(id);
    const Vec3 along = pose.orientation * Vec3(0.0, 1.0, 0.0);
    const Real top = world.bodyPose(slab).center.y + 0.5;  // the slab itself rests on the ground
    EXPECT_NEAR(pose.center.y - top, radius, 1e-6) << dt;
    EXPECT_LT(std::abs(along.y), 1e-6) << dt;  // level
  }
}

// The same capsule dropped tumbling from 1 m at dt 0.3 s, 1 substep of 3 passes: each pass turns it
// by as much as a radian, and a ground point left where the substep's start put it is then no longer
// the lowest point of its end sphere, which the pass leaves under the ground by up to the radius.
// Placed again before each pass, the points follow the turn. Measured, deepest below the ground
// after any step of 60 (the lowest point of its core's spheres), for the three spins: 3.0 cm, 1.4 mm
// and 2.2 cm with the points placed once a substep (and the second at rest 0.1 mm low); 0.06, 0.04
// and 0.17 mm placed before each pass. Tolerance: 1 mm.
TEST(RigidBody, ATumblingCapsuleLandsWithoutSinkingAtLongSteps) {
  const Real radius = 0.05;
  const Real degree = std::numbers::pi / 180.0;
  for (const Vec3& spin : {Vec3(300.0, 100.0, -200.0), Vec3(-100.0, 400.0, 50.0), Vec3(0.0, 0.0, 500.0)}) {
    phys::SolverSettings s = xpbd(1, 3);
    s.dt = 0.3;
    phys::World world({}, s);
    BodyDesc d = rigidBox({0.0, 1.0, 0.0}, {2.0 * radius, 0.4, 2.0 * radius});
    d.shape = phys::Shape::Capsule;
    d.orientation = glm::quat(Vec3(30.0, 20.0, 60.0) * degree);
    d.angularVelocity = spin * degree;
    const BodyId id = world.addBody(d);
    Real deepest = 0.0;
    for (int i = 0; i < 60; ++i) {
      world.step();
      deepest = std::max(deepest, world.metrics().maxPenetration);
    }
    std::printf(
        "capsule spun at (%g, %g, %g) deg/s, dropped at dt 0.3 x 1 x 3: deepest %.3g m, at rest %.3g m\n",
        spin.x, spin.y, spin.z, deepest, world.bodyPose(id).center.y);
    EXPECT_LT(deepest, 1e-3) << spin.x << " " << spin.y << " " << spin.z;
    EXPECT_NEAR(world.bodyPose(id).center.y, radius, 1e-6);
  }
}

// A box dropped flat from 1 m with e = 0.5 rises to e^2 = 25 cm; the bounce is the velocity pass's
// (restitution of each point, Müller et al. 2020), and a flat landing stays flat.
TEST(RigidBody, RestitutionGivesBackTheSquareOfItsCoefficientInHeight) {
  phys::SolverSettings s = xpbd(8);
  s.restitution = 0.5;
  phys::World world({}, s);
  const BodyId box = world.addBody(rigidBox({0.0, 1.5, 0.0}));
  bool landed = false;
  Real highest = 0.0;
  for (int i = 0; i < 120; ++i) {
    world.step();
    const Real y = world.bodyPose(box).center.y;
    if (y < 0.52) landed = true;
    if (landed) highest = std::max(highest, y - 0.5);
  }
  EXPECT_TRUE(landed);
  EXPECT_NEAR(highest, 0.25, 0.02);
}

// A 1 m box on another at the origin, one rigid and the other a corners box; returns the upper one.
BodyId addMixedPair(phys::World& world, bool rigidOnTop, const Vec3& upperAt) {
  BodyDesc bottom = rigidBox({0.0, 0.5, 0.0}), top = rigidBox(upperAt);
  (rigidOnTop ? bottom : top).model = BodyModel::Corners;
  world.addBody(bottom);
  return world.addBody(top);
}

// Mixed models: a rigid box on a particle box, and a particle box on a rigid one, rest where they
// are put (the contacts between models are solved by the rigid passes, both sides by their own
// inverse masses).
TEST(RigidBody, RestsOnParticleBodiesAndCarriesThem) {
  for (const bool rigidOnTop : {true, false}) {
    phys::World world({}, xpbd(4, 2));
    const BodyId upper = addMixedPair(world, rigidOnTop, {0.0, 1.5, 0.0});
    for (int i = 0; i < 300; ++i) world.step();
    const phys::BodyPose pose = world.bodyPose(upper);
    EXPECT_NEAR(pose.center.y, 1.5, 0.01) << rigidOnTop;
    EXPECT_LT(std::hypot(pose.center.x, pose.center.z), 0.01) << rigidOnTop;
    EXPECT_FALSE(world.rigidBodyContacts().empty());
  }
}

// A particle box on a rigid box, off its centre (docs/physics.md, "Failures at rest"), and a rigid box
// on a particle one, at the default 3 x 1: after 10 s of settling, neither moves nor turns over the
// next 50 s, as boxes of one model on each other do. Measured: 7e-10 m and 3e-6 degrees (the
// corners box), 1.1e-7 m (the rigid box). Before, the corners box's patch held its slide against
// the substep's own motion only with the wrong weights (37% too light), its twist not at all, and
// the pair's normal was the corners box's wobbling face every other step: the corners box turned
// 38 degrees and moved 6 cm in a minute, the rigid box 0.4 mm.
TEST(RigidBody, AParticleBoxAndARigidBoxRestOnEachOtherStill) {
  for (const bool rigidOnTop : {false, true}) {
    phys::World world({}, phys::SolverSettings{});
    const BodyId upper = addMixedPair(world, rigidOnTop, {0.2, 1.5, 0.1});
    for (int i = 0; i < 600; ++i) world.step();
    const phys::BodyPose settled = world.bodyPose(upper);
    for (int i = 0; i < 3000; ++i) world.step();
    const phys::BodyPose pose = world.bodyPose(upper);
    const Real moved = glm::length(pose.center - settled.center);
    const Real turned = testing_phys::angleBetween(settled.orientation, pose.orientation);
    std::printf("%s box on a %s box at 3 x 1, 10 s to 60 s: moved %.3g m, turned %.3g rad\n",
                rigidOnTop ? "rigid" : "corners", rigidOnTop ? "corners" : "rigid", moved, turned);
    EXPECT_LT(moved, 1e-6) << rigidOnTop;
    EXPECT_LT(turned, 1e-6) << rigidOnTop;
    EXPECT_EQ(world.metrics().frozen, 0);
  }
}

// Between a rigid box and a particle box resting face on face, the contact's normal is the rigid box's
// face normal in every step: taken from the particle box's fitted frame whenever that was the
// shallower axis, it tilted by up to 5e-4 rad every other step (PreferFaces).
TEST(RigidBody, ARigidBoxsFaceIsTheNormalOfItsContactWithAParticleBox) {
  phys::World world({}, phys::SolverSettings{});
  BodyDesc top = rigidBox({0.2, 1.5, 0.1});
  top.model = BodyModel::Corners;
  const BodyId rigid = world.addBody(rigidBox({0.0, 0.5, 0.0}));
  world.addBody(top);
  Real worst = 0.0;
  for (int i = 0; i < 120; ++i) {
    world.step();
    ASSERT_FALSE(world.rigidBodyContacts().empty());
    // The contacts are found at the step's start, and the rigid box turns by 1e-8 rad at most as
    // the other settles: its face's normal as the step left it is within that.
    const Vec3 face = world.bodyPose(rigid).orientation * Vec3(0.0, 1.0, 0.0);
    for (const phys::RigidContact& c : world.rigidBodyContacts())
      worst = std::max(worst, glm::length(c.normal - face));
  }
  std::printf("the contact's normal from the rigid box's face: %.3g at most\n", worst);
  EXPECT_LT(worst, 1e-7);
}

// The mouse spring holds a 1 kg rigid box by its centre at m g / k below the target (4.9 mm at the
// default 2000 N/m), as it holds a particle box (drag_test.cpp).
TEST(RigidBody, TheDragHoldsItsWeightAtMgOverK) {
  phys::WorldSettings w;
  w.ground = false;
  {
    phys::World world(w, xpbd(4));
    const BodyId id = world.addBody(rigidBox(Vec3(0.0)));
    world.setDrag(world.dragAt(id, Vec3(0.0)));
    EXPECT_EQ(world.drag()->body, id);
    for (int i = 0; i < 300; ++i) world.step();
    EXPECT_NEAR(world.dragPoint().y, -9.81 / phys::kDragStiffness, 1e-6);
    EXPECT_NEAR(world.dragPoint().x, 0.0, 1e-9);
    world.setDragTarget({1.0, 0.0, 0.0});  // and follows the target
    for (int i = 0; i < 300; ++i) world.step();
    EXPECT_NEAR(world.bodyPose(id).center.x, 1.0, 1e-6);
  }
  phys::World world;
  world.addParticle({Vec3(0.0, 5.0, 0.0)});
  const BodyId box = world.addBody(BodyDesc{});  // a particle body: its drag is an embedding
  EXPECT_EQ(world.dragAt(box, Vec3(0.0)).body, phys::kNoBody);
  phys::Drag bad;
  bad.body = box;
  EXPECT_THROW(world.setDrag(bad), std::invalid_argument);
}

TEST(RigidBody, TheGuardFreezesABodyThatLeavesTheBound) {
  phys::WorldSettings w = noGravity();
  w.bound = 10.0;
  phys::World world(w, xpbd(1));
  BodyDesc d = rigidBox(Vec3(0.0));
  d.velocity = {600.0, 0.0, 0.0};  // 10 m a step
  const BodyId id = world.addBody(d);
  for (int i = 0; i < 5; ++i) world.step();
  ASSERT_EQ(world.freezes().size(), 1u);
  EXPECT_EQ(world.freezes()[0].body, id);
  EXPECT_NE(world.freezes()[0].reason.find("bound"), std::string::npos);
  EXPECT_EQ(world.metrics().frozen, 1);
  EXPECT_LE(std::abs(world.bodyPose(id).center.x), 10.0);
  EXPECT_TRUE(std::isfinite(world.metrics().energy()));
}

TEST(RigidBody, BadInputIsRefusedAndNothingIsAdded) {
  phys::World world;
  BodyDesc d = rigidBox(Vec3(0.0));
  d.mass = 1e-320;  // 1 / m overflows
  EXPECT_THROW(world.addBody(d), std::invalid_argument);
  d = rigidBox(Vec3(0.0), Vec3(1e-170));  // m (b^2 + c^2) / 12 underflows to 0
  EXPECT_THROW(world.addBody(d), std::invalid_argument);
  EXPECT_TRUE(world.bodies().empty());
  EXPECT_EQ(world.rigidBodies().size(), 0u);
  const BodyId id = world.addBody(rigidBox(Vec3(0.0)));
  EXPECT_THROW(static_cast<void>(world.anchor(id, Vec3(0.0))), std::invalid_argument);
}

TEST(RigidBody, SameInputSameState) {
  auto run = [] {
    phys::World world({}, xpbd(4));
    for (int k = 0; k < 5; ++k) {
      BodyDesc d = rigidBox({0.1 * k, 0.6 + 1.1 * k, 0.0});
      d.angularVelocity = {0.3 * k, 0.0, 0.1};
      world.addBody(d);
    }
    for (int i = 0; i < 120; ++i) world.step();
    return world.stateHash();
  };
  EXPECT_EQ(run(), run());
}

// A face patch solved as a block starts each substep from the normal impulses its last substep
// ended with (PatchAnchor::normal). A substep in which the patch does not press must leave it
// none, or the next press would start from impulses of a substep before. A unit cube on the ground:
// pressing 1 mm into it, then 10 cm above it, each a substep of the passes' own functions.
TEST(RigidBody, APatchThatDidNotPressKeepsNoImpulseForTheNextSubstep) {
  phys::Particles particles;
  phys::RigidBodies r;
  r.position = {Vec3(0.0, 0.499, 0.0)};
  r.orientation = {phys::Quat(1.0, 0.0, 0.0, 0.0)};
  r.previousPosition = r.position;
  r.previousOrientation = r.orientation;
  r.velocity = r.angularVelocity = {Vec3(0.0)};
  r.inverseMass = {1.0};
  r.inverseInertia = {Vec3(6.0)};  // a solid unit cube of 1 kg: I = 1/6 kg m^2
  r.inverseInertiaWorld = {glm::dmat3(6.0)};
  r.body = {BodyId{0}};
  r.jointed = {0};
  std::vector<phys::RigidContact> contacts;
  for (const Real x : {-0.5, 0.5}) {
    for (const Real z : {-0.5, 0.5}) {
      phys::RigidContact c;
      c.bodyB = BodyId{0};
      c.localB = Vec3(x, -0.5, z);
      c.normal = Vec3(0.0, 1.0, 0.0);
      contacts.push_back(c);
    }
  }
  const phys::RigidPassInput in{particles, r, Vec3(0.0, 1.0, 0.0), 0.0, 1.0 / 60.0, 0.1};
  phys::RigidContactState state;
  state.resize(contacts.size());
  std::vector<phys::ContactPatch> patches;
  auto substep = [&](Real height) {
    r.position[0].y = r.previousPosition[0].y = height;
    phys::detail::measureRigidGroundStarts(in, contacts, state);
    phys::detail::startRigidContacts(in, contacts, state, 1.0);
    phys::detail::findPatches(in, contacts, patches);
    phys::detail::carryAnchors(contacts, patches, state);
    phys::detail::solveRigidContacts(in, contacts, patches, state);
    EXPECT_EQ(patches.size(), 1u);
    return state.anchors[patches[0].anchor];
  };
  const phys::PatchAnchor pressed = substep(0.499);
  ASSERT_EQ(pressed.points, 4);
  for (int k = 0; k < 4; ++k) EXPECT_GT(pressed.normal[k], 0.0) << "point " << k;
  const phys::PatchAnchor apart = substep(0.6);
  for (int k = 0; k < apart.points; ++k) EXPECT_EQ(apart.normal[k], 0.0) << "point " << k;
}

}  // namespace

// The lowest point of a shape at a pose (what the lab's peers measure their penetration by):
// the analytic heights of a box and a capsule standing, lying and tilted, along a tilted "up" too.
TEST(LowestAlong, BoxesAndCapsulesAtAnyPose) {
  using phys::Quat;
  using phys::Vec3;
  const Vec3 up(0.0, 1.0, 0.0);
  const Quat standing(1.0, 0.0, 0.0, 0.0);
  const Quat lying = glm::angleAxis(std::numbers::pi / 2.0, Vec3(0.0, 0.0, 1.0));
  const Quat tilted = glm::angleAxis(std::numbers::pi / 4.0, Vec3(0.0, 0.0, 1.0));
  const Vec3 centre(3.0, 2.0, -1.0);
  const Vec3 box(1.0, 0.5, 0.25);
  EXPECT_NEAR(phys::lowestAlong(phys::Shape::Box, box, {centre, standing}, up), 1.5, 1e-12);
  EXPECT_NEAR(phys::lowestAlong(phys::Shape::Box, box, {centre, lying}, up), 1.0, 1e-12);
  // Tilted 45 degrees about z: the lowest corner is down by (hx + hy) / sqrt(2).
  EXPECT_NEAR(phys::lowestAlong(phys::Shape::Box, box, {centre, tilted}, up), 2.0 - 1.5 / std::sqrt(2.0),
              1e-12);
  // A capsule inscribed in a 0.4 x 2 x 0.4 box: radius 0.2, core from -0.8 to 0.8 along y.
  const Vec3 capsule(0.2, 1.0, 0.2);
  EXPECT_NEAR(phys::lowestAlong(phys::Shape::Capsule, capsule, {centre, standing}, up), 1.0, 1e-12);
  EXPECT_NEAR(phys::lowestAlong(phys::Shape::Capsule, capsule, {centre, lying}, up), 1.8, 1e-12);
  EXPECT_NEAR(phys::lowestAlong(phys::Shape::Capsule, capsule, {centre, tilted}, up),
              2.0 - 0.8 / std::sqrt(2.0) - 0.2, 1e-12);
  // Along another "up" (a sloped ground's normal) the same capsule standing: its core's end and
  // its radius, measured along that normal.
  const Vec3 slope = glm::normalize(Vec3(1.0, 1.0, 0.0));
  EXPECT_NEAR(phys::lowestAlong(phys::Shape::Capsule, capsule, {centre, standing}, slope),
              glm::dot(slope, centre) - 0.8 / std::sqrt(2.0) - 0.2, 1e-12);
}

// World::bodyMass against the analytic moments: eight corner particles of M/8 at (+-hx, +-hy,
// +-hz) give I_xx = M (hy^2 + hz^2); the solid box M (hy^2 + hz^2) / 3. The peers build their
// bodies from these, so a wrong moment would make every engine turn a box differently from ours.
TEST(BodyMass, CornersAndSolidBoxesHaveTheirAnalyticMoments) {
  phys::World world = testing_phys::openSpace();
  BodyDesc d;
  d.size = Vec3(2.0, 4.0, 6.0);  // half extents 1, 2, 3
  d.mass = 8.0;
  d.model = BodyModel::Corners;
  const BodyId corners = world.addBody(d);
  d.model = BodyModel::Rigid;
  d.center = Vec3(10.0, 0.0, 0.0);
  const BodyId solid = world.addBody(d);

  const phys::BodyMass c = world.bodyMass(corners);
  EXPECT_FALSE(c.fixed());
  EXPECT_DOUBLE_EQ(c.mass, 8.0);
  EXPECT_NEAR(c.inertia.x, 8.0 * (4.0 + 9.0), 1e-12);
  EXPECT_NEAR(c.inertia.y, 8.0 * (1.0 + 9.0), 1e-12);
  EXPECT_NEAR(c.inertia.z, 8.0 * (1.0 + 4.0), 1e-12);

  const phys::BodyMass s = world.bodyMass(solid);
  EXPECT_DOUBLE_EQ(s.mass, 8.0);
  EXPECT_NEAR(s.inertia.x, 8.0 * (4.0 + 9.0) / 3.0, 1e-12);
  EXPECT_NEAR(s.inertia.y, 8.0 * (1.0 + 9.0) / 3.0, 1e-12);
  EXPECT_NEAR(s.inertia.z, 8.0 * (1.0 + 4.0) / 3.0, 1e-12);
  EXPECT_THROW((void)world.bodyMass(BodyId{7}), std::invalid_argument);
}

// World::poseVelocity gives back a body's starting motion at load: each particle's velocity is
// stored half a substep back (v - g h / 2), and poseVelocity moves it on again, so a thrown box of
// either model reads as thrown. The spin is about a principal axis, which Euler's equations keep.
TEST(BodyMass, PoseVelocityIsTheVelocityABodyWasGiven) {
  for (const BodyModel model : {BodyModel::Corners, BodyModel::Tetra, BodyModel::Rigid}) {
    phys::World world = testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::GaussSeidel, 2, 4));
    BodyDesc d;
    d.size = Vec3(1.0, 2.0, 3.0);
    d.center = Vec3(0.0, 5.0, 0.0);
    d.model = model;
    d.velocity = Vec3(1.0, -2.0, 0.5);
    d.angularVelocity = Vec3(3.0, 0.0, 0.0);
    const BodyId id = world.addBody(d);
    const auto [velocity, spin] = world.poseVelocity(id);
    EXPECT_NEAR(glm::length(velocity - d.velocity), 0.0, 1e-12) << phys::toString(model);
    EXPECT_NEAR(glm::length(spin - d.angularVelocity), 0.0, 1e-12) << phys::toString(model);
  }
}
