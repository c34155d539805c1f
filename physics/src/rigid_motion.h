#pragma once
// The rigid body model's motion (rigid_motion.cpp): integration of a substep, the velocities
// derived from the change of pose, and the pose corrections every rigid constraint applies.
#include <optional>
#include <span>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "physics/rigid_bodies.h"
#include "physics/settings.h"

namespace phys::detail {

/// [v]x, the matrix of the cross product: [v]x a = v x a.
glm::dmat3 crossMatrix(const Vec3& v);
/// Acceleration of gravity at x (m/s^2) in the world's mode: the vector, or the fixed-strength
/// pull towards gravityPoint (none at the point itself).
Vec3 gravityAt(const WorldSettings& world, const Vec3& x);
/// R diag(d) R^T: principal inverse moments d (body frame) in world axes for orientation q.
glm::dmat3 worldInverseInertia(const Quat& q, const Vec3& principalInverse);
/// q turned by the rotation vector `angle` (rad, world frame): exp(angle / 2) q, exactly, so a
/// turn of any size keeps q a unit quaternion.
Quat turned(const Quat& q, const Vec3& angle);
/// The rotation vector (rad, world frame) that turns `from` into `to` the short way: the exact
/// inverse of turned(), so a body's angular velocity comes back from its change of pose unchanged.
Vec3 turnBetween(const Quat& from, const Quat& to);

/// dw/dt of a free body (rad/s^2, world frame) spinning at w (world frame) with orientation q and
/// principal inverse moments d: Euler's equations, I w' = (I w) x w in the body frame. What shifts
/// a given spin to the substep's middle, as gravity shifts a velocity.
Vec3 freeSpinRate(const Quat& q, const Vec3& principalInverse, const Vec3& w);

/// The fastest turn per substep (rad) whose spin is kept half a substep back. Beyond it a substep
/// does not resolve the spin, the shift's w' h / 2 is no small correction, and the shift's inverse
/// (spinBeforeShift) has no root near the spin to converge to: the spin is kept as it is.
inline constexpr Real kMostShiftedTurn = 1.0;
/// The spin w(0) kept half a substep back: w(0) - w'(w(0)) h / 2, or w(0) itself beyond
/// kMostShiftedTurn (what addBody keeps).
Vec3 spinShiftedBack(const Quat& q, const Vec3& principalInverse, const Vec3& w, Real h);
/// Its inverse: the spin w(0) that spinShiftedBack turns into `kept`, the root of
/// w(0) = kept + w'(w(0)) h / 2 by fixed-point iteration (or `kept` itself beyond
/// kMostShiftedTurn); none where the iteration does not reach a root within kMostShiftedTurn.
std::optional<Vec3> spinBeforeShift(const Quat& q, const Vec3& principalInverse, const Vec3& kept, Real h);

/// A kept spin w(-hOld/2) moved to w(-hNew/2) for a new substep: w(0) recovered as the root of
/// w(0) = kept + w'(w(0)) hOld / 2, then shifted back by w'(w(0)) hNew / 2. Both shifts read w' at
/// the same w(0), so changing the substep and changing it back returns the spin it had; reading w'
/// at the kept spin instead would move the body's start by O(hOld^2), which no later h removes.
Vec3 shiftedSpin(const Quat& q, const Vec3& principalInverse, const Vec3& kept, Real hOld, Real hNew);

/// q turned by a correction's small angle (rad, world frame): q + [angle / 2, 0] q, normalised.
Quat nudged(const Quat& q, const Vec3& angle);
/// The start of a substep (the 2020 paper's integration): the pose is kept as the previous one
/// and as where the guard last found the body good (Guard::checkedRigidPositions),
/// gravity and the world's damping act on the velocities, the angular velocity follows Euler's
/// equations for a free body (implicit midpoint rule, which keeps both the kinetic energy and the
/// angular momentum's length: docs/physics.md, "Rigid bodies"), and the pose moves on by them.
/// Frozen bodies (inverse mass 0) do not move.
void integrateRigid(RigidBodies& r, const WorldSettings& world, Real h, std::span<Vec3> checkedPosition,
                    std::span<Quat> checkedOrientation);
/// The same for the bodies [begin, end) alone, bit for bit.
void integrateRigidRange(RigidBodies& r, const WorldSettings& world, Real h, std::span<Vec3> checkedPosition,
                         std::span<Quat> checkedOrientation, RigidId begin, RigidId end);
/// After the position passes: v = (x - x*) / h, w = turnBetween(q*, q) / h.
void deriveRigidVelocities(RigidBodies& r, Real h);

/// World-frame I^-1 v of body i (1/(kg m^2) times v), with I^-1 as the substep started.
Vec3 inverseInertiaTimes(const RigidBodies& r, RigidId i, const Vec3& v);
/// How far body i's point at r (m, from its centre, world axes) moves along the unit direction n
/// per unit of impulse along n: 1/m + (r x n)^T I^-1 (r x n) (unit: 1/kg).
Real pointInverseMass(const RigidBodies& r, RigidId i, const Vec3& at, const Vec3& n);
/// How far a pin's point must move along the gap n, turned about its start lever, against how far
/// it moves turned about its lever now, for the pin to turn the body about the start lever
/// (pinLever). Below it the body has turned far in the substep, or its lever swings through n, and
/// the start lever is a poor guide to the correction: with a share of 0.5 (or a limit of 0.3 rad on
/// the lever's turn), a chain of five boxes crushed at 8 m/s by 200 kg at 1 x 2 sank 0.58 m into
/// the ground with its joints projected, 0.06 m with 0.95 or turned about the levers as they are.
inline constexpr Real kLeastStartLeverShare = 0.95;
/// The lever a pin's impulse turns body i about (docs/physics.md, "Joints"): `start`, where the
/// pin's point was from the centre as the substep started (the body's axes then, world frame), as
/// SHAKE takes a constraint's gradient at the start of the step; or `at`, its lever now, where the
/// start lever moves the point along n less than kLeastStartLeverShare as far.
Vec3 pinLever(const RigidBodies& r, RigidId i, const Vec3& at, const Vec3& start, const Vec3& n);
/// How far body i's point at `at` moves along the unit n per unit of impulse along n that turns the
/// body about `lever`: 1/m + (at x n)^T I^-1 (lever x n) (unit: 1/kg); pointInverseMass when
/// lever = at.
Real leveredInverseMass(const RigidBodies& r, RigidId i, const Vec3& at, const Vec3& lever, const Vec3& n);
/// Applies the positional impulse p (kg m) at r (m, from the centre, world axes) to body i's pose:
/// x += p / m, q turned by I^-1 (r x p).
void applyPositionalImpulse(RigidBodies& r, RigidId i, const Vec3& at, const Vec3& p);
/// Turns body i by the angular positional impulse L (kg m^2): q turned by I^-1 L.
void applyAngularImpulse(RigidBodies& r, RigidId i, const Vec3& L);
/// Takes the share `share` (0 to 1) of bodies a and b's relative spin away by an angular impulse
/// between them, which keeps their angular momentum: the joints' damping.
void dampRelativeSpin(RigidBodies& r, RigidId a, RigidId b, Real share);
/// Applies the impulse p (N s) at r to body i's velocities: v += p / m, w += I^-1 (r x p).
void applyVelocityImpulse(RigidBodies& r, RigidId i, const Vec3& at, const Vec3& p);
/// The mouse spring on a rigid body's point `local` (its frame, m): as applyDrag (drag.cpp), an
/// implicit impulse over the substep with the point's inverse mass matrix 1/m + [r]x^T I^-1 [r]x,
/// applied to the velocities and to the pose the substep's integration has just moved.
void applyRigidDrag(RigidBodies& r, RigidId i, const Vec3& local, const Vec3& target, Real stiffness,
                    Real damping, Real h);
/// Velocity (m/s) of body i's point at r (from the centre, world axes): v + w x r.
inline Vec3 pointVelocity(const RigidBodies& r, RigidId i, const Vec3& at) {
  return r.velocity[i] + glm::cross(r.angularVelocity[i], at);
}

}  // namespace phys::detail
