// Box-box contact in motion: the seed's singular face-to-face case, random overlaps, and the
// project's stack and box-of-boxes scenes standing for 10 s.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "physics/world.h"
#include "scenes/scene.h"

namespace {

using phys::Vec3;

scenes::Scene projectScene(const char* name) {
  return scenes::loadSceneFile(scenes::resolveScene(name, scenes::sceneDirectory(DATA_DIR)));
}

// The seed inverted a 4x4 matrix of a face's corners to place a contact, which is singular
// when two faces meet exactly aligned, and then guessed until "objects fly off to infinity".
// Here the same meeting must not gain energy, and both boxes come to rest where they should.
// The energy may rise by what the contact slop allows: the upper box sinking into the lower by
// up to the slop and being held there, m g slop. The corners model then rests; the tetra model
// keeps a small wobble (its contact points are carried by weights of both signs, up to 1.5, and
// a few passes do not settle them), bounded here and recorded in docs/physics.md.
TEST(BoxContact, AlignedFaceToFaceGainsNoEnergyAndRests) {
  for (auto model : {phys::BodyModel::Corners, phys::BodyModel::Tetra}) {
    phys::World world;
    phys::BodyDesc lower, upper;
    lower.model = upper.model = model;
    lower.center = {0.0, 0.5, 0.0};
    upper.center = {0.0, 1.5, 0.0};  // exactly on top: faces coincide
    world.addBody(lower);
    world.addBody(upper);
    const double e0 = world.metrics().energy();
    double most = e0;
    for (int i = 0; i < 300; ++i) {
      world.step();
      most = std::max(most, world.metrics().energy());
    }
    const double slopEnergy = 2.0 * 9.81 * world.solverSettings().contactSlop;
    EXPECT_LE(most, e0 + slopEnergy) << toString(model);
    EXPECT_NEAR(world.bodyPose(phys::BodyId{1}).center.y, 1.5, 0.01) << toString(model);
    std::printf("aligned face to face, %s: upper box off centre by %.4f m, max speed %.4f m/s after 5 s\n",
                std::string(toString(model)).c_str(), std::abs(world.bodyPose(phys::BodyId{1}).center.x),
                world.metrics().maxSpeed);
    if (model == phys::BodyModel::Corners) {
      EXPECT_NEAR(world.bodyPose(phys::BodyId{1}).center.x, 0.0, 1e-4);
      EXPECT_LT(world.metrics().maxSpeed, 1e-3);
    } else {
      EXPECT_NEAR(world.bodyPose(phys::BodyId{1}).center.x, 0.0, 0.05);
      EXPECT_LT(world.metrics().maxSpeed, 0.2);
    }
  }
}

// The project's stack of ten, at its own 1 x 8, stays at rest: after 20 s no particle moves faster
// than 0.6 mm/s. Its contacts are found once per step and kept through the substeps (docs/physics.md,
// "Contacts once per step"); with each kept contact's normal held fixed in the world it still moved
// at 1.4 mm/s, with the normal turned with its face 0.22 mm/s (found every substep: 0.10 mm/s).
TEST(BoxContact, TheStackOfTenStaysAtRest) {
  scenes::Scene scene = projectScene("stack");
  for (int i = 0; i < 1200; ++i) scene.world.step();
  EXPECT_LT(scene.world.metrics().maxSpeed, 6e-4);
}

// Overlap of two oriented boxes along the SAT's axis, for a box moved along a direction.
phys::Obb obbOf(const phys::BodyDesc& d) {
  phys::Obb o;
  o.center = d.center;
  o.axes = glm::mat3_cast(d.orientation);
  o.halfExtents = d.size * 0.5;
  return o;
}

TEST(BoxContact, ThousandRandomOverlapsSeparateWithoutSpeed) {
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> unit(0.0, 1.0), size(0.3, 1.5);
  int separated = 0;
  double fastest = 0.0, worstOverlap = 0.0;
  for (int trial = 0; trial < 1000; ++trial) {
    phys::BodyDesc a, b;
    a.size = {size(random), size(random), size(random)};
    b.size = {size(random), size(random), size(random)};
    // Drawn one declarator at a time: the order of a call's arguments is the compiler's (GCC's right
    // to left, clang's left to right), and each compiler would test its own thousand overlaps.
    auto turn = [&] {
      const double w = unit(random), x = unit(random) - 0.5, y = unit(random) - 0.5, z = unit(random) - 0.5;
      return glm::normalize(glm::dquat(w, x, y, z));
    };
    a.orientation = turn();
    b.orientation = turn();
    a.model = trial % 2 == 0 ? phys::BodyModel::Corners : phys::BodyModel::Tetra;
    b.model = trial % 3 == 0 ? phys::BodyModel::Corners : phys::BodyModel::Tetra;
    const double dx = unit(random) - 0.5, dy = unit(random) - 0.5, dz = unit(random) - 0.5;
    const Vec3 direction = glm::normalize(Vec3(dx, dy, dz));
    const double smallest = std::min({a.size.x, a.size.y, a.size.z, b.size.x, b.size.y, b.size.z});
    const double target = unit(random) * 0.25 * smallest;  // up to 25% of the smaller box
    // Move b out along the direction until the SAT overlap is the target (it shrinks as b leaves).
    double lo = 0.0, hi = 4.0;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      b.center = direction * mid;
      const phys::SatResult r = phys::satTest(obbOf(a), obbOf(b));
      if (r.overlap && r.depth > target)
        lo = mid;
      else
        hi = mid;
    }
    b.center = direction * hi;

    phys::WorldSettings ws;
    ws.ground = false;
    ws.gravity = Vec3(0.0);
    phys::World world(ws);
    world.addBody(a);
    world.addBody(b);
    for (int i = 0; i < 60; ++i) {
      world.step();
      fastest = std::max(fastest, world.metrics().maxSpeed);
    }
    // Separated: the contact points are apart to within the slop, and the boxes fitted to the
    // particles overlap by less than the feature epsilon (a box bent by its sticks' residual
    // error differs from its fitted frame by millimetres).
    // The overlap is the least along any axis: the SAT's chosen axis leans to faces, and a slanted
    // pair can be apart but for a hair along an edge-edge axis while a face axis says a centimetre.
    const phys::SatResult after = phys::satTest(world.bodyFrames()[0], world.bodyFrames()[1]);
    const double overlap = !after.overlap        ? 0.0
                           : after.edgeAxis >= 0 ? std::min(after.depth, after.edgeDepth)
                                                 : after.depth;
    worstOverlap = std::max(worstOverlap, overlap);
    const bool apart = world.metrics().maxPenetration <= world.solverSettings().contactSlop + 1e-4 &&
                       overlap <= world.solverSettings().featureEpsilon;
    separated += apart ? 1 : 0;
    for (const Vec3& p : world.particles().position) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
  }
  std::printf(
      "1000 random overlaps: %d separated within 60 steps, worst overlap left %.4f m, fastest %.4f m/s\n",
      separated, worstOverlap, fastest);
  EXPECT_EQ(separated, 1000);
  EXPECT_LT(fastest, 5.0);
}

// The largest distance any box moved between two moments, in units of its own size.
struct Standing {
  double topDrift;    // m, the last box of the scene, from 2 s to the end
  double worstDrift;  // the largest drift of any box over its smallest edge
  double maxPenetration;
};

Standing standFor(scenes::Scene scene, double seconds = 10.0) {
  phys::World& w = scene.world;
  while (w.time() < 2.0) w.step();
  std::vector<Vec3> settled;
  for (phys::BodyId b{}; b < w.bodies().size(); ++b) settled.push_back(w.bodyPose(b).center);
  Standing s{0.0, 0.0, 0.0};
  while (w.time() < seconds) {
    w.step();
    s.maxPenetration = std::max(s.maxPenetration, w.metrics().maxPenetration);
  }
  for (phys::BodyId b{}; b < w.bodies().size(); ++b) {
    const Vec3 half = w.bodies()[b].halfExtents;
    const double drift = glm::length(w.bodyPose(b).center - settled[b]);
    s.worstDrift = std::max(s.worstDrift, drift / (2.0 * std::min({half.x, half.y, half.z})));
  }
  s.topDrift =
      glm::length(w.bodyPose(static_cast<phys::BodyId>(w.bodies().size() - 1)).center - settled.back());
  EXPECT_EQ(w.metrics().frozen, 0);
  return s;
}

TEST(Stacking, TenBoxStackStandsFor10Seconds) {
  const Standing s = standFor(projectScene("stack"));
  std::printf(
      "stack of 10 (1 iteration x 8 substeps): top drift %.5f m from 2 s to 10 s, max overlap %.4f m\n",
      s.topDrift, s.maxPenetration);
  EXPECT_LT(s.topDrift, 0.05 * 1.0);  // 5% of the 1 m box
  EXPECT_LT(s.maxPenetration, 0.01);
}

TEST(Stacking, SeedsBoxOfBoxesStandsFor10Seconds) {
  const Standing s = standFor(projectScene("box-of-boxes"));
  std::printf(
      "box of boxes (3 iterations, 1 substep): worst drift %.4f of a box's size, max overlap %.4f m\n",
      s.worstDrift, s.maxPenetration);
  EXPECT_LT(s.worstDrift, 0.05);
  EXPECT_LT(s.maxPenetration, 0.01);
}

// For a minute, not 10 s: at 10 iterations x 1 substep, its settings before, its worst box crept
// 2% of its size in the first 10 s and 20% in the minute. At 1 x 8 it comes to rest (0.005%); the bound, 1%,
// is what "stands" means here.
TEST(Stacking, SeedsPyramidStandsForAMinute) {
  const Standing s = standFor(projectScene("pyramid"), 60.0);
  std::printf(
      "pyramid of 15 boxes that vary in size (1 iteration x 8 substeps): worst drift %.6f of a box's size "
      "from 2 s to 60 s, max overlap %.4f m\n",
      s.worstDrift, s.maxPenetration);
  EXPECT_LT(s.worstDrift, 0.01);
  EXPECT_LT(s.maxPenetration, 0.01);
}

// 16 ragdolls dropped in crossed layers settle into a pile with no part inside another by
// more than 2 cm (the bound), checked over the last 5 of 10 s.
TEST(RagdollPile, SixteenRagdollsSettleWithoutDeepOverlap) {
  scenes::Scene scene = projectScene("ragdolls");
  phys::World& w = scene.world;
  ASSERT_EQ(w.bodies().size(), 160u);
  double worstOverlap = 0.0, lastSpeed = 0.0;
  for (int step = 1; step <= 600; ++step) {
    w.step();
    if (step <= 300) continue;
    for (const phys::BodyContact& c : w.bodyContacts()) {
      worstOverlap = std::max(worstOverlap, -glm::dot(c.normal, w.position(c.pointB) - w.position(c.pointA)));
    }
    lastSpeed = w.metrics().maxSpeed;
  }
  const phys::Metrics m = w.metrics();
  std::printf(
      "pile of 16 ragdolls: worst part-part overlap %.4f m from 5 s to 10 s; at 10 s fastest particle %.3f "
      "m/s, stick error %.4f, joint gap %.4f m\n",
      worstOverlap, lastSpeed, m.maxConstraintError, m.maxJointError);
  EXPECT_LT(worstOverlap, 0.02);
  EXPECT_EQ(m.frozen, 0);
  EXPECT_TRUE(std::isfinite(m.energy()));
}

// A pile's fastest point (metrics().maxSpeed) sampled each second from 10 s to 30 s of 60 Hz steps.
struct Settling {
  double median = 0.0;  // m/s
  double most = 0.0;    // m/s
};

Settling settleFor30Seconds(phys::World& w) {
  std::vector<double> fastest;
  for (int step = 1; step <= 1800; ++step) {
    w.step();
    if (step >= 600 && step % 60 == 0) fastest.push_back(w.metrics().maxSpeed);
  }
  std::sort(fastest.begin(), fastest.end());
  return {fastest[fastest.size() / 2], fastest.back()};
}

// The same pile from 10 s to 30 s, sampled each second: the median of its fastest particle is
// under 5 cm/s (measured 0.016 m/s). Contact points far beside a face, which rocked crossed limbs
// against their joints, kept it at 0.25 m/s (docs/physics.md, "Piles at rest").
TEST(RagdollPile, SixteenRagdollsComeNearlyToRest) {
  scenes::Scene scene = projectScene("ragdolls");
  const Settling s = settleFor30Seconds(scene.world);
  std::printf("pile of 16 ragdolls from 10 s to 30 s: fastest particle median %.4f m/s, most %.4f m/s\n",
              s.median, s.most);
  EXPECT_LT(s.median, 0.05);
  EXPECT_EQ(scene.world.metrics().frozen, 0);
}

// The same pile with rigid parts, at the scene's 2 iterations x 4 substeps: the median of its fastest
// point from 10 s to 30 s is under 0.4 m/s (measured 0.22). With each part's solid inertia
// (inertia floor 0) forearms at their elbows' stops turned about their long axes and back every
// substep, and the median was 0.71 m/s (docs/physics.md, "Inertia floor"). The pile still settles
// more slowly than the particle one: whole parts creep and slip at a few cm/s.
TEST(RagdollPile, SixteenRigidRagdollsSettleAtFourSubsteps) {
  scenes::LoadOptions rigid;
  rigid.ragdollModel = phys::RagdollModel::Rigid;
  scenes::Scene scene =
      scenes::loadSceneFile(scenes::resolveScene("ragdolls", scenes::sceneDirectory(DATA_DIR)), rigid);
  phys::World& w = scene.world;
  ASSERT_EQ(w.rigidBodies().size(), 160u);
  ASSERT_EQ(w.solverSettings().substeps, 4);
  const Settling s = settleFor30Seconds(w);
  std::printf("rigid pile of 16 ragdolls from 10 s to 30 s: fastest point median %.4f m/s, most %.4f m/s\n",
              s.median, s.most);
  EXPECT_LT(s.median, 0.4);
  EXPECT_EQ(w.metrics().frozen, 0);
}

// Where the seed's settings fail: the same stack at 3 iterations and 1 substep does not stand
// (it wobbles and starts to topple within 10 s). Recorded so the docs can point at it; if it
// ever stands, the docs are out of date.
TEST(Stacking, TenBoxStackAtTheSeedsSettingsDoesNotStand) {
  scenes::Scene scene = projectScene("stack");
  phys::SolverSettings seed = scene.world.solverSettings();
  seed.iterations = 3;
  seed.substeps = 1;
  scene.world.setSolverSettings(seed);
  const Standing s = standFor(std::move(scene));
  std::printf("stack of 10 at 3 iterations x 1 substep: top drift %.3f m\n", s.topDrift);
  EXPECT_GT(s.topDrift, 0.05);
}

// Issue 14's targets for the rigid model, on the stability suite's own files with every box made
// rigid (scenes::LoadOptions, as `lab stability --models rigid`) at the cheapest setting, one
// substep of one iteration: the pyramid of 20 rows (210 boxes) and the stack of 40 stand a minute,
// no box moving more than 0.1 m from where it started (the suite's criterion, over 60 s instead of
// its 4 and 10). Measured (docs/physics.md, "Standing for a minute"): the pyramid's worst box 55 um,
// the stack's top box 1.4 cm, most of it in the first 10 steps. What each costs beside Bullet's step
// is a benchmark (docs/performance.md, "Beside Bullet awake"). Not run under ASan (a minute of 210
// boxes); RigidBody.PyramidStandsAtOneSubstep and RigidBody.StackOfFortyStandsAMinuteAtOneSubstep
// are its fast counterparts there.
double worstDriftOverAMinute(const char* suiteScene, bool topOnly) {
  scenes::LoadOptions rigid;
  rigid.boxModel = phys::BodyModel::Rigid;
  const auto file = scenes::sceneDirectory(DATA_DIR) / "stability" / suiteScene;
  scenes::Scene scene = scenes::loadSceneFile(file, rigid);
  phys::World& w = scene.world;
  phys::SolverSettings s = w.solverSettings();
  s.method = phys::SolverMethod::Xpbd;
  s.iterations = 1;
  s.substeps = 1;
  w.setSolverSettings(s);
  std::vector<Vec3> start;
  for (phys::BodyId b{}; b < w.bodies().size(); ++b) {
    EXPECT_EQ(w.bodies()[b].model, phys::BodyModel::Rigid);
    start.push_back(w.bodyPose(b).center);
  }
  const phys::BodyId first = topOnly ? static_cast<phys::BodyId>(w.bodies().size() - 1) : phys::BodyId{};
  double worst = 0.0;
  while (w.time() < 60.0 - 1e-9) {
    w.step();
    for (phys::BodyId b = first; b < w.bodies().size(); ++b)
      worst = std::max(worst, glm::length(w.bodyPose(b).center - start[b]));
  }
  EXPECT_EQ(w.metrics().frozen, 0);
  return worst;
}

TEST(RigidSuite, PyramidOfTwentyRowsStandsAMinuteAtOneSubstep) {
  const double worst = worstDriftOverAMinute("pyramid-20.xml", false);
  std::printf("pyramid-20, rigid, xpbd 1 x 1: worst box moved %.3g m in 60 s\n", worst);
  EXPECT_LT(worst, 0.1 * 0.01);  // a hundredth of the suite's limit; measured 5.5e-5 m
}

TEST(RigidSuite, StackOfFortyStandsAMinuteAtOneSubstep) {
  const double worst = worstDriftOverAMinute("stack-40.xml", true);
  std::printf("stack-40, rigid, xpbd 1 x 1: top box moved %.3g m in 60 s\n", worst);
  EXPECT_LT(worst, 0.1 * 0.3);  // under a third of the suite's limit; measured 1.4 cm
}

}  // namespace
