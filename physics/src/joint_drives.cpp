// Joint drives (physics/joint_drive.h): each a compliant angular constraint between a rigid joint's
// two bodies, solved by XPBD with a multiplier kept over the substep's passes (Macklin et al. 2016,
// eqs. 17-18, in the angular form of Müller et al. 2020, 3.3.2).
#include <algorithm>
#include <limits>

#include <glm/geometric.hpp>

#include "physics/joint_drive.h"
#include "physics/rigid_joints.h"
#include "rigid_motion.h"

namespace phys {

Real driveCompliance(const JointDrive& drive) {
  if (drive.strength <= 0.0) return std::numeric_limits<Real>::infinity();
  return (1.0 - drive.strength) / (drive.strength * drive.stiffness);
}

namespace detail {

// The constraint is the angle of the turn that takes the child to its target, about that turn's own
// axis n: a rotation vector's length, as the 2020 paper writes every angular constraint. With
// compliance a, its passes settle where the angle left is a lambda / h^2, which is the torque
// lambda / h^2 a spring of stiffness 1 / a answers that angle with.
void driveRigidJoints(const RigidPassInput& in, std::span<const RigidJoint> joints,
                      std::span<const JointDrive> drives, std::span<Real> lambda, bool firstPass) {
  RigidBodies& r = in.rigid;
  if (firstPass) std::fill(lambda.begin(), lambda.end(), 0.0);
  const Real hh = in.h * in.h;
  for (std::size_t k = 0; k < joints.size(); ++k) {
    const JointDrive& drive = drives[k];
    if (drive.strength <= 0.0) continue;
    const RigidJoint& j = joints[k];
    const Vec3 turn = turnBetween(r.orientation[j.b], r.orientation[j.a] * drive.target);
    const Real angle = glm::length(turn);
    if (angle == 0.0) continue;
    const Vec3 n = turn / angle;
    const Real w = glm::dot(n, inverseInertiaTimes(r, j.a, n)) + glm::dot(n, inverseInertiaTimes(r, j.b, n));
    if (w <= 0.0) continue;  // both frozen
    const Real alpha = driveCompliance(drive) / hh;
    const Real delta = (angle - alpha * lambda[k]) / (w + alpha);
    lambda[k] += delta;
    applyAngularImpulse(r, j.b, delta * n);
    applyAngularImpulse(r, j.a, -delta * n);
  }
}

}  // namespace detail
}  // namespace phys
