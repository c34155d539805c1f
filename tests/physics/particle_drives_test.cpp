// Drives of particle bodies (docs/physics.md, "Joint drives"): a particle joint's drive against the
// torsion spring's period, the same whatever the passes and substeps; strength 1 holding the target;
// the pair's angular momentum kept; the particle ragdolls' strengths; a particle body's drive against
// the spring's sag; and bad input. (The particle ragdolls held standing: drives_test.cpp.)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "physics/capsule_ragdoll.h"
#include "physics/ragdoll.h"
#include "physics/world.h"
#include "test_util.h"

namespace {

using phys::BodyId;
using phys::BodyModel;
using phys::JointDrive;
using phys::Quat;
using phys::Real;
using phys::Vec3;

const Vec3 kZ(0.0, 0.0, 1.0);

phys::SolverSettings gaussSeidel(int iterations, int substeps) {
  return testing_phys::solver(phys::SolverMethod::GaussSeidel, iterations, substeps);
}

phys::BodyDesc particleBox(BodyModel model, const Vec3& centre, const Vec3& size, Real mass) {
  phys::BodyDesc d;
  d.model = model;
  d.center = centre;
  d.size = size;
  d.mass = mass;
  return d;
}

// A 1 kg particle bar, 1 m x 0.1 m x 0.1 m, hinged about z at its end (two pins on the axis) to a
// particle body a million times heavier, in space; the particle joint at the pivot carries the drive.
struct Hinged {
  phys::World world;
  BodyId parent, child;
};

Hinged hinged(BodyModel model, const phys::SolverSettings& solver) {
  Hinged h{testing_phys::openSpace(solver, Vec3(0.0)), BodyId{}, BodyId{}};
  h.parent = h.world.addBody(particleBox(model, Vec3(-0.5, 0.0, 0.0), Vec3(1.0), 1e6));
  h.child = h.world.addBody(particleBox(model, Vec3(0.5, 0.0, 0.0), Vec3(1.0, 0.1, 0.1), 1.0));
  for (const Real z : {-0.05, 0.05}) {
    const Vec3 pin(0.0, 0.0, z);
    h.world.addLink(h.world.anchor(h.parent, pin), h.world.anchor(h.child, pin));
  }
  h.world.addParticleJoint(h.parent, h.child, Vec3(0.0));
  h.world.ignoreCollision(h.parent, h.child);
  return h;
}

// The child's turn about z relative to the parent (rad).
Real angleOf(const Hinged& h) {
  const Quat q =
      glm::conjugate(h.world.bodyPose(h.parent).orientation) * h.world.bodyPose(h.child).orientation;
  return 2.0 * std::atan2(q.z, q.w);
}

// The mean period (s) of the bar's swing about a drive's target at `target` from rest at 0, between
// upward passes through the target, over 4 s.
Real swingPeriod(BodyModel model, const phys::SolverSettings& solver, Real target, Real stiffness) {
  Hinged h = hinged(model, solver);
  h.world.setParticleJointDrive(0, JointDrive{glm::angleAxis(target, kZ), 0.5, stiffness});
  std::vector<Real> crossings;
  Real previous = angleOf(h) - target;
  for (int step = 1; step * solver.dt <= 4.0; ++step) {
    h.world.step();
    const Real now = angleOf(h) - target;
    if (previous < 0.0 && now >= 0.0) crossings.push_back((step - now / (now - previous)) * solver.dt);
    previous = now;
  }
  EXPECT_GE(crossings.size(), 3u);
  if (crossings.size() < 2) return 0.0;
  return (crossings.back() - crossings.front()) / static_cast<Real>(crossings.size() - 1);
}

// A torsion spring k on the bar turning about its end: T = 2 pi sqrt(I_p / k), I_p the particles'
// moment about the pivot, I_c + m (L / 2)^2 with I_c their own about the centre (bodyMass: a
// particle box's second moment is three times a solid box's). The compliance makes k the model's
// stiffness: the period is the same at 1 and 4 passes and at 4 to 16 substeps, within 0.5%
// (measured: 0.1% at most).
TEST(ParticleJointDrive, ADrivenParticleHingeSwingsAtTheTorsionSpringsPeriod) {
  for (const BodyModel model : {BodyModel::Tetra, BodyModel::Corners}) {
    SCOPED_TRACE(phys::toString(model));
    const Real k = 20.0;
    const Hinged probe = hinged(model, gaussSeidel(1, 4));
    const Real inertia = probe.world.bodyMass(probe.child).inertia.z + 1.0 * 0.25;
    const Real expected = 2.0 * std::numbers::pi * std::sqrt(inertia / k);
    for (const auto& [iterations, substeps] : {std::pair{1, 4}, {4, 4}, {1, 16}, {4, 16}}) {
      SCOPED_TRACE(testing::Message() << iterations << "x" << substeps);
      const Real ratio = swingPeriod(model, gaussSeidel(iterations, substeps), 0.3, k) / expected;
      std::printf("%s %d x %d: period / 2 pi sqrt(I_p / k) = %.5f\n",
                  std::string(phys::toString(model)).c_str(), iterations, substeps, ratio);
      EXPECT_NEAR(ratio, 1.0, 0.005);
    }
  }
}

// Strength 1, compliance 0: each pass puts the child on its target; the pins' corrections after it
// are taken back by the next pass, and within a second it holds to a thousandth of a radian.
TEST(ParticleJointDrive, AtStrengthOneTheChildHoldsItsTarget) {
  Hinged h = hinged(BodyModel::Tetra, gaussSeidel(2, 8));
  h.world.setParticleJointDrive(0, JointDrive{glm::angleAxis(0.7, kZ), 1.0, phys::kDriveStiffness});
  for (int step = 0; step < 60; ++step) h.world.step();
  EXPECT_NEAR(angleOf(h), 0.7, 1e-3);
  EXPECT_GT(h.world.particleJointDriveTorque(0), 0.0);  // it still works against the swing it started
}

// The drive turns the two bodies against each other: two equal bars end to end, at rest, bent by a
// drive, keep the pair's momentum (zero) and angular momentum, the second to what the Verlet velocities
// of a turned particle body keep (a rotation's chord, not its arc): under 1e-4 of the largest angular
// momentum a bar swings with (measured: 2.8e-5).
TEST(ParticleJointDrive, TheDriveTurnsThePartsAgainstEachOtherNotThePair) {
  phys::World w = testing_phys::openSpace(gaussSeidel(2, 8), Vec3(0.0));
  const BodyId a = w.addBody(particleBox(BodyModel::Tetra, Vec3(-0.5, 0.0, 0.0), Vec3(1.0, 0.1, 0.1), 1.0));
  const BodyId b = w.addBody(particleBox(BodyModel::Tetra, Vec3(0.5, 0.0, 0.0), Vec3(1.0, 0.1, 0.1), 1.0));
  w.addLink(w.anchor(a, Vec3(0.0)), w.anchor(b, Vec3(0.0)));
  w.ignoreCollision(a, b);
  w.setParticleJointDrive(w.addParticleJoint(a, b, Vec3(0.0)),
                          JointDrive{glm::angleAxis(1.0, kZ), 0.5, 20.0});
  Real largest = 0.0, worstAngular = 0.0;
  for (int step = 0; step < 60; ++step) {
    w.step();
    Vec3 momentum(0.0), angular(0.0);
    for (const BodyId id : {a, b}) {
      const auto [v, spin] = w.bodyVelocity(id);
      const phys::BodyMass m = w.bodyMass(id);
      const Vec3 c = w.bodyPose(id).center;
      momentum += m.mass * v;
      angular +=
          m.mass * glm::cross(c, v) +
          w.bodyPose(id).orientation * (m.inertia * (glm::conjugate(w.bodyPose(id).orientation) * spin));
      largest = std::max(largest, m.inertia.z * std::abs(spin.z));
    }
    EXPECT_LT(glm::length(momentum), 1e-9);
    EXPECT_LT(glm::length(angular), 1e-4 * largest);
    worstAngular = std::max(worstAngular, glm::length(angular));
  }
  std::printf("the pair's angular momentum at most %.2g of the largest a bar swings with\n",
              worstAngular / largest);
  EXPECT_GT(largest, 0.01);  // it did bend them
}

// A particle body's drive holds it against gravity as a spring of its stiffness: started at the sag
// m g / k below its target, it stays there, whatever the passes and substeps, within a millimetre.
TEST(ParticleBodyDrive, ABodyHeldAgainstGravitySagsByItsWeightOverTheStiffness) {
  for (const BodyModel model : {BodyModel::Tetra, BodyModel::Corners}) {
    for (const auto& [iterations, substeps] : {std::pair{1, 4}, {4, 16}}) {
      SCOPED_TRACE(testing::Message() << phys::toString(model) << " " << iterations << "x" << substeps);
      phys::World w = testing_phys::openSpace(gaussSeidel(iterations, substeps));
      const Real k = 2000.0, m = 10.0, sag = m * 9.81 / k;
      const Vec3 target(0.0, 1.0, 0.0);
      const BodyId id = w.addBody(particleBox(model, target - Vec3(0.0, sag, 0.0), Vec3(0.5), m));
      w.setBodyDrive(id, phys::BodyDrive{target, Quat(1.0, 0.0, 0.0, 0.0), 0.5, k, phys::kDriveStiffness});
      Real lowest = 1e9, highest = -1e9;
      for (int step = 0; step < 120; ++step) {
        w.step();
        const Real y = w.bodyPose(id).center.y;
        lowest = std::min(lowest, y), highest = std::max(highest, y);
      }
      EXPECT_NEAR(lowest, target.y - sag, 1.5e-3);
      EXPECT_NEAR(highest, target.y - sag, 1.5e-3);
      EXPECT_NEAR(w.bodyDriveLoad(id).force, m * 9.81, 0.5);
      EXPECT_LT(testing_phys::angleBetween(w.bodyPose(id).orientation, Quat(1.0, 0.0, 0.0, 0.0)), 1e-6);
    }
  }
}

// Both particle ragdolls make a particle joint at each of their joints, driven at their strength,
// with a stiffness for their size, the joint's rest as its target; a root strength drives the root.
TEST(ParticleJointDrive, ParticleRagdollsDrivesTakeTheirStrengths) {
  phys::World w = testing_phys::openSpace(gaussSeidel(2, 8));
  phys::RagdollDesc d;
  d.model = phys::RagdollModel::Lean;
  d.strength = 0.25;
  d.rootStrength = 0.5;
  d.mass = 35.0;
  d.scale = 2.0;
  const phys::Ragdoll boxes = phys::addRagdoll(w, d);
  d.hips = Vec3(3.0, 0.0, 0.0);
  d.model = phys::RagdollModel::Seed;
  d.driveStiffness = 400.0;
  const phys::CapsuleRagdoll capsules = phys::addCapsuleRagdoll(w, d);
  EXPECT_EQ(boxes.firstJoint, 0u);
  EXPECT_EQ(capsules.firstJoint, static_cast<std::size_t>(phys::kRagdollHinges));
  EXPECT_TRUE(w.rigidJoints().empty());
  ASSERT_EQ(w.particleJoints().size(), static_cast<std::size_t>(phys::kRagdollHinges + phys::kCapsuleJoints));
  for (std::size_t k = 0; k < w.particleJoints().size(); ++k) {
    const phys::JointDrive& drive = w.particleJointDrive(k);
    EXPECT_EQ(drive.strength, 0.25);
    EXPECT_DOUBLE_EQ(drive.stiffness, k < phys::kRagdollHinges ? phys::kDriveStiffness : 400.0);
    EXPECT_LT(testing_phys::angleBetween(drive.target, w.particleJoints()[k].rest), 1e-15);
  }
  for (const BodyId root : {boxes.part(phys::RagdollPart::Torso), capsules.part(phys::CapsulePart::Pelvis)}) {
    ASSERT_TRUE(w.bodyDrive(root).has_value());
    EXPECT_EQ(w.bodyDrive(root)->strength, 0.5);
  }
}

TEST(ParticleJointDrive, BadInputIsRefusedAndNothingAdded) {
  phys::World w = testing_phys::openSpace(gaussSeidel(2, 8));
  const BodyId a = w.addBody(particleBox(BodyModel::Tetra, Vec3(0.0), Vec3(1.0), 1.0));
  const BodyId b = w.addBody(particleBox(BodyModel::Corners, Vec3(1.0, 0.0, 0.0), Vec3(1.0), 1.0));
  const BodyId r = w.addBody(testing_phys::rigidBox(Vec3(3.0, 0.0, 0.0)));
  EXPECT_THROW(w.addParticleJoint(a, a, Vec3(0.5, 0.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(w.addParticleJoint(a, r, Vec3(0.5, 0.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(w.addParticleJoint(a, BodyId(7), Vec3(0.5, 0.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(w.addParticleJoint(a, b, Vec3(std::nan(""), 0.0, 0.0)), std::invalid_argument);
  EXPECT_TRUE(w.particleJoints().empty());
  const std::size_t k = w.addParticleJoint(a, b, Vec3(0.5, 0.0, 0.0));
  EXPECT_EQ(w.particleJoints()[k].pivotA, Vec3(0.5, 0.0, 0.0));
  EXPECT_EQ(w.particleJoints()[k].pivotB, Vec3(-0.5, 0.0, 0.0));
  EXPECT_EQ(w.particleJointDrive(k).strength, 0.0);
  EXPECT_THROW(w.setParticleJointDrive(k, JointDrive{Quat(1.0, 0.0, 0.0, 0.0), 1.5, 10.0}),
               std::invalid_argument);
  EXPECT_THROW(w.setParticleJointDrive(k, JointDrive{Quat(1.0, 0.0, 0.0, 0.0), 0.5, 0.0}),
               std::invalid_argument);
  EXPECT_THROW(w.setParticleJointDrive(k, JointDrive{Quat(2.0, 0.0, 0.0, 0.0), 0.5, 10.0}),
               std::invalid_argument);
  EXPECT_THROW(w.setParticleJointDrive(k + 1, JointDrive{}), std::invalid_argument);
  EXPECT_EQ(w.particleJointDrive(k).strength, 0.0);
}

}  // namespace
