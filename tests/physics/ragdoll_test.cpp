// Ragdolls dropped onto flat ground: they must land, tumble and come to rest without NaN,
// without sliding, with their boxes rigid and their hinges within their limits. Run at the
// settings of assets/scenes/ragdoll.xml, for every model: 2 iterations x 4 substeps (at the seed's
// 3 x 1 a light part under the torso is crushed), and the seed's wind resistance at 0.2 1/s (with none, a
// forearm hanging off a propped-up body swings as a frictionless pendulum for tens of
// seconds). docs/physics.md, "Ragdolls".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "physics/ragdoll.h"

namespace {

using phys::Vec3;

constexpr double kDegree = std::numbers::pi / 180.0;

// Rigid parts too at 4 substeps: with each part's true inertia a forearm at its elbow's stop turned
// about its long axis and back, and two of the four landings were still moving at 2 to 3 cm/s at
// 10 s; the ragdoll's inertia floor (RagdollDesc::inertiaFloor) brings them under 3 mm/s
// (docs/physics.md, "Inertia floor").
phys::SolverSettings ragdollSettings() {
  phys::SolverSettings s;
  s.iterations = 2;
  s.substeps = 4;
  s.bodyDamping = 1.0;
  return s;
}

Vec3 centreOf(const phys::World& w, const phys::Ragdoll& r) {
  Vec3 sum(0.0);
  for (phys::BodyId id : r.parts) sum += w.bodyPose(id).center;
  return sum / static_cast<double>(r.parts.size());
}

// Largest |length - rest| / rest over the sticks of the ragdoll's boxes.
double worstStickError(const phys::World& w) {
  double worst = 0.0;
  for (const phys::Stick& s : w.sticks()) {
    const double length = glm::length(w.particles().position[s.b] - w.particles().position[s.a]);
    worst = std::max(worst, std::abs(length - s.maxLength) / s.maxLength);
  }
  return worst;
}

// How far the hinge is outside [min, max], in radians; 0 within.
double pastLimit(const phys::World& w, const phys::Ragdoll& r, const phys::RagdollHinge& h) {
  const double angle = phys::hingeAngle(w, r, h);
  return std::max({0.0, h.minAngle - angle, angle - h.maxAngle});
}

struct Drop {
  double speedAt5s = 0.0;       // max particle speed at 5 s (m/s)
  double speedAt10s = 0.0;      // and at 10 s
  double laterSpeed = 0.0;      // the most it reaches between the two
  double slide = 0.0;           // horizontal travel of the centre once down, to 10 s (m)
  double stickError = 0.0;      // at 10 s, relative
  double jointError = 0.0;      // at 10 s (m)
  double restLimit = 0.0;       // worst hinge past its limit at 10 s (rad)
  double transientLimit = 0.0;  // worst hinge past its limit at any step (rad)
  bool finite = true;
  int frozen = 0;
};

Drop drop(phys::RagdollModel model, const Vec3& eulerDegrees) {
  phys::WorldSettings air;
  air.damping = 0.2;
  phys::World w(air, ragdollSettings());
  phys::RagdollDesc d;
  d.model = model;
  d.hips = Vec3(0.0, 2.9, 0.0);  // the lowest part starts about 2 m up whatever the orientation
  d.orientation = glm::dquat(glm::radians(eulerDegrees));
  const phys::Ragdoll r = phys::addRagdoll(w, d);
  Drop out;
  // Down: touching the ground with every particle slower than 10 cm/s for the first time. What
  // moves after that is what the seed's ragdolls did: slide on along the ground.
  bool down = false;
  Vec3 whereDown(0.0);
  const int steps = 600;  // 10 s
  for (int step = 1; step <= steps; ++step) {
    w.step();
    const phys::Metrics m = w.metrics();
    out.finite = out.finite && std::isfinite(m.maxSpeed) && std::isfinite(m.energy());
    if (!down && m.contacts > 0 && m.maxSpeed < 0.1) {
      down = true;
      whereDown = centreOf(w, r);
    }
    if (step == 300) out.speedAt5s = m.maxSpeed;
    if (step > 300) out.laterSpeed = std::max(out.laterSpeed, m.maxSpeed);
    if (step == steps) out.speedAt10s = m.maxSpeed;
    for (const phys::RagdollHinge& h : r.hinges)
      out.transientLimit = std::max(out.transientLimit, pastLimit(w, r, h));
  }
  EXPECT_TRUE(down);
  const Vec3 travel = centreOf(w, r) - whereDown;
  out.slide = std::hypot(travel.x, travel.z);
  out.stickError = worstStickError(w);
  out.jointError = w.metrics().maxJointError;
  for (const phys::RagdollHinge& h : r.hinges) out.restLimit = std::max(out.restLimit, pastLimit(w, r, h));
  out.frozen = w.metrics().frozen;
  return out;
}

class RagdollDrop : public testing::TestWithParam<phys::RagdollModel> {};

// Four ways of landing: tumbling on a shoulder, flat on the face, feet first, on the back.
TEST_P(RagdollDrop, LandsAndRestsWithoutSlidingOrBreakingItsJoints) {
  const Vec3 orientations[] = {{70.0, 20.0, 10.0}, {90.0, 0.0, 5.0}, {0.0, 30.0, 8.0}, {-95.0, 60.0, 0.0}};
  for (const Vec3& euler : orientations) {
    const Drop d = drop(GetParam(), euler);
    std::printf(
        "%s ragdoll, euler (%g %g %g): speed at 5 s %.4f m/s, at 10 s %.4f, most between %.4f, slide %.4f m, "
        "stick error %.4f, joint gap "
        "%.4f m, past a limit at rest %.2f deg, at worst %.1f deg\n",
        std::string(phys::toString(GetParam())).c_str(), euler.x, euler.y, euler.z, d.speedAt5s, d.speedAt10s,
        d.laterSpeed, d.slide, d.stickError, d.jointError, d.restLimit / kDegree, d.transientLimit / kDegree);
    EXPECT_TRUE(d.finite);
    EXPECT_EQ(d.frozen, 0);
    // At rest within 5 s: every particle under 1 cm/s, and so again at 10 s. Not asserted in
    // between: a limb left balanced on an edge may topple later, as one lean landing does.
    EXPECT_LT(d.speedAt5s, 0.01);
    EXPECT_LT(d.speedAt10s, 0.01);
    EXPECT_LT(d.slide, 0.05);               // slides under 5 cm once down
    EXPECT_LT(d.stickError, 0.01);          // every stick within 1% of its length
    EXPECT_LT(d.jointError, 0.005);         // pins within 5 mm
    EXPECT_LT(d.restLimit, 3.0 * kDegree);  // no hinge rests past its limit (3 degrees: the give of 2 passes)
    // At the instant of impact (6 m/s) a few passes let a hinge overshoot before the limit
    // link turns it back; bounded so a broken limit (a hinge swinging through) fails.
    EXPECT_LT(d.transientLimit, 45.0 * kDegree);
  }
}

// A ragdoll's rigid parts take its inertia floor (kRagdollInertiaFloor unless given); particle parts
// have no inertia of their own to floor, and record none. A floor outside 0 to 1 is refused.
TEST(Ragdoll, RigidPartsTakeTheInertiaFloor) {
  phys::World w;
  phys::RagdollDesc d;
  d.model = phys::RagdollModel::Rigid;
  const phys::Ragdoll rigid = phys::addRagdoll(w, d);
  for (const phys::BodyId id : rigid.parts) {
    const phys::Body& part = w.bodies()[id];
    EXPECT_EQ(part.inertiaFloor, phys::kRagdollInertiaFloor) << part.name;
    const Vec3 inertia = 1.0 / w.rigidBodies().inverseInertia[part.rigid];
    const double largest = std::max({inertia.x, inertia.y, inertia.z});
    EXPECT_GE(std::min({inertia.x, inertia.y, inertia.z}),
              phys::kRagdollInertiaFloor * largest * (1.0 - 1e-12))
        << part.name;
  }
  d.model = phys::RagdollModel::Seed;
  d.hips = Vec3(3.0, 1.0, 0.0);
  for (const phys::BodyId id : phys::addRagdoll(w, d).parts) EXPECT_EQ(w.bodies()[id].inertiaFloor, 0.0);
  const std::size_t bodies = w.bodies().size();
  d.model = phys::RagdollModel::Rigid;
  d.inertiaFloor = 1.01;
  EXPECT_THROW(phys::addRagdoll(w, d), std::invalid_argument);
  EXPECT_EQ(w.bodies().size(), bodies);
}

// Two rigid ragdolls, one dropped across the other, lie on the edges and corners of their parts,
// held on the ground by patches of one or two points while their joints and contacts pull against
// each other every substep. Nothing drives them, so once they lie their energy must not rise. While
// static friction held such a patch only against each substep's own motion, what one substep left
// slipped for good, and the pile gained 7.9 mJ from 20 s to 60 s (the tackle 0.005 J/s: docs/physics.md,
// "Reaction"); held at its anchor, it loses 6e-7 J. The bound, 1 mJ, is an eighth of the creep's gain
// and far above round-off.
TEST(Ragdoll, RigidPileGainsNoEnergyOnceItLies) {
  phys::WorldSettings ground;
  ground.ground = true;
  phys::SolverSettings solver;
  solver.iterations = 2;
  solver.substeps = 8;
  phys::World w(ground, solver);
  phys::RagdollDesc below;
  below.model = phys::RagdollModel::Rigid;
  below.hips = Vec3(0.0, 1.2, 0.0);
  below.orientation = glm::angleAxis(std::numbers::pi / 2, Vec3(1.0, 0.0, 0.0));  // face down
  phys::addRagdoll(w, below);
  phys::RagdollDesc across = below;
  across.name = "across";
  across.hips = Vec3(0.3, 2.0, 0.3);
  across.orientation = glm::angleAxis(std::numbers::pi / 2, Vec3(0.0, 1.0, 0.0)) * below.orientation;
  phys::addRagdoll(w, across);
  const int perSecond = 60;
  for (int step = 0; step < 20 * perSecond; ++step) w.step();
  const double settled = w.metrics().energy();
  for (int step = 0; step < 40 * perSecond; ++step) w.step();
  const double gain = w.metrics().energy() - settled;
  std::printf("energy gained from 20 s to 60 s: %.3g J\n", gain);
  EXPECT_LT(gain, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Models, RagdollDrop,
                         testing::Values(phys::RagdollModel::Seed, phys::RagdollModel::Lean,
                                         phys::RagdollModel::Rigid),
                         [](const testing::TestParamInfo<phys::RagdollModel>& model) {
                           return std::string(phys::toString(model.param));
                         });

}  // namespace
