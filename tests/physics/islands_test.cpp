// Islands and sleeping (physics/include/physics/islands.h): which bodies make an island, when an
// island sleeps, that a sleeping island keeps its state to the bit and costs no step, and what
// wakes it.
#include <array>
#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "character_util.h"
#include "physics/animation.h"
#include "physics/islands.h"
#include "physics/particles.h"
#include "physics/ragdoll.h"
#include "physics/rigid_bodies.h"
#include "physics/world.h"
#include "test_util.h"

namespace {

using phys::BodyId;
using phys::Vec3;

phys::SolverSettings sleeping(phys::BodyModel model = phys::BodyModel::Corners) {
  phys::SolverSettings s;
  s.sleep.enabled = true;
  if (model == phys::BodyModel::Corners) {
    s.iterations = 10;  // a corners box at rest stops within a second at these settings
    s.substeps = 4;
  }
  return s;
}

phys::BodyDesc box(const Vec3& centre, phys::BodyModel model = phys::BodyModel::Corners) {
  phys::BodyDesc d;
  d.center = centre;
  d.model = model;
  return d;
}

// Steps until the body sleeps or `seconds` pass; returns the time it fell asleep, or -1.
double stepUntilAsleep(phys::World& world, BodyId id, double seconds) {
  while (world.time() < seconds) {
    world.step();
    if (world.islands().bodyAsleep(id)) return world.time();
  }
  return -1.0;
}

TEST(Islands, BodiesApartAreIslandsOfTheirOwnAndAStackIsOne) {
  phys::World world({}, sleeping());
  world.addBody(box(Vec3(-5.0, 0.5, 0.0)));
  world.addBody(box(Vec3(5.0, 0.5, 0.0)));
  world.addBody(box(Vec3(0.0, 0.5, 0.0)));
  world.addBody(box(Vec3(0.0, 1.5, 0.0)));
  world.addBody(box(Vec3(0.0, 2.5, 0.0)));
  for (int i = 0; i < 10; ++i) world.step();
  EXPECT_EQ(world.islands().islandCount(), 3u);  // the ground joins nothing
  const auto island = world.islands().bodyIsland();
  EXPECT_NE(island[0], island[1]);
  EXPECT_EQ(island[2], island[3]);
  EXPECT_EQ(island[3], island[4]);
  EXPECT_NE(island[0], island[2]);
}

TEST(Islands, JointsAndSticksJoinForGoodAndAPinnedParticleJoinsNothing) {
  phys::World world = testing_phys::openSpace(sleeping());
  phys::RagdollDesc r;
  r.hips = Vec3(0.0, 10.0, 0.0);
  phys::addRagdoll(world, r);  // ten boxes, apart in the air: one island by its joints
  // Two chains hung from one pinned particle: two islands, not one through the pin.
  const phys::ParticleId pin = world.addParticle({Vec3(20.0, 10.0, 0.0), Vec3(0.0), 1.0, true, "pin"});
  for (const double side : {-1.0, 1.0}) {
    phys::ParticleId last = pin;
    for (int k = 1; k <= 3; ++k) {
      const phys::ParticleId p =
          world.addParticle({Vec3(20.0 + side * k, 10.0, 0.0), Vec3(0.0), 1.0, false, ""});
      world.addStick(last, p);
      last = p;
    }
  }
  world.step();
  EXPECT_EQ(world.islands().islandCount(), 3u);
  const phys::NodeId left = world.islands().particleNode(pin + 1),
                     right = world.islands().particleNode(pin + 4);
  EXPECT_NE(left, right);
}

TEST(Islands, SleepingIsOffUnlessAsked) {
  phys::World world;
  const BodyId id = world.addBody(box(Vec3(0.0, 0.5, 0.0), phys::BodyModel::Rigid));
  for (int i = 0; i < 300; ++i) world.step();
  EXPECT_FALSE(world.islands().bodyAsleep(id));
  EXPECT_EQ(world.islands().sleepingBodies(), 0u);
  // Not counted by the step with sleeping off, the islands are counted when asked.
  world.addBody(box(Vec3(5.0, 0.5, 0.0), phys::BodyModel::Rigid));
  world.step();
  EXPECT_EQ(world.profile()[phys::Stage::Islands], 0.0);
  EXPECT_EQ(world.islands().islandCount(), 2u);
  EXPECT_EQ(world.islands().awakeBodies(), 2u);
}

// A box dropped on the ground sleeps once it has rested SleepSettings::time, and from then on a
// step changes nothing: the same hash, step after step, and no stage timed.
TEST(Islands, ARestingBoxSleepsAndKeepsItsStateToTheBit) {
  for (const phys::BodyModel model :
       {phys::BodyModel::Corners, phys::BodyModel::Tetra, phys::BodyModel::Rigid}) {
    phys::World world({}, sleeping(model));
    const BodyId id = world.addBody(box(Vec3(0.0, 1.0, 0.0), model));
    const double asleep = stepUntilAsleep(world, id, 5.0);
    ASSERT_GT(asleep, 0.0) << phys::toString(model);
    // It falls for about 0.3 s and must rest 0.5 s after that.
    EXPECT_GT(asleep, 0.5) << phys::toString(model);
    EXPECT_EQ(world.islands().sleepingIslands(), 1u);
    const std::uint64_t hash = world.stateHash();
    const phys::BodyPose pose = world.bodyPose(id);
    for (int i = 0; i < 120; ++i) {
      world.step();
      EXPECT_EQ(world.profile().staged(), 0.0);
    }
    EXPECT_EQ(world.stateHash(), hash) << phys::toString(model);
    EXPECT_EQ(world.bodyPose(id).center, pose.center);
    EXPECT_NEAR(world.time(), asleep + 2.0, 1e-9);  // the clock still runs
  }
}

// A sleeping body is at rest: metrics() gives it no speed and no kinetic energy, though its x and
// x* (or a rigid body's velocities) keep the motion it fell asleep with.
TEST(Islands, ASleepingBodyHasNoSpeedInTheMetrics) {
  for (const phys::BodyModel model : {phys::BodyModel::Corners, phys::BodyModel::Rigid}) {
    // Jacobi at 1 x 4 leaves a resting box's particles trembling at about 2 cm/s, under the
    // sleeping speed (the stability suite's face-face).
    phys::SolverSettings s = sleeping(model);
    s.method = phys::SolverMethod::Jacobi;
    s.iterations = 1;
    s.substeps = 4;
    phys::World world({}, s);
    const BodyId id = world.addBody(box(Vec3(0.0, 1.0, 0.0), model));
    ASSERT_GT(stepUntilAsleep(world, id, 5.0), 0.0);
    const auto [v, w] = world.bodyVelocity(id);
    double kept = glm::length(v) + glm::length(w);
    for (phys::ParticleId i{}; i < world.particles().size(); ++i)
      kept = std::max(kept, glm::length(world.particles().position[i] - world.particles().previous[i]));
    ASSERT_GT(kept, 0.0) << phys::toString(model);  // something to hide, or the test says nothing
    const phys::Metrics m = world.metrics();
    EXPECT_EQ(m.maxSpeed, 0.0) << phys::toString(model);
    EXPECT_EQ(m.kineticEnergy, 0.0) << phys::toString(model);
    EXPECT_NEAR(m.potentialEnergy, 9.81 * world.bodyPose(id).center.y, 1e-3) << phys::toString(model);
  }
}

// Waking gives back the state it slept in: the woken world steps exactly as one that never slept
// would from the same state (here: one whose sleeping is off from the moment the first fell asleep).
TEST(Islands, WakingGivesBackTheStateItSleptIn) {
  phys::World world({}, sleeping());
  const BodyId id = world.addBody(box(Vec3(0.0, 1.0, 0.0)));
  ASSERT_GT(stepUntilAsleep(world, id, 5.0), 0.0);
  const std::vector<Vec3> x = world.particles().position, previous = world.particles().previous;
  for (int i = 0; i < 60; ++i) world.step();
  phys::SolverSettings off = world.solverSettings();
  off.sleep.enabled = false;
  world.setSolverSettings(off);  // a changed setting wakes every island
  EXPECT_FALSE(world.islands().bodyAsleep(id));
  EXPECT_EQ(world.particles().position, x);
  EXPECT_EQ(world.particles().previous, previous);
}

// A sleeping island is not stepped while another island moves: a stack of three asleep keeps its
// particles to the bit while a box falls beside it (stepped, the stack's boxes would be pressed
// into each other by gravity and pushed back, a few ulps off each substep).
TEST(Islands, ASleepingIslandIsNotSteppedWhileAnotherMoves) {
  for (const phys::BodyModel model : {phys::BodyModel::Corners, phys::BodyModel::Rigid}) {
    phys::World world({}, sleeping(model));
    for (int k = 0; k < 3; ++k) world.addBody(box(Vec3(0.0, 0.5 + k, 0.0), model));
    ASSERT_GT(stepUntilAsleep(world, BodyId(2), 10.0), 0.0) << phys::toString(model);
    const std::vector<Vec3> x = world.particles().position, previous = world.particles().previous;
    const phys::RigidBodies rigid = world.rigidBodies();
    const BodyId falling = world.addBody(box(Vec3(5.0, 3.0, 0.0), model));
    for (int i = 0; i < 120; ++i) {
      world.step();
      ASSERT_TRUE(world.islands().bodyAsleep(BodyId(0)));
      const auto& p = world.particles();
      ASSERT_EQ(std::vector<Vec3>(p.position.begin(), p.position.begin() + x.size()), x)
          << "t = " << world.time();
      ASSERT_EQ(std::vector<Vec3>(p.previous.begin(), p.previous.begin() + x.size()), previous);
      for (phys::RigidId r{}; r < rigid.size(); ++r) {
        ASSERT_EQ(world.rigidBodies().position[r], rigid.position[r]) << "t = " << world.time();
        ASSERT_EQ(world.rigidBodies().orientation[r], rigid.orientation[r]);
        ASSERT_EQ(world.rigidBodies().velocity[r], rigid.velocity[r]);
        ASSERT_EQ(world.rigidBodies().angularVelocity[r], rigid.angularVelocity[r]);
      }
    }
    EXPECT_LT(world.bodyPose(falling).center.y, 0.51) << phys::toString(model);  // it fell and landed
    EXPECT_EQ(world.islands().islandCount(), 2u);
  }
}

// The step skips what sleeps (World::skipSleepers: the lanes' still groups, the ground points,
// frames and bounds of sleeping bodies, their pairs with each other), and that must change nothing
// for what is awake: a ragdoll of boxes dropped beside a sleeping row of 20 boxes (whose ground
// points it lands among) moves to the bit as the same ragdoll alone in a world. Its first four
// parts share a lane group of the sticks and of the body damping with the row's last four boxes
// (groups of eight of one shape, in body order), so a group half asleep must still be relaxed.
TEST(Islands, ABodyBesideASleepingRowMovesAsIfAlone) {
  phys::SolverSettings s = sleeping();
  s.bodyDamping = 0.3;
  phys::World beside({}, s), alone({}, s);
  for (int k = 0; k < 20; ++k) beside.addBody(box(Vec3(1.5 * k, 0.5, 0.0)));
  for (int k = 0; k < 20; ++k) ASSERT_GT(stepUntilAsleep(beside, BodyId(k), 10.0), 0.0) << k;
  const std::size_t rowParticles = beside.particles().size();
  phys::RagdollDesc r;
  r.hips = Vec3(-6.0, 2.5, 0.0);
  r.orientation = glm::angleAxis(0.7, glm::normalize(Vec3(1.0, 0.0, 1.0)));
  phys::addRagdoll(beside, r);
  phys::addRagdoll(alone, r);
  for (int i = 0; i < 180; ++i) {
    beside.step();
    alone.step();
    // The row sleeps throughout; the ragdoll sleeps as it does alone (it comes to rest at step 165).
    ASSERT_EQ(beside.islands().sleepingBodies(), 20u + alone.islands().sleepingBodies()) << "step " << i;
    const auto& b = beside.particles().position;
    const auto& a = alone.particles().position;
    ASSERT_EQ(std::vector<Vec3>(b.begin() + static_cast<std::ptrdiff_t>(rowParticles), b.end()), a)
        << "step " << i;
  }
  EXPECT_LT(alone.metrics().maxSpeed, 2.0);  // it fell, landed and tumbled (not still in the air)
}

// More passes wake every island and relax at once what fewer left (World::settleWithoutVelocity),
// sleeping bodies' sag included: the lanes' still groups hold only while the step's masks do, so
// the settle relaxes the sleeping row's two groups of eight boxes too. (It skipped them when the
// marks of the step before, taken while a box fell beside the row, were left in place.)
TEST(Islands, MorePassesSettleWhatSlept) {
  phys::SolverSettings s = sleeping();
  s.iterations = 2;
  s.substeps = 1;
  phys::World world({}, s);
  for (int k = 0; k < 20; ++k) world.addBody(box(Vec3(1.5 * k, 0.5, 0.0)));
  for (int k = 0; k < 20; ++k) ASSERT_GT(stepUntilAsleep(world, BodyId(k), 20.0), 0.0) << k;
  world.addBody(box(Vec3(-10.0, 20.0, 0.0)));
  for (int i = 0; i < 10; ++i) world.step();
  ASSERT_EQ(world.islands().sleepingBodies(), 20u);
  const double before = world.metrics().maxConstraintError;  // the row's sag at 2 passes
  s.iterations = 40;
  world.setSolverSettings(s);
  EXPECT_LT(world.metrics().maxConstraintError, 0.01 * before) << "before " << before;
}

// A box dropped on a sleeping one wakes it through their contact; neither falls through, and the
// two sleep again once they rest together.
TEST(Islands, ABodyThatLandsOnASleepingOneWakesIt) {
  phys::World world({}, sleeping());
  const BodyId below = world.addBody(box(Vec3(0.0, 0.5, 0.0)));
  ASSERT_GT(stepUntilAsleep(world, below, 5.0), 0.0);
  const Vec3 rested = world.bodyPose(below).center;
  const BodyId above = world.addBody(box(Vec3(0.0, 3.0, 0.0)));
  EXPECT_EQ(world.islands().sleepingBodies(), 1u);
  // While the other falls, the sleeping box's particles do not move by a bit: the step sees them
  // as pinned.
  const phys::Body& b = world.bodies()[below];
  const auto particlesOfBelow = [&] {
    const auto& x = world.particles().position;
    return std::vector<Vec3>(x.begin() + b.firstParticle, x.begin() + b.firstParticle + b.particleCount);
  };
  const std::vector<Vec3> slept = particlesOfBelow();
  bool woke = false;
  for (int i = 0; i < 120 && !woke; ++i) {
    world.step();
    woke = !world.islands().bodyAsleep(below);
    if (!woke) {
      ASSERT_EQ(particlesOfBelow(), slept) << "t = " << world.time();
    }
  }
  EXPECT_TRUE(woke);
  ASSERT_GT(stepUntilAsleep(world, above, world.time() + 5.0), 0.0);
  EXPECT_TRUE(world.islands().bodyAsleep(below));
  EXPECT_EQ(world.islands().islandCount(), 1u);
  EXPECT_NEAR(world.bodyPose(above).center.y, 1.5, 0.01);
  EXPECT_NEAR(world.bodyPose(below).center.y, rested.y, 0.01);
}

// A sleeping island that a contact joins to an awake body wakes in the substep the contact is found
// in, before the passes (World::wakeTouched), and passes a blow on: in zero gravity A at 5 m/s
// strikes B, which rests 3 cm from C, both asleep long before A arrives at 1 s. Woken only at the
// step's end, B took up A's blow as a wall would, and C then took up B's: of 5 kg m/s, 0.31 was
// left with rigid boxes at 1 substep. Now the three keep the momentum they keep awake, to 1%.
TEST(Islands, AStruckSleepingBodyPassesTheBlowOn) {
  for (const phys::BodyModel model : {phys::BodyModel::Rigid, phys::BodyModel::Corners}) {
    for (const int substeps : {1, 4}) {
      auto momentum = [&](bool sleep) {
        phys::SolverSettings s = sleeping(model);
        s.sleep.enabled = sleep;
        s.substeps = substeps;
        phys::WorldSettings space;
        space.gravity = Vec3(0.0);
        space.ground = false;
        phys::World world(space, s);
        phys::BodyDesc a = box(Vec3(-6.0, 0.0, 0.0), model);
        a.velocity = Vec3(5.0, 0.0, 0.0);
        const std::array<BodyId, 3> row{world.addBody(a), world.addBody(box(Vec3(0.0), model)),
                                        world.addBody(box(Vec3(1.03, 0.0, 0.0), model))};
        for (int i = 0; i < 55; ++i) world.step();
        if (sleep) {  // else the test could not fail
          EXPECT_TRUE(world.islands().bodyAsleep(row[1]) && world.islands().bodyAsleep(row[2]))
              << phys::toString(model);
        }
        for (int i = 0; i < 120; ++i) world.step();
        phys::Real sum = 0.0;
        for (const BodyId id : row) sum += world.bodyMass(id).mass * world.bodyVelocity(id).first.x;
        return sum;
      };
      const phys::Real awake = momentum(false);
      EXPECT_NEAR(awake, 5.0, 0.05) << phys::toString(model) << ", " << substeps << " substeps";
      EXPECT_NEAR(momentum(true), awake, 0.05) << phys::toString(model) << ", " << substeps << " substeps";
    }
  }
}

TEST(Islands, ADragWakesTheBodyAndHoldsItAwake) {
  phys::World world({}, sleeping(phys::BodyModel::Rigid));
  const BodyId id = world.addBody(box(Vec3(0.0, 0.5, 0.0), phys::BodyModel::Rigid));
  ASSERT_GT(stepUntilAsleep(world, id, 5.0), 0.0);
  const Vec3 start = world.bodyPose(id).center;
  world.setDrag(world.dragAt(id, start));  // a drag whose target is where the point is: no pull
  EXPECT_FALSE(world.islands().bodyAsleep(id));
  for (int i = 0; i < 120; ++i) world.step();
  EXPECT_FALSE(world.islands().bodyAsleep(id));  // held awake while dragged, though it does not move
  world.clearDrag();
  EXPECT_GT(stepUntilAsleep(world, id, world.time() + 5.0), 0.0);
}

// A push holds its body awake while it lasts, as a drag does: a rigid box on the ground pushed
// sideways by half what static friction holds (it does not move) for 2 s.
TEST(Islands, APushHoldsItsBodyAwakeWhileItLasts) {
  phys::World world({}, sleeping(phys::BodyModel::Rigid));
  const BodyId id = world.addBody(box(Vec3(0.0, 0.5, 0.0), phys::BodyModel::Rigid));
  ASSERT_GT(stepUntilAsleep(world, id, 5.0), 0.0);
  const phys::Material both = phys::combine(world.worldSettings().groundMaterial, phys::BodyDesc{}.material);
  const double hold = 0.5 * both.staticFriction * 9.81 * world.bodyMass(id).mass;
  world.push(id, Vec3(hold, 0.0, 0.0), 2.0);
  const double start = world.time();
  while (!world.pushes().empty()) {
    world.step();
    ASSERT_FALSE(world.islands().bodyAsleep(id)) << "t = " << world.time() << ": asleep while pushed";
    ASSERT_LT(world.time(), start + 2.1);
  }
  EXPECT_GT(world.time(), start + 1.99);
  EXPECT_GT(stepUntilAsleep(world, id, world.time() + 5.0), 0.0);
}

// What the islands say between steps counts what was added since the last step: a box added to a
// world of one sleeping box is an island of its own at once, with sleeping on or off.
TEST(Islands, TheCountBetweenStepsSeesWhatWasAdded) {
  for (const bool sleep : {true, false}) {
    phys::SolverSettings settings = sleeping(phys::BodyModel::Rigid);
    settings.sleep.enabled = sleep;
    phys::World world({}, settings);
    world.addBody(box(Vec3(0.0, 0.5, 0.0), phys::BodyModel::Rigid));
    for (int i = 0; i < 90; ++i) world.step();
    ASSERT_EQ(world.islands().islandCount(), 1u);
    ASSERT_EQ(world.islands().sleepingIslands(), sleep ? 1u : 0u);
    const BodyId added = world.addBody(box(Vec3(5.0, 0.5, 0.0), phys::BodyModel::Rigid));
    EXPECT_EQ(world.islands().islandCount(), 2u) << "sleep " << sleep;
    EXPECT_EQ(world.islands().bodyIsland()[added], 1u) << "sleep " << sleep;
    EXPECT_EQ(world.islands().awakeBodies(), sleep ? 1u : 2u);
    EXPECT_EQ(world.islands().sleepingIslands(), sleep ? 1u : 0u);
  }
}

// unmask() gives back exactly what mask() took, to the nodes it took it from, whatever woke in
// between: three loose particles of different masses asleep, the first woken after the masks.
TEST(Islands, UnmaskGivesEachNodeBackWhatMaskTookFromIt) {
  phys::Islands islands;
  phys::Particles p;
  for (int i = 0; i < 3; ++i) {
    islands.addParticle(false);
    p.position.push_back(Vec3(2.0 * i, 0.0, 0.0));
    p.inverseMass.push_back(1.0 / (i + 1.0));
  }
  p.previous = p.position;  // at rest
  const std::vector<phys::Real> own = p.inverseMass;
  const phys::RigidBodies rigid;
  phys::SleepSettings sleep;
  sleep.enabled = true;
  sleep.time = 0.0;
  islands.update({p, rigid, {}, {}, 1.0 / 240.0, 1.0 / 60.0, sleep, {}});
  ASSERT_TRUE(islands.allAsleep());
  phys::RigidBodies masked;
  islands.mask(p, masked, {});
  EXPECT_EQ(p.inverseMass, std::vector<phys::Real>(3, 0.0));
  islands.wake(islands.particleNode(phys::ParticleId(0)));  // in the step, after the masks
  EXPECT_TRUE(islands.masked());
  islands.unmask(p, masked, {});
  EXPECT_EQ(p.inverseMass, own);
  EXPECT_FALSE(islands.masked());
}

// A character whose drives move it is held awake however still it stands: asleep, the next step's
// drives would wake it in its first substep, after the masks, and it would stand pinned for that
// step (with a sleep time of 0, for every step). A heavy box beside it sleeps as ever.
TEST(Islands, ACharacterWhoseDrivesMoveItNeverSleeps) {
  phys::SolverSettings settings = testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8);
  settings.sleep.enabled = true;
  settings.sleep.time = 0.0;
  phys::World w(phys::WorldSettings{}, settings);
  const phys::Ragdoll r = testing_phys::rigidRagdoll(w, "r");
  phys::BodyDesc heavy = box(Vec3(3.0, 0.5, 0.0), phys::BodyModel::Rigid);
  heavy.mass = 7.0;
  const BodyId block = w.addBody(heavy);
  phys::CharacterDesc desc;
  desc.ragdoll = "r";
  desc.playback.clip = std::make_shared<const phys::Clip>(
      testing_phys::ragdollClip(2, [](const std::string&, phys::Real) { return 0.0; }));
  w.addCharacter(desc);
  std::vector<phys::BodyMass> masses;
  for (BodyId id{}; id < w.bodies().size(); ++id) masses.push_back(w.bodyMass(id));
  const BodyId root = r.part(phys::RagdollPart::Torso);
  for (int i = 0; i < 300; ++i) {
    w.step();
    ASSERT_FALSE(w.islands().bodyAsleep(root)) << "after step " << i;
    for (BodyId id{}; id < w.bodies().size(); ++id)
      ASSERT_EQ(w.bodyMass(id).mass, masses[id].mass) << "body " << id << ", step " << i;
  }
  EXPECT_TRUE(w.islands().bodyAsleep(block));
  // Limp, it sleeps like any body.
  w.setCharacterStrength(0, 0.0, 0.0);
  for (int i = 0; i < 600 && !w.islands().bodyAsleep(root); ++i) w.step();
  EXPECT_TRUE(w.islands().bodyAsleep(root));
}

TEST(Islands, AMovingBodyNeverSleeps) {
  phys::World world = testing_phys::openSpace(sleeping());
  const phys::ParticleId pin = world.addParticle({Vec3(0.0, 5.0, 0.0), Vec3(0.0), 1.0, true, "pin"});
  const phys::ParticleId bob = world.addParticle({Vec3(1.0, 5.0, 0.0), Vec3(0.0), 1.0, false, "bob"});
  world.addStick(pin, bob);
  for (int i = 0; i < 600; ++i) {
    world.step();
    ASSERT_FALSE(world.islands().asleep(world.islands().particleNode(bob))) << "t = " << world.time();
  }
}

// A body that starts to fall slowly from rest stays under the sleeping speed for the whole sleep
// time when it speeds up by less than sleep.speed / sleep.time (0.1 m/s^2 at the defaults), and
// slept mid-fall: a 1 x 4 x 1 m rigid column standing on a 1 m box with its centre 5 mm past the
// box's edge slept from step 40, tipping at 0.033 m/s, leaning at x 0.510 for good. Its speed rises
// step after step, which a settling body's does not, so it must tip over onto the ground (awake it
// lies there with its centre at x 3.15, 0.5 m up) at the default sleep settings.
TEST(Islands, AColumnTippingSlowlyOverAnEdgeDoesNotSleepMidFall) {
  phys::SolverSettings s = sleeping(phys::BodyModel::Rigid);
  s.method = phys::SolverMethod::Xpbd;
  s.iterations = 1;
  s.substeps = 4;
  phys::World world({}, s);
  world.addBody(box(Vec3(0.0, 0.5, 0.0), phys::BodyModel::Rigid));
  phys::BodyDesc column = box(Vec3(0.505, 3.0, 0.0), phys::BodyModel::Rigid);
  column.size = Vec3(1.0, 4.0, 1.0);
  const BodyId id = world.addBody(column);
  for (int i = 0; i < 1200; ++i) world.step();
  const Vec3 centre = world.bodyPose(id).center;
  EXPECT_GT(centre.x, 2.5);  // fallen off the box: 2 m of its own height past the edge
  EXPECT_NEAR(centre.y, 0.5, 0.05);
}

// The same for a particle pendulum of 1 m balanced 1 mm off straight up over its pin: it speeds up
// by a share of its speed each step (its angle grows as cosh(3.13 t)), and slept there, never
// leaving the top. It must swing down past the pin's height within 3.5 s (a quarter turn takes
// 2.57 s by that law).
TEST(Islands, AnInvertedPendulumFallsFromItsBalance) {
  phys::World world({}, sleeping());
  const phys::ParticleId pin = world.addParticle({Vec3(0.0, 2.0, 0.0), Vec3(0.0), 1.0, true, "pin"});
  const phys::ParticleId bob = world.addParticle({Vec3(0.001, 3.0, 0.0), Vec3(0.0), 1.0, false, "bob"});
  world.addStick(pin, bob);
  while (world.time() < 3.5 && world.particles().position[bob].y > 2.0) world.step();
  EXPECT_LT(world.particles().position[bob].y, 2.0)
      << "asleep " << world.islands().asleep(world.islands().particleNode(bob));
}

// A box on a slope a little steeper than its friction speeds up uniformly from rest, by a share of
// its speed that falls as it goes (1/n at its n-th step), so the step-by-step rise no longer
// counts from its 50th step while it is still under the sleeping speed: it slept mid-slide, after
// 1.9 cm. A 1 m box on a 20 degree slope (tan 20 = 0.364), ground friction 0.6 and the box's mu
// (together sqrt(0.6 mu), 0.360 to 0.364), stepped as the lab does by default (Gauss-Seidel 3 x 1),
// must slide for 20 s as the same box awake does, to the bit, never asleep: the corners box of
// 0.216 slides 7.8 m in that time and that of 0.219 3.3 m, the tetra box of 0.218 4.6 m and that
// of 0.219 3.1 m (at 0.015 to 0.039 m/s^2 from rest; Coulomb's 4.25 and 2.73 m for the tetra box).
// The tetra box of 0.2206 slid 2.0 m here while it walked lying still (docs/physics.md, "A tetra
// box lying still"); now it slides 0.63 m awake (Coulomb 0.29 m, at 0.0016 m/s^2), under what the
// halves' test catches (0.01 m/s^2, Islands::fasterThanItsLastHalf), and sleeps mid-slide: the
// known limit of a slope just steeper than the friction.
TEST(Islands, ABoxSlidingSlowlyDownASlopeDoesNotSleepMidSlide) {
  struct Slope {
    phys::BodyModel model;
    double mu;
    double slides;  // m, at least, in 20 s
  };
  for (const Slope& slope :
       {Slope{phys::BodyModel::Corners, 0.216, 7.0}, Slope{phys::BodyModel::Corners, 0.219, 3.0},
        Slope{phys::BodyModel::Tetra, 0.218, 4.0}, Slope{phys::BodyModel::Tetra, 0.219, 2.5}}) {
    const double angle = glm::radians(20.0);
    phys::WorldSettings ws;
    ws.groundNormal = {-std::sin(angle), std::cos(angle), 0.0};
    ws.groundMaterial = {0.6, 0.6};
    phys::BodyDesc desc = box(ws.groundNormal * 0.5, slope.model);
    desc.material = {slope.mu, slope.mu};
    desc.orientation = glm::angleAxis(angle, Vec3(0.0, 0.0, 1.0));
    phys::SolverSettings s;  // the lab's defaults
    s.sleep.enabled = true;
    phys::World asleep(ws, s);
    s.sleep.enabled = false;
    phys::World awake(ws, s);
    const BodyId id = asleep.addBody(desc);
    awake.addBody(desc);
    const std::string what = std::string(phys::toString(slope.model)) + ", mu " + std::to_string(slope.mu);
    for (int i = 0; i < 1200; ++i) {
      asleep.step();
      awake.step();
      ASSERT_FALSE(asleep.islands().bodyAsleep(id))
          << what << ": asleep at t = " << asleep.time() << ", "
          << glm::length(asleep.bodyPose(id).center - desc.center) << " m down the slope";
    }
    EXPECT_EQ(asleep.stateHash(), awake.stateHash()) << what;
    EXPECT_GT(glm::length(asleep.bodyPose(id).center - desc.center), slope.slides) << what;
  }
}

// A body faster than the sleeping speed never sleeps, even with a sleep time of 0: its rest, 0, met
// the time, 0, and a box thrown up slept on its first step, in the air. In zero gravity a box
// drifting at 1 m/s must drift on: 1 m a second, awake.
TEST(Islands, AFastBodyNeverSleepsEvenWithASleepTimeOfZero) {
  for (const phys::BodyModel model : {phys::BodyModel::Rigid, phys::BodyModel::Corners}) {
    phys::SolverSettings s = sleeping(model);
    s.sleep.time = 0.0;
    phys::WorldSettings space;
    space.gravity = Vec3(0.0);
    space.ground = false;
    phys::World world(space, s);
    phys::BodyDesc drifting = box(Vec3(0.0), model);
    drifting.velocity = Vec3(1.0, 0.0, 0.0);
    const BodyId id = world.addBody(drifting);
    for (int i = 0; i < 60; ++i) {
      world.step();
      ASSERT_FALSE(world.islands().bodyAsleep(id)) << phys::toString(model) << ", t = " << world.time();
    }
    EXPECT_NEAR(world.bodyPose(id).center.x, 1.0, 1e-9) << phys::toString(model);
  }
}

// A stick or a link wakes the body it pulls on though it joins no island: from a pinned particle, or
// within one body. Asleep, the body held it stretched: a 1 m stick from a pin 3 m up to a sleeping
// box's top corner stayed 1.5 m too long.
TEST(Islands, AStickFromAPinOrWithinABodyWakesTheBody) {
  phys::World world({}, sleeping());
  const BodyId hung = world.addBody(box(Vec3(0.0, 0.5, 0.0)));
  const BodyId roped = world.addBody(box(Vec3(4.0, 0.5, 0.0), phys::BodyModel::Rigid));
  const BodyId braced = world.addBody(box(Vec3(-4.0, 0.5, 0.0)));
  for (const BodyId id : {hung, roped, braced}) ASSERT_GT(stepUntilAsleep(world, id, 5.0), 0.0) << id;
  const phys::ParticleId pin = world.addParticle({Vec3(0.0, 3.0, 0.0), Vec3(0.0), 1.0, true, "pin"});
  const phys::ParticleId ropePin = world.addParticle({Vec3(4.0, 3.0, 0.0), Vec3(0.0), 1.0, true, "rope"});
  const phys::ParticleId corner = world.bodies()[hung].firstParticle + 2;  // -x, +y, -z: a top corner
  world.addStick(pin, corner, 1.0, 0.0);
  EXPECT_FALSE(world.islands().bodyAsleep(hung));
  phys::Embedding top;  // a rope of 1 m from the pin to the rigid box's top face
  top.particle[0] = ropePin;
  top.weight[0] = 1.0;
  top.count = 1;
  world.addLink(phys::BodyPoint::embedded(top), world.pointOn(roped, Vec3(4.0, 1.0, 0.0)), 0.0, 1.0);
  EXPECT_FALSE(world.islands().bodyAsleep(roped));
  const phys::Body& b = world.bodies()[braced];
  world.addStick(b.firstParticle, b.firstParticle + 7);  // along a body diagonal, as it is
  EXPECT_FALSE(world.islands().bodyAsleep(braced));
  for (int i = 0; i < 180; ++i) world.step();
  const auto& x = world.particles().position;
  EXPECT_NEAR(glm::length(x[corner] - x[pin]), 1.0, 0.01);
  EXPECT_NEAR(world.bodyPose(roped).center.y, 1.5, 0.01);  // hanging 1 m below the pin
}

// Ignoring the collision of two bodies wakes both: asleep, a box stacked on another stayed up,
// held by the contact the filter had taken away. It must fall through to the ground.
TEST(Islands, IgnoringACollisionWakesBothBodies) {
  phys::World world({}, sleeping(phys::BodyModel::Rigid));
  const BodyId below = world.addBody(box(Vec3(0.0, 0.5, 0.0), phys::BodyModel::Rigid));
  const BodyId above = world.addBody(box(Vec3(0.0, 1.5, 0.0), phys::BodyModel::Rigid));
  ASSERT_GT(stepUntilAsleep(world, above, 5.0), 0.0);
  world.ignoreCollision(below, above);
  EXPECT_FALSE(world.islands().bodyAsleep(below));
  EXPECT_FALSE(world.islands().bodyAsleep(above));
  for (int i = 0; i < 120; ++i) world.step();
  EXPECT_NEAR(world.bodyPose(above).center.y, 0.5, 0.01);
}

// A particle joint joins its two bodies' islands, links or none, so that setting its drive wakes
// both: two boxes asleep apart on the ground, joined by a joint without links, whose drive is set to
// turn the child a quarter turn about y. Only the parent woke, and the child stayed as it was.
TEST(Islands, AParticleJointJoinsItsBodiesSoItsDriveWakesBoth) {
  phys::World world({}, sleeping());
  const BodyId parent = world.addBody(box(Vec3(0.0, 0.5, 0.0)));
  const BodyId child = world.addBody(box(Vec3(2.0, 0.5, 0.0)));
  const std::size_t k = world.addParticleJoint(parent, child, Vec3(1.0, 0.5, 0.0));
  EXPECT_EQ(world.islands().islandCount(), 1u);
  ASSERT_GT(stepUntilAsleep(world, child, 5.0), 0.0);
  ASSERT_TRUE(world.islands().bodyAsleep(parent));
  phys::JointDrive drive = world.particleJointDrive(k);
  drive.target = glm::angleAxis(glm::half_pi<phys::Real>(), Vec3(0.0, 1.0, 0.0)) * drive.target;
  drive.strength = 0.9;
  world.setParticleJointDrive(k, drive);
  EXPECT_FALSE(world.islands().bodyAsleep(parent));
  EXPECT_FALSE(world.islands().bodyAsleep(child));
}

// A setting that changes wakes every island; one set again unchanged does not.
TEST(Islands, ChangedSettingsWakeEverything) {
  phys::World world({}, sleeping(phys::BodyModel::Rigid));
  const BodyId id = world.addBody(box(Vec3(0.0, 0.5, 0.0), phys::BodyModel::Rigid));
  ASSERT_GT(stepUntilAsleep(world, id, 5.0), 0.0);
  world.setSolverSettings(world.solverSettings());
  world.setWorldSettings(world.worldSettings());
  EXPECT_TRUE(world.islands().bodyAsleep(id));
  // A ground normal not of unit length is kept unit length: given again, it is no change.
  phys::WorldSettings longNormal = world.worldSettings();
  longNormal.groundNormal = Vec3(0.0, 2.0, 0.0);
  world.setWorldSettings(longNormal);
  EXPECT_TRUE(world.islands().bodyAsleep(id));
  world.setWorldSettings(longNormal);
  world.setWorldSettings(world.worldSettings());
  EXPECT_TRUE(world.islands().bodyAsleep(id));
  phys::WorldSettings stronger = world.worldSettings();
  stronger.gravity *= 2.0;
  world.setWorldSettings(stronger);
  EXPECT_FALSE(world.islands().bodyAsleep(id));
}

// The same input gives the same states with sleeping on, run after run.
TEST(Islands, SleepingIsDeterministic) {
  auto run = [] {
    phys::World world({}, sleeping());
    for (int k = 0; k < 4; ++k) world.addBody(box(Vec3(0.3 * k, 0.5 + 1.2 * k, 0.0)));
    for (int i = 0; i < 400; ++i) world.step();
    return std::pair(world.stateHash(), world.islands().sleepingBodies());
  };
  const auto first = run();
  EXPECT_EQ(run(), first);
  EXPECT_GT(first.second, 0u);
}

}  // namespace
