// Boxes spawned into each other and into the ground part without turning the overlap into speed
// (docs/physics.md, "Box-box contact": parting without velocity, and the depenetration limit),
// while landings and resting boxes are stepped exactly as without the limit.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "physics/capsule_ragdoll.h"
#include "test_util.h"

namespace {

using phys::BodyModel;
using phys::Vec3;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Setting {
  int iterations;
  int substeps;
  double dt = 1.0 / 60.0;  // s, per step
};

phys::World world(const Setting& s, double maxDepenetrationSpeed = phys::kDefaultMaxDepenetrationSpeed,
                  phys::Vec3 gravity = {0.0, -9.81, 0.0}) {
  phys::WorldSettings ws;
  ws.gravity = gravity;
  phys::SolverSettings ss;
  ss.iterations = s.iterations;
  ss.substeps = s.substeps;
  ss.dt = s.dt;
  ss.maxDepenetrationSpeed = maxDepenetrationSpeed;
  return phys::World(ws, ss);
}

phys::BodyId addBody(phys::World& w, Vec3 centre, BodyModel model = BodyModel::Corners) {
  phys::BodyDesc d;
  d.center = centre;
  d.model = model;
  return w.addBody(d);
}

// The fastest particle seen after any step (what the lab's stability criteria sample), and the
// deepest overlap (box-box or ground) from `settleTime` to the end.
struct Outcome {
  double fastest = 0.0;  // m/s
  double deepest = 0.0;  // m
};

Outcome run(phys::World& w, double seconds, double settleTime) {
  Outcome r;
  while (w.time() < seconds - 1e-9) {
    w.step();
    const phys::Metrics m = w.metrics();
    r.fastest = std::max(r.fastest, m.maxSpeed);
    if (w.time() >= settleTime - 1e-9) r.deepest = std::max(r.deepest, m.maxPenetration);
  }
  return r;
}

const char* name(BodyModel model) {
  return model == BodyModel::Corners ? "corners" : model == BodyModel::Tetra ? "tetra" : "rigid";
}

// The stability suite's overlap case in three boxes: two 1 m boxes side by side 25% into each
// other, a third 25% into both from above. Parted pair by pair, the lower boxes were pushed into
// the ground and the projection threw them out: 7.5 m/s at 1 iteration x 1 substep, 44 m/s at
// 1 x 16 (63 m/s for tetra boxes). Now every particle stays under 5 m/s (measured: under 0.4 m/s),
// and from 2 s to 3 s the deepest overlap is under 5 mm, the stack standing where it belongs.
// Tetra boxes at 1 iteration keep about 5 to 6 mm of overlap even when placed touching (their
// contact weights of both signs, docs/physics.md), so for them 1 x 1 is held to 1 cm. Rigid boxes
// were left to their contacts' depenetration limit, whose push stays in the velocity a rigid body
// takes from its change of pose: here 1.2 to 1.4 m/s, 8 m/s in the suite's ten-box `overlap`.
// Parted whole like the others, they stay under 0.1 m/s (measured: 1 mm/s).
TEST(Overlap, ThreeBoxesSpawned25PercentIntoEachOtherPartCalmly) {
  for (BodyModel model : {BodyModel::Corners, BodyModel::Tetra, BodyModel::Rigid}) {
    for (Setting s : {Setting{1, 1}, Setting{3, 1}, Setting{1, 16}}) {
      phys::World w = world(s);
      const phys::BodyId left = addBody(w, {-0.375, 0.5, 0.0}, model);
      const phys::BodyId right = addBody(w, {0.375, 0.5, 0.0}, model);
      const phys::BodyId top = addBody(w, {0.0, 1.25, 0.0}, model);
      const Outcome r = run(w, 3.0, 2.0);
      std::printf(
          "three boxes 25%% into each other, %s, %d x %d: fastest %.3f m/s, deepest overlap from 2 s "
          "%.4f m\n",
          name(model), s.iterations, s.substeps, r.fastest, r.deepest);
      const std::string what =
          std::string(name(model)) + " " + std::to_string(s.iterations) + " x " + std::to_string(s.substeps);
      EXPECT_LT(r.fastest, model == BodyModel::Rigid ? 0.1 : 5.0) << what;
      EXPECT_LT(r.deepest, model == BodyModel::Tetra && s.iterations == 1 && s.substeps == 1 ? 0.01 : 0.005)
          << what;
      EXPECT_EQ(w.metrics().frozen, 0) << what;
      // Parted, not scattered: the lower two on the ground side by side, the third on them.
      EXPECT_NEAR(w.bodyPose(left).center.y, 0.5, 0.01) << what;
      EXPECT_NEAR(w.bodyPose(right).center.y, 0.5, 0.01) << what;
      EXPECT_NEAR(w.bodyPose(top).center.y, 1.5, 0.02) << what;
      EXPECT_GT(w.bodyPose(right).center.x - w.bodyPose(left).center.x, 0.99) << what;
      EXPECT_LT(w.bodyPose(right).center.x - w.bodyPose(left).center.x, 1.2) << what;
    }
  }
}

// The smallest chain: a box 25% into a box resting on the ground. The pair parted alone pushed
// the lower box 12.5 cm into the ground, and both flew off at 0.125 m / h (45 m/s at 16 substeps).
// Now the upper box is lifted out whole, and the two end as two boxes placed touching end (at 1
// iteration the lower box is squeezed and the upper one rests 2 cm low either way). The same for
// rigid boxes, held to 1 cm/s (left to the depenetration limit, they left at up to 0.38 m/s; parted,
// at 1 mm/s).
TEST(Overlap, ABoxSpawnedIntoARestingBoxDoesNotDriveItIntoTheGround) {
  for (BodyModel model : {BodyModel::Corners, BodyModel::Rigid})
    for (Setting s : {Setting{1, 1}, Setting{3, 1}, Setting{1, 16}}) {
      auto pair = [&](double upperHeight) {
        phys::World w = world(s);
        addBody(w, {0.0, 0.5, 0.0}, model);
        addBody(w, {0.0, upperHeight, 0.0}, model);
        return w;
      };
      phys::World spawned = pair(1.25), placed = pair(1.5);
      const Outcome r = run(spawned, 2.0, 1.0);
      run(placed, 2.0, 1.0);
      std::printf(
          "a %s box 25%% into a resting box, %d x %d: fastest %.3f m/s, upper box at %.4f m (placed "
          "touching: %.4f m)\n",
          name(model), s.iterations, s.substeps, r.fastest, spawned.bodyPose(phys::BodyId{1}).center.y,
          placed.bodyPose(phys::BodyId{1}).center.y);
      const std::string what =
          std::string(name(model)) + " " + std::to_string(s.iterations) + " x " + std::to_string(s.substeps);
      EXPECT_LT(r.fastest, model == BodyModel::Rigid ? 0.01 : 1.0) << what;
      EXPECT_LT(r.deepest, 0.005) << what;
      EXPECT_NEAR(spawned.bodyPose(phys::BodyId{1}).center.y, placed.bodyPose(phys::BodyId{1}).center.y,
                  0.002)
          << what;
      EXPECT_NEAR(spawned.bodyPose(phys::BodyId{0}).center.y, placed.bodyPose(phys::BodyId{0}).center.y,
                  0.002)
          << what;
    }
}

// Overlap shallower than the feature epsilon is not parted whole (resting contacts have that
// much), so the projections remove it, at most maxDepenetrationSpeed * h per substep. Without
// gravity, 8 mm of overlap in a substep of h = 1/960 s (16 substeps at 60 Hz; stepped one substep
// per step here, so that every substep is sampled) left at 7.7 m/s; with the limit, about at the
// limit, whatever it is set to, and it is gone within a few hundredths of a second.
TEST(Overlap, ShallowOverlapLeavesNoFasterThanTheDepenetrationSpeed) {
  const Setting fine{1, 1, 1.0 / 960.0};
  for (double limit : {1.0, 0.25, kInfinity}) {
    // Into the ground.
    phys::World ground = world(fine, limit, Vec3(0.0));
    addBody(ground, {0.0, 0.5 - 0.008, 0.0});
    const Outcome g = run(ground, 0.5, 0.25);
    // Into another box, no ground.
    phys::World pair = world(fine, limit, Vec3(0.0));
    phys::WorldSettings open = pair.worldSettings();
    open.ground = false;
    pair.setWorldSettings(open);
    addBody(pair, {0.0, 0.0, 0.0});
    addBody(pair, {1.0 - 0.008 - pair.solverSettings().contactSlop, 0.0, 0.0});
    const Outcome b = run(pair, 0.5, 0.25);
    std::printf("8 mm of overlap, limit %g m/s: into the ground leaves at %.3f m/s, two boxes at %.3f m/s\n",
                limit, g.fastest, b.fastest);
    if (std::isinf(limit)) {
      EXPECT_GT(g.fastest, 7.0) << "without the limit the overlap becomes d / h";
      EXPECT_GT(b.fastest, 3.5);
      continue;
    }
    // Each contact point parts at the limit. The box's far particles can go faster for a few
    // substeps: its sticks pass the pushed particles' motion on to them while the contact keeps
    // topping the pushed ones up (measured 1.5 times the limit into the ground at 1 iteration,
    // 0.75 times for each of two boxes parting, their relative speed again 1.5 times).
    EXPECT_LT(g.fastest, 1.6 * limit) << limit;
    EXPECT_LT(b.fastest, 0.8 * limit) << limit;
    EXPECT_LT(g.deepest, 1e-6) << limit;
    EXPECT_LT(b.deepest, pair.solverSettings().contactSlop + 1e-6) << limit;
  }
}

// A contact that only stops this substep's approach is stopped in full: landings, a column of
// boxes dropped onto each other and resting boxes are stepped bit for bit as without the limit.
// With more than one pass per step the single landings are, even with the limit at 0.1 m/s (0.1 mm
// per substep at 16 substeps). At 1 x 1 they are not at such a low limit: the one pass leaves
// some of a landing's overlap for the next substep (22 mm for a tetra box dropped on a tetra box),
// and the limit then slows its removal (that box ended 1.6 mm lower at 0.1 m/s; the top of a
// column of five, 7 cm lower).
TEST(Overlap, LandingsAndRestingBoxesAreUntouchedByTheLimit) {
  for (Setting s : {Setting{1, 1}, Setting{3, 1}, Setting{1, 16}, Setting{10, 1}}) {
    auto landings = [&](double limit) {
      phys::World w = world(s, limit);
      addBody(w, {-3.0, 1.5, 0.0});                   // dropped 1 m onto the ground
      addBody(w, {0.0, 0.5, 0.0});                    // resting, and landed on
      addBody(w, {0.0, 2.5, 0.0}, BodyModel::Tetra);  // dropped 1 m onto it
      for (int i = 0; i < 120; ++i) w.step();
      return w.stateHash();
    };
    auto column = [&](double limit) {
      phys::World w = world(s, limit);
      for (int i = 0; i < 4; ++i) addBody(w, {0.0, 0.5 + 1.2 * i, 0.0});  // 0.2 m apart
      for (int i = 0; i < 120; ++i) w.step();
      return w.stateHash();
    };
    const std::string what = std::to_string(s.iterations) + " x " + std::to_string(s.substeps);
    EXPECT_EQ(landings(phys::kDefaultMaxDepenetrationSpeed), landings(kInfinity)) << what;
    if (s.iterations * s.substeps > 1) {
      EXPECT_EQ(landings(0.1), landings(kInfinity)) << what;
    }
    EXPECT_EQ(column(phys::kDefaultMaxDepenetrationSpeed), column(kInfinity)) << what;
  }
}

TEST(Overlap, DepenetrationSpeedMustBePositive) {
  phys::SolverSettings s;
  for (double bad : {0.0, -1.0, std::nan("")}) {
    s.maxDepenetrationSpeed = bad;
    EXPECT_FALSE(phys::validate(s).empty()) << bad;
  }
  s.maxDepenetrationSpeed = kInfinity;
  EXPECT_TRUE(phys::validate(s).empty()) << "infinity turns the limit off";
}

// Contacts between bodies are found once per step, after the first substep: a box 3 cm above
// another and falling at 3 m/s (5 cm a step) is still beyond the feature epsilon then (1.75 cm at
// 4 substeps), and meets the other box within the step. Its points are there as speculative ones,
// so it is stopped at the slop in the substep it arrives, not left 2 cm deep for the next step.
TEST(Overlap, AContactThatClosesWithinTheStepIsThereWhenItDoes) {
  for (const int substeps : {4, 16}) {
    phys::World w = world({1, substeps}, kInfinity, Vec3(0.0));
    addBody(w, {0.0, 5.0, 0.0});  // clear of the ground
    phys::BodyDesc d;
    d.center = {0.0, 6.03, 0.0};
    d.velocity = {0.0, -3.0, 0.0};
    w.addBody(d);
    w.step();
    // Face to face, from the corners (particles 0-7 and 8-15; bit 1 of a corner's index is +y):
    // the box is squashed by the landing, so its centre says less.
    double top = -kInfinity, bottom = kInfinity;
    for (phys::ParticleId k{}; k < 8; ++k) {
      if ((k & 2) != 0) top = std::max(top, w.particles().position[k].y);
      if ((k & 2) == 0) bottom = std::min(bottom, w.particles().position[8 + k].y);
    }
    EXPECT_GT(bottom - top, -w.solverSettings().contactSlop - 1e-6) << substeps << " substeps";
  }
}

}  // namespace

// Bullet's pile spawns each ragdoll's hands 5.5 cm into its neighbours'. Parted alone, a hand
// stretched its elbow, whose pins pulled it back into the overlap, and at 128 substeps the fight
// threw the hands at 110 m/s. Jointed parts are parted as one body: whole ragdolls move apart,
// rigid ones (joined by joints, not links) too.
TEST(Overlap, JointedBodiesArePartedWholeSoTheirJointsDoNotFightIt) {
  for (const phys::RagdollModel model : {phys::RagdollModel::Lean, phys::RagdollModel::Rigid})
    for (const int substeps : {4, 128}) {
      phys::World world = testing_phys::openSpace(
          testing_phys::solver(phys::SolverMethod::GaussSeidel, 4, substeps), phys::Vec3(0.0));
      phys::RagdollDesc d;
      d.model = model;
      d.hips = phys::Vec3(-0.85, 0.0, 0.0);  // arms span 1.73 m: the hands overlap 3 cm
      phys::addCapsuleRagdoll(world, d);
      d.hips = phys::Vec3(0.85, 0.0, 0.0);
      phys::addCapsuleRagdoll(world, d);
      world.step();
      ASSERT_GT(world.bodyContacts().size() + world.rigidBodyContacts().size(), 0u) << "the hands touch";
      for (int i = 0; i < 2; ++i) world.step();
      const std::string what = std::string(model == phys::RagdollModel::Lean ? "lean" : "rigid") + ", " +
                               std::to_string(substeps) + " substeps";
      const phys::Metrics m = world.metrics();
      std::printf("two ragdolls' hands 3 cm into each other, %s: fastest %.4f m/s, penetration %.5f m\n",
                  what.c_str(), m.maxSpeed, m.maxPenetration);
      EXPECT_LT(m.maxSpeed, 0.1) << what;
      EXPECT_LT(m.maxPenetration, 2e-3) << what;
      EXPECT_LT(m.maxJointError, 1e-3) << what;
    }
}

namespace {

// The parting's sweeps are SolverSettings::parting: with none, a box spawned 25 cm into another
// in empty space is parted by the projections alone, at most at the depenetration speed (3 m/s,
// 5 cm a step); with the defaults it is parted in the first substep. Neither gives it speed.
TEST(Overlap, ThePartingSweepsAreTheSettingsOnes) {
  auto overlapAfterAStep = [](const phys::PartingSettings& parting) {
    phys::SolverSettings solver;
    solver.parting = parting;
    phys::World w = testing_phys::openSpace(solver, Vec3(0.0));
    addBody(w, {0.0, 0.0, 0.0});
    addBody(w, {0.75, 0.0, 0.0});
    w.step();
    const double gap = w.bodyPose(phys::BodyId{1}).center.x - w.bodyPose(phys::BodyId{0}).center.x - 1.0;
    double fastest = 0.0;
    for (phys::ParticleId p{}; p < w.particles().size(); ++p)
      fastest = std::max(fastest, glm::length(w.velocity(p)));
    EXPECT_LT(fastest, 3.0 + 1e-9);
    return -gap;
  };
  EXPECT_LT(overlapAfterAStep({}), 2e-3);
  phys::PartingSettings none;
  none.plainSweeps = 0;
  none.overRelaxedSweeps = 0;
  const double left = overlapAfterAStep(none);
  EXPECT_GT(left, 0.25 - 3.0 / 60.0 - 2e-3);
  EXPECT_LT(left, 0.25);
}

}  // namespace
