// Boxes of both models: pose read-back, rest on the ground, an incline with friction, a drop.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "physics/tetra_volumes.h"
#include "test_util.h"

namespace {

using phys::BodyModel;
using phys::Vec3;
using testing_phys::angleBetween;

double maxSpeed(const phys::World& world) {
  double v = 0.0;
  for (phys::ParticleId i{}; i < world.particles().size(); ++i)
    v = std::max(v, glm::length(world.velocity(i)));
  return v;
}

class BoxModels : public ::testing::TestWithParam<BodyModel> {};

TEST_P(BoxModels, PoseAndCornersReadBackWhatWasCreated) {
  phys::World world;
  phys::BodyDesc desc;
  desc.model = GetParam();
  desc.center = {1.0, 2.0, -3.0};
  desc.size = {0.5, 1.0, 2.0};
  desc.orientation = glm::dquat(glm::radians(glm::dvec3(30.0, -50.0, 75.0)));
  const phys::BodyId id = world.addBody(desc);
  const phys::BodyPose pose = world.bodyPose(id);
  EXPECT_LE(glm::length(pose.center - desc.center), 1e-12);
  EXPECT_LE(angleBetween(pose.orientation, desc.orientation), 1e-7);
  const phys::Body& box = world.bodies()[id];
  for (int k = 0; k < 8; ++k) {
    const Vec3 expected = desc.center + desc.orientation * phys::boxCornerLocal(box.halfExtents, k);
    EXPECT_LE(glm::length(world.position(world.corners()[box.firstCorner + k]) - expected), 1e-12) << k;
  }
}

// A needle or a sheet: the shape-matching matrix's singular values are up to 1e12 apart, which
// unscaled Newton did not resolve in its 20 steps (a 0.001 x 10 x 0.001 m box turned by 30
// degrees read back 1.5e-5 rad off, and each save and reload turned it as much again; at
// 0.001 x 1000 x 0.001, by 1.2 rad). The fuzzer's harness found it.
TEST_P(BoxModels, PoseReadsBackAtAnyAspectRatio) {
  const Vec3 sizes[] = {
      {0.001, 10.0, 0.001}, {0.001, 1000.0, 0.001}, {1000.0, 0.001, 1000.0}, {0.001, 1.0, 1000.0}};
  for (const Vec3& size : sizes) {
    for (const Vec3& euler : {Vec3(0.0, 0.0, 30.0), Vec3(30.0, -50.0, 75.0), Vec3(0.0, 179.0, 0.0)}) {
      phys::World world;
      phys::BodyDesc desc;
      desc.model = GetParam();
      desc.size = size;
      desc.orientation = glm::dquat(glm::radians(euler));
      const phys::BodyPose pose = world.bodyPose(world.addBody(desc));
      // Round-off of the corners, 1e-16 of the longest side, seen over the shortest: 1e-10 rad.
      EXPECT_LE(angleBetween(pose.orientation, desc.orientation), 1e-10)
          << size.x << " x " << size.y << " x " << size.z << " turned " << euler.x << " " << euler.y << " "
          << euler.z;
    }
  }
}

// The rest test: 10 s on the ground, drift < 1 mm, penetration < 1% of the size, final
// speed < 1 mm/s.
TEST_P(BoxModels, AtRestOnTheGroundFor10Seconds) {
  phys::World world;
  phys::BodyDesc desc;
  desc.model = GetParam();
  desc.center = {0.0, 0.5, 0.0};
  const phys::BodyId id = world.addBody(desc);
  double deepest = 0.0;
  for (int i = 0; i < 600; ++i) {
    world.step();
    deepest = std::max(deepest, world.metrics().maxPenetration);
  }
  const phys::BodyPose pose = world.bodyPose(id);
  EXPECT_LT(glm::length(pose.center - desc.center), 1e-3);
  EXPECT_LT(deepest, 0.01 * desc.size.y);
  EXPECT_LT(maxSpeed(world), 1e-3);
  // Gauss-Seidel visits the bottom corners in order, so the sag is not quite level: a tilt of
  // under a milliradian, set in the first steps and then constant.
  EXPECT_LE(angleBetween(pose.orientation, desc.orientation), 1e-3);
}

// Slabs lying flat at the seed's settings (3 passes, 1 substep). A tetra slab's tetrahedron is as
// flat as the slab, and its sticks alone held its thickness only as (thickness / edge)^2 per pass:
// the 2 x 0.1 x 0.5 m slab's top particles sank through its bottom ones in 9 steps, leaving it
// inside out with its centre at 0.7 mm, and a 1 x 0.3 x 1 m one sank 5 mm. At rest, the slab
// keeps its centre within the 1 mm contact slop (under 1% of its thickness) and its orientation.
TEST_P(BoxModels, ASlabLyingOnTheGroundKeepsItsThickness) {
  for (const Vec3& size : {Vec3(2.0, 0.1, 0.5), Vec3(1.0, 0.15, 1.0), Vec3(1.0, 0.3, 1.0)}) {
    phys::World world;
    phys::BodyDesc desc;
    desc.model = GetParam();
    desc.size = size;
    desc.center = {0.0, 0.5 * size.y, 0.0};
    const phys::BodyId id = world.addBody(desc);
    for (int i = 0; i < 600; ++i) world.step();
    const phys::BodyPose pose = world.bodyPose(id);
    EXPECT_LT(glm::length(pose.center - desc.center), 1e-3) << size.x << " x " << size.y << " x " << size.z;
    EXPECT_LE(angleBetween(pose.orientation, desc.orientation), 1e-3)
        << size.x << " x " << size.y << " x " << size.z;
    EXPECT_LT(maxSpeed(world), 1e-3) << size.x << " x " << size.y << " x " << size.z;
  }
}

// A 20 degree incline: tan(20) = 0.36, so friction 0.5 holds the box and 0.2 lets it slide with
// acceleration g (sin - mu cos) = 1.51 m/s^2. The ground plane is tilted, gravity is not.
struct Incline {
  double acceleration;  // m/s^2 along the slope, downhill, fitted over the second second
  double startSlip;     // m moved in the first second, while the contacts take up the load
  double drift;         // m moved from 1 s to 10 s
};

Incline onIncline(BodyModel model, double mu) {
  const double angle = glm::radians(20.0);
  phys::WorldSettings ws;
  ws.groundNormal = {-std::sin(angle), std::cos(angle), 0.0};
  ws.groundMaterial = {mu, mu};
  phys::World world(ws);
  phys::BodyDesc desc;
  desc.model = model;
  desc.material = {mu, mu};
  desc.orientation = glm::angleAxis(angle, Vec3(0.0, 0.0, 1.0));
  desc.center = ws.groundNormal * 0.5;
  world.addBody(desc);
  const Vec3 downhill = -Vec3(std::cos(angle), std::sin(angle), 0.0);
  auto along = [&] { return glm::dot(world.bodyPose(phys::BodyId{0}).center - desc.center, downhill); };
  std::vector<double> s;  // position along the slope at t = 1, 1.5, 2 s
  for (int i = 1; i <= 600; ++i) {
    world.step();
    if (i == 60 || i == 90 || i == 120) s.push_back(along());
  }
  const double dt = 0.5;
  return {(s[2] - 2.0 * s[1] + s[0]) / (dt * dt), s[0], along() - s[0]};
}

TEST_P(BoxModels, InclineHoldsWithFriction05AndSlidesAtCoulombRateWith02) {
  const Incline held = onIncline(GetParam(), 0.5);
  const Incline slid = onIncline(GetParam(), 0.2);
  const double expected = 9.81 * (std::sin(glm::radians(20.0)) - 0.2 * std::cos(glm::radians(20.0)));
  std::printf(
      "%s box on a 20 degree incline: mu 0.5 slips %.2g m in the first second, then %.2g m in 9 s; "
      "mu 0.2 accelerates at %.4f m/s^2 (Coulomb: %.4f)\n",
      std::string(toString(GetParam())).c_str(), held.startSlip, held.drift, slid.acceleration, expected);
  // In the first steps only the bottom corners' own weight presses on the ground, so static
  // friction is short of what it will be; the box slips a few millimetres and then holds. The
  // tetra model's corners are carried by weights of both signs, and friction's corrections
  // through them leave a slow creep (under a millimetre a second; docs/physics.md).
  EXPECT_LT(std::abs(held.startSlip), 5e-3);
  EXPECT_LT(std::abs(held.drift), GetParam() == BodyModel::Corners ? 1e-4 : 1e-2);
  EXPECT_NEAR(slid.acceleration, expected, 0.1 * expected);
}

// Dropped tilted from 3 m it may tumble over an edge or two (contacts are inelastic, friction
// 0.6), but it never gains energy, comes to rest on a face, and then stays put.
TEST_P(BoxModels, DroppedTiltedTumblesAndSettlesOnAFace) {
  phys::World world;
  phys::BodyDesc desc;
  desc.model = GetParam();
  desc.center = {0.0, 3.0, 0.0};
  desc.orientation = glm::dquat(glm::radians(glm::dvec3(20.0, 35.0, 10.0)));
  const phys::BodyId id = world.addBody(desc);
  const double e0 = world.metrics().energy();
  double maxEnergy = e0;
  for (int i = 0; i < 240; ++i) {  // 4 s
    world.step();
    maxEnergy = std::max(maxEnergy, world.metrics().energy());
  }
  EXPECT_LE(maxEnergy, e0 + 1e-6 * std::abs(e0) + 1e-9);
  EXPECT_LT(maxSpeed(world), 0.01) << "still moving after 4 s";
  const phys::BodyPose settled = world.bodyPose(id);
  EXPECT_NEAR(settled.center.y, 0.5, 0.01) << "not lying on a face";
  for (int i = 0; i < 60; ++i) world.step();
  EXPECT_LT(glm::length(world.bodyPose(id).center - settled.center), 1e-4) << "slides after settling";
  // Friction runs after each pass, so the next pass relaxes what it bends: a resting box keeps
  // little shear (it was 0.47% with friction once after all passes).
  EXPECT_LT(world.metrics().maxConstraintError, 2e-3);
  EXPECT_LT(world.metrics().maxPenetration, 1e-9);
}

TEST_P(BoxModels, SpinningFreeBoxKeepsItsShape) {
  phys::World world = testing_phys::openSpace({}, Vec3(0.0));
  phys::BodyDesc desc;
  desc.model = GetParam();
  desc.size = {0.4, 1.0, 2.0};
  desc.angularVelocity = {0.1, 5.0, 0.1};
  world.addBody(desc);
  for (int i = 0; i < 600; ++i) world.step();
  EXPECT_LT(world.metrics().maxConstraintError, 1e-3);
  EXPECT_LT(glm::length(world.bodyPose(phys::BodyId{0}).center), 1e-9);  // the centre of mass stays put
}

// The suite's Dzhanibekov box (stability/dzhanibekov.xml): flat enough (0.4 under half of 1) for
// its tetrahedron's volume to be kept. SHAKE moves each stick along its direction at the
// substep's start and so nearly keeps a free body's energy; the volume moved along its gradient at
// x instead took 41% of it in 12 s, along the start's gradient it keeps it within 1%.
TEST(TetraVolume, AFlatTumblerUnderShakeKeepsItsEnergy) {
  phys::SolverSettings solver;
  solver.method = phys::SolverMethod::Shake;
  phys::World world = testing_phys::openSpace(solver, Vec3(0.0));
  phys::BodyDesc desc;
  desc.model = BodyModel::Tetra;
  desc.size = {0.4, 1.0, 2.0};
  desc.angularVelocity = glm::radians(Vec3(0.36, 360.0, 0.36));
  world.addBody(desc);
  const double before = world.metrics().energy();
  for (int i = 0; i < 720; ++i) world.step();
  EXPECT_NEAR(world.metrics().energy() / before, 1.0, 0.01);
}

// SHAKE keeps energy only as far as its passes solve the sticks (docs/physics.md, "Order of
// accuracy"): this box, spun at 30 rad/s mostly about its middle axis, gains 51% in 60 s at 2 x 4,
// its sticks left 2e-3 off, and 0.43% at 8 x 4, 1e-6 off, 0.40% of which is the O(h^2) offset of a
// converged run. Projection along the sticks' current directions loses nearly all of it.
TEST(Shake, AFastSpinningBoxKeepsItsEnergyOnceItsPassesConverge) {
  phys::World world =
      testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::Shake, 8, 4), Vec3(0.0));
  phys::BodyDesc desc;
  desc.size = {0.4, 1.0, 2.0};
  desc.mass = 2.0;
  desc.angularVelocity = glm::radians(Vec3(85.9, 1718.9, 143.2));
  world.addBody(desc);
  const double before = world.metrics().energy();
  for (int i = 0; i < 3600; ++i) world.step();
  const phys::Metrics after = world.metrics();
  std::printf("spinning box under shake at 8 x 4, 60 s: energy %+.3f%%, largest stick error %.1e\n",
              100.0 * (after.energy() / before - 1.0), after.maxConstraintError);
  EXPECT_LT(after.maxConstraintError, 1e-4);
  EXPECT_NEAR(after.energy() / before, 1.0, 0.01);
}

// Six times the signed volume of a tetra body's tetrahedron (its four particles).
double tetraSixVolume(const phys::World& world, phys::BodyId id) {
  const auto& x = world.particles().position;
  const phys::ParticleId f = world.bodies()[id].firstParticle;
  return glm::dot(x[f + 1] - x[f], glm::cross(x[f + 2] - x[f], x[f + 3] - x[f]));
}

// A cube (not flat, so only its floor is kept) and a 1 x 0.51 x 1 m slab, dropped flat from 3 m at
// dt 0.1 s, arrive up to 0.64 m into the ground in one step. The contacts pushed the embedded bottom corners
// up and, through their weights of -1/2, the top particles down through the base: the cube rested whole but
// inside out, the slab inside out and crushed to 5% of its thickness at 11% stick error, which the
// guard does not catch. Each must rest with its volume's sign, and at least half of it.
TEST(TetraVolume, ABodyLandingDeepInOneStepDoesNotTurnInsideOut) {
  for (const double height : {1.0, 0.51}) {
    phys::SolverSettings solver;
    solver.dt = 0.1;
    phys::World world(phys::WorldSettings{}, solver);
    phys::BodyDesc desc;
    desc.model = BodyModel::Tetra;
    desc.size = {1.0, height, 1.0};
    desc.center = {0.0, 3.0, 0.0};
    const phys::BodyId id = world.addBody(desc);
    const double rest = tetraSixVolume(world, id);
    for (int i = 0; i < 100; ++i) {
      world.step();
      ASSERT_GT(tetraSixVolume(world, id) / rest, phys::TetraVolumes::kVolumeFloor - 0.15)
          << "size y " << height << ", step " << i + 1;
    }
    EXPECT_TRUE(world.freezes().empty());
  }
}

// A tetra capsule (a lean ragdoll's part: 0.3 x 1.2 x 0.3 m) dropped tilted from 10 m at the default
// step lands at 14 m/s; its ends' contacts turned it inside out, whole, and it rested so (six times
// its volume -1.001 of its rest one), its anchors mirrored across it. Not flat, so only its floor is
// kept, and that holds it the right way out.
TEST(TetraVolume, ACapsuleLandingFastDoesNotTurnInsideOut) {
  phys::World world;
  phys::BodyDesc desc;
  desc.model = BodyModel::Tetra;
  desc.shape = phys::Shape::Capsule;
  desc.size = {0.3, 1.2, 0.3};
  desc.center = {0.0, 10.0, 0.0};
  desc.orientation = glm::angleAxis(1.2, glm::normalize(Vec3(1.0, 0.2, 0.5)));
  const phys::BodyId id = world.addBody(desc);
  const double rest = tetraSixVolume(world, id);
  for (int i = 0; i < 300; ++i) {
    world.step();
    ASSERT_GT(tetraSixVolume(world, id) / rest, phys::TetraVolumes::kVolumeFloor - 0.1) << "step " << i + 1;
  }
  EXPECT_NEAR(tetraSixVolume(world, id) / rest, 1.0, 0.05);  // whole again once it rests
}

INSTANTIATE_TEST_SUITE_P(BothModels, BoxModels, ::testing::Values(BodyModel::Corners, BodyModel::Tetra),
                         [](const auto& param) { return std::string(toString(param.param)); });

// Friction anchors (docs/physics.md, "Friction anchors"): a point of a face-on-face contact
// between particle boxes is held to where static friction took hold, not only kept from sliding
// further in each substep, so what one substep's passes leave of a slide the next ones take back.

// The stability suite's pyramid-10 (stability/pyramid-10.xml): 55 boxes of 1 m and 1 kg in 10 rows,
// each across the seam of two below, on ground of friction 0.6. Returns the largest distance any
// box's centre moved in 5 s.
double pyramidDrift(phys::SolverMethod method, int iterations, int substeps) {
  phys::WorldSettings ws;
  ws.groundMaterial = {0.6, 0.6};
  phys::World world(ws);
  phys::SolverSettings solver = world.solverSettings();
  solver.method = method;
  solver.iterations = iterations;
  solver.substeps = substeps;
  world.setSolverSettings(solver);
  std::vector<Vec3> start;
  for (int row = 0; row < 10; ++row) {
    for (int i = 0; i < 10 - row; ++i) {
      phys::BodyDesc box;
      box.center = {i - 0.5 * (9 - row), row + 0.5, 0.0};
      world.addBody(box);
      start.push_back(box.center);
    }
  }
  double drift = 0.0;
  for (int step = 0; step < 300; ++step) {
    world.step();
    for (std::uint32_t b = 0; b < start.size(); ++b)
      drift = std::max(drift, glm::length(world.bodyPose(phys::BodyId{b}).center - start[b]));
  }
  return drift;
}

// 0.055 m in 5 s (the suite's bar is 0.1 m): with the anchors the pyramid moves 0.045 m under both
// methods. Without them each substep's friction stopped only that substep's slide, the rows crept
// apart a little every step, and at 1 x 4 the pyramid moved 0.16 m (Gauss-Seidel) and 0.29 m
// (SHAKE); with a slipped point anchored afresh at x* rather than where its slip left it, 0.063 m
// (docs/physics.md, "Friction anchors").
TEST(FrictionAnchors, APyramidOfTenHoldsAtOnePassAndFourSubsteps) {
  for (const phys::SolverMethod method : {phys::SolverMethod::GaussSeidel, phys::SolverMethod::Shake}) {
    const double drift = pyramidDrift(method, 1, 4);
    std::printf("%s 1 x 4: the pyramid's boxes moved at most %.3g m in 5 s\n",
                std::string(phys::toString(method)).c_str(), drift);
    EXPECT_LT(drift, 0.055) << phys::toString(method);
  }
}

// A box sliding on a box slides at the Coulomb rate: a slip leaves the anchor where it is to the
// substep's end. Both on the 20 degree incline, both of friction 0.2, the ground 1.0 (so the bottom
// box's friction with it, the geometric mean 0.45, holds it: tan 20 = 0.36), and the top box slides
// over the bottom one at g (sin 20 - 0.2 cos 20) = 1.51 m/s^2, fitted over 0.25 to 0.65 s, before it
// reaches the edge. Within 6%: 1.582 (corners) and 1.544 (tetra); an anchor that follows each slip
// within the substep drags too little, and the tetra box slides at 1.603, 6.1% fast.
TEST_P(BoxModels, ABoxSlidingOnABoxSlidesAtTheCoulombRate) {
  const double angle = glm::radians(20.0);
  phys::WorldSettings ws;
  ws.groundNormal = {-std::sin(angle), std::cos(angle), 0.0};
  ws.groundMaterial = {1.0, 1.0};
  phys::World world(ws);
  phys::BodyDesc desc;
  desc.model = GetParam();
  desc.material = {0.2, 0.2};
  desc.orientation = glm::angleAxis(angle, Vec3(0.0, 0.0, 1.0));
  desc.center = ws.groundNormal * 0.5;
  const phys::BodyId bottom = world.addBody(desc);
  desc.center = ws.groundNormal * 1.5;
  const phys::BodyId top = world.addBody(desc);
  const Vec3 downhill = -Vec3(std::cos(angle), std::sin(angle), 0.0);
  std::vector<double> s;  // the top box along the slope from the bottom one at t = 0.25, 0.45, 0.65 s
  for (int i = 1; i <= 39; ++i) {
    world.step();
    if (i == 15 || i == 27 || i == 39)
      s.push_back(glm::dot(world.bodyPose(top).center - world.bodyPose(bottom).center, downhill));
  }
  const double acceleration = (s[2] - 2.0 * s[1] + s[0]) / (0.2 * 0.2);
  const double expected = 9.81 * (std::sin(angle) - 0.2 * std::cos(angle));
  std::printf("%s: the top box slides at %.4f m/s^2 over the bottom one (Coulomb: %.4f)\n",
              std::string(toString(GetParam())).c_str(), acceleration, expected);
  EXPECT_NEAR(acceleration, expected, 0.06 * expected);
}

}  // namespace

// A box resting off centre on a tetra box, at the seed's 3 passes and 1 substep, stays where it was
// put (docs/physics.md, "A tetra box walking on a box"). The tetra box's face shears under the load
// within each step and the passes leave up to 0.1 mm of slide; while the pair's manifold was clipped
// again every step and its points anchored afresh, that slide was never taken back, and the top
// box walked 0.23 m in 20 s on a tetra box (0.036 m a corners box). Now 5.6 and 2.3 mm: 1 cm is
// the 3 mm a corners box on a corners box moves as the pair settles in its first steps (the bottom
// box sags and tilts a milliradian under the off-centre load), with room, and a walk of the old
// pace passes it in under a second.
class OnATetraBox : public ::testing::TestWithParam<BodyModel> {};

// A 1 m tetra box on the ground (friction 0.6) under Gauss-Seidel at `iterations` x 1, and a 1 m box
// of `model` on it at `top`: the world, and the top box's id.
std::pair<phys::World, phys::BodyId> boxOnATetraBox(int iterations, BodyModel model, const Vec3& top) {
  phys::WorldSettings ws;
  ws.groundMaterial = {0.6, 0.6};
  phys::World world(ws, testing_phys::solver(phys::SolverMethod::GaussSeidel, iterations, 1));
  phys::BodyDesc desc;
  desc.model = BodyModel::Tetra;
  desc.center = {0.0, 0.5, 0.0};
  world.addBody(desc);
  desc.model = model;
  desc.center = top;
  const phys::BodyId id = world.addBody(desc);
  return {std::move(world), id};
}

TEST_P(OnATetraBox, ABoxRestingOffCentreDoesNotWalk) {
  const Vec3 start{0.2, 1.5, 0.1};
  auto [world, top] = boxOnATetraBox(3, GetParam(), start);
  for (int i = 0; i < 1200; ++i) world.step();  // 20 s
  const Vec3 moved = world.bodyPose(top).center - start;
  const double across = std::hypot(moved.x, moved.z);
  std::printf("%s box on a tetra box: moved %.4f m across in 20 s\n",
              std::string(toString(GetParam())).c_str(), across);
  EXPECT_LT(across, 0.01);
}

INSTANTIATE_TEST_SUITE_P(BothModels, OnATetraBox, ::testing::Values(BodyModel::Corners, BodyModel::Tetra),
                         [](const auto& param) { return std::string(toString(param.param)); });

// Two tetra boxes stacked exactly face to face (the stability suite's `face-face`) at 10 passes and
// 1 substep come to rest. The faces are the same square, so the clipping finds the same corners as
// the reference face flips between the two boxes and as the points it keeps change order, and each
// new order or face rocked the top box by 0.25 mm once. While a pair clipped again handed all its
// new points one shift and twist fitted to the old points' slides, whichever points they were, the
// top box kept rocking 0.23 mm every other step, its reference face flipping each time, and its
// corners kept 1.3 cm/s over 4 to 5 s (the suite's bar is 1 cm/s); with nothing handed on it comes
// to rest at 0.26 mm from 1 to 5 s (the suite's bar 2 mm).
TEST(OnATetraBox, ATetraBoxFaceToFaceOnATetraBoxComesToRest) {
  auto [world, top] = boxOnATetraBox(10, BodyModel::Tetra, {0.0, 1.5, 0.0});
  for (int i = 0; i < 60; ++i) world.step();  // 1 s to settle
  const Vec3 settled = world.bodyPose(top).center;
  double drift = 0.0, fastest = 0.0;
  for (int i = 60; i < 300; ++i) {
    world.step();
    drift = std::max(drift, glm::length(world.bodyPose(top).center - settled));
    if (i >= 240) fastest = std::max(fastest, maxSpeed(world));
  }
  std::printf("face to face: drift %.3g m from 1 to 5 s, fastest corner %.3g m/s from 4 to 5 s\n", drift,
              fastest);
  EXPECT_LT(drift, 0.002);
  EXPECT_LT(fastest, 0.01);
}
