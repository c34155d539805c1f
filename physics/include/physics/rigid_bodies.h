#pragma once
// The rigid body model's store: one pose and one pair of velocities per body, where the particle
// models carry 4 or 8 particles. Solved by XPBD with substeps (Müller, Macklin, Chentanez, Jeschke,
// Kim 2020; docs/physics.md, "Rigid bodies"): integrate, correct poses by positional impulses, take
// the velocities from the change of pose, then a velocity pass for friction and restitution.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>

#include "physics/types.h"

namespace phys {

/// Index of a rigid body in the world's RigidBodies.
using RigidId = Id<struct RigidTag>;

/// Every rigid body's state as a structure of arrays, in RigidId order.
struct RigidBodies {
  std::vector<Vec3> position;             ///< unit: m; centre of mass now
  std::vector<Quat> orientation;          ///< unit quaternion, body to world, now
  std::vector<Vec3> previousPosition;     ///< unit: m; at the start of the substep
  std::vector<Quat> previousOrientation;  ///< at the start of the substep
  std::vector<Vec3> velocity;             ///< unit: m/s; of the centre, at the end of the last substep
  std::vector<Vec3> angularVelocity;      ///< unit: rad/s; world frame, at the end of the last substep
  std::vector<Real> inverseMass;          ///< unit: 1/kg; 0 when frozen by the guard
  /// unit: 1/(kg m^2); the principal moments' inverses, body frame (a box's and a capsule's axes
  /// are principal); 0 when frozen.
  std::vector<Vec3> inverseInertia;
  /// unit: 1/(kg m^2); I^-1 in world axes at the substep's start (integration sets it): what the
  /// contacts' corrections use, the body's turn within a substep being a small fraction of a radian.
  std::vector<glm::dmat3> inverseInertiaWorld;
  std::vector<BodyId> body;  ///< the Body it is
  /// 1 when a joint or a link holds it: its contacts are never solved by shock propagation, whose
  /// holding one body still fights the joint (docs/physics.md, "Rigid bodies").
  std::vector<std::uint8_t> jointed;

  std::size_t size() const { return position.size(); }
};

/// Principal moments of inertia (kg m^2) of a solid box of the given half extents and mass.
Vec3 solidBoxInertia(const Vec3& halfExtents, Real mass);
/// Principal moments of inertia (kg m^2) of a solid capsule along y, of radius r and core half
/// length `halfSegment` (cylinder plus two hemispheres of uniform density), of the given mass.
Vec3 solidCapsuleInertia(Real radius, Real halfSegment, Real mass);
/// The principal moments raised to at least `floor` (0 to 1) times the largest (BodyDesc::inertiaFloor).
Vec3 flooredInertia(const Vec3& inertia, Real floor);

}  // namespace phys
