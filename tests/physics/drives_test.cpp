// Drives (docs/physics.md, "Joint drives"): a driven hinge against the torsion spring's period, the
// same whatever the passes, substeps and step (XPBD's compliance); strength 1 as a locked joint;
// strength 0 as no drive, to the bit; the pair's momentum kept; the rest as a new joint's target;
// waking; ragdolls' strengths; a body's drive (the hand of god) against the spring's sag and periods;
// and bad input.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>
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
using phys::JointDesc;
using phys::JointDrive;
using phys::JointKind;
using phys::Quat;
using phys::Real;
using phys::Vec3;
using testing_phys::rigidBox;

const Vec3 kZ(0.0, 0.0, 1.0);

// A 1 kg bar, 1 m x 0.1 m x 0.1 m, hinged about z at its end to a body a million times heavier, in
// space: the heavy parent stands still to a part in a million, and the bar turns about the pivot.
struct Hinged {
  phys::World world;
  BodyId parent, child;
};

Hinged hinged(const phys::SolverSettings& solver, Vec3 gravity = Vec3(0.0), Real damping = 0.0) {
  Hinged h{testing_phys::openSpace(solver, gravity), BodyId{}, BodyId{}};
  h.parent = h.world.addBody(rigidBox(Vec3(-0.5, 0.0, 0.0), Vec3(1.0), 1e6));
  h.child = h.world.addBody(rigidBox(Vec3(0.5, 0.0, 0.0), Vec3(1.0, 0.1, 0.1), 1.0));
  JointDesc j = testing_phys::joint(JointKind::Hinge, h.parent, h.child, Vec3(0.0), kZ, Vec3(1.0, 0.0, 0.0));
  j.minAngle = -std::numbers::pi;
  j.maxAngle = std::numbers::pi;
  j.damping = damping;
  h.world.addJoint(j);
  h.world.ignoreCollision(h.parent, h.child);  // they touch at the pivot
  return h;
}

phys::SolverSettings xpbd(int iterations, int substeps, Real dt = 1.0 / 60.0) {
  phys::SolverSettings s = testing_phys::solver(phys::SolverMethod::Xpbd, iterations, substeps);
  s.dt = dt;
  return s;
}

JointDrive drive(Real angle, Real strength, Real stiffness) {
  return JointDrive{glm::angleAxis(angle, kZ), strength, stiffness};
}

struct Swing {
  Real period = 0.0;  // s: the mean between upward passes through the target
  Real centre = 0.0;  // rad: the mean angle over the whole swings between the first and last crossing
  Real decay = 0.0;   // unitless: the last swing's amplitude over the first's
};

// The bar starts at rest at angle 0 with the drive's target at `target`: it swings about the target.
Swing swingAbout(const phys::SolverSettings& solver, Real target, Real stiffness) {
  Hinged h = hinged(solver);
  const Real strength = 0.5;  // the stiffness as given
  h.world.setJointDrive(0, drive(target, strength, stiffness));
  std::vector<Real> crossings, sums(1, 0.0), counts(1, 0.0), peaks(1, 0.0);
  Real previous = h.world.jointAngle(0) - target;
  const Real dt = solver.dt;
  for (int step = 1; step * dt <= 6.0; ++step) {
    h.world.step();
    const Real now = h.world.jointAngle(0) - target;
    if (previous < 0.0 && now >= 0.0) {
      crossings.push_back((step - 1 + previous / (previous - now)) * dt);
      sums.push_back(0.0);
      counts.push_back(0.0);
      peaks.push_back(0.0);
    }
    sums.back() += now;
    counts.back() += 1.0;
    peaks.back() = std::max(peaks.back(), now);
    previous = now;
  }
  Swing out;
  EXPECT_GE(crossings.size(), 4u);
  if (crossings.size() < 4) return out;
  out.period = (crossings.back() - crossings.front()) / static_cast<Real>(crossings.size() - 1);
  Real sum = 0.0, count = 0.0;  // the whole swings: between the first crossing and the last
  for (std::size_t k = 1; k + 1 < sums.size(); ++k) {
    sum += sums[k];
    count += counts[k];
  }
  out.centre = target + sum / count;
  out.decay = peaks[peaks.size() - 2] / peaks[1];
  return out;
}

// A torsion spring k on a bar turning about its end: T = 2 pi sqrt(I_p / k), I_p = m (L^2 + t^2) / 12
// + m (L / 2)^2. XPBD's compliance makes k a stiffness of the model, not of the solver: the period
// is the same at 1 and 4 passes, at 4 to 16 substeps and at two steps, within 0.5% (measured: 0.1%
// at most). The swing's centre is the target; the mean over whole swings leans up to 1% towards each
// swing's first half, since the swing decays: XPBD's implicit step damps it, by 20% of its amplitude
// in four swings at 4 substeps and 5% at 16 (docs/physics.md, "Joint drives").
TEST(JointDrive, AHingeDrivenTowardsAnAngleSwingsAtTheTorsionSpringsPeriod) {
  const Real stiffness = 10.0, ip = 1.01 / 12.0 + 0.25;
  const Real expected = 2.0 * std::numbers::pi * std::sqrt(ip / stiffness);
  const struct {
    int iterations, substeps;
    Real dt;
  } cases[] = {
      {1, 4, 1.0 / 60.0}, {4, 4, 1.0 / 60.0}, {1, 16, 1.0 / 60.0}, {2, 8, 1.0 / 60.0}, {1, 4, 1.0 / 120.0}};
  std::vector<Real> decays;
  for (const auto& c : cases) {
    SCOPED_TRACE(testing::Message() << c.iterations << " x " << c.substeps << " at dt " << c.dt);
    const Swing s = swingAbout(xpbd(c.iterations, c.substeps, c.dt), 0.3, stiffness);
    EXPECT_NEAR(s.period, expected, 0.005 * expected);
    EXPECT_NEAR(s.centre, 0.3, 0.005);
    decays.push_back(s.decay);
    // The figures docs/physics.md's table quotes.
    std::printf("  %d x %d at dt 1/%.0f: period %.4f s (exact %.4f), amplitude left %.0f%%\n", c.iterations,
                c.substeps, 1.0 / c.dt, s.period, expected, 100.0 * s.decay);
  }
  // The damping is the step's, and goes as h: a quarter of the substep keeps most of what 1 x 4 lost.
  EXPECT_GT(decays[2], 0.93);
  EXPECT_GT(1.0 - decays[0], 3.0 * (1.0 - decays[2]));
}

// What the drive exerts is what holds the bar: pushed at its tip by a force across it, the bar
// settles (the joint's damping takes the swing) where the drive's torque k angle answers the push's
// F L cos(angle), and jointDriveTorque reports that torque, at any passes and substeps, within 1%.
TEST(JointDrive, ItsTorqueIsWhatHoldsTheChildAgainstAPush) {
  const Real stiffness = 10.0, force = 2.0;
  for (const auto& [iterations, substeps] : {std::pair{1, 4}, std::pair{2, 8}, std::pair{4, 16}}) {
    SCOPED_TRACE(testing::Message() << iterations << " x " << substeps);
    Hinged h = hinged(xpbd(iterations, substeps), Vec3(0.0), 5.0);
    EXPECT_EQ(h.world.jointDriveTorque(0), 0.0);  // no drive, and no step yet
    h.world.setJointDrive(0, drive(0.0, 0.5, stiffness));
    h.world.push(h.child, Vec3(0.0, force, 0.0), 20.0, Vec3(1.0, 0.0, 0.0));
    for (int step = 0; step < 600; ++step) h.world.step();
    const Real angle = h.world.jointAngle(0);
    const Real torque = h.world.jointDriveTorque(0);
    EXPECT_GT(angle, 0.1);
    EXPECT_NEAR(torque, force * std::cos(angle), 0.01 * force);
    EXPECT_NEAR(torque, stiffness * angle, 0.01 * torque);
  }
}

// Compliance 0: each pass puts the child on its target, and the pin's corrections after it are
// taken back by the next pass; within a few steps it holds to a thousandth of a radian.
TEST(JointDrive, AtStrengthOneTheChildHoldsItsTargetAsALockedJoint) {
  Hinged h = hinged(xpbd(2, 8));
  h.world.setJointDrive(0, drive(0.5, 1.0, phys::kDriveStiffness));
  Real worst = 0.0;
  for (int step = 1; step <= 120; ++step) {
    h.world.step();
    if (step > 10) worst = std::max(worst, std::abs(h.world.jointAngle(0) - 0.5));
  }
  EXPECT_LT(worst, 1e-3);
}

// A limp joint is a joint with no drive: strength 0 with any target and stiffness changes nothing,
// to the bit, under gravity and a drag.
TEST(JointDrive, StrengthZeroIsNoDriveToTheBit) {
  Hinged a = hinged(xpbd(2, 8), Vec3(0.0, -9.81, 0.0));
  Hinged b = hinged(xpbd(2, 8), Vec3(0.0, -9.81, 0.0));
  b.world.setJointDrive(0, drive(1.0, 0.0, 50.0));
  for (Hinged* h : {&a, &b}) {
    phys::Drag pull = h->world.dragAt(h->child, Vec3(1.0, 0.0, 0.0));
    pull.target = Vec3(1.0, 1.0, 0.5);
    h->world.setDrag(pull);
    for (int step = 0; step < 90; ++step) h->world.step();
  }
  EXPECT_EQ(a.world.stateHash(), b.world.stateHash());
}

// The drive turns the two bodies against each other by equal and opposite angular impulses, so the
// pair's momentum and angular momentum stay what they were (zero): two equal bars at rest, end to end
// on a cone, bent by a drive. What is left is the angular momentum of the velocities XPBD derives from
// the poses (each substep's turn through its start's I^-1), under a thousandth of the angular momentum
// each bar swings with.
TEST(JointDrive, TheDriveTurnsThePartsAgainstEachOtherNotThePair) {
  phys::World w = testing_phys::openSpace(xpbd(2, 8), Vec3(0.0));
  const BodyId a = w.addBody(rigidBox(Vec3(-0.5, 0.0, 0.0), Vec3(1.0, 0.1, 0.1)));
  const BodyId b = w.addBody(rigidBox(Vec3(0.5, 0.0, 0.0), Vec3(1.0, 0.1, 0.1)));
  JointDesc j =
      testing_phys::joint(JointKind::Cone, a, b, Vec3(0.0), Vec3(1.0, 0.0, 0.0), Vec3(0.0, 1.0, 0.0));
  j.swing = 2.0;
  j.twist = 1.0;
  w.addJoint(j);
  w.ignoreCollision(a, b);
  w.setJointDrive(0, JointDrive{glm::angleAxis(1.2, glm::normalize(Vec3(0.0, 1.0, 1.0))), 0.5, 2.0});
  Real worst = 0.0, largestOwn = 0.0;
  for (int step = 0; step < 120; ++step) {
    w.step();
    Vec3 linear(0.0), angular(0.0), centre(0.0);
    const phys::RigidBodies& r = w.rigidBodies();
    for (phys::RigidId i{}; i < r.size(); ++i) centre += 0.5 * r.position[i];
    for (phys::RigidId i{}; i < r.size(); ++i) {
      const glm::dmat3 R = glm::mat3_cast(r.orientation[i]);
      const glm::dmat3 inertia =
          R *
          glm::dmat3(1.0 / r.inverseInertia[i].x, 0.0, 0.0, 0.0, 1.0 / r.inverseInertia[i].y, 0.0, 0.0, 0.0,
                     1.0 / r.inverseInertia[i].z) *
          glm::transpose(R);
      const Vec3 own = inertia * r.angularVelocity[i] + glm::cross(r.position[i] - centre, r.velocity[i]);
      largestOwn = std::max(largestOwn, glm::length(own));
      linear += r.velocity[i];
      angular += own;
    }
    EXPECT_LT(glm::length(linear), 1e-9);
    worst = std::max(worst, glm::length(angular));
  }
  EXPECT_GT(largestOwn, 0.05);  // it did bend
  EXPECT_LT(worst, 1e-3 * largestOwn);
}

// A joint is made with its rest as the target: a joint between bodies at different orientations
// holds them so, and one made away from its rest (its child's frame given apart) pulls back to it.
TEST(JointDrive, AJointsDriveStartsAtItsRest) {
  phys::World w = testing_phys::openSpace(xpbd(2, 8), Vec3(0.0));
  phys::BodyDesc parent = rigidBox(Vec3(0.0, 1.0, 0.0));
  parent.orientation = glm::angleAxis(0.7, glm::normalize(Vec3(1.0, 2.0, 3.0)));
  phys::BodyDesc child = rigidBox(Vec3(0.0, -1.0, 0.0));
  child.orientation = glm::angleAxis(-0.4, glm::normalize(Vec3(3.0, -1.0, 0.5)));
  const BodyId a = w.addBody(parent), b = w.addBody(child);
  JointDesc j =
      testing_phys::joint(JointKind::Cone, a, b, Vec3(0.0), Vec3(0.0, -1.0, 0.0), Vec3(1.0, 0.0, 0.0));
  j.swing = 1.0;
  j.twist = 0.5;
  w.addJoint(j);
  EXPECT_EQ(w.jointDrive(0).strength, 0.0);
  EXPECT_EQ(w.jointDrive(0).stiffness, phys::kDriveStiffness);
  const Quat relative = glm::conjugate(parent.orientation) * child.orientation;
  EXPECT_LT(testing_phys::angleBetween(w.jointDrive(0).target, relative), 1e-12);

  // The same joint made again with the child's frame turned 0.3 rad about the limb: the child
  // is then 0.3 rad from its rest, and a full-strength drive takes it there.
  Hinged h = hinged(xpbd(2, 8));
  JointDesc bent = h.world.jointDesc(0);
  bent.axisB = bent.axis;
  bent.referenceB = glm::angleAxis(-0.3, kZ) * bent.reference;
  h.world.addJoint(bent);
  EXPECT_NEAR(h.world.jointAngle(1), -0.3, 1e-12);
  JointDrive hold = h.world.jointDrive(1);
  hold.strength = 1.0;
  h.world.setJointDrive(1, hold);
  for (int step = 0; step < 60; ++step) h.world.step();
  EXPECT_NEAR(h.world.jointAngle(1), 0.0, 1e-3);
}

TEST(JointDrive, ANewDriveWakesItsIsland) {
  phys::WorldSettings ws;
  phys::SolverSettings s = xpbd(2, 8);
  s.sleep.enabled = true;
  phys::World w(ws, s);
  const BodyId a = w.addBody(rigidBox(Vec3(-0.5, 0.05, 0.0), Vec3(1.0, 0.1, 0.1)));
  const BodyId b = w.addBody(rigidBox(Vec3(0.5, 0.05, 0.0), Vec3(1.0, 0.1, 0.1)));
  JointDesc j = testing_phys::joint(JointKind::Hinge, a, b, Vec3(0.0, 0.05, 0.0), kZ, Vec3(1.0, 0.0, 0.0));
  j.minAngle = -1.0;
  j.maxAngle = 1.0;
  w.addJoint(j);
  w.ignoreCollision(a, b);
  for (int step = 0; step < 120; ++step) w.step();
  ASSERT_TRUE(w.islands().bodyAsleep(b));
  w.setJointDrive(0, drive(0.5, 0.9, 100.0));
  EXPECT_FALSE(w.islands().bodyAsleep(a));
  EXPECT_FALSE(w.islands().bodyAsleep(b));
  for (int step = 0; step < 60; ++step) w.step();
  EXPECT_GT(w.jointAngle(0), 0.3);  // it bent up off the ground
}

TEST(JointDrive, BadDrivesAreRefusedAndTheOldOneKept) {
  Hinged h = hinged(xpbd(1, 4));
  h.world.setJointDrive(0, drive(0.2, 0.5, 10.0));
  const Real nan = std::nan("");
  const JointDrive bad[] = {
      JointDrive{Quat(2.0, 0.0, 0.0, 0.0), 0.5, 10.0},  // not unit
      JointDrive{Quat(nan, 0.0, 0.0, 0.0), 0.5, 10.0},  // not finite
      drive(0.2, -0.1, 10.0),                           // strength below 0
      drive(0.2, 1.5, 10.0),                            // above 1
      drive(0.2, nan, 10.0),                            // not a number
      drive(0.2, 0.5, 0.0),                             // no stiffness
      drive(0.2, 0.5, std::numeric_limits<Real>::infinity()),
  };
  for (const JointDrive& d : bad) EXPECT_THROW(h.world.setJointDrive(0, d), std::invalid_argument);
  EXPECT_THROW(h.world.setJointDrive(1, drive(0.2, 0.5, 10.0)), std::invalid_argument);
  EXPECT_THROW((void)h.world.jointDrive(1), std::invalid_argument);
  EXPECT_EQ(h.world.jointDrive(0).strength, 0.5);
  EXPECT_EQ(h.world.jointDrive(0).stiffness, 10.0);
  // A target a little off unit is taken, made unit.
  h.world.setJointDrive(0, JointDrive{Quat(1.0 + 5e-7, 0.0, 0.0, 0.0), 0.5, 10.0});
  EXPECT_DOUBLE_EQ(glm::length(h.world.jointDrive(0).target), 1.0);
}

// A ragdoll's strength drives each of its joints towards the pose it was made in. The box ragdoll of
// rigid parts, standing on the flat ends of its lower legs, stays standing at strength 1 (a statue)
// and at 1/2 (each joint at kDriveStiffness); limp, it folds and falls.
Real headHeightAfter(Real strength, Real seconds, phys::RagdollModel model = phys::RagdollModel::Rigid) {
  phys::WorldSettings ws;
  phys::World w(ws, xpbd(2, 8));
  phys::RagdollDesc d;
  d.model = model;
  d.hips = Vec3(0.0, 0.85, 0.0);  // the lower legs' ends at the ground
  d.strength = strength;
  const phys::Ragdoll r = phys::addRagdoll(w, d);
  for (int step = 0; step * w.solverSettings().dt < seconds; ++step) w.step();
  EXPECT_TRUE(w.freezes().empty());
  return w.bodyPose(r.part(phys::RagdollPart::Head)).center.y;
}

TEST(JointDrive, ARigidRagdollHeldAtItsPoseStandsAndALimpOneFalls) {
  const Real standing = 1.59;  // the head's centre as built
  EXPECT_NEAR(headHeightAfter(1.0, 10.0), standing, 0.005);
  EXPECT_NEAR(headHeightAfter(0.5, 10.0), standing, 0.005);
  EXPECT_LT(headHeightAfter(0.0, 10.0), 0.5);
}

// The particle ragdolls too, their joints driven through their particle joints
// (particle_drives_test.cpp): a little lower, their pins and sticks giving a little.
TEST(JointDrive, AParticleRagdollHeldAtItsPoseStandsAndALimpOneFalls) {
  const Real standing = 1.59;
  for (const phys::RagdollModel model : {phys::RagdollModel::Lean, phys::RagdollModel::Seed}) {
    SCOPED_TRACE(phys::toString(model));
    EXPECT_NEAR(headHeightAfter(1.0, 10.0, model), standing, 0.01);
    EXPECT_NEAR(headHeightAfter(0.5, 10.0, model), standing, 0.02);
    EXPECT_LT(headHeightAfter(0.0, 10.0, model), 0.5);
  }
}

TEST(JointDrive, ARagdollsDrivesTakeItsStrengthAndAStiffnessForItsSize) {
  phys::World w = testing_phys::openSpace(xpbd(2, 8));
  phys::RagdollDesc d;
  d.model = phys::RagdollModel::Rigid;
  d.strength = 0.25;
  d.mass = 35.0;
  d.scale = 2.0;
  const phys::Ragdoll boxes = phys::addRagdoll(w, d);
  d.hips = Vec3(3.0, 0.0, 0.0);
  d.driveStiffness = 400.0;
  const phys::CapsuleRagdoll capsules = phys::addCapsuleRagdoll(w, d);
  EXPECT_EQ(boxes.firstJoint, 0u);
  EXPECT_EQ(capsules.firstJoint, static_cast<std::size_t>(phys::kRagdollHinges));
  ASSERT_EQ(w.rigidJoints().size(), static_cast<std::size_t>(phys::kRagdollHinges + phys::kCapsuleJoints));
  for (std::size_t k = 0; k < w.rigidJoints().size(); ++k) {
    EXPECT_EQ(w.jointDrive(k).strength, 0.25);
    // Half the mass at twice the size: the same stiffness as a 70 kg ragdoll at scale 1.
    EXPECT_DOUBLE_EQ(w.jointDrive(k).stiffness,
                     k < boxes.firstJoint + phys::kRagdollHinges ? phys::kDriveStiffness : 400.0);
    EXPECT_LT(testing_phys::angleBetween(w.jointDrive(k).target, w.jointRest(k)), 1e-15);
  }
  for (const Real strength : {-0.5, 1.5, std::nan("")}) {
    d.strength = strength;
    EXPECT_THROW(phys::addCapsuleRagdoll(w, d), std::invalid_argument);
  }
  d.strength = 0.5;
  for (const Real root : {-0.5, 1.5}) {
    d.rootStrength = root;
    EXPECT_THROW(phys::addRagdoll(w, d), std::invalid_argument);
  }
  d.rootStrength = 0.5;
  d.driveStiffness = 0.0;
  EXPECT_THROW(phys::addRagdoll(w, d), std::invalid_argument);
  EXPECT_EQ(w.rigidJoints().size(), static_cast<std::size_t>(phys::kRagdollHinges + phys::kCapsuleJoints));
}

// The stiffness for the ragdoll's size is set at strength 0 too, where a character takes the joints
// up with strengths of its own: it was left at the 70 kg default unless the ragdoll had a strength.
TEST(JointDrive, ALimpRagdollsDrivesHaveTheStiffnessForItsSize) {
  phys::World w = testing_phys::openSpace(xpbd(2, 8));
  phys::RagdollDesc d;
  d.strength = 0.0;
  d.mass = 700.0;
  d.model = phys::RagdollModel::Rigid;
  phys::addRagdoll(w, d);
  d.model = phys::RagdollModel::Lean;
  d.hips = Vec3(3.0, 0.0, 0.0);
  phys::addRagdoll(w, d);
  ASSERT_EQ(w.rigidJoints().size(), static_cast<std::size_t>(phys::kRagdollHinges));
  ASSERT_FALSE(w.particleJoints().empty());
  for (std::size_t k = 0; k < w.rigidJoints().size(); ++k) {
    EXPECT_EQ(w.jointDrive(k).strength, 0.0);
    EXPECT_DOUBLE_EQ(w.jointDrive(k).stiffness, 10.0 * phys::kDriveStiffness);
  }
  for (std::size_t k = 0; k < w.particleJoints().size(); ++k) {
    EXPECT_EQ(w.particleJointDrive(k).strength, 0.0);
    EXPECT_DOUBLE_EQ(w.particleJointDrive(k).stiffness, 10.0 * phys::kDriveStiffness);
  }
}

// A strength so small that its compliance, (1 - s) / (s k), or that over h^2, is infinite is no
// drive: 1e-310 made the XPBD step inf * 0, NaN, and the guard froze the ragdoll at once. Such a
// ragdoll falls limp, as one of strength 0, to the bit.
TEST(JointDrive, AStrengthTooSmallForItsComplianceIsNoDrive) {
  for (const phys::RagdollModel model : {phys::RagdollModel::Rigid, phys::RagdollModel::Lean}) {
    SCOPED_TRACE(phys::toString(model));
    auto limp = [model](Real strength) {
      phys::World w(phys::WorldSettings{}, xpbd(2, 8));
      phys::RagdollDesc d;
      d.model = model;
      d.hips = Vec3(0.0, 0.85, 0.0);
      d.strength = strength;
      phys::addRagdoll(w, d);
      for (int step = 0; step < 120; ++step) w.step();
      EXPECT_TRUE(w.freezes().empty()) << strength;
      return w.stateHash();
    };
    const auto none = limp(0.0);
    for (const Real tiny : {1e-310, 1e-320, std::numeric_limits<Real>::denorm_min()})
      EXPECT_EQ(limp(tiny), none) << tiny;
  }
}

// A body's drive holds it against gravity as a spring of its stiffness: started at the sag m g / k
// below its target, a body stays there whatever the passes and substeps, bobbing only by what it
// starts with: a body given no velocity at the pose's time keeps g h / 2 of gravity's for the
// substep before (World::poseVelocity), an amplitude of g h / (2 omega), 1.4 mm at 1 x 4. Started on
// the target it bobs about the sag at 2 pi sqrt(m / k).
TEST(BodyDrive, ABodyHeldAgainstGravitySagsByItsWeightOverTheStiffness) {
  const Real mass = 2.0, stiffness = 400.0, g = 9.81;
  const Real sag = mass * g / stiffness;  // 4.9 cm
  const Vec3 target(0.0, 1.0, 0.0);
  for (const auto& [iterations, substeps] : {std::pair{1, 4}, std::pair{2, 8}, std::pair{1, 16}}) {
    SCOPED_TRACE(testing::Message() << iterations << " x " << substeps);
    for (const Real start : {sag, 0.0}) {
      phys::World w = testing_phys::openSpace(xpbd(iterations, substeps));
      const BodyId id = w.addBody(rigidBox(target - Vec3(0.0, start, 0.0), Vec3(0.5), mass));
      w.setBodyDrive(id, phys::BodyDrive{target, Quat(1.0, 0.0, 0.0, 0.0), 0.5, stiffness, 10.0});
      const Real h = w.solverSettings().dt / substeps;
      Real previous = start - sag, lowest = 0.0, highest = 0.0, first = -1.0, last = -1.0;
      int crossings = 0;
      for (int step = 1; step <= 180; ++step) {
        w.step();
        const Real off = target.y - w.bodyPose(id).center.y - sag;  // from the sag, + below it
        lowest = std::min(lowest, off);
        highest = std::max(highest, off);
        if (previous < 0.0 && off >= 0.0) {
          const Real t = (step - 1 + previous / (previous - off)) * w.solverSettings().dt;
          if (first < 0.0) first = t;
          last = t;
          ++crossings;
        }
        previous = off;
      }
      if (start == sag) {
        EXPECT_LT(std::max(-lowest, highest), 1.05 * g * h / (2.0 * std::sqrt(stiffness / mass)));
        // What the drive exerted holds the body up: its weight, within the bob's 3%.
        EXPECT_NEAR(w.bodyDriveLoad(id).force, mass * g, 0.03 * mass * g);
        EXPECT_NEAR(w.bodyDriveLoad(id).torque, 0.0, 1e-9);
      } else {
        ASSERT_GE(crossings, 3);
        const Real period = (last - first) / (crossings - 1);
        EXPECT_NEAR(period, 2.0 * std::numbers::pi * std::sqrt(mass / stiffness), 0.005 * period);
      }
    }
  }
}

// The turn the same way: a box spun about z with its drive holding it at its start twists back and
// forth at 2 pi sqrt(I_z / k); at strength 1 the hand of god holds a body at its pose exactly,
// against gravity and a spin, and with the drive cleared it falls.
TEST(BodyDrive, ABodysTurnSwingsAtItsTorsionPeriodAndStrengthOneHoldsItStill) {
  phys::World w = testing_phys::openSpace(xpbd(1, 16), Vec3(0.0));
  phys::BodyDesc spun = rigidBox(Vec3(0.0), Vec3(1.0, 0.5, 0.2), 3.0);
  spun.angularVelocity = Vec3(0.0, 0.0, 1.0);
  const BodyId id = w.addBody(spun);
  const Real k = 8.0, iz = 3.0 * (1.0 + 0.25) / 12.0;  // a period of 1.24 s
  w.setBodyDrive(id, phys::BodyDrive{Vec3(0.0), Quat(1.0, 0.0, 0.0, 0.0), 0.5, 100.0, k});
  std::vector<Real> crossings;
  Real previous = 0.0;
  for (int step = 1; step <= 6 * 60; ++step) {
    w.step();
    const phys::Quat q = w.bodyPose(id).orientation;
    const Real angle = 2.0 * std::atan2(q.z, q.w);
    if (previous < 0.0 && angle >= 0.0)
      crossings.push_back((step - 1 + previous / (previous - angle)) / 60.0);
    previous = angle;
  }
  ASSERT_GE(crossings.size(), 3u);
  const Real period = (crossings.back() - crossings.front()) / static_cast<Real>(crossings.size() - 1);
  EXPECT_NEAR(period, 2.0 * std::numbers::pi * std::sqrt(iz / k), 0.005 * period);

  phys::World held = testing_phys::openSpace(xpbd(2, 8));
  phys::BodyDesc d = rigidBox(Vec3(0.0, 1.0, 0.0), Vec3(0.5), 5.0);
  d.orientation = glm::angleAxis(0.4, glm::normalize(Vec3(1.0, 1.0, 0.0)));
  d.angularVelocity = Vec3(3.0, 0.0, 1.0);
  const BodyId b = held.addBody(d);
  held.setBodyDrive(
      b, phys::BodyDrive{d.center, d.orientation, 1.0, phys::kBodyDriveStiffness, phys::kDriveStiffness});
  for (int step = 0; step < 60; ++step) held.step();
  EXPECT_LT(glm::length(held.bodyPose(b).center - d.center), 1e-9);
  EXPECT_LT(testing_phys::angleBetween(held.bodyPose(b).orientation, d.orientation), 1e-9);
  held.clearBodyDrive(b);
  EXPECT_FALSE(held.bodyDrive(b).has_value());
  for (int step = 0; step < 30; ++step) held.step();
  EXPECT_LT(held.bodyPose(b).center.y, 1.0 - 0.5 * 9.81 * 0.25 + 0.01);  // half a second of fall
}

// The capsule ragdoll cannot stand on its round soles by its joints alone: a statue on two round
// ends, given a nudge (0.5 m/s forwards at the start), it topples. With the hand of god on its pelvis
// it is pulled back and stands, its legs held under it by their drives.
Real capsuleHeadAfter(Real rootStrength, Real seconds) {
  phys::WorldSettings ws;
  phys::World w(ws, xpbd(2, 8));
  phys::RagdollDesc d;
  d.model = phys::RagdollModel::Rigid;
  d.hips = Vec3(0.0, 0.9225, 0.0);  // the soles at the ground
  d.strength = 1.0;
  d.rootStrength = rootStrength;
  d.velocity = Vec3(0.0, 0.0, 0.5);
  const phys::CapsuleRagdoll r = phys::addCapsuleRagdoll(w, d);
  if (rootStrength > 0.0) {
    const phys::BodyDrive hand = *w.bodyDrive(r.part(phys::CapsulePart::Pelvis));
    EXPECT_EQ(hand.strength, rootStrength);
    EXPECT_EQ(hand.position, w.bodyPose(r.part(phys::CapsulePart::Pelvis)).center);
    EXPECT_EQ(hand.stiffness, phys::kBodyDriveStiffness);
  }
  for (int step = 0; step * w.solverSettings().dt < seconds; ++step) w.step();
  return w.bodyPose(r.part(phys::CapsulePart::Head)).center.y;
}

TEST(BodyDrive, TheHandOfGodOnItsPelvisHoldsACapsuleRagdollUp) {
  EXPECT_GT(capsuleHeadAfter(1.0, 10.0), 1.5);
  EXPECT_GT(capsuleHeadAfter(0.5, 10.0), 1.5);
  EXPECT_LT(capsuleHeadAfter(0.0, 10.0), 0.5);
}

TEST(BodyDrive, BadBodyDrivesAreRefusedAndTheOldOneKept) {
  phys::World w = testing_phys::openSpace(xpbd(1, 4));
  const BodyId rigid = w.addBody(rigidBox(Vec3(0.0)));
  phys::BodyDesc particles = rigidBox(Vec3(3.0, 0.0, 0.0));
  particles.model = phys::BodyModel::Tetra;
  const BodyId tetra = w.addBody(particles);
  const phys::BodyDrive good{Vec3(0.0, 1.0, 0.0), Quat(1.0, 0.0, 0.0, 0.0), 0.5, 100.0, 10.0};
  w.setBodyDrive(rigid, good);
  const Real nan = std::nan(""), inf = std::numeric_limits<Real>::infinity();
  std::vector<phys::BodyDrive> bad(7, good);
  bad[0].position.x = nan;
  bad[1].orientation = Quat(0.5, 0.0, 0.0, 0.0);
  bad[2].strength = -0.1;
  bad[3].strength = nan;
  bad[4].stiffness = -1.0;  // 0 is a drive that only turns the body (a character's balance)
  bad[5].angularStiffness = inf;
  bad[6].orientation.w = inf;
  for (const phys::BodyDrive& d : bad) EXPECT_THROW(w.setBodyDrive(rigid, d), std::invalid_argument);
  for (const phys::BodyDrive& d : bad) EXPECT_THROW(w.setBodyDrive(tetra, d), std::invalid_argument);
  EXPECT_THROW(w.setBodyDrive(BodyId(7), good), std::invalid_argument);
  ASSERT_TRUE(w.bodyDrive(rigid).has_value());
  EXPECT_EQ(w.bodyDrive(rigid)->position, good.position);
  EXPECT_EQ(w.bodyDrive(rigid)->stiffness, 100.0);
  EXPECT_FALSE(w.bodyDrive(tetra).has_value());
  EXPECT_EQ(w.bodyDrives().size(), 1u);
  // A particle body takes a drive too (particle_drives_test.cpp).
  w.setBodyDrive(tetra, good);
  EXPECT_TRUE(w.bodyDrive(tetra).has_value());
}

}  // namespace
