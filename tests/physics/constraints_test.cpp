// Sticks and range sticks in each method, metrics of a known state, and debug drawing.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_util.h"

namespace {

using phys::SolverMethod;
using phys::Vec3;

const SolverMethod kMethods[] = {SolverMethod::GaussSeidel, SolverMethod::Jacobi, SolverMethod::Xpbd,
                                 SolverMethod::Shake};

TEST(Sticks, RelaxationRestoresLengthAndKeepsTheCentreOfMass) {
  for (SolverMethod m : kMethods) {
    phys::World world = testing_phys::openSpace(testing_phys::solver(m, 1, 1), Vec3(0.0));
    // Start stretched by 20%: the corrected projection moves each end in proportion to 1/m, so
    // the length comes back in one pass and the centre of mass stays where it was (the
    // printed listing would move them apart instead).
    const auto a = world.addParticle({Vec3(-0.2, 0.0, 0.0), Vec3(0.0), 1.0});
    const auto b = world.addParticle({Vec3(1.0, 0.0, 0.0), Vec3(0.0), 3.0});
    world.addParticle({Vec3(5.0)});  // unrelated particle, must not matter
    world.addStick(a, b, 1.0, 0.0);
    world.step();
    const auto& p = world.particles().position;
    EXPECT_NEAR(p[b].x - p[a].x, 1.0, 1e-12) << toString(m);
    EXPECT_NEAR((1.0 * p[a].x + 3.0 * p[b].x) / 4.0, (1.0 * -0.2 + 3.0 * 1.0) / 4.0, 1e-12) << toString(m);
  }
}

TEST(RangeSticks, PushOnlyBelowMinAndPullOnlyAboveMax) {
  for (SolverMethod m : kMethods) {
    // Jacobi scales each stick by 1 / the larger stick count at its ends (4 at the pivot), so it
    // needs more passes to converge; the others are exact in one.
    const int passes = m == SolverMethod::Jacobi ? 200 : 1;
    phys::World world = testing_phys::openSpace(testing_phys::solver(m, passes, 1), Vec3(0.0));
    const auto pivot = world.addParticle({Vec3(0.0), Vec3(0.0), 0.0, true});
    const auto inside = world.addParticle({Vec3(1.5, 0.0, 0.0), Vec3(0.0), 1.0});
    const auto tooClose = world.addParticle({Vec3(0.0, 0.5, 0.0), Vec3(0.0), 1.0});
    const auto tooFar = world.addParticle({Vec3(0.0, 0.0, 3.0), Vec3(0.0), 1.0});
    const auto minOnlyFar = world.addParticle({Vec3(0.0, -5.0, 0.0), Vec3(0.0), 1.0});
    world.addRange(pivot, inside, 1.0, 2.0);
    world.addRange(pivot, tooClose, 1.0, 2.0);
    world.addRange(pivot, tooFar, 1.0, 2.0);
    world.addRange(pivot, minOnlyFar, 1.0, phys::kNoMaxLength);  // one-sided: never pulls
    world.step();
    const auto& p = world.particles().position;
    EXPECT_EQ(p[inside], Vec3(1.5, 0.0, 0.0)) << toString(m);
    EXPECT_NEAR(glm::length(p[tooClose]), 1.0, 1e-12) << toString(m);
    EXPECT_NEAR(glm::length(p[tooFar]), 2.0, 1e-12) << toString(m);
    EXPECT_EQ(p[minOnlyFar], Vec3(0.0, -5.0, 0.0)) << toString(m);
  }
}

// Every method keeps the total momentum of a free network: each stick's two corrections are
// equal and opposite in momentum. A free, lopsided network with unequal masses, thrown and
// spinning, is stepped for 10 s.
TEST(Momentum, EveryMethodKeepsTheMomentumOfAFreeNetwork) {
  for (SolverMethod m : kMethods) {
    phys::World world = testing_phys::openSpace(testing_phys::solver(m, 4, 2), Vec3(0.0));
    const Vec3 positions[] = {{0, 0, 0}, {1, 0, 0}, {0, 1.5, 0}, {0, 0, 2}, {1, 1, 1}};
    const double masses[] = {1.0, 3.0, 0.5, 2.0, 7.0};
    const Vec3 velocities[] = {{-3, 20, 1}, {0, 0, 0}, {5, 0, -2}, {0, -4, 0}, {1, 1, 1}};
    for (int i = 0; i < 5; ++i) world.addParticle({positions[i], velocities[i], masses[i]});
    const int pairs[][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2},
                            {1, 4}, {2, 4}, {3, 4}};  // particle 4 has 3 sticks, 0 has 3, 2 has 3
    for (const auto& pair : pairs) world.addStick(phys::ParticleId(pair[0]), phys::ParticleId(pair[1]));
    auto momentum = [&] {
      Vec3 sum(0.0);
      for (phys::ParticleId i{}; i < 5; ++i) sum += world.velocity(i) / world.particles().inverseMass[i];
      return sum;
    };
    const Vec3 before = momentum();
    for (int i = 0; i < 600; ++i) world.step();
    EXPECT_LT(glm::length(momentum() - before), 1e-9 * glm::length(before)) << toString(m);
  }
}

TEST(Validation, SolverSettingsNameTheBadField) {
  phys::SolverSettings s;
  EXPECT_EQ(phys::validate(s), "");
  s.dt = 0.0;
  EXPECT_NE(phys::validate(s).find("dt"), std::string::npos);
  s.dt = std::nan("");
  EXPECT_NE(phys::validate(s).find("dt"), std::string::npos);
  s = {};
  s.iterations = 0;
  EXPECT_NE(phys::validate(s).find("iterations"), std::string::npos);
  s.iterations = phys::kMaxIterations + 1;
  EXPECT_NE(phys::validate(s).find("iterations"), std::string::npos);
  s = {};
  s.dt = 1e-200;  // h^2 would underflow and XPBD's compliance / h^2 become infinite
  EXPECT_NE(phys::validate(s).find("dt"), std::string::npos);
  s = {};
  s.substeps = -1;
  EXPECT_NE(phys::validate(s).find("substeps"), std::string::npos);
  s = {};
  s.broadPhase.maxStrips = 0;
  EXPECT_NE(phys::validate(s).find("broadPhase.maxStrips"), std::string::npos);
  s = {};
  s.broadPhase.maxStripsPerBody = 0;
  EXPECT_NE(phys::validate(s).find("broadPhase.maxStripsPerBody"), std::string::npos);
  s = {};
  s.parting.overRelaxation = 2.0;  // does not converge
  EXPECT_NE(phys::validate(s).find("parting.overRelaxation"), std::string::npos);
  s = {};
  s.parting.progressSweeps = 0;  // a division by it
  EXPECT_NE(phys::validate(s).find("parting.progressSweeps"), std::string::npos);
  s = {};
  s.parting.tolerance = std::nan("");
  EXPECT_NE(phys::validate(s).find("parting.tolerance"), std::string::npos);
  s = {};
  s.manifoldReuse.maxShift = -0.001;
  EXPECT_NE(phys::validate(s).find("manifoldReuse.maxShift"), std::string::npos);
  s = {};
  s.manifoldReuse.maxTurn = std::numeric_limits<phys::Real>::infinity();
  EXPECT_NE(phys::validate(s).find("manifoldReuse.maxTurn"), std::string::npos);
}

TEST(Validation, WorldSettingsNameTheBadField) {
  phys::WorldSettings w;
  EXPECT_EQ(phys::validate(w), "");
  w.damping = -1.0;
  EXPECT_NE(phys::validate(w).find("damping"), std::string::npos);
  w = {};
  w.gravity.y = INFINITY;
  EXPECT_NE(phys::validate(w).find("gravity"), std::string::npos);
  w = {};
  w.groundNormal = Vec3(0.0);
  EXPECT_NE(phys::validate(w).find("groundNormal"), std::string::npos);
  w = {};
  w.groundMaterial.staticFriction = -0.1;
  EXPECT_NE(phys::validate(w).find("static friction"), std::string::npos);
  w = {};
  w.shapeCheckInterval = 0.0;
  EXPECT_NE(phys::validate(w).find("shapeCheckInterval"), std::string::npos);
}

// The ground's point nearest the origin must lie within the bound along each axis, or every body
// resting on it would be frozen as lost; a tilted ground may lie farther than the bound.
TEST(Validation, AGroundBeyondTheBoundIsRefused) {
  phys::WorldSettings w;
  w.bound = 100.0;
  w.groundHeight = 100.0;
  EXPECT_EQ(phys::validate(w), "");
  w.groundHeight = -100.5;
  EXPECT_NE(phys::validate(w).find("groundHeight"), std::string::npos);
  w.groundNormal = Vec3(1.0, 1.0, 0.0);  // its nearest point at (71, 71, 0) m
  EXPECT_EQ(phys::validate(w), "");
  w.groundHeight = 1e300;
  EXPECT_NE(phys::validate(w).find("groundHeight"), std::string::npos);
}

// Every component finite, but the length overflows to inf: setWorldSettings would normalise the
// normal to 0, a ground that holds nothing up, without a word.
TEST(Validation, GroundNormalOfOverflowingLengthIsRefused) {
  phys::WorldSettings w;
  w.groundNormal = Vec3(0.0, 1e200, 0.0);
  EXPECT_NE(phys::validate(w).find("groundNormal"), std::string::npos);
  phys::World world;
  EXPECT_THROW(world.setWorldSettings(w), std::invalid_argument);
  EXPECT_EQ(world.worldSettings().groundNormal, Vec3(0.0, 1.0, 0.0));
  w.groundNormal = Vec3(0.0, 1e150, 0.0);  // long, but its length is finite: made unit
  ASSERT_EQ(phys::validate(w), "");
  world.setWorldSettings(w);
  EXPECT_EQ(world.worldSettings().groundNormal, Vec3(0.0, 1.0, 0.0));
}

TEST(Validation, RejectedInputChangesNothing) {
  phys::World world;
  phys::SolverSettings bad;
  bad.iterations = 0;
  EXPECT_THROW(world.setSolverSettings(bad), std::invalid_argument);
  EXPECT_EQ(world.solverSettings().iterations, phys::SolverSettings{}.iterations);
  EXPECT_THROW(phys::World(phys::WorldSettings{}, bad), std::invalid_argument);
  EXPECT_THROW(world.addParticle({Vec3(std::nan(""), 0, 0)}), std::invalid_argument);
  EXPECT_THROW(world.addParticle({Vec3(0.0), Vec3(0.0), -1.0}), std::invalid_argument);
  phys::BodyDesc box;
  box.size = {1.0, 0.0, 1.0};
  EXPECT_THROW(world.addBody(box), std::invalid_argument);
  box = {};
  box.mass = 0.0;
  EXPECT_THROW(world.addBody(box), std::invalid_argument);
  box = {};
  box.orientation = phys::Quat(0.0, 0.0, 0.0, 0.0);
  EXPECT_THROW(world.addBody(box), std::invalid_argument);
  EXPECT_EQ(world.particles().size(), 0u);  // nothing half-added
  EXPECT_TRUE(world.bodies().empty());
  EXPECT_THROW(world.addStick(phys::ParticleId{0}, phys::ParticleId{1}), std::invalid_argument);
  const auto a = world.addParticle({Vec3(0.0)});
  const auto b = world.addParticle({Vec3(1.0)});
  EXPECT_THROW(world.addStick(a, b, -1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(world.addStick(a, b, 1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(world.addStick(a, b, 1.0, 1e300), std::invalid_argument);  // compliance beyond kMaxCompliance
  EXPECT_THROW(world.addParticle({Vec3(0.0), Vec3(0.0), 1e-320}), std::invalid_argument);  // 1/m overflows
  phys::BodyDesc huge;
  huge.center = Vec3(1e308);
  huge.size = Vec3(1e308);
  const std::size_t particlesBefore = world.particles().size();
  EXPECT_THROW(world.addBody(huge), std::invalid_argument);
  EXPECT_EQ(world.particles().size(), particlesBefore);  // nothing half-added
  EXPECT_THROW(world.addRange(a, b, 2.0, 1.0), std::invalid_argument);
  EXPECT_THROW(world.addStick(a, a), std::invalid_argument);
  EXPECT_TRUE(world.sticks().empty());
}

TEST(Metrics, EnergyAndErrorsOfAKnownState) {
  phys::World world = testing_phys::openSpace();
  const auto a = world.addParticle({Vec3(0.0, 2.0, 0.0), Vec3(3.0, 0.0, 0.0), 2.0});
  const auto b = world.addParticle({Vec3(1.1, 2.0, 0.0), Vec3(0.0), 0.0, true});
  world.addStick(a, b, 1.0, 0.0);  // 10% too long
  const phys::Metrics m = world.metrics();
  // The velocity of a new particle is the one at its creation time, up to half a substep of
  // gravity in x - x* (see addParticle); kinetic energy 1/2 m v^2 to that accuracy.
  EXPECT_NEAR(m.kineticEnergy, 0.5 * 2.0 * 9.0, 0.01);
  // Potential at the half step (see Metrics), a quarter of g h^2 below x; the pinned one has none.
  const double h = 1.0 / 60.0;
  EXPECT_NEAR(m.potentialEnergy, 2.0 * 9.81 * (2.0 - 9.81 * h * h / 4.0), 1e-9);
  EXPECT_NEAR(m.maxConstraintError, 0.1, 1e-12);
  EXPECT_NEAR(m.rmsConstraintError, 0.1, 1e-12);
  EXPECT_NEAR(m.maxSpeed, 3.0, 0.1);
}

TEST(Metrics, ContactsAndPenetrationOnTheGround) {
  phys::World world;
  phys::BodyDesc box;
  box.center = {0.0, 0.5, 0.0};
  world.addBody(box);
  world.addParticle({Vec3(3.0, 0.0, 0.0)});
  world.step();
  const phys::Metrics m = world.metrics();
  EXPECT_EQ(m.contacts, 5);  // four bottom corners and the particle
  EXPECT_LE(m.maxPenetration, 1e-12);
  const phys::Profile& p = world.profile();
  EXPECT_GT(p.total, 0.0);
  EXPECT_GE(p.total, p.staged() - 1e-6);
  // A box on the ground: its 22 sticks and its contacts were projected, three times each.
  EXPECT_GT(p[phys::Stage::Sticks], 0.0);
  EXPECT_GT(p[phys::Stage::Contacts], 0.0);
}

class RecordingDraw : public phys::DebugDraw {
 public:
  int lines = 0, points = 0, boxes = 0, red = 0, green = 0;
  void line(const Vec3&, const Vec3&, phys::Color c) override {
    ++lines;
    red += c.r > 0.8f && c.g < 0.2f ? 1 : 0;
  }
  void point(const Vec3&, phys::Real, phys::Color c) override {
    ++points;
    green += c.g > 0.8f && c.r < 0.2f ? 1 : 0;
  }
  void box(const Vec3&, const phys::Quat&, const Vec3&, phys::Color) override { ++boxes; }
};

TEST(DebugDraw, DrawsWhatTheFlagsAskFor) {
  phys::World world;
  phys::BodyDesc box;
  box.center = {0.0, 0.5, 0.0};
  world.addBody(box);
  box.center = {3.0, 0.5, 0.0};
  box.model = phys::BodyModel::Tetra;
  world.addBody(box);
  world.step();
  RecordingDraw all;
  world.debugDraw(all, {true, true, true, false, true});
  EXPECT_EQ(all.lines, 22 + 6);
  EXPECT_EQ(all.red, 28);
  EXPECT_EQ(all.points, 12 + 8);  // particles, then the 8 bottom corners touching the ground
  EXPECT_EQ(all.green, 8);
  EXPECT_EQ(all.boxes, 2);
  RecordingDraw none;
  world.debugDraw(none, {false, false, false, false, false});
  EXPECT_EQ(none.lines + none.points + none.boxes, 0);
}

}  // namespace
