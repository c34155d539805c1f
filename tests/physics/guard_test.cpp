// The guard: a particle or body that goes non-finite or leaves the world bound is frozen where
// it last was good, reported by name, and the rest of the world keeps stepping.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "passes.h"
#include "physics/capsule_ragdoll.h"
#include "physics/guard.h"
#include "test_util.h"

namespace {

using phys::Vec3;

TEST(Guard, BoxLeavingTheBoundIsFrozenAndReportedByName) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.bound = 100.0;
  phys::World world(ws);
  std::vector<phys::FreezeReport> reported;
  world.setFreezeCallback([&](const phys::FreezeReport& r) { reported.push_back(r); });
  phys::BodyDesc runaway;
  runaway.name = "runaway";
  runaway.center = {90.0, 0.0, 0.0};
  runaway.velocity = {600.0, 0.0, 0.0};  // 10 m per step: out within two steps
  world.addBody(runaway);
  const auto bystander = world.addParticle({Vec3(0.0), Vec3(0.0), 1.0, false, "bystander"});

  for (int i = 0; i < 60; ++i) world.step();

  ASSERT_EQ(reported.size(), 1u);
  EXPECT_EQ(reported[0].name, "runaway");
  EXPECT_NE(reported[0].reason.find("bound"), std::string::npos) << reported[0].reason;
  EXPECT_EQ(world.freezes().size(), 1u);
  EXPECT_EQ(world.metrics().frozen, 8);  // the whole box, not just the first corner
  const phys::BodyPose pose = world.bodyPose(phys::BodyId{0});
  EXPECT_LE(pose.center.x, 110.0);  // stopped where it was caught, not flying on
  // The bystander fell freely all along: 1 s of free fall.
  EXPECT_NEAR(world.particles().position[bystander].y, -0.5 * 9.81, 1e-9);
}

TEST(Guard, NonFinitePositionIsFrozenAtItsLastGoodPlace) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.gravity = Vec3(0.0);
  ws.bound = std::numeric_limits<double>::max();  // let it run to overflow
  phys::World world(ws);
  const double big = 1.0e308;
  const auto id = world.addParticle({Vec3(big, 0.0, 0.0), Vec3(1.7e308, 0.0, 0.0), 1.0, false, "overflow"});
  for (int i = 0; i < 100; ++i) world.step();  // overflows to infinity after about 28 steps
  ASSERT_EQ(world.freezes().size(), 1u);
  EXPECT_EQ(world.freezes()[0].name, "overflow");
  EXPECT_EQ(world.freezes()[0].reason, "non-finite position");
  EXPECT_TRUE(std::isfinite(world.particles().position[id].x));
  EXPECT_EQ(world.particles().inverseMass[id], 0.0);
  const auto m = world.metrics();
  EXPECT_TRUE(std::isfinite(m.energy()));
  EXPECT_EQ(m.frozen, 1);
}

// Found by the soak test (seed 21): more passes relax a world at once, outside the step
// (setSolverSettings' settling), and a stick 2e308 m long made its particles NaN there, with no
// guard after it; the next step copied the NaN as their last good place and froze them at it.
// Now the settings change ends with the guard's look at every particle.
TEST(Guard, ASettingsChangeThatOverflowsFreezesAtTheLastGoodPlace) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.gravity = Vec3(0.0);
  ws.bound = std::numeric_limits<double>::infinity();
  phys::World world(ws);
  const auto a = world.addParticle({Vec3(1e308, 0.0, 0.0), Vec3(0.0), 1.0, false, "a"});
  const auto b = world.addParticle({Vec3(-1e308, 0.0, 0.0), Vec3(0.0), 1.0, false, "b"});
  world.addStick(a, b, 1.0, 0.0);  // its length overflows: every correction is NaN
  phys::SolverSettings more = world.solverSettings();
  more.iterations *= 4;  // stiffer: settles at once
  world.setSolverSettings(more);
  for (const auto id : {a, b}) {
    EXPECT_EQ(world.particles().position[id].x, id == a ? 1e308 : -1e308) << id;  // where it was made
    EXPECT_EQ(world.particles().inverseMass[id], 0.0) << id;
  }
  ASSERT_EQ(world.freezes().size(), 2u);
  EXPECT_EQ(world.freezes()[0].reason, "non-finite position");
  world.step();
  for (const auto id : {a, b}) EXPECT_TRUE(phys::finite(world.particles().position[id])) << id;
}

// A pinned particle tied to one gone NaN: every method's correction is NaN, but a pinned end is
// never written (0 times NaN would still be NaN), so it stays exactly put for the guard to see
// the real culprit. Tested on the passes themselves, since a NaN cannot be made through the API.
TEST(Guard, PinnedEndOfANaNStickIsNeverWritten) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto fresh = [&] {
    phys::Particles p;
    p.position = {Vec3(0.0), Vec3(nan, 0.0, 0.0)};
    p.previous = {Vec3(0.0), Vec3(1.0, 0.0, 0.0)};
    p.inverseMass = {0.0, 1.0};
    return p;
  };
  const std::vector<phys::Stick> sticks{{phys::ParticleId{0}, phys::ParticleId{1}, 1.0, 1.0, 0.0}};
  std::vector<double> lambda(1, 0.0), degree{1.0, 1.0};
  std::vector<Vec3> delta(2, Vec3(0.0));
  const phys::StickLayout layout = phys::StickLayout::inOrder(sticks.size());
  phys::Particles p = fresh();
  phys::detail::relaxGaussSeidel(p, sticks, layout);
  EXPECT_EQ(p.position[0], Vec3(0.0)) << "gauss-seidel";
  p = fresh();
  phys::detail::relaxJacobi(p, sticks, layout, degree, delta);
  EXPECT_EQ(p.position[0], Vec3(0.0)) << "jacobi";
  p = fresh();
  phys::detail::relaxXpbd(p, sticks, layout, lambda, 1.0 / 60.0, 0.0);
  EXPECT_EQ(p.position[0], Vec3(0.0)) << "xpbd";
  p = fresh();
  phys::detail::relaxShake(p, sticks, layout);
  EXPECT_EQ(p.position[0], Vec3(0.0)) << "shake";
  p = fresh();
  phys::Embedding both;
  both.particle = {phys::ParticleId{0}, phys::ParticleId{1}, phys::ParticleId{}, phys::ParticleId{}};
  both.weight = {0.5, 0.5, 0.0, 0.0};
  both.count = 2;
  phys::detail::moveEmbedded(p.position, p.inverseMass, both, Vec3(nan));
  EXPECT_EQ(p.position[0], Vec3(0.0)) << "embedded point";
}

// Under 10,000 m/s^2 a corners box on the ground is pressed flat within a step, 73% off in its
// worst stick, and stays flat: its sticks then lie in the ground's plane and cannot lift it. A
// tetra box stands 10,000 but not 1e6 m/s^2: it is torn (83%) and thrown 61 m up in a second.
// Each is frozen kCrushedTime later where the guard last checked it, the substep before, and
// reported as crushed. The tetra box hangs by a slack link from a pin far above, which never pulls:
// a free tetra box's corners move it as a rigid body (GroundContacts::markFreeTetraBoxes), which
// gravity alone, however strong, does not tear; joined to something, it is pushed by its corners'
// weights, as a stacked or jointed one is.
TEST(Guard, ABoxCrushedByHugeGravityIsFrozenAndReported) {
  for (const phys::BodyModel model : {phys::BodyModel::Corners, phys::BodyModel::Tetra}) {
    phys::WorldSettings ws;
    ws.gravity = Vec3(0.0, model == phys::BodyModel::Corners ? -1.0e4 : -1.0e6, 0.0);
    phys::World world(ws);
    phys::BodyDesc d;
    d.name = "crate";
    d.center = Vec3(0.0, 0.5, 0.0);
    d.model = model;
    const phys::BodyId crate = world.addBody(d);
    if (model == phys::BodyModel::Tetra) {
      phys::ParticleDesc pin;
      pin.position = Vec3(0.0, 100.0, 0.0);
      pin.pinned = true;
      const phys::ParticleId above = world.addParticle(pin);
      world.addLink(world.anchor(crate, d.center), phys::embedParticle(above), 0.0, 1.0e3);
    }
    std::vector<Vec3> last;
    for (int i = 0; i < 180 && world.freezes().empty(); ++i) {
      last = world.particles().position;
      world.step();
    }
    ASSERT_EQ(world.freezes().size(), 1u) << phys::toString(model);
    EXPECT_EQ(world.freezes()[0].name, "crate");
    EXPECT_EQ(world.freezes()[0].reason.rfind("crushed", 0), 0u) << world.freezes()[0].reason;
    // It went past the limit in the first step, at 1/60 s, and is caught kCrushedTime after that,
    // when the guard next looks at shapes (every 0.1 s), to a step of round-off in the clock.
    EXPECT_GE(world.freezes()[0].time, phys::kCrushedTime + 1.0 / 60.0 - 1e-9);
    EXPECT_LE(world.freezes()[0].time, phys::kCrushedTime + 1.0 / 60.0 + 0.1 + 1.0 / 60.0 + 1e-9);
    for (std::size_t j = 0; j < last.size(); ++j) {
      EXPECT_EQ(world.particles().position[j], last[j]) << phys::toString(model) << " particle " << j;
      EXPECT_EQ(world.particles().previous[j], last[j]);  // at rest
    }
    const phys::BodyPose pose = world.bodyPose(phys::BodyId{0});
    EXPECT_TRUE(phys::finite(pose.center) && std::isfinite(glm::length(pose.orientation)));
  }
}

// The limit is not reached by a world that merely strains a body: at 2,500 m/s^2 a box rests
// squashed by 20% (three passes cannot undo more of a step of that gravity). And a body past it
// for a moment is not frozen: a box dropped at 80 m/s with one pass a step is squashed 85% as it
// lands, for 0.1 s, and comes back whole.
TEST(Guard, ABoxSquashedOrSquashedForAMomentIsNotFrozen) {
  {
    phys::WorldSettings ws;
    ws.gravity = Vec3(0.0, -2500.0, 0.0);
    phys::World world(ws);
    phys::BodyDesc d;
    d.center = Vec3(0.0, 0.5, 0.0);
    world.addBody(d);
    for (int i = 0; i < 180; ++i) world.step();
    EXPECT_TRUE(world.freezes().empty()) << world.freezes()[0].reason;
    EXPECT_GT(world.metrics().maxConstraintError, 0.15);
  }
  phys::SolverSettings one;
  one.iterations = 1;
  phys::World world(phys::WorldSettings{}, one);
  phys::BodyDesc d;
  d.center = Vec3(0.0, 1.0, 0.0);
  d.velocity = Vec3(0.0, -80.0, 0.0);
  d.orientation = glm::angleAxis(0.5, glm::normalize(Vec3(1.0, 0.2, 0.4)));  // lands on a corner
  world.addBody(d);
  double worst = 0.0;
  for (int i = 0; i < 300; ++i) {
    world.step();
    worst = std::max(worst, world.metrics().maxConstraintError);
  }
  EXPECT_GT(worst, phys::kCrushedStickError);  // the limit was passed
  EXPECT_TRUE(world.freezes().empty()) << world.freezes()[0].reason;
  EXPECT_LT(world.metrics().maxConstraintError, 0.05);  // and the box is whole again
}

// A box that leaves the bound stops where it last was inside it, at the end of the substep before,
// not out where it was caught.
TEST(Guard, ABoxLeavingTheBoundIsFrozenAtItsLastPlaceInside) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.gravity = Vec3(0.0);
  ws.bound = 100.0;
  phys::World world(ws);
  phys::BodyDesc d;
  d.center = Vec3(85.0, 0.0, 0.0);
  d.velocity = Vec3(600.0, 0.0, 0.0);  // 10 m a step: at 95 after one, its far face at 95.5
  world.addBody(d);
  for (int i = 0; i < 5; ++i) world.step();
  ASSERT_EQ(world.freezes().size(), 1u);
  EXPECT_NEAR(world.freezes()[0].time, 2.0 / 60.0, 1e-12);  // caught at 105, in the second step
  EXPECT_NEAR(world.bodyPose(phys::BodyId{0}).center.x, 95.0, 1e-9);
  for (int j = 0; j < 8; ++j) {
    EXPECT_LE(world.particles().position[j].x, 100.0);
    EXPECT_EQ(world.particles().position[j], world.particles().previous[j]);  // at rest
  }
}

// A rigid box half buried in the ground is parted out of it at the substep's start, its previous
// pose moved with it; lifted past the bound, it is frozen where the substep started, inside it, not
// at its previous pose out there (found by the scene fuzzer: the writer then refused the world).
TEST(Guard, ARigidBoxPartedPastTheBoundIsFrozenWhereItStarted) {
  phys::WorldSettings ws;
  ws.bound = 100.0;
  phys::World world(ws);
  phys::BodyDesc d = testing_phys::rigidBox(Vec3(0.0), Vec3(400.0));  // 200 m into the ground
  world.addBody(d);
  world.step();
  ASSERT_EQ(world.freezes().size(), 1u);
  EXPECT_NE(world.freezes()[0].reason.find("left the world bound"), std::string::npos);
  const phys::BodyPose pose = world.bodyPose(phys::BodyId{0});
  EXPECT_EQ(pose.center, Vec3(0.0));
  for (int i = 0; i < 3; ++i) world.step();
  EXPECT_EQ(world.bodyPose(phys::BodyId{0}).center, Vec3(0.0));  // frozen: it stays
}

// Gravity of 1e308 m/s^2 on a capsule ragdoll: every part leaves the bound (or overflows) in the
// first substep. Each is frozen where it was created, so every pose is finite and where it was,
// and so is every figure metrics() gives of the world after a step.
TEST(Guard, UnderGravityOf1e308EveryFrozenPoseAndEveryMetricIsFinite) {
  for (const phys::RagdollModel model : {phys::RagdollModel::Seed, phys::RagdollModel::Lean}) {
    phys::WorldSettings ws;
    ws.ground = false;
    ws.gravity = Vec3(1e308, 1e308, -1e308);
    phys::World world(ws);
    phys::RagdollDesc d;
    d.hips = Vec3(0.0, 1.0, 0.0);
    d.model = model;
    const phys::CapsuleRagdoll r = phys::addCapsuleRagdoll(world, d);
    std::vector<phys::BodyPose> placed;
    for (const phys::BodyId part : r.parts) placed.push_back(world.bodyPose(part));
    for (int i = 0; i < 3; ++i) world.step();
    EXPECT_EQ(world.freezes().size(), static_cast<std::size_t>(phys::kCapsuleParts));
    for (int k = 0; k < phys::kCapsuleParts; ++k) {
      const phys::BodyPose pose = world.bodyPose(r.parts[k]);
      ASSERT_TRUE(phys::finite(pose.center) && std::isfinite(pose.orientation.w) &&
                  std::isfinite(pose.orientation.x) && std::isfinite(pose.orientation.y) &&
                  std::isfinite(pose.orientation.z))
          << "part " << k;
      EXPECT_NEAR(glm::length(pose.center - placed[k].center), 0.0, 1e-12) << "part " << k;
      EXPECT_NEAR(testing_phys::angleBetween(pose.orientation, placed[k].orientation), 0.0, 1e-6);
    }
    const phys::Metrics m = world.metrics();
    for (const double figure : {m.kineticEnergy, m.potentialEnergy, m.maxConstraintError,
                                m.rmsConstraintError, m.maxJointError, m.maxPenetration, m.maxSpeed}) {
      EXPECT_TRUE(std::isfinite(figure)) << phys::toString(model);
    }
    EXPECT_EQ(m.frozen, static_cast<int>(world.particles().size()));
  }
}

}  // namespace

// Guard::checkParticles first asks one pass over all coordinates whether anything is wrong, and
// looks at each particle only then: every kind of bad coordinate, on each axis and at each place
// in the array (the pass runs in SIMD lanes, whose last lane a short array leaves half used), must
// still be found, and a coordinate exactly on the bound is in it.
TEST(Guard, EveryBadCoordinateIsFoundWhereverItIs) {
  constexpr double kBound = 100.0;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    bool previous;  // the bad value in x* rather than x
    double value;
    const char* reason;
  };
  const std::vector<Case> cases = {
      {false, nan, "non-finite position"},
      {false, kInf, "non-finite position"},
      {false, -kInf, "non-finite position"},
      {false, 100.5, "left the world bound of 100 m"},
      {false, -1e300, "left the world bound of 100 m"},
      {true, nan, "non-finite velocity"},
      {true, -kInf, "non-finite velocity"},
  };
  for (std::size_t count : {1u, 2u, 5u}) {
    for (const Case& c : cases) {
      for (std::size_t bad = 0; bad < count; ++bad) {
        for (int axis = 0; axis < 3; ++axis) {
          phys::Particles particles;
          phys::Guard guard;
          for (std::size_t i = 0; i < count; ++i) {
            const Vec3 x(kBound, -kBound, 0.5 * static_cast<double>(i));  // on the bound: good
            particles.position.push_back(x);
            particles.previous.push_back(x);
            particles.inverseMass.push_back(1.0);
            guard.addParticle(x);
          }
          (c.previous ? particles.previous : particles.position)[bad][axis] = c.value;
          const std::vector<std::string> names(count);
          const std::vector<phys::BodyId> bodies(count, phys::kNoBody);
          guard.checkParticles({particles, {}, {}, names, bodies, 0.0}, kBound);
          const std::string where = std::to_string(count) + " particles, the bad one " + std::to_string(bad) +
                                    ", axis " + std::to_string(axis) + ", " + c.reason;
          ASSERT_EQ(guard.freezes().size(), 1u) << where;
          EXPECT_EQ(guard.freezes()[0].particle, phys::ParticleId(bad)) << where;
          EXPECT_EQ(guard.freezes()[0].reason, c.reason) << where;
        }
      }
    }
  }
  // Nothing wrong: nothing frozen, the bound itself included.
  phys::Particles particles;
  phys::Guard guard;
  for (const Vec3& x : {Vec3(kBound, -kBound, kBound), Vec3(-kBound, 0.0, 99.999)}) {
    particles.position.push_back(x);
    particles.previous.push_back(x);
    particles.inverseMass.push_back(1.0);
    guard.addParticle(x);
  }
  const std::vector<std::string> names(2);
  const std::vector<phys::BodyId> bodies(2, phys::kNoBody);
  guard.checkParticles({particles, {}, {}, names, bodies, 0.0}, kBound);
  EXPECT_TRUE(guard.freezes().empty());
}

// On the step's threads the look runs in ranges of at most 2,048 particles (5,000 are halved into
// four of 1,250): a bad coordinate at either end of any range is found and frozen as on one thread.
TEST(Guard, OnThreadsTheLookFindsABadCoordinateInAnyRange) {
  constexpr double kBound = 100.0;
  constexpr std::size_t kCount = 5000;
  phys::Workers workers;
  workers.setThreads(2);
  for (const std::size_t bad : {0, 1249, 1250, 2047, 2048, 2499, 2500, 3749, 3750, 4999}) {
    for (const bool threads : {false, true}) {
      phys::Particles particles;
      phys::Guard guard;
      for (std::size_t i = 0; i < kCount; ++i) {
        const Vec3 x(0.001 * static_cast<double>(i), 1.0, 0.0);
        particles.position.push_back(x);
        particles.previous.push_back(x);
        particles.inverseMass.push_back(1.0);
        guard.addParticle(x);
      }
      particles.position[bad].y = kBound + 1.0;
      const std::vector<std::string> names(kCount);
      const std::vector<phys::BodyId> bodies(kCount, phys::kNoBody);
      guard.checkParticles({particles, {}, {}, names, bodies, 0.0}, kBound, threads ? &workers : nullptr);
      ASSERT_EQ(guard.freezes().size(), 1u) << "bad " << bad << (threads ? " on threads" : "");
      EXPECT_EQ(guard.freezes()[0].particle, phys::ParticleId(bad));
      EXPECT_EQ(particles.inverseMass[bad], 0.0);
    }
  }
}
