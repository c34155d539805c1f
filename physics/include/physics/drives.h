#pragma once
// Drives: compliant pulls towards a target, what an animation asks of a ragdoll (docs/physics.md,
// "Joint drives"). A joint's drive pulls a joint's child towards a turn relative to its parent
// (a rigid joint's, or a particle joint's: two particle bodies' turns, made of their particles'
// moves); a body's drive, the "hand of god", pulls a body towards a pose in the world. All
// are XPBD's compliance (Macklin et al. 2016; the angular form of Müller et al. 2020, 3.3.2), so a
// drive's stiffness is a force or torque per unit of error that does not change with the
// iterations, the substeps or the step.
#include "physics/rigid_bodies.h"
#include "physics/types.h"

namespace phys {

/// A joint drive's stiffness at strength 1/2 unless it is given one: a joint held this hard turns
/// 0.1 rad under 100 N m, about the torque a 70 kg body leaning 8 degrees puts on its legs.
inline constexpr Real kDriveStiffness = 1000.0;  ///< unit: N m / rad
/// A body drive's stiffness at strength 1/2 unless it is given one: a 70 kg body hangs 6.9 cm below
/// its target.
inline constexpr Real kBodyDriveStiffness = 10000.0;  ///< unit: N / m

/// The compliance of a drive of strength s (0 to 1) and stiffness k at strength 1/2: (1 - s) / (s k),
/// 0 at strength 1 and infinite (no pull) at 0. At strength s the stiffness is k s / (1 - s): a
/// linear map could not reach 1, whose compliance is 0. Unit: the inverse of k's.
Real driveCompliance(Real strength, Real stiffness);

/// What pulls a rigid joint's child (JointDesc::b) towards a turn relative to its parent (a).
struct JointDrive {
  /// The child's orientation in the parent's frame that the drive pulls towards: the child is where
  /// it should be when q_b = q_a target. A joint is made with this set to its rest (the two bodies'
  /// orientations as addJoint found them, taken through the joint's frames), so that a drive given
  /// a strength and nothing else holds the pose the joint was made in.
  Quat target{1.0, 0.0, 0.0, 0.0};
  /// unitless, 0 to 1: 0 is limp (no drive), 1 holds the target as rigidly as the joint's own axes
  /// (driveCompliance).
  Real strength = 0.0;
  Real stiffness = kDriveStiffness;  ///< unit: N m / rad; at strength 1/2; finite, > 0
};

/// What pulls a rigid body's centre towards a point and its orientation towards a target, against
/// the world: the hand of god that can carry a ragdoll by its root, or hold it up while it learns
/// to stand.
struct BodyDrive {
  Vec3 position{0.0};                    ///< unit: m; where the body's centre is pulled
  Quat orientation{1.0, 0.0, 0.0, 0.0};  ///< the orientation it is turned towards
  Real strength = 0.0;                   ///< unitless, 0 to 1, as JointDrive::strength
  /// unit: N / m; of the centre, at strength 1/2; 0 leaves the centre free (a drive that only
  /// turns the body, as a character's balance)
  Real stiffness = kBodyDriveStiffness;
  Real angularStiffness = kDriveStiffness;  ///< unit: N m / rad; at strength 1/2
};

/// What a drive needs of a joint between two particle bodies (World::addParticleJoint), which their
/// links hold together: the turn the joint was made at, and where its pivot is in each body. The
/// drive turns each body about its centre as a rigid body of its particles' inertia.
struct ParticleJoint {
  BodyId a{}, b{};   ///< the parent and the child; both particle bodies
  Vec3 pivotA{0.0};  ///< unit: m; the pivot in a's frame (BodyPose's)
  Vec3 pivotB{0.0};  ///< unit: m; in b's frame
  /// b's orientation in a's frame when the joint was made: conj(q_a) q_b. Its drive is made with
  /// this as its target, as a rigid joint's is with its rest.
  Quat rest{1.0, 0.0, 0.0, 0.0};
};

/// What a body drive exerted in a substep (World::bodyDriveLoad).
struct DriveLoad {
  Real force = 0.0;   ///< unit: N; on the body's centre
  Real torque = 0.0;  ///< unit: N m
};

/// A body drive as the solver holds it: the body it pulls, rigid or of particles.
struct DrivenBody {
  BodyId body{};
  RigidId rigid{};         ///< a rigid body's pose and velocities; unused for a particle body
  bool particles = false;  ///< a particle body: its particles are moved, as a rigid body of their inertia
  BodyDrive drive;
};

}  // namespace phys
