#pragma once
// A joint's drive: a compliant angular constraint that pulls the child of a rigid joint towards a
// target orientation relative to its parent, what an animation's pose asks of each joint
// (docs/physics.md, "Joint drives"). It is XPBD's compliance (Macklin et al. 2016; the angular form
// of Müller et al. 2020, 3.3.2), so a drive's stiffness is a torque per radian that does not change
// with the iterations, the substeps or the step.
#include "physics/types.h"

namespace phys {

/// A drive's stiffness at strength 1/2 unless it is given one: a joint held this hard turns 0.1 rad
/// under 100 N m, about the torque a 70 kg body leaning 8 degrees puts on its legs.
inline constexpr Real kDriveStiffness = 1000.0;  ///< unit: N m / rad

/// What pulls a rigid joint's child (JointDesc::b) towards a turn relative to its parent (a).
struct JointDrive {
  /// The child's orientation in the parent's frame that the drive pulls towards: the child is where
  /// it should be when q_b = q_a target. A joint is made with this set to its rest (the two bodies'
  /// orientations as addJoint found them, taken through the joint's frames), so that a drive given
  /// a strength and nothing else holds the pose the joint was made in.
  Quat target{1.0, 0.0, 0.0, 0.0};
  /// unitless, 0 to 1: 0 is limp (no drive), 1 holds the target as rigidly as the joint's own axes,
  /// and between them the stiffness is stiffness s / (1 - s): a linear map could not reach 1, whose
  /// compliance is 0.
  Real strength = 0.0;
  Real stiffness = kDriveStiffness;  ///< unit: N m / rad; at strength 1/2; finite, > 0
};

/// The drive's compliance, (1 - s) / (s stiffness) (unit: rad / (N m)): 0 at strength 1, infinite
/// (no pull) at strength 0.
Real driveCompliance(const JointDrive& drive);

}  // namespace phys
