// Capsule ragdolls (Bullet's benchmark layout): built as laid out, dropped, they land, tumble and
// settle without NaN, without sliding, with their joints held; at the settings of our ragdoll
// scenes (2 iterations x 4 substeps, body damping 1, wind resistance 0.2 1/s).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "physics/capsule_ragdoll.h"
#include "test_util.h"

namespace {

using phys::Vec3;

// testing_phys::ragdollWorld: 2 iterations x 4 substeps, as the box ragdoll's scene, for every
// model. Rigid parts rest there thanks to their inertia floor: with each capsule's true inertia a
// forearm kept turning on its long axis at its elbow's stop, 0.2 m/s at 8 s (docs/physics.md,
// "Inertia floor").
using testing_phys::ragdollWorld;

double worstLinkGap(const phys::World& w) {
  double worst = 0.0;
  for (const phys::Link& l : w.links()) {
    const double d = glm::length(w.position(l.b) - w.position(l.a));
    worst = std::max({worst, l.minLength - d, d - l.maxLength});
  }
  for (const phys::RigidLink& l : w.rigidLinks()) {
    const double d = glm::length(w.position(l.b) - w.position(l.a));
    worst = std::max({worst, l.minLength - d, d - l.maxLength});
  }
  return worst;
}

double lowestSurface(const phys::World& w) {
  double lowest = 1e300;
  for (const phys::GroundContact& c : w.groundContacts()) lowest = std::min(lowest, w.position(c.point).y);
  return lowest;
}

TEST(CapsuleRagdoll, IsBuiltAsBulletLaysItOut) {
  phys::World world = ragdollWorld();
  phys::RagdollDesc d;
  d.name = "bob";
  d.hips = Vec3(1.0, 0.9225, -2.0);
  const phys::CapsuleRagdoll r = phys::addCapsuleRagdoll(world, d);
  ASSERT_EQ(world.bodies().size(), 11u);
  for (int i = 0; i < phys::kCapsuleParts; ++i) {
    const phys::Body& b = world.bodies()[r.parts[i]];
    EXPECT_EQ(b.shape, phys::Shape::Capsule);
    EXPECT_EQ(b.name, "bob." + std::string(phys::toString(static_cast<phys::CapsulePart>(i))));
  }
  // Bullet's sizes: the pelvis has radius 0.15 and a core of 0.20, a lower arm 0.04 and 0.25.
  const phys::Body& pelvis = world.bodies()[r.part(phys::CapsulePart::Pelvis)];
  EXPECT_NEAR(pelvis.capsuleRadius(), 0.15, 1e-12);
  EXPECT_NEAR(2.0 * pelvis.capsuleHalfSegment(), 0.20, 1e-12);
  const phys::Body& forearm = world.bodies()[r.part(phys::CapsulePart::LowerArmLeft)];
  EXPECT_NEAR(forearm.capsuleRadius(), 0.04, 1e-12);
  EXPECT_NEAR(2.0 * forearm.capsuleHalfSegment(), 0.25, 1e-12);
  // Standing on its feet at y = 0, 1.76 m tall, the left arm out along +x, every joint closed.
  EXPECT_NEAR(lowestSurface(world), 0.0, 1e-9);
  EXPECT_NEAR(world.bodyPose(r.part(phys::CapsulePart::Head)).center.y, 1.635, 1e-9);
  EXPECT_GT(world.bodyPose(r.part(phys::CapsulePart::LowerArmLeft)).center.x, 1.6);
  EXPECT_LT(worstLinkGap(world), 1e-12);
  // Ten joints: 5 hinges of 4 links, 5 cones of 3; jointed parts do not collide.
  EXPECT_EQ(world.links().size(), 35u);
  EXPECT_EQ(world.ignoredCollisions().size(), 10u);
  // The mass split evenly, as Bullet gives every part the same.
  double total = 0.0, pelvisMass = 0.0;
  for (phys::ParticleId i{}; i < world.particles().size(); ++i)
    total += 1.0 / world.particles().inverseMass[i];
  for (int j = 0; j < pelvis.particleCount; ++j)
    pelvisMass += 1.0 / world.particles().inverseMass[pelvis.firstParticle + j];
  EXPECT_NEAR(total, 70.0, 1e-9);
  EXPECT_NEAR(pelvisMass, 70.0 / 11.0, 1e-9);
}

TEST(CapsuleRagdoll, FallsTumblesAndSettlesWithoutSliding) {
  for (const phys::RagdollModel model :
       {phys::RagdollModel::Seed, phys::RagdollModel::Lean, phys::RagdollModel::Rigid}) {
    phys::World world = ragdollWorld();
    phys::RagdollDesc d;
    d.hips = Vec3(0.0, 2.0, 0.0);
    d.model = model;
    d.orientation = glm::angleAxis(0.6, glm::normalize(Vec3(1.0, 0.3, 0.2)));  // lands on a side
    d.velocity = Vec3(1.0, 0.0, 0.0);
    const phys::CapsuleRagdoll r = phys::addCapsuleRagdoll(world, d);
    const int steps = 60 * 8;
    Vec3 pelvisAt6s(0.0);
    double worstGap = 0.0;
    for (int i = 1; i <= steps; ++i) {
      world.step();
      worstGap = std::max(worstGap, worstLinkGap(world));
      if (i == 60 * 6) pelvisAt6s = world.bodyPose(r.part(phys::CapsulePart::Pelvis)).center;
    }
    ASSERT_TRUE(world.freezes().empty()) << world.freezes()[0].name;
    const Vec3 pelvis = world.bodyPose(r.part(phys::CapsulePart::Pelvis)).center;
    EXPECT_LT(pelvis.y, 0.5) << "it lies on the ground";
    // Settled: no part moves faster than 2 cm/s, and the pelvis crept less than 5 mm in 2 s.
    double fastest = 0.0;
    for (phys::ParticleId i{}; i < world.particles().size(); ++i)
      fastest = std::max(fastest, glm::length(world.velocity(i)));
    if (model == phys::RagdollModel::Rigid) fastest = world.metrics().maxSpeed;  // its farthest corner's
    std::printf("%s capsule ragdoll at 8 s: fastest %.4f m/s\n", std::string(phys::toString(model)).c_str(),
                fastest);
    EXPECT_LT(fastest, 0.02) << phys::toString(model);
    const Vec3 creep = pelvis - pelvisAt6s;
    EXPECT_LT(std::hypot(creep.x, creep.z), 0.005) << phys::toString(model);
    // Joints held through the landing (2 cm at worst) and at rest within 5 mm, as the box
    // ragdoll's (the give of 2 passes against the ground), nothing below the ground by more than
    // the slop and a millimetre.
    EXPECT_LT(worstGap, 0.02) << phys::toString(model);
    EXPECT_LT(worstLinkGap(world), 5e-3) << phys::toString(model);
    EXPECT_LT(world.metrics().maxPenetration, 2e-3) << phys::toString(model);
  }
}

TEST(CapsuleRagdoll, TheSeedModelComesToRest) {
  // A body at rest stays at rest. The seed model's capsules are corners boxes, and the ground pushed
  // each at its lowest point's projection onto the nearest face of its box, which turned it about its
  // core onto its box's edge; there the face switched from substep to substep and its head, lying on
  // the ground, jittered at 1.2 to 1.6 cm/s from 9 s to 30 s, never decaying (docs/physics.md,
  // "Capsules", "A capsule lying on an edge"). Now this drop is still, its fastest particle under
  // 3e-5 m/s from 15 s: 1 mm/s, a twelfth of the jitter, leaves room for other builds' rounding. The
  // drop is chaotic and not every one is still so soon: of 12 at 0.90 to 1.12 m/s
  // (scripts/probes/capsule-ragdoll-drops.cpp), 4 are under 1 mm/s at 15, 20 and 30 s, and the
  // others' parts still roll slowly, up to 8.9 mm/s at 30 s and decaying (a head at 0.05 mm/s by
  // 64 s), where before none decayed.
  phys::World world = ragdollWorld();
  phys::RagdollDesc d;
  d.hips = Vec3(0.0, 2.0, 0.0);
  d.model = phys::RagdollModel::Seed;
  d.orientation = glm::angleAxis(0.6, glm::normalize(Vec3(1.0, 0.3, 0.2)));  // as the test above
  d.velocity = Vec3(1.0, 0.0, 0.0);
  phys::addCapsuleRagdoll(world, d);
  double worst = 0.0;
  for (int i = 1; i <= 60 * 30; ++i) {
    world.step();
    if (i < 60 * 15 || i % 60 != 0) continue;
    for (phys::ParticleId p{}; p < world.particles().size(); ++p)
      worst = std::max(worst, glm::length(world.velocity(p)));
  }
  std::printf("seed capsule ragdoll from 15 s to 30 s: fastest %.6f m/s\n", worst);
  ASSERT_TRUE(world.freezes().empty());
  EXPECT_LT(worst, 1e-3);
}

}  // namespace
