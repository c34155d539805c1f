// Drives (physics/drives.h): compliant constraints solved by XPBD with a multiplier kept over the
// substep's passes (Macklin et al. 2016, eqs. 17-18, in the angular form of Müller et al. 2020,
// 3.3.2). A joint's drive is an angular constraint between its two bodies; a body's drive a
// positional constraint on its centre and an angular one on its orientation, against the world.
// A particle body takes the same corrections as a rigid body whose mass and inertia are its
// particles' (massProperties): a turn of all its particles about their centre, or a move of them
// all, so its sticks keep their lengths and the links see the body move as one.
#include "physics/drives.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include "passes.h"
#include "physics/rigid_joints.h"
#include "pose.h"
#include "rigid_motion.h"

namespace phys {

Real driveCompliance(Real strength, Real stiffness) {
  if (strength <= 0.0) return std::numeric_limits<Real>::infinity();
  return (1.0 - strength) / (strength * stiffness);
}

namespace detail {
namespace {

// A drive's compliance over the substep squared hh, XPBD's alpha~; infinite for no drive: strength
// 0, or a strength so small that (1 - s) / (s k), or that over hh, is not finite. Such a drive is
// skipped as strength 0 is: stepped, 1e-310 made inf * 0 in complianceStep, NaN, and the guard froze
// the ragdoll.
Real complianceOver(Real strength, Real stiffness, Real hh) {
  return driveCompliance(strength, stiffness) / hh;
}

// One XPBD update of a constraint whose error is `error` (> 0) with generalised inverse mass w and
// compliance over h^2 `a` (finite): the multiplier's change, which the caller applies along the
// error's direction. Converged, the error left is a lambda (alpha lambda / h^2): the force (or
// torque) lambda / h^2 a spring of stiffness 1 / alpha answers that error with.
Real complianceStep(Real error, Real w, Real a, Real& lambda) {
  const Real delta = (error - a * lambda) / (w + a);
  lambda += delta;
  return delta;
}

// complianceStep with the change held to at most `most` (> 0): a pass that may close only part of
// the error (driveParticleJoints' share).
Real complianceStep(Real error, Real w, Real a, Real& lambda, Real most) {
  const Real delta = std::min((error - a * lambda) / (w + a), most);
  lambda += delta;
  return delta;
}

// The turn (rotation vector, rad, world frame) that takes `from` to `to`, split into its angle and
// unit axis; false for none.
bool turnTowards(const Quat& from, const Quat& to, Real& angle, Vec3& axis) {
  const Vec3 turn = turnBetween(from, to);
  angle = glm::length(turn);
  if (angle == 0.0) return false;
  axis = turn / angle;
  return true;
}

// A particle body as a drive moves it: its pose and centre of mass, and the inverses of its mass and
// inertia (world axes) from its particles now. One with a particle pinned, frozen or asleep, or crushed
// flat, is held still (inverses 0), as a frozen rigid body is; its pose still counts.
struct ParticleFrame {
  BodyPose pose;
  Vec3 centre{0.0};  ///< unit: m; of mass, what it turns about
  Real inverseMass = 0.0;
  glm::dmat3 inverseInertia{0.0};
  bool movable() const { return inverseMass > 0.0; }
};

ParticleFrame frameOf(const Particles& p, const Body& body) {
  ParticleFrame f;
  f.pose = particleBodyPose(p, body);
  MassProperties m;
  if (!massProperties(p, body, m)) return f;
  f.centre = m.centre;
  f.inverseMass = 1.0 / m.mass;
  f.inverseInertia = glm::inverse(m.inertia);
  return f;
}

// Turns the body's particles by the rotation vector `by` (rad) about its centre: the exact rotation,
// not its first order, so that a large correction does not stretch the body.
void turnParticles(Particles& p, const Body& body, const ParticleFrame& f, const Vec3& by) {
  const Real angle = glm::length(by);
  if (!(angle > 0.0) || !f.movable()) return;
  const Quat q = glm::angleAxis(angle, by / angle);
  for (ParticleId i = body.firstParticle; i < body.firstParticle + body.particleCount; ++i)
    p.position[i] = f.centre + q * (p.position[i] - f.centre);
}

}  // namespace

// The constraint is the angle of the turn that takes the child to its target, about that turn's own
// axis n: a rotation vector's length, as the 2020 paper writes every angular constraint.
void driveRigidJoints(const RigidPassInput& in, std::span<const RigidJoint> joints,
                      std::span<const JointDrive> drives, std::span<Real> lambda, bool firstPass) {
  RigidBodies& r = in.rigid;
  if (firstPass) std::fill(lambda.begin(), lambda.end(), 0.0);
  const Real hh = in.h * in.h;
  for (std::size_t k = 0; k < joints.size(); ++k) {
    const JointDrive& drive = drives[k];
    const Real a = complianceOver(drive.strength, drive.stiffness, hh);
    if (!std::isfinite(a)) continue;  // no drive
    const RigidJoint& j = joints[k];
    Real angle = 0.0;
    Vec3 n(0.0);
    if (!turnTowards(r.orientation[j.b], r.orientation[j.a] * drive.target, angle, n)) continue;
    const Real w = glm::dot(n, inverseInertiaTimes(r, j.a, n)) + glm::dot(n, inverseInertiaTimes(r, j.b, n));
    if (w <= 0.0) continue;  // both frozen
    const Real delta = complianceStep(angle, w, a, lambda[k]);
    applyAngularImpulse(r, j.b, delta * n);
    applyAngularImpulse(r, j.a, -delta * n);
  }
}

// Two constraints a body: its centre's distance from the target point, along the gap, and the angle
// of the turn to the target orientation. The world is the other side, of infinite mass.
void driveRigidBodies(const RigidPassInput& in, std::span<const DrivenBody> bodies, std::span<Real> lambda,
                      bool firstPass) {
  RigidBodies& r = in.rigid;
  const Real hh = in.h * in.h;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    if (bodies[k].particles) continue;  // driveParticleBodies' own, and their multipliers
    if (firstPass) lambda[2 * k] = lambda[2 * k + 1] = 0.0;
    const BodyDrive& drive = bodies[k].drive;
    const RigidId i = bodies[k].rigid;
    if (drive.strength <= 0.0 || r.inverseMass[i] == 0.0) continue;  // none, or frozen
    const Vec3 gap = drive.position - r.position[i];
    const Real distance = glm::length(gap);
    const Real a = complianceOver(drive.strength, drive.stiffness, hh);
    if (distance > 0.0 && drive.stiffness > 0.0 && std::isfinite(a)) {  // stiffness 0: it only turns the body
      const Real w = r.inverseMass[i];
      const Real delta = complianceStep(distance, w, a, lambda[2 * k]);
      applyPositionalImpulse(r, i, Vec3(0.0), (delta / distance) * gap);
    }
    const Real angular = complianceOver(drive.strength, drive.angularStiffness, hh);
    Real angle = 0.0;
    Vec3 n(0.0);
    if (!std::isfinite(angular) || !turnTowards(r.orientation[i], drive.orientation, angle, n)) continue;
    const Real w = glm::dot(n, inverseInertiaTimes(r, i, n));
    const Real delta = complianceStep(angle, w, angular, lambda[2 * k + 1]);
    applyAngularImpulse(r, i, delta * n);
  }
}

// As driveRigidJoints, with each body's orientation read from its particles (shape matching) and its
// inertia theirs, found again for every drive, since the drive before may have turned it.
void driveParticleJoints(Particles& p, std::span<const Body> bodies, std::span<const ParticleJoint> joints,
                         std::span<const JointDrive> drives, std::span<Real> lambda,
                         std::span<const Real> share, bool firstPass, Real h) {
  if (firstPass) std::fill(lambda.begin(), lambda.end(), 0.0);
  const Real hh = h * h;
  for (std::size_t k = 0; k < joints.size(); ++k) {
    const JointDrive& drive = drives[k];
    const Real alpha = complianceOver(drive.strength, drive.stiffness, hh);
    if (!std::isfinite(alpha)) continue;  // no drive
    const Body &bodyA = bodies[joints[k].a], &bodyB = bodies[joints[k].b];
    const ParticleFrame a = frameOf(p, bodyA), b = frameOf(p, bodyB);
    Real angle = 0.0;
    Vec3 n(0.0);
    if (!turnTowards(b.pose.orientation, a.pose.orientation * drive.target, angle, n)) continue;
    const Real w = glm::dot(n, a.inverseInertia * n) + glm::dot(n, b.inverseInertia * n);
    if (w <= 0.0) continue;  // both held still
    // Held to a share of what is left of the gap (a character turning in, Character::turnIn): a drive
    // of compliance near 0 turns a part by the whole gap in a pass, and from a far pose the joints'
    // pins then drag a box's corners into a fold that the drive, stiffer than the sticks, keeps. The
    // multiplier takes only the change made, so later passes go on from it.
    const Real delta = share[k] < 1.0 ? complianceStep(angle, w, alpha, lambda[k], share[k] * angle / w)
                                      : complianceStep(angle, w, alpha, lambda[k]);
    turnParticles(p, bodyB, b, b.inverseInertia * (delta * n));
    turnParticles(p, bodyA, a, a.inverseInertia * (-delta * n));
  }
}

// As driveRigidBodies, for the drives of particle bodies: the centre moved by moving every particle,
// the turn as driveParticleJoints' with the world on the other side.
void driveParticleBodies(Particles& p, std::span<const Body> bodies, std::span<const DrivenBody> driven,
                         std::span<Real> lambda, bool firstPass, Real h) {
  const Real hh = h * h;
  for (std::size_t k = 0; k < driven.size(); ++k) {
    if (!driven[k].particles) continue;
    if (firstPass) lambda[2 * k] = lambda[2 * k + 1] = 0.0;
    const BodyDrive& drive = driven[k].drive;
    if (drive.strength <= 0.0) continue;
    const Body& body = bodies[driven[k].body];
    ParticleFrame f = frameOf(p, body);
    if (!f.movable()) continue;
    const Vec3 gap = drive.position - f.centre;
    const Real distance = glm::length(gap);
    const Real a = complianceOver(drive.strength, drive.stiffness, hh);
    if (distance > 0.0 && drive.stiffness > 0.0 && std::isfinite(a)) {
      const Real delta = complianceStep(distance, f.inverseMass, a, lambda[2 * k]);
      const Vec3 move = (delta * f.inverseMass / distance) * gap;
      for (ParticleId i = body.firstParticle; i < body.firstParticle + body.particleCount; ++i)
        p.position[i] += move;
      f.centre += move;
    }
    const Real angular = complianceOver(drive.strength, drive.angularStiffness, hh);
    Real angle = 0.0;
    Vec3 n(0.0);
    if (!std::isfinite(angular) || !turnTowards(f.pose.orientation, drive.orientation, angle, n)) continue;
    const Real w = glm::dot(n, f.inverseInertia * n);
    const Real delta = complianceStep(angle, w, angular, lambda[2 * k + 1]);
    turnParticles(p, body, f, f.inverseInertia * (delta * n));
  }
}

}  // namespace detail
}  // namespace phys
