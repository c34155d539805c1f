// The world's joints with a rigid body at one end or both: links between body points and the
// hinges and cones of rigid ragdolls (physics/rigid_links.h, physics/rigid_joints.h).
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "physics/world.h"
#include "require.h"

namespace phys {

using detail::require;
using detail::requireIndex;
namespace {

// The joint's frame (axis, reference, their cross product) as a turn from the body's frame.
Quat jointFrame(const Vec3& axis, const Vec3& reference) {
  return glm::quat_cast(glm::dmat3(axis, reference, glm::cross(axis, reference)));
}

// The child's orientation in the parent's frame when the joint is at rest, its two frames one:
// q_a F_A = q_b F_B, so q_b = q_a F_A F_B^-1.
Quat restTarget(const RigidJoint& j) {
  return glm::normalize(jointFrame(j.axisA, j.referenceA) *
                        glm::conjugate(jointFrame(j.axisB, j.referenceB)));
}

// q made unit, or std::invalid_argument naming `what` when it is not unit within 1e-6.
Quat unitQuaternion(const Quat& q, const std::string& what) {
  const Real length = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  require(std::isfinite(length) && std::abs(length - 1.0) <= 1e-6, what + " must be a unit quaternion");
  return q / length;
}

// "x y z", for a message.
std::string vectorText(const Vec3& v) {
  return detail::numberText(v.x) + " " + detail::numberText(v.y) + " " + detail::numberText(v.z);
}

}  // namespace

void World::addLink(const BodyPoint& a, const BodyPoint& b, Real minLength, Real maxLength) {
  if (a.side == ContactSide::Particles && b.side == ContactSide::Particles) {
    addLink(a.point, b.point, minLength, maxLength);
    return;
  }
  for (const BodyPoint* end : {&a, &b}) {
    if (end->side == ContactSide::Particles) {
      checkEmbedding(end->point, "addLink");
      continue;
    }
    require(end->side == ContactSide::Rigid, "addLink: an end is on a body or on particles, not the ground");
    requireIndex(end->rigid, rigidBodies_.size(), "addLink", "rigid body");
    require(finite(end->local), "addLink: a rigid body's point must be finite");
  }
  require(std::isfinite(minLength) && minLength >= 0.0, "addLink: min length must be finite and >= 0 (m)");
  require(!std::isnan(maxLength) && maxLength >= minLength, "addLink: max length must be >= min length (m)");
  constraints_.addRigidLink({a, b, minLength, maxLength});
  for (const BodyPoint* end : {&a, &b}) {
    if (end->side == ContactSide::Rigid) rigidBodies_.jointed[end->rigid] = 1;
  }
  // The parting moves the two bodies as one, as it does those of a link between particles.
  auto bodyOf = [this](const BodyPoint& end) {
    return end.side == ContactSide::Rigid ? rigidBodies_.body[end.rigid]
                                          : particleBody_[end.point.particle[0]];
  };
  const BodyId bodyA = bodyOf(a), bodyB = bodyOf(b);
  if (bodyA != kNoBody && bodyB != kNoBody && bodyA != bodyB) parting_.join(bodyA, bodyB);
  auto nodeOf = [this](const BodyPoint& end) {
    return end.side == ContactSide::Rigid ? islands_.nodeOf(rigidBodies_.body[end.rigid])
                                          : islands_.nodeOf(end.point.particle[0]);
  };
  islands_.join(nodeOf(a), nodeOf(b));
}

JointFrameProblem jointFrameProblem(const Vec3& axis, const Vec3& reference) {
  // A length that overflows (a component near 1e200) would normalise the vector to 0.
  const Real axisLength = glm::length(axis);
  if (!(axisLength > 0.0 && std::isfinite(axisLength))) return JointFrameProblem::Axis;
  const Vec3 unit = glm::normalize(axis);
  const Real across = glm::length(reference - glm::dot(reference, unit) * unit);
  if (!(across > 1e-9 && std::isfinite(across))) return JointFrameProblem::Reference;
  return JointFrameProblem::None;
}

void World::addJoint(const JointDesc& d) {
  requireIndex(d.a, bodies_.size(), "addJoint", "body");
  requireIndex(d.b, bodies_.size(), "addJoint", "body");
  auto rigid = [this](BodyId id) { return bodies_[id].model == BodyModel::Rigid; };
  require(rigid(d.a) && rigid(d.b) && d.a != d.b, "addJoint: a and b must be two different rigid bodies");
  require(d.kind == JointKind::Hinge || d.kind == JointKind::Cone,
          "addJoint: kind must be Hinge or Cone (is " + std::to_string(static_cast<int>(d.kind)) + ")");
  require(finite(d.pivot) && finite(d.pivotB) && finite(d.axis) && finite(d.reference) && finite(d.axisB) &&
              finite(d.referenceB),
          "addJoint: the pivot, axes and references must be finite");
  // Each body's axis made unit and its reference made normal to it, in the body's own frame.
  auto frame = [this](BodyId id, Vec3 axis, Vec3 reference, Vec3& axisOut, Vec3& referenceOut) {
    const JointFrameProblem problem = jointFrameProblem(axis, reference);
    require(problem != JointFrameProblem::Axis,
            "addJoint: the axis must be non-zero and of finite length (is " + vectorText(axis) + ")");
    require(problem != JointFrameProblem::Reference,
            "addJoint: the reference must not lie along the axis, and be of finite length (is " +
                vectorText(reference) + ")");
    axis = glm::normalize(axis);
    reference -= glm::dot(reference, axis) * axis;
    const Quat toBody = glm::conjugate(rigidBodies_.orientation[bodies_[id].rigid]);
    axisOut = toBody * axis;
    referenceOut = toBody * glm::normalize(reference);
  };
  const Real pi = std::numbers::pi;
  if (d.kind == JointKind::Hinge) {
    require(d.minAngle >= -pi && d.minAngle <= d.maxAngle && d.maxAngle <= pi,
            "addJoint: a hinge's stops must be within [-pi, pi] and min <= max (rad)");
  } else {
    require(d.swing > 0.0 && d.swing < pi, "addJoint: a cone's swing must be in (0, pi) (rad)");
    require(d.twist >= 0.0 && d.twist <= pi, "addJoint: a cone's twist must be in [0, pi] (rad)");
  }
  require(std::isfinite(d.damping) && d.damping >= 0.0, "addJoint: damping must be finite and >= 0 (1/s)");
  RigidJoint j;
  j.kind = d.kind;
  j.a = bodies_[d.a].rigid;
  j.b = bodies_[d.b].rigid;
  frame(d.a, d.axis, d.reference, j.axisA, j.referenceA);
  const bool ownB = glm::length(d.axisB) > 0.0 || glm::length(d.referenceB) > 0.0;
  frame(d.b, ownB ? d.axisB : d.axis, ownB ? d.referenceB : d.reference, j.axisB, j.referenceB);
  const RigidBodies& r = rigidBodies_;
  j.pivotA = glm::conjugate(r.orientation[j.a]) * (d.pivot - r.position[j.a]);
  j.pivotB = glm::conjugate(r.orientation[j.b]) * ((d.pivotBSet ? d.pivotB : d.pivot) - r.position[j.b]);
  j.minAngle = d.minAngle;
  j.maxAngle = d.maxAngle;
  j.swing = d.swing;
  j.twist = d.twist;
  j.damping = d.damping;
  constraints_.addRigidJoint(j, JointDrive{restTarget(j), 0.0, kDriveStiffness});
  rigidBodies_.jointed[j.a] = rigidBodies_.jointed[j.b] = 1;
  parting_.join(d.a, d.b);  // moved as one by the parting, as a ragdoll's particle parts are
  islands_.join(islands_.nodeOf(d.a), islands_.nodeOf(d.b));
}

JointDesc World::jointDesc(std::size_t k) const {
  requireIndex(k, constraints_.rigidJoints().size(), "jointDesc", "joint");
  const RigidJoint& j = constraints_.rigidJoints()[k];
  const RigidBodies& r = rigidBodies_;
  JointDesc d;
  d.kind = j.kind;
  d.a = r.body[j.a];
  d.b = r.body[j.b];
  d.pivot = r.position[j.a] + r.orientation[j.a] * j.pivotA;
  d.pivotB = r.position[j.b] + r.orientation[j.b] * j.pivotB;
  d.pivotBSet = true;
  d.axis = r.orientation[j.a] * j.axisA;
  d.reference = r.orientation[j.a] * j.referenceA;
  d.axisB = r.orientation[j.b] * j.axisB;
  d.referenceB = r.orientation[j.b] * j.referenceB;
  d.minAngle = j.minAngle;
  d.maxAngle = j.maxAngle;
  d.swing = j.swing;
  d.twist = j.twist;
  d.damping = j.damping;
  return d;
}

Real World::jointAngle(std::size_t k) const {
  requireIndex(k, constraints_.rigidJoints().size(), "jointAngle", "joint");
  return detail::jointAngle(rigidBodies_, constraints_.rigidJoints()[k]);
}

const JointDrive& World::jointDrive(std::size_t k) const {
  requireIndex(k, constraints_.rigidJoints().size(), "jointDrive", "joint");
  return constraints_.drives()[k];
}

// A multiplier is an impulse times h (the position change it makes is w lambda), so the force is
// lambda / h^2; the passes of a substep add to one multiplier, zeroed by the first.
Real World::jointDriveTorque(std::size_t k) const {
  requireIndex(k, constraints_.rigidJoints().size(), "jointDriveTorque", "joint");
  const Real h = substepDt();
  return std::abs(constraints_.driveLambda()[k]) / (h * h);
}

DriveLoad World::bodyDriveLoad(BodyId id) const {
  requireIndex(id, bodies_.size(), "bodyDriveLoad", "body");
  const std::span<const DrivenBody> driven = constraints_.bodyDrives();
  const std::span<const Real> lambda = constraints_.bodyDriveLambda();
  const Real hh = substepDt() * substepDt();
  for (std::size_t k = 0; k < driven.size(); ++k) {
    if (driven[k].body == id)
      return DriveLoad{std::abs(lambda[2 * k]) / hh, std::abs(lambda[2 * k + 1]) / hh};
  }
  return {};
}

Quat World::jointRest(std::size_t k) const {
  requireIndex(k, constraints_.rigidJoints().size(), "jointRest", "joint");
  return restTarget(constraints_.rigidJoints()[k]);
}

void World::setJointDrive(std::size_t k, const JointDrive& drive) {
  requireIndex(k, constraints_.rigidJoints().size(), "setJointDrive", "joint");
  require(drive.strength >= 0.0 && drive.strength <= 1.0, "setJointDrive: strength must be in [0, 1]");
  require(std::isfinite(drive.stiffness) && drive.stiffness > 0.0,
          "setJointDrive: stiffness must be finite and > 0 (N m/rad)");
  JointDrive kept = drive;
  kept.target = unitQuaternion(drive.target, "setJointDrive: the target");
  constraints_.setDrive(k, kept);
  islands_.wake(islands_.nodeOf(rigidBodies_.body[constraints_.rigidJoints()[k].a]));
}

std::optional<BodyDrive> World::bodyDrive(BodyId id) const {
  requireIndex(id, bodies_.size(), "bodyDrive", "body");
  for (const DrivenBody& d : constraints_.bodyDrives()) {
    if (d.body == id) return d.drive;
  }
  return std::nullopt;
}

void World::setBodyDrive(BodyId id, const BodyDrive& drive) {
  requireIndex(id, bodies_.size(), "setBodyDrive", "body");
  require(finite(drive.position), "setBodyDrive: the position must be finite");
  require(drive.strength >= 0.0 && drive.strength <= 1.0, "setBodyDrive: strength must be in [0, 1]");
  require(std::isfinite(drive.stiffness) && drive.stiffness >= 0.0,
          "setBodyDrive: stiffness must be finite and >= 0 (N/m)");
  require(std::isfinite(drive.angularStiffness) && drive.angularStiffness > 0.0,
          "setBodyDrive: angular stiffness must be finite and > 0 (N m/rad)");
  BodyDrive kept = drive;
  kept.orientation = unitQuaternion(drive.orientation, "setBodyDrive: the orientation");
  const Body& body = bodies_[id];
  constraints_.setBodyDrive(DrivenBody{id, body.rigid, body.model != BodyModel::Rigid, kept});
  islands_.wake(islands_.nodeOf(id));
}

void World::clearBodyDrive(BodyId id) {
  requireIndex(id, bodies_.size(), "clearBodyDrive", "body");
  constraints_.clearBodyDrive(id);
  islands_.wake(islands_.nodeOf(id));
}

std::size_t World::addParticleJoint(BodyId parent, BodyId child, const Vec3& pivot) {
  requireIndex(parent, bodies_.size(), "addParticleJoint", "body");
  requireIndex(child, bodies_.size(), "addParticleJoint", "body");
  require(finite(pivot), "addParticleJoint: the pivot must be finite");
  return addParticleJoint(particleJointAt(parent, child, pivot, pivot));
}

ParticleJoint World::particleJointAt(BodyId parent, BodyId child, const Vec3& pivot,
                                     const Vec3& pivotB) const {
  requireIndex(parent, bodies_.size(), "particleJointAt", "body");
  requireIndex(child, bodies_.size(), "particleJointAt", "body");
  const BodyPose a = poseOf(parent), b = poseOf(child);
  ParticleJoint j;
  j.a = parent;
  j.b = child;
  j.pivotA = glm::conjugate(a.orientation) * (pivot - a.center);
  j.pivotB = glm::conjugate(b.orientation) * (pivotB - b.center);
  j.rest = glm::normalize(glm::conjugate(a.orientation) * b.orientation);
  return j;
}

std::size_t World::addParticleJoint(const ParticleJoint& joint) {
  const std::string who = "addParticleJoint: ";
  requireIndex(joint.a, bodies_.size(), "addParticleJoint", "body");
  requireIndex(joint.b, bodies_.size(), "addParticleJoint", "body");
  require(joint.a != joint.b, who + "a joint needs two bodies");
  require(bodies_[joint.a].model != BodyModel::Rigid && bodies_[joint.b].model != BodyModel::Rigid,
          who + "both bodies must be particle bodies (a rigid joint is addJoint's)");
  require(finite(joint.pivotA) && finite(joint.pivotB), who + "the pivots must be finite");
  ParticleJoint j = joint;
  j.rest = unitQuaternion(joint.rest, who + "the rest");
  constraints_.addParticleJoint(j, JointDrive{j.rest, 0.0, kDriveStiffness});
  // Its drive turns the two against each other: one island, as a joint's links would make them (a
  // joint may have none), so that setting the drive wakes both.
  islands_.join(islands_.nodeOf(j.a), islands_.nodeOf(j.b));
  return constraints_.particleJoints().size() - 1;
}

const JointDrive& World::particleJointDrive(std::size_t k) const {
  requireIndex(k, constraints_.particleJoints().size(), "particleJointDrive", "particle joint");
  return constraints_.particleDrives()[k];
}

Real World::particleJointDriveTorque(std::size_t k) const {
  requireIndex(k, constraints_.particleJoints().size(), "particleJointDriveTorque", "particle joint");
  const Real h = substepDt();
  return std::abs(constraints_.particleDriveLambda()[k]) / (h * h);
}

Real World::particleJointDriveShare(std::size_t k) const {
  requireIndex(k, constraints_.particleJoints().size(), "particleJointDriveShare", "particle joint");
  return constraints_.particleDriveShare()[k];
}

void World::setParticleJointDrive(std::size_t k, const JointDrive& drive) {
  const std::string who = "setParticleJointDrive: ";
  requireIndex(k, constraints_.particleJoints().size(), "setParticleJointDrive", "particle joint");
  require(drive.strength >= 0.0 && drive.strength <= 1.0, who + "strength must be in [0, 1]");
  require(std::isfinite(drive.stiffness) && drive.stiffness > 0.0,
          who + "stiffness must be finite and > 0 (N m/rad)");
  JointDrive kept = drive;
  kept.target = unitQuaternion(drive.target, who + "the target");
  constraints_.setParticleDrive(k, kept);
  islands_.wake(islands_.nodeOf(constraints_.particleJoints()[k].a));
}

BodyPoint World::pointOn(BodyId id, const Vec3& worldPoint) const {
  requireIndex(id, bodies_.size(), "pointOn", "body");
  if (bodies_[id].model != BodyModel::Rigid) return BodyPoint::embedded(anchor(id, worldPoint));
  require(finite(worldPoint), "pointOn: the point must be finite");
  const RigidId i = bodies_[id].rigid;
  return BodyPoint::onRigid(
      i, glm::conjugate(rigidBodies_.orientation[i]) * (worldPoint - rigidBodies_.position[i]));
}

Vec3 World::position(const BodyPoint& point) const {
  if (point.side != ContactSide::Rigid) return position(point.point);
  requireIndex(point.rigid, rigidBodies_.size(), "position", "rigid body");
  return positionOf(point);
}

Vec3 World::positionOf(const BodyPoint& point) const {
  if (point.side != ContactSide::Rigid) return positionOf(point.point);
  return rigidBodies_.position[point.rigid] + rigidBodies_.orientation[point.rigid] * point.local;
}

BodyId World::carrier(const BodyPoint& point) const {
  if (point.side == ContactSide::Rigid) {
    requireIndex(point.rigid, rigidBodies_.size(), "carrier", "rigid body");
    return rigidBodies_.body[point.rigid];
  }
  if (point.point.count < 1) [[unlikely]]
    throw std::invalid_argument("carrier: an embedding needs a particle");
  requireIndex(point.point.particle[0], particles_.size(), "carrier", "particle");
  return particleBody_[point.point.particle[0]];
}

}  // namespace phys
