// Hinges and cones between rigid bodies (physics/rigid_joints.h): XPBD's angular and positional
// corrections with zero compliance (Müller et al. 2020, eqs. 2-5 and 11-14).
#include "physics/rigid_joints.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "rigid_motion.h"

namespace phys::detail {
namespace {

// Turns B by `angle` (rad) about the unit n relative to A: an angular impulse shared by the two
// bodies' inverse inertias about n, B turning by +, A by -.
void turnApart(RigidBodies& r, RigidId a, RigidId b, const Vec3& n, Real angle) {
  const Real w = glm::dot(n, inverseInertiaTimes(r, a, n)) + glm::dot(n, inverseInertiaTimes(r, b, n));
  if (w <= 0.0 || angle == 0.0) return;
  const Vec3 L = (angle / w) * n;
  applyAngularImpulse(r, b, L);
  applyAngularImpulse(r, a, -L);
}

// The angle (rad) of `to` from `from` about the unit n, both taken in the plane normal to n.
Real angleAbout(const Vec3& n, Vec3 from, Vec3 to) {
  from -= glm::dot(from, n) * n;
  to -= glm::dot(to, n) * n;
  return std::atan2(glm::dot(n, glm::cross(from, to)), glm::dot(from, to));
}

// Turns B so that its direction `db` comes to within `limit` (rad) of A's `da`: the whole angle
// between them for limit 0 (a hinge's axes), the excess over the cone's half-angle otherwise.
void bringWithin(RigidBodies& r, const RigidJoint& j, const Vec3& da, const Vec3& db, Real limit) {
  const Vec3 c = glm::cross(db, da);
  const Real sine = glm::length(c);
  const Real angle = std::atan2(sine, glm::dot(da, db));
  if (angle <= limit || sine == 0.0) return;  // at 180 degrees apart no axis is better than another
  turnApart(r, j.a, j.b, c / sine, angle - limit);
}

// Keeps the angle of B's reference from A's about n within [lo, hi].
void limitAbout(RigidBodies& r, const RigidJoint& j, const Vec3& n, Real lo, Real hi) {
  const Vec3 fromA = r.orientation[j.a] * j.referenceA, fromB = r.orientation[j.b] * j.referenceB;
  const Real angle = angleAbout(n, fromA, fromB);
  if (angle < lo) turnApart(r, j.a, j.b, n, lo - angle);
  if (angle > hi) turnApart(r, j.a, j.b, n, hi - angle);
}

// The pin: the two pivots brought together by a positional impulse along the gap, each body turned
// about the lever its pivot had as the substep started (pinLever; docs/physics.md, "Joints"). The
// two impulses, equal and opposite, then act at the same point, the pivot where the substep started,
// so the pair's angular momentum is kept; turned about the levers now, they act at two points a
// substep's motion apart, and a pair spinning as one at 1 turn/s lost a third of it in 10 s at 2 x 8.
void pin(RigidBodies& r, const RigidJoint& j) {
  const Vec3 atA = r.orientation[j.a] * j.pivotA, atB = r.orientation[j.b] * j.pivotB;
  const Vec3 d = (r.position[j.b] + atB) - (r.position[j.a] + atA);
  const Real length = glm::length(d);
  if (length == 0.0) return;
  const Vec3 n = d / length;
  const Vec3 leverA = pinLever(r, j.a, atA, r.previousOrientation[j.a] * j.pivotA, n);
  const Vec3 leverB = pinLever(r, j.b, atB, r.previousOrientation[j.b] * j.pivotB, n);
  const Real w = leveredInverseMass(r, j.a, atA, leverA, n) + leveredInverseMass(r, j.b, atB, leverB, n);
  if (w <= 0.0) return;
  const Vec3 p = (length / w) * n;
  applyPositionalImpulse(r, j.a, leverA, p);
  applyPositionalImpulse(r, j.b, leverB, -p);
}

}  // namespace

Real jointAngle(const RigidBodies& r, const RigidJoint& j) {
  const Vec3 axisA = r.orientation[j.a] * j.axisA, axisB = r.orientation[j.b] * j.axisB;
  const Vec3 fromA = r.orientation[j.a] * j.referenceA, fromB = r.orientation[j.b] * j.referenceB;
  if (j.kind == JointKind::Hinge) return angleAbout(axisA, fromA, fromB);
  const Vec3 mean = axisA + axisB;
  const Real length = glm::length(mean);
  return length > 0.0 ? angleAbout(mean / length, fromA, fromB) : 0.0;
}

// Angles first, then the pin, so that each pass ends with the pivots together: a turn about a
// point other than the pivot moves it. A hinge's axes aligned, then its stops about A's axis; a
// cone's swing, then its twist about the mean of the two limb axes (Müller et al. 2020, 3.4.2), a
// twist that does not depend on which way the limb swung.
void solveRigidJoints(const RigidPassInput& in, std::span<const RigidJoint> joints) {
  RigidBodies& r = in.rigid;
  for (const RigidJoint& j : joints) {
    const Vec3 axisA = r.orientation[j.a] * j.axisA, axisB = r.orientation[j.b] * j.axisB;
    if (j.kind == JointKind::Hinge) {
      bringWithin(r, j, axisA, axisB, 0.0);
      limitAbout(r, j, r.orientation[j.a] * j.axisA, j.minAngle, j.maxAngle);
    } else {
      bringWithin(r, j, axisA, axisB, j.swing);
      const Vec3 mean = r.orientation[j.a] * j.axisA + r.orientation[j.b] * j.axisB;
      const Real length = glm::length(mean);
      if (length > 0.0) limitAbout(r, j, mean / length, -j.twist, j.twist);
    }
    pin(r, j);
  }
}

// The 2020 paper's joint damping (3.6) on spin alone: the pin holds the pivots together, so what a
// joint's friction resists is the parts turning against each other.
void dampRigidJoints(const RigidPassInput& in, std::span<const RigidJoint> joints) {
  for (const RigidJoint& j : joints) {
    if (j.damping > 0.0) dampRelativeSpin(in.rigid, j.a, j.b, std::min(j.damping * in.h, 1.0));
  }
}

}  // namespace phys::detail
