// Drives (physics/drives.h): compliant constraints solved by XPBD with a multiplier kept over the
// substep's passes (Macklin et al. 2016, eqs. 17-18, in the angular form of Müller et al. 2020,
// 3.3.2). A joint's drive is an angular constraint between its two bodies; a body's drive a
// positional constraint on its centre and an angular one on its orientation, against the world.
#include "physics/drives.h"

#include <algorithm>
#include <limits>

#include <glm/geometric.hpp>

#include "physics/rigid_joints.h"
#include "rigid_motion.h"

namespace phys {

Real driveCompliance(Real strength, Real stiffness) {
  if (strength <= 0.0) return std::numeric_limits<Real>::infinity();
  return (1.0 - strength) / (strength * stiffness);
}

namespace detail {
namespace {

// One XPBD update of a constraint whose error is `error` (> 0) with generalised inverse mass w and
// compliance alpha over a substep of h squared hh: the multiplier's change, which the caller applies
// along the error's direction. Converged, the error left is alpha lambda / h^2: the force (or torque)
// lambda / h^2 a spring of stiffness 1 / alpha answers that error with.
Real complianceStep(Real error, Real w, Real alpha, Real hh, Real& lambda) {
  const Real a = alpha / hh;
  const Real delta = (error - a * lambda) / (w + a);
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
    if (drive.strength <= 0.0) continue;
    const RigidJoint& j = joints[k];
    Real angle = 0.0;
    Vec3 n(0.0);
    if (!turnTowards(r.orientation[j.b], r.orientation[j.a] * drive.target, angle, n)) continue;
    const Real w = glm::dot(n, inverseInertiaTimes(r, j.a, n)) + glm::dot(n, inverseInertiaTimes(r, j.b, n));
    if (w <= 0.0) continue;  // both frozen
    const Real delta =
        complianceStep(angle, w, driveCompliance(drive.strength, drive.stiffness), hh, lambda[k]);
    applyAngularImpulse(r, j.b, delta * n);
    applyAngularImpulse(r, j.a, -delta * n);
  }
}

// Two constraints a body: its centre's distance from the target point, along the gap, and the angle
// of the turn to the target orientation. The world is the other side, of infinite mass.
void driveRigidBodies(const RigidPassInput& in, std::span<const DrivenBody> bodies, std::span<Real> lambda,
                      bool firstPass) {
  RigidBodies& r = in.rigid;
  if (firstPass) std::fill(lambda.begin(), lambda.end(), 0.0);
  const Real hh = in.h * in.h;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const BodyDrive& drive = bodies[k].drive;
    const RigidId i = bodies[k].rigid;
    if (drive.strength <= 0.0 || r.inverseMass[i] == 0.0) continue;  // none, or frozen
    const Vec3 gap = drive.position - r.position[i];
    const Real distance = glm::length(gap);
    if (distance > 0.0 && drive.stiffness > 0.0) {  // stiffness 0: it only turns the body
      const Real w = r.inverseMass[i];
      const Real delta =
          complianceStep(distance, w, driveCompliance(drive.strength, drive.stiffness), hh, lambda[2 * k]);
      applyPositionalImpulse(r, i, Vec3(0.0), (delta / distance) * gap);
    }
    Real angle = 0.0;
    Vec3 n(0.0);
    if (!turnTowards(r.orientation[i], drive.orientation, angle, n)) continue;
    const Real w = glm::dot(n, inverseInertiaTimes(r, i, n));
    const Real delta = complianceStep(angle, w, driveCompliance(drive.strength, drive.angularStiffness), hh,
                                      lambda[2 * k + 1]);
    applyAngularImpulse(r, i, delta * n);
  }
}

}  // namespace detail
}  // namespace phys
