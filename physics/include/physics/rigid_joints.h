#pragma once
// Joints between two rigid bodies as the 2020 XPBD paper builds them (Müller et al. 2020, 3.3 and
// 3.4): a hinge is one pin at its pivot, its two axes held aligned, and its angle held within two
// stops; a cone is a pin, the child's limb axis held within a cone about the parent's, and its twist
// about that axis bounded. A particle body's joints are made of pins and range links (constraints.h);
// a rigid one's are these, since a pair of pins on a thin part asks the solver to turn it about its
// long axis to close either pin, and at two iterations the two corrections overshoot each other every
// substep (docs/physics.md, "Rigid bodies").
#include <cstdint>
#include <span>

#include "physics/drives.h"
#include "physics/rigid_bodies.h"
#include "physics/rigid_contacts.h"

namespace phys {

enum class JointKind : std::uint8_t { Hinge, Cone };

/// A joint as it is made: both bodies' frames given by world vectors now (the same for both when
/// the joint is at rest: World::addJoint takes B's from A's when B's are not set).
struct JointDesc {
  JointKind kind = JointKind::Hinge;
  BodyId a = kNoBody;  ///< the parent; rigid
  BodyId b = kNoBody;  ///< the child; rigid
  Vec3 pivot{0.0};     ///< unit: m; world point held in both bodies
  /// unit vector: a hinge's axis, or the limb's direction for a cone (the cone's centre line)
  Vec3 axis{1.0, 0.0, 0.0};
  /// unit vector normal to axis: where the hinge's angle (and the cone's twist) is 0
  Vec3 reference{0.0, -1.0, 0.0};
  /// The child's axis and reference when they differ from the parent's (a joint saved away from
  /// its rest); zero vectors take the parent's.
  Vec3 axisB{0.0}, referenceB{0.0};
  Vec3 pivotB{0.0};  ///< unit: m; the child's pivot when pivotBSet, else pivot
  bool pivotBSet = false;
  Real minAngle = 0.0;  ///< unit: rad; hinge: lower stop of the child's turn about axis
  Real maxAngle = 0.0;  ///< unit: rad; hinge: upper stop
  Real swing = 0.0;     ///< unit: rad; cone: half-angle, in (0, pi)
  Real twist = 0.0;     ///< unit: rad; cone: |twist about the limb| at most this, >= 0
  Real damping = 0.0;   ///< unit: 1/s; joint friction: the relative spin decays as exp(-damping t)
};

/// What World::addJoint refuses in one body's axis and reference: an axis of zero or infinite length
/// (Axis), or a reference whose part across the axis is at most 1e-9 long or not finite
/// (Reference). One rule, so that a reader that names the attribute refuses exactly what the world does.
enum class JointFrameProblem : std::uint8_t { None, Axis, Reference };
JointFrameProblem jointFrameProblem(const Vec3& axis, const Vec3& reference);

/// A joint as the solver holds it: everything in the two bodies' frames.
struct RigidJoint {
  JointKind kind = JointKind::Hinge;
  RigidId a{}, b{};
  Vec3 pivotA{0.0}, pivotB{0.0};          ///< unit: m; from each body's centre, its frame
  Vec3 axisA{0.0}, axisB{0.0};            ///< unit; each body's frame
  Vec3 referenceA{0.0}, referenceB{0.0};  ///< unit; each body's frame
  Real minAngle = 0.0, maxAngle = 0.0;    ///< unit: rad; hinge
  Real swing = 0.0, twist = 0.0;          ///< unit: rad; cone
  Real damping = 0.0;                     ///< unit: 1/s
};

namespace detail {
/// The hinge's angle (rad, in (-pi, pi]) of B's reference from A's about A's axis; the cone's
/// twist about the mean of the two limb axes.
Real jointAngle(const RigidBodies& r, const RigidJoint& j);
/// One pass over the joints: for each, the angular constraints (alignment and limits) by angular
/// impulses, then the pin by a positional one.
void solveRigidJoints(const RigidPassInput& in, std::span<const RigidJoint> joints);
/// One pass over the joints' drives (drives.h), drives[k] and lambda[k] joint k's; the first
/// pass of a substep zeroes the multipliers.
void driveRigidJoints(const RigidPassInput& in, std::span<const RigidJoint> joints,
                      std::span<const JointDrive> drives, std::span<Real> lambda, bool firstPass);
/// One pass over the bodies' drives (drives.h), lambda holding two multipliers a drive (its centre's
/// and its turn's); the first pass of a substep zeroes them.
void driveRigidBodies(const RigidPassInput& in, std::span<const DrivenBody> bodies, std::span<Real> lambda,
                      bool firstPass);
/// After the velocities are derived: each joint with damping mu takes the share min(mu h, 1) of its
/// bodies' relative spin away, by an angular impulse that keeps their angular momentum.
void dampRigidJoints(const RigidPassInput& in, std::span<const RigidJoint> joints);
}  // namespace detail

}  // namespace phys
