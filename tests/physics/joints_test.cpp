// Joints between bodies (World::addLink on points from World::anchor), the damping of a box's
// internal motion (SolverSettings::bodyDamping) and the friction of particle bodies' joints
// (World::addJointFriction).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "passes.h"
#include "physics/capsule_ragdoll.h"
#include "physics/ragdoll.h"
#include "test_util.h"

namespace {

using phys::Vec3;

phys::BodyId addCube(phys::World& w, const Vec3& centre, phys::BodyModel model, double mass = 1.0) {
  phys::BodyDesc d;
  d.center = centre;
  d.size = Vec3(1.0);
  d.model = model;
  d.mass = mass;
  return w.addBody(d);
}

// An anchor is an affine combination of the box's particles: it follows the box exactly, inside
// the box or outside it, and its weights sum to 1 with nothing inverted.
TEST(Anchors, FollowTheirBoxWhereverThePointIs) {
  for (auto model : {phys::BodyModel::Corners, phys::BodyModel::Tetra}) {
    phys::World w = testing_phys::openSpace();
    phys::BodyDesc d;
    d.center = Vec3(1.0, 2.0, 3.0);
    d.size = Vec3(0.4, 1.0, 2.0);
    d.orientation = glm::dquat(glm::radians(Vec3(20.0, 40.0, -10.0)));
    d.velocity = Vec3(1.0, 4.0, -2.0);
    d.model = model;
    const phys::BodyId box = w.addBody(d);
    const Vec3 points[] = {Vec3(1.0, 2.0, 3.0), Vec3(1.1, 2.3, 3.9), Vec3(3.0, -1.0, 0.0)};
    const phys::BodyPose before = w.bodyPose(box);
    phys::Embedding anchors[3];
    Vec3 local[3];
    for (int k = 0; k < 3; ++k) {
      anchors[k] = w.anchor(box, points[k]);
      EXPECT_NEAR(glm::length(w.position(anchors[k]) - points[k]), 0.0, 1e-12);
      local[k] = glm::inverse(before.orientation) * (points[k] - before.center);
    }
    // Carried along: the same body-frame points after the box has flown for a second.
    for (int i = 0; i < 60; ++i) w.step();
    const phys::BodyPose after = w.bodyPose(box);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(glm::length(w.position(anchors[k]) - (after.center + after.orientation * local[k])), 0.0,
                  1e-6)
          << phys::toString(model) << " point " << k;
    }
  }
}

// A pin is a linear constraint: one projection brings its two points together exactly, moving
// each body in inverse proportion to its mass, whatever direction the gap has (even none). The
// pin is created 0.2 m open, which the world closes at most at maxDepenetrationSpeed
// (EnergyFromNowhere.*); with no limit, the step is the projection alone.
TEST(Links, APinClosesItsGapInOnePassByInverseMass) {
  phys::SolverSettings s = testing_phys::solver(phys::SolverMethod::GaussSeidel, 1, 1);
  s.maxDepenetrationSpeed = std::numeric_limits<double>::infinity();
  phys::World w = testing_phys::openSpace(s, Vec3(0.0));
  const phys::BodyId a = addCube(w, Vec3(0.0), phys::BodyModel::Tetra, 1.0);
  const phys::BodyId b = addCube(w, Vec3(1.2, 0.0, 0.0), phys::BodyModel::Tetra, 3.0);
  // The right face centre of a, the left face centre of b: 0.2 m apart along x.
  w.addLink(w.anchor(a, Vec3(0.5, 0.0, 0.0)), w.anchor(b, Vec3(0.7, 0.0, 0.0)));
  EXPECT_NEAR(w.metrics().maxJointError, 0.2, 1e-12);
  w.step();
  const phys::Link& pin = w.links()[0];
  EXPECT_NEAR(glm::length(w.position(pin.b) - w.position(pin.a)), 0.0, 1e-12);
  EXPECT_NEAR(w.metrics().maxJointError, 0.0, 1e-12);
  // Momentum: the light box moved three times as far as the heavy one.
  const double movedA = w.bodyPose(a).center.x - 0.0, movedB = 1.2 - w.bodyPose(b).center.x;
  EXPECT_GT(movedA, 0.0);
  EXPECT_NEAR(movedA * 1.0 - movedB * 3.0, 0.0, 1e-9);
}

// The second link is created 0.2 m past its max; as above, with no limit on how fast that closes.
TEST(Links, ARangeLinkActsOnlyOutsideItsBounds) {
  phys::SolverSettings s = testing_phys::solver(phys::SolverMethod::GaussSeidel, 1, 1);
  s.maxDepenetrationSpeed = std::numeric_limits<double>::infinity();
  phys::World w = testing_phys::openSpace(s, Vec3(0.0));
  const phys::ParticleId p = w.addParticle({Vec3(0.0), Vec3(0.0), 1.0});
  const phys::ParticleId q = w.addParticle({Vec3(1.0, 0.0, 0.0), Vec3(0.0), 1.0});
  auto at = [](phys::ParticleId id) {
    phys::Embedding e;
    e.particle[0] = id;
    e.weight[0] = 1.0;
    e.count = 1;
    return e;
  };
  w.addLink(at(p), at(q), 0.5, phys::kNoMaxLength);  // a one-sided stop: no closer than 0.5 m
  w.step();
  EXPECT_NEAR(w.particles().position[q].x, 1.0, 1e-12);  // 1 m apart: untouched
  w.addLink(at(p), at(q), 0.0, 0.8);                     // and now no farther than 0.8 m
  w.step();
  EXPECT_NEAR(w.particles().position[q].x - w.particles().position[p].x, 0.8, 1e-12);
}

TEST(Links, BadInputIsRefusedAndNothingIsAdded) {
  phys::World w = testing_phys::openSpace();
  const phys::BodyId a = addCube(w, Vec3(0.0), phys::BodyModel::Corners);
  const phys::Embedding good = w.anchor(a, Vec3(0.5, 0.0, 0.0));
  phys::Embedding badWeights = good;
  badWeights.weight[0] += 0.1;  // no longer sums to 1
  phys::Embedding badId = good;
  badId.particle[1] = phys::ParticleId{9999};
  EXPECT_THROW(w.addLink(good, badWeights), std::invalid_argument);
  EXPECT_THROW(w.addLink(good, badId), std::invalid_argument);
  EXPECT_THROW(w.addLink(good, good, 0.5, 0.2), std::invalid_argument);
  EXPECT_THROW(w.addLink(good, good, -1.0, 1.0), std::invalid_argument);
  EXPECT_THROW((void)w.anchor(phys::BodyId{7}, Vec3(0.0)), std::invalid_argument);
  EXPECT_TRUE(w.links().empty());
}

// The pass itself: a box's particles with arbitrary velocities. Fully damped, what is left is
// a rigid motion with the same momentum and angular momentum; half damped, half the rest.
TEST(BodyDamping, LeavesTheRigidMotionWithTheSameMomenta) {
  for (double fraction : {1.0, 0.5}) {
    phys::Particles p;
    phys::Body box;
    box.particleCount = 8;
    for (int k = 0; k < 8; ++k) {
      const Vec3 x = phys::boxCornerLocal(Vec3(0.5, 0.25, 1.0), k) + Vec3(3.0, 1.0, -2.0);
      const Vec3 v(std::sin(1.0 + k), std::cos(2.0 * k), 0.3 * k - 1.0);  // anything, per particle
      p.position.push_back(x);
      p.previous.push_back(x - v * 0.01);
      p.inverseMass.push_back(1.0 / (1.0 + 0.25 * k));
    }
    auto momenta = [&](Vec3& linear, Vec3& angular) {
      linear = angular = Vec3(0.0);
      for (int i = 0; i < 8; ++i) {
        const double m = 1.0 / p.inverseMass[i];
        linear += m * (p.position[i] - p.previous[i]);
        angular += m * glm::cross(p.position[i], p.position[i] - p.previous[i]);
      }
    };
    // Rate of change of the distance of each pair: zero for a rigid motion.
    auto internal = [&] {
      double worst = 0.0;
      for (int i = 0; i < 8; ++i) {
        for (int j = i + 1; j < 8; ++j) {
          const Vec3 r = p.position[j] - p.position[i];
          const Vec3 dv = (p.position[j] - p.previous[j]) - (p.position[i] - p.previous[i]);
          worst = std::max(worst, std::abs(glm::dot(r, dv)) / glm::length(r));
        }
      }
      return worst;
    };
    Vec3 linear0, angular0, linear1, angular1;
    momenta(linear0, angular0);
    const double before = internal();
    const phys::Body boxes[] = {box};
    phys::BodyLayout layout;
    layout.build(boxes);
    phys::detail::dampBodyMotion(p, boxes, layout, fraction);
    momenta(linear1, angular1);
    EXPECT_NEAR(glm::length(linear1 - linear0), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(angular1 - angular0), 0.0, 1e-12);
    EXPECT_GT(before, 1e-3);
    // Internal motion is linear in the velocities, so half damping leaves half of it.
    EXPECT_NEAR(internal(), (1.0 - fraction) * before, 1e-12);
  }
}

// In the world: one particle of a free box is displaced by 1 cm. Without body damping the
// sticks' corrections keep ringing through the box; with it the box moves rigidly at once.
TEST(BodyDamping, AKnockedBoxDoesNotRing) {
  for (double damping : {0.0, 1.0}) {
    phys::SolverSettings s = testing_phys::solver(phys::SolverMethod::GaussSeidel, 3, 1);
    s.bodyDamping = damping;
    phys::World w = testing_phys::openSpace(s, Vec3(0.0));
    phys::BodyDesc d;
    d.velocity = Vec3(1.0, 0.0, 0.0);
    d.angularVelocity = Vec3(0.0, 2.0, 0.0);
    w.addBody(d);
    w.step();
    phys::Particles& p = const_cast<phys::Particles&>(w.particles());
    p.position[0] += Vec3(0.0, 0.01, 0.0);
    p.previous[0] += Vec3(0.0, 0.01, 0.0);  // displaced, not launched
    w.step();
    w.step();
    double internal = 0.0;
    for (phys::ParticleId i{}; i < 8; ++i) {
      for (phys::ParticleId j = i + 1; j < 8; ++j) {
        const Vec3 r = w.particles().position[j] - w.particles().position[i];
        internal = std::max(internal, std::abs(glm::dot(r, w.velocity(j) - w.velocity(i))) / glm::length(r));
      }
    }
    std::printf("body damping %g: internal speed %.3g m/s after the knock\n", damping, internal);
    if (damping == 1.0) {
      EXPECT_LT(internal, 1e-9);
    } else {
      EXPECT_GT(internal, 0.01);  // still ringing at 10 cm/s
    }
  }
}

// Two spinning tetra boxes in free space with friction between them, stepped once with the rate
// `rate` (0: the reference). Returns their rigid motions over the last substep and the momenta
// of all the particles, linear and angular about the origin (per substep: times h).
struct FrictionRun {
  phys::detail::RigidMotion a, b;
  Vec3 linear{0.0}, angular{0.0};
};
FrictionRun spinPairOnce(double rate, bool pinA = false) {
  phys::World w =
      testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::GaussSeidel, 3, 2), Vec3(0.0));
  phys::BodyDesc d;
  d.model = phys::BodyModel::Tetra;
  d.size = Vec3(0.4, 1.2, 0.6);
  d.mass = 3.0;
  d.velocity = Vec3(0.5, 0.0, 0.0);
  d.angularVelocity = Vec3(0.3, 2.0, 0.0);
  const phys::BodyId a = w.addBody(d);
  d.center = Vec3(1.5, 0.2, 0.0);
  d.orientation = glm::dquat(glm::radians(Vec3(10.0, 30.0, 50.0)));
  d.mass = 1.0;
  d.velocity = Vec3(0.0, -1.0, 0.0);
  d.angularVelocity = Vec3(-1.0, 0.0, 0.5);
  const phys::BodyId b = w.addBody(d);
  // As the guard freezes a particle: inverse mass 0.
  if (pinA) const_cast<phys::Particles&>(w.particles()).inverseMass[w.bodies()[a].firstParticle] = 0.0;
  w.addJointFriction(a, b, rate);
  w.step();
  FrictionRun run;
  const phys::Particles& p = w.particles();
  phys::detail::MassProperties m;
  EXPECT_EQ(phys::detail::massProperties(p, w.bodies()[b], m), true);
  run.b = phys::detail::rigidMotion(p, w.bodies()[b], m);
  if (phys::detail::massProperties(p, w.bodies()[a], m))
    run.a = phys::detail::rigidMotion(p, w.bodies()[a], m);
  for (phys::ParticleId i{}; i < p.size(); ++i) {
    if (p.inverseMass[i] == 0.0) continue;
    const double mass = 1.0 / p.inverseMass[i];
    run.linear += mass * (p.position[i] - p.previous[i]);
    run.angular += mass * glm::cross(p.position[i], p.position[i] - p.previous[i]);
  }
  return run;
}

// Once a step the relative spin's component along itself loses the share rate dt (an angular
// impulse along it, as a rigid joint's damping: Mueller et al. 2020, section 3.6), and the bodies'
// momentum and angular momentum nothing: the same step without friction is the reference.
TEST(JointFriction, TakesItsShareOfTheRelativeSpinAndKeepsTheMomenta) {
  const FrictionRun free = spinPairOnce(0.0), damped = spinPairOnce(6.0);  // 6/s x 1/60 s: a tenth
  const Vec3 relativeFree = free.b.angular - free.a.angular;
  const Vec3 d = glm::normalize(relativeFree);
  const double along = glm::length(relativeFree);
  EXPECT_NEAR(glm::dot(damped.b.angular - damped.a.angular, d), 0.9 * along, 1e-9 * along);
  EXPECT_NEAR(glm::length(damped.linear - free.linear), 0.0, 1e-14);
  EXPECT_NEAR(glm::length(damped.angular - free.angular), 0.0, 1e-14);
  // The share is at most all of it.
  const FrictionRun stuck = spinPairOnce(1e9);
  EXPECT_NEAR(glm::dot(stuck.b.angular - stuck.a.angular, d), 0.0, 1e-9 * along);
}

// A body in several joints has its spin found once and kept up to date as each joint turns it: the
// same as finding it again from its particles for every joint (massProperties, rigidMotion).
TEST(JointFriction, ABodyInSeveralJointsIsTurnedByEachInTurn) {
  phys::World w =
      testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::GaussSeidel, 3, 1), Vec3(0.0));
  for (int k = 0; k < 3; ++k) {
    phys::BodyDesc d;
    d.model = phys::BodyModel::Tetra;
    d.center = Vec3(1.2 * k, 0.1 * k, 0.0);
    d.size = Vec3(0.3 + 0.2 * k, 1.0, 0.5);
    d.orientation = glm::dquat(glm::radians(Vec3(15.0 * k, 10.0, 5.0 * k)));
    d.angularVelocity = Vec3(std::sin(k + 1.0), 2.0 * std::cos(k * 2.0), 0.5 * k - 1.0);
    w.addBody(d);
  }
  w.step();
  const std::vector<phys::JointFriction> frictions = {{phys::BodyId(0), phys::BodyId(1), 9.0},
                                                      {phys::BodyId(1), phys::BodyId(2), 30.0},
                                                      {phys::BodyId(2), phys::BodyId(0), 12.0}};
  const double dt = 1.0 / 60.0;
  phys::Particles cached = w.particles(), reference = w.particles();
  std::vector<phys::BodySpin> spins(3);
  phys::detail::dampJointFriction(cached, w.bodies(), frictions, dt, spins);
  for (const phys::JointFriction& f : frictions) {
    phys::detail::MassProperties ma, mb;
    const phys::Body &a = w.bodies()[f.a], &b = w.bodies()[f.b];
    ASSERT_TRUE(phys::detail::massProperties(reference, a, ma) &&
                phys::detail::massProperties(reference, b, mb));
    const Vec3 relative = phys::detail::rigidMotion(reference, b, mb).angular -
                          phys::detail::rigidMotion(reference, a, ma).angular;
    const Vec3 d = glm::normalize(relative);
    const glm::dmat3 ia = glm::inverse(ma.inertia), ib = glm::inverse(mb.inertia);
    const Vec3 impulse =
        (std::min(f.rate * dt, 1.0) * glm::length(relative) / (glm::dot(d, ia * d) + glm::dot(d, ib * d))) *
        d;
    for (int k = 0; k < 4; ++k) {
      reference.previous[a.firstParticle + k] -=
          glm::cross(ia * impulse, reference.position[a.firstParticle + k] - ma.centre);
      reference.previous[b.firstParticle + k] +=
          glm::cross(ib * impulse, reference.position[b.firstParticle + k] - mb.centre);
    }
  }
  for (phys::ParticleId i{}; i < cached.size(); ++i) {
    EXPECT_NEAR(glm::length(cached.previous[i] - reference.previous[i]), 0.0, 1e-14) << i;
    EXPECT_NE(cached.previous[i], w.particles().previous[i]) << i;  // every body was turned
  }
}

// A part with a pinned or frozen particle has no rigid motion to turn: the pair is left as it would be
// without friction.
TEST(JointFriction, LeavesAPinnedPartAlone) {
  const FrictionRun free = spinPairOnce(0.0, true), damped = spinPairOnce(6.0, true);
  EXPECT_EQ(damped.b.angular, free.b.angular);
  EXPECT_EQ(damped.linear, free.linear);
}

TEST(JointFriction, RefusesBadInputAndAddsNothing) {
  phys::World w = testing_phys::openSpace();
  const phys::BodyId a = addCube(w, Vec3(0.0), phys::BodyModel::Tetra);
  const phys::BodyId b = addCube(w, Vec3(2.0, 0.0, 0.0), phys::BodyModel::Corners);
  const phys::BodyId rigid = addCube(w, Vec3(4.0, 0.0, 0.0), phys::BodyModel::Rigid);
  EXPECT_THROW(w.addJointFriction(a, a, 1.0), std::invalid_argument);
  EXPECT_THROW(w.addJointFriction(a, rigid, 1.0), std::invalid_argument);
  EXPECT_THROW(w.addJointFriction(a, phys::BodyId(7), 1.0), std::invalid_argument);
  EXPECT_THROW(w.addJointFriction(a, b, -1.0), std::invalid_argument);
  EXPECT_THROW(w.addJointFriction(a, b, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(w.addJointFriction(a, b, std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_TRUE(w.jointFrictions().empty());
  w.addJointFriction(a, b, 2.0);
  ASSERT_EQ(w.jointFrictions().size(), 1u);
  EXPECT_EQ(w.jointFrictions()[0].rate, 2.0);
}

// A ragdoll's joint-damping is friction in every joint, whatever its model; unset, only the
// rigid model's joints have it (kRagdollJointDamping).
TEST(JointFriction, ARagdollsJointDampingIsFrictionInEveryJoint) {
  for (const phys::RagdollModel model :
       {phys::RagdollModel::Seed, phys::RagdollModel::Lean, phys::RagdollModel::Rigid}) {
    for (const bool capsules : {false, true}) {
      for (const std::optional<double> damping : {std::optional<double>(), std::optional<double>(3.0)}) {
        phys::World w = testing_phys::openSpace();
        phys::RagdollDesc d;
        d.model = model;
        d.jointDamping = damping;
        const int joints = capsules ? static_cast<int>(phys::addCapsuleRagdoll(w, d).parts.size()) - 1
                                    : (phys::addRagdoll(w, d), phys::kRagdollHinges);
        const double expected =
            damping.value_or(model == phys::RagdollModel::Rigid ? phys::kRagdollJointDamping : 0.0);
        if (model == phys::RagdollModel::Rigid) {
          ASSERT_EQ(w.rigidJoints().size(), static_cast<std::size_t>(joints));
          for (const phys::RigidJoint& j : w.rigidJoints()) EXPECT_EQ(j.damping, expected);
          EXPECT_TRUE(w.jointFrictions().empty());
          continue;
        }
        ASSERT_EQ(w.jointFrictions().size(), damping ? static_cast<std::size_t>(joints) : 0u);
        for (const phys::JointFriction& f : w.jointFrictions()) EXPECT_EQ(f.rate, expected);
      }
    }
  }
}

}  // namespace
