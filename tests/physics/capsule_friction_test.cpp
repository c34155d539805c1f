// Friction between a capsule and the body it lies on, against Coulomb: a capsule lying along a
// slope made by a heavy box, or in the groove between two heavy capsules, stays put where its
// friction holds it and slides at the Coulomb rate where it does not; and a pass's friction impulse
// is mu times its push's, whichever particle weighs more.
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <numbers>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "passes.h"
#include "physics/world.h"
#include "test_util.h"

namespace {

using phys::Vec3;

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kG = 10.0;
constexpr double kMu = 0.25;
constexpr double kRadius = 0.2;
constexpr double kStart = -3.0;  // the capsule's centre along the 8 m support, uphill of its middle
const phys::Quat kLying = glm::angleAxis(std::numbers::pi / 2.0, Vec3(0.0, 0.0, 1.0));  // core along x

phys::BodyDesc lyingCapsule(phys::BodyModel model, const Vec3& centre, double length, double mass) {
  phys::BodyDesc d = testing_phys::capsule(model, centre, kRadius, length);
  d.orientation = kLying;
  d.mass = mass;
  d.material = {kMu, kMu};
  return d;
}

// What the capsule lies on: a box 1000 times its mass, or the groove between two capsules of its
// model, each 1000 times its mass, side by side (its contacts' normals 30 degrees off the vertical,
// so their normal forces sum to m g cos(theta) / cos 30 and friction holds it while tan(theta) <
// mu / cos 30 = 0.289).
enum class Support { Box, Groove };

// The capsule's centre's slide relative to what it lies on along the slope (x) at each of
// `seconds`, and by the last, how far it moved across (z) and turned.
struct SlopeRun {
  std::vector<double> along;
  double across = 0.0;
  double turned = 0.0;  // rad
};

// A 1 kg capsule of `model`, radius 0.2 m and 1.4 m long, lying along a slope of `degrees` made by
// tilting gravity (g = 10, downhill +x) on `support`, friction 0.25 between them. The supports stay
// on the ground by friction 1 (the ground's 4 with their 0.25).
SlopeRun lyingOnASupport(Support support, phys::BodyModel model, double degrees, phys::SolverSettings solver,
                         std::initializer_list<double> seconds) {
  phys::WorldSettings ws;
  ws.gravity = kG * Vec3(std::sin(degrees * kDegree), -std::cos(degrees * kDegree), 0.0);
  ws.groundMaterial = {4.0, 4.0};
  phys::World world(ws, solver);
  phys::BodyId below = phys::kNoBody;
  double top = 0.0;  // the capsule's core's height at rest
  if (support == Support::Box) {
    phys::BodyDesc box;
    box.model = model == phys::BodyModel::Tetra ? phys::BodyModel::Tetra : phys::BodyModel::Corners;
    box.center = Vec3(0.0, 0.25, 0.0);
    box.size = Vec3(8.0, 0.5, 1.2);
    box.mass = 1000.0;
    box.material = {kMu, kMu};
    below = world.addBody(box);
    top = 0.5 + kRadius;
  } else {
    // Between two walls, which keep the two from rolling apart under the wedge.
    for (const double side : {-1.0, 1.0}) {
      phys::BodyDesc wall;
      wall.center = Vec3(0.0, 0.25, side * (2.0 * kRadius + 0.2 + 2e-4));
      wall.size = Vec3(8.0, 0.5, 0.4);
      wall.mass = 1000.0;
      wall.material = {kMu, kMu};
      world.addBody(wall);
    }
    below = world.addBody(lyingCapsule(model, Vec3(0.0, kRadius, -kRadius - 1e-4), 8.0, 1000.0));
    world.addBody(lyingCapsule(model, Vec3(0.0, kRadius, kRadius + 1e-4), 8.0, 1000.0));
    top = kRadius + std::sqrt(3.0) * kRadius;
  }
  const phys::BodyId id = world.addBody(lyingCapsule(model, Vec3(kStart, top, 0.0), 1.4, 1.0));
  const phys::Quat laid = world.bodyPose(id).orientation;
  SlopeRun run;
  int step = 0;
  for (const double t : seconds) {
    for (; step < static_cast<int>(std::lround(t * 60.0)); ++step) world.step();
    run.along.push_back(world.bodyPose(id).center.x - world.bodyPose(below).center.x - kStart);
  }
  const phys::BodyPose end = world.bodyPose(id);
  run.across = end.center.z;
  run.turned = testing_phys::angleBetween(end.orientation, laid);
  return run;
}

// The fit of the slide's acceleration over t = 1, 2, 3 s (after the contacts took up the load):
// x(3) - 2 x(2) + x(1).
double acceleration(const SlopeRun& run) {
  return run.along[2] - 2.0 * run.along[1] + run.along[0];
}

// The methods whose contacts hold a capsule still where friction holds it; Jacobi turns a corners
// capsule lying on a box off the fall line, as it does on the ground (docs/physics.md, "A capsule
// on a slope, on a body").
constexpr phys::SolverMethod kHolding[] = {phys::SolverMethod::GaussSeidel, phys::SolverMethod::Xpbd,
                                           phys::SolverMethod::Shake};
constexpr phys::SolverMethod kAll[] = {phys::SolverMethod::GaussSeidel, phys::SolverMethod::Jacobi,
                                       phys::SolverMethod::Xpbd, phys::SolverMethod::Shake};

TEST(CapsuleFriction, ACornersCapsuleLyingAlongASlopeOnABoxItsFrictionHoldsStaysPut) {
  // tan 10 degrees = 0.176 < 0.25. Bounded by the push at the face point while it cut at the
  // surface point, friction was 0.25 / 1.66 in effect and the capsule slid at 0.255 m/s^2 (off the
  // 8 m box within 20 s) at both settings; with the bound right but the surface point carried by
  // one inscribed tetrahedron, chiral, it held along the slope but turned off the fall line and
  // rolled across it, 0.23 m by 18 s (1.13 rad). Now, at the ragdoll scenes' 2 x 4 and the seed's
  // 3 x 1, 0.17 and 0.32 mm down the slope in 20 s (0.5 to 1 mm while the box's side, flagged by
  // round-off, was carried by its tetrahedron: below), under 1e-7 m across and 3e-4 rad turned:
  // 3 mm and 1 mm, 1 mrad leave room for rounding.
  for (const auto& [iterations, substeps] : {std::pair{2, 4}, std::pair{3, 1}}) {
    for (const phys::SolverMethod method : kHolding) {
      const SlopeRun run = lyingOnASupport(Support::Box, phys::BodyModel::Corners, 10.0,
                                           testing_phys::solver(method, iterations, substeps), {20.0});
      std::printf(
          "%s %d x %d: moved %.3g m down a 10 degree slope on a box in 20 s, %.3g m across, turned %.3g "
          "rad\n",
          phys::toString(method).data(), iterations, substeps, run.along[0], run.across, run.turned);
      const std::string at = std::string(phys::toString(method)) + " " + std::to_string(iterations) + " x " +
                             std::to_string(substeps);
      EXPECT_LT(std::abs(run.along[0]), 3e-3) << at;
      EXPECT_LT(std::abs(run.across), 1e-3) << at;
      EXPECT_LT(run.turned, 1e-3) << at;
    }
  }
}

TEST(CapsuleFriction, ACornersCapsuleLyingAlongASteeperSlopeOnABoxSlidesAtTheCoulombRate) {
  // tan 16 degrees = 0.287 > 0.25: it slides at g (sin - mu cos) = 0.3532 m/s^2. It slid at 1.3106
  // (friction 0.25 / 1.66, as on the ground before its fix). Measured 0.3532 to 0.3533 under all four
  // methods at 2 x 4 and 3 x 1 but Jacobi's 0.3577 at 3 x 1: 5% leaves room for that, not for the bug.
  const double expected = kG * (std::sin(16.0 * kDegree) - kMu * std::cos(16.0 * kDegree));
  for (const auto& [iterations, substeps] : {std::pair{2, 4}, std::pair{3, 1}}) {
    for (const phys::SolverMethod method : kAll) {
      const double a =
          acceleration(lyingOnASupport(Support::Box, phys::BodyModel::Corners, 16.0,
                                       testing_phys::solver(method, iterations, substeps), {1.0, 2.0, 3.0}));
      std::printf("%s %d x %d: slides down a 16 degree slope on a box at %.4f m/s^2 (Coulomb %.4f)\n",
                  phys::toString(method).data(), iterations, substeps, a, expected);
      EXPECT_NEAR(a, expected, 0.05 * expected)
          << phys::toString(method) << " " << iterations << " x " << substeps;
    }
  }
}

TEST(CapsuleFriction, ACornersCapsuleInAGrooveOfCapsulesHoldsWhereItsFrictionDoesAndSlidesWhereNot) {
  // Both sides of each contact are corners capsules. Its two contacts' normals are 30 degrees off
  // the vertical, so friction holds it while tan(theta) < mu / cos 30 = 0.289: on 14 degrees (0.249)
  // it held with the bound right (4 cm up the slope in 20 s, the creep below) and slid before (by the
  // bare push, 7.65 m at 0.30 m/s^2); on 20 degrees it slides at g (sin - mu cos / cos 30) = 0.7075 m/s^2:
  // 0.7009 under Gauss-Seidel, XPBD and SHAKE at 2 x 4, where it slid at 1.3734. A capsule of either model in
  // the groove creeps up the slope by some 1.5 mm/s, before the fix as after, and not on the flat
  // (docs/physics.md, "A capsule on a slope, on a body"): 6 cm in 20 s bounds it. (At 3 x 1 the
  // 8 m supports themselves give way under the walls' squeeze, so only 2 x 4 is checked.)
  const double expected =
      kG * (std::sin(20.0 * kDegree) - kMu * std::cos(20.0 * kDegree) / std::cos(30.0 * kDegree));
  for (const phys::SolverMethod method : kHolding) {
    const phys::SolverSettings solver = testing_phys::solver(method, 2, 4);
    const SlopeRun held = lyingOnASupport(Support::Groove, phys::BodyModel::Corners, 14.0, solver, {20.0});
    const double a = acceleration(
        lyingOnASupport(Support::Groove, phys::BodyModel::Corners, 20.0, solver, {1.0, 2.0, 3.0}));
    std::printf(
        "%s 2 x 4: in the groove moved %.3g m down 14 degrees in 20 s; slides down 20 degrees at %.4f m/s^2 "
        "(Coulomb %.4f)\n",
        phys::toString(method).data(), held.along[0], a, expected);
    EXPECT_LT(std::abs(held.along[0]), 0.06) << phys::toString(method);
    EXPECT_NEAR(a, expected, 0.05 * expected) << phys::toString(method);
  }
}

TEST(CapsuleFriction, AFrictionImpulseBetweenCornersCapsulesIsMuTimesThePushsWithAHeavierSide) {
  // A pass's push moves the face points, an impulse push / K_face (K = sum c^2 w over both sides'
  // points); friction cuts the surface points, carried by both inscribed tetrahedra of each capsule.
  // A sliding cut's impulse on each body (its particles' change of momentum) is mu_d times the
  // push's, to round-off, whichever of the 16 particles is four times heavier. Bounded by the bare
  // push, it was K_face / K_surface of that (0.74 here).
  // The capsule in the groove of two (as above, without walls, for one step): its contacts are 30
  // degrees round each side's core from the line where it touches its box's face, so both sides'
  // surface points are off their face points.
  phys::World world({}, testing_phys::solver(phys::SolverMethod::GaussSeidel, 2, 4));
  world.addBody(lyingCapsule(phys::BodyModel::Corners, Vec3(0.0, kRadius, -kRadius - 1e-4), 2.0, 1.0));
  world.addBody(lyingCapsule(phys::BodyModel::Corners, Vec3(0.0, kRadius, kRadius + 1e-4), 2.0, 1.0));
  world.addBody(
      lyingCapsule(phys::BodyModel::Corners, Vec3(0.1, kRadius + std::sqrt(3.0) * kRadius, 0.0), 1.4, 1.0));
  world.step();
  std::vector<phys::BodyContact> contacts;
  std::vector<phys::BodyContactExtra> extras;
  for (std::size_t k = 0; k < world.bodyContacts().size(); ++k) {
    const phys::BodyContact& c = world.bodyContacts()[k];
    if (!c.frictionAtSurfaceA || !c.frictionAtSurfaceB || !contacts.empty()) continue;
    contacts.push_back(c);
    extras.push_back(world.bodyContactExtras()[k]);
  }
  ASSERT_EQ(contacts.size(), 1u);
  const phys::Body& a = world.bodies()[contacts[0].bodyA];
  const phys::Body& b = world.bodies()[contacts[0].bodyB];
  auto impulseOn = [](const phys::Body& body, const phys::Particles& before, const phys::Particles& after) {
    Vec3 j(0.0);
    for (int i = 0; i < body.particleCount; ++i) {
      const std::size_t k = body.firstParticle + i;
      j += (after.position[k] - before.position[k]) / after.inverseMass[k];
    }
    return j;
  };
  for (int heavy = 0; heavy <= 16; ++heavy) {  // 16: all alike
    phys::Particles p = world.particles();
    if (heavy < 16) p.inverseMass[(heavy < 8 ? a.firstParticle : b.firstParticle) + heavy % 8] *= 0.25;
    for (int i = 0; i < b.particleCount; ++i)
      p.position[b.firstParticle + i] = p.previous[b.firstParticle + i] + Vec3(0.05, 0.0, 0.02);
    for (int i = 0; i < a.particleCount; ++i)
      p.position[a.firstParticle + i] = p.previous[a.firstParticle + i];
    const phys::Particles before = p;
    const std::vector<phys::Real> push{1e-4};  // its slide far past mu * push: a sliding cut
    phys::detail::applyBodyFriction(p, contacts, extras, push);
    const Vec3 onA = impulseOn(a, before, p), onB = impulseOn(b, before, p);
    const phys::Real kFace = phys::detail::embeddedWeight(p.inverseMass, contacts[0].pointA) +
                             phys::detail::embeddedWeight(p.inverseMass, contacts[0].pointB);
    const phys::Real expected = contacts[0].combined.dynamicFriction * push[0] / kFace;
    EXPECT_NEAR(glm::length(onB), expected, 1e-9 * expected) << "particle " << heavy << " heavy";
    EXPECT_NEAR(glm::length(onA + onB), 0.0, 1e-9 * expected) << "particle " << heavy << " heavy";
  }
}

TEST(CapsuleFriction, ABoxsSideOfACapsuleContactTakesFrictionAtItsFacePoint) {
  // A box's contact point is on its face already: the narrow phase "moves" it there by round-off
  // alone (1e-17 to 2e-16 m), which flagged 280 (corners) and 405 (tetra) of the 480 box sides of
  // the contacts below in 2 s, and friction took the box at a point carried by its inscribed
  // tetrahedron. Two capsules of each model lying between two box walls (the groove above, its
  // slope 10 degrees) touch them along their sides; no box side of those contacts is flagged.
  phys::WorldSettings ws;
  ws.gravity = kG * Vec3(std::sin(10.0 * kDegree), -std::cos(10.0 * kDegree), 0.0);
  ws.groundMaterial = {4.0, 4.0};
  for (const phys::BodyModel model : {phys::BodyModel::Corners, phys::BodyModel::Tetra}) {
    phys::World world(ws, testing_phys::solver(phys::SolverMethod::GaussSeidel, 2, 4));
    for (const double side : {-1.0, 1.0}) {
      phys::BodyDesc wall;
      wall.center = Vec3(0.0, 0.25, side * (2.0 * kRadius + 0.2 + 2e-4));
      wall.size = Vec3(8.0, 0.5, 0.4);
      wall.mass = 1000.0;
      world.addBody(wall);
    }
    world.addBody(lyingCapsule(model, Vec3(0.0, kRadius, -kRadius - 1e-4), 8.0, 1000.0));
    world.addBody(lyingCapsule(model, Vec3(0.0, kRadius, kRadius + 1e-4), 8.0, 1000.0));
    int boxSides = 0, flagged = 0;
    for (int i = 0; i < 120; ++i) {
      world.step();
      for (const phys::BodyContact& c : world.bodyContacts()) {
        for (const auto& [body, atSurface] :
             {std::pair{c.bodyA, c.frictionAtSurfaceA}, std::pair{c.bodyB, c.frictionAtSurfaceB}}) {
          if (world.bodies()[body].shape != phys::Shape::Box) continue;
          ++boxSides;
          flagged += atSurface ? 1 : 0;
        }
      }
    }
    std::printf("%s capsules against box walls: %d of %d box sides flagged\n", phys::toString(model).data(),
                flagged, boxSides);
    EXPECT_GT(boxSides, 0) << phys::toString(model);
    EXPECT_EQ(flagged, 0) << phys::toString(model);
  }
}

}  // namespace
