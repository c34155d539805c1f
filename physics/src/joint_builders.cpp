#include "joint_builders.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "require.h"

namespace phys::detail {
namespace {

// How far past a stop its limit link still catches the hinge (see addHinge).
constexpr Real kStopReach = std::numbers::pi / 3.0;
// The largest angle a cone's twist link is asked to hold: a chord link works poorly near 180
// degrees, where its push is almost all along the radius (see addHinge).
constexpr Real kLargestHeldAngle = 150.0 * std::numbers::pi / 180.0;

}  // namespace

RagdollFrame ragdollFrame(const RagdollDesc& desc, Real hipHeight, const std::string& who) {
  auto require = [&who](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(who + ": " + what);
  };
  require(finite(desc.hips) && finite(desc.velocity), "hips and velocity must be finite");
  require(std::isfinite(desc.scale) && desc.scale > 0.0 && desc.scale < 1e6, "scale must be > 0 and < 1e6");
  require(std::isfinite(desc.mass) && desc.mass > 0.0, "mass must be finite and > 0 (kg)");
  const Real qLength = glm::length(desc.orientation);
  require(std::isfinite(qLength) && qLength > 0.0, "orientation must be a finite non-zero quaternion");
  require(validate(desc.material).empty(), "friction coefficients must be finite and >= 0");
  require(!desc.jointDamping || (std::isfinite(*desc.jointDamping) && *desc.jointDamping >= 0.0),
          "joint damping must be finite and >= 0 (1/s)");
  require(desc.inertiaFloor >= 0.0 && desc.inertiaFloor <= 1.0, "inertia floor must be from 0 to 1");
  require(desc.strength >= 0.0 && desc.strength <= 1.0, "strength must be from 0 to 1");
  require(desc.rootStrength >= 0.0 && desc.rootStrength <= 1.0, "root strength must be from 0 to 1");
  require(!desc.driveStiffness || (std::isfinite(*desc.driveStiffness) && *desc.driveStiffness > 0.0),
          "drive stiffness must be finite and > 0 (N m/rad)");
  const Quat q = desc.orientation / qLength;
  const Vec3 hips = desc.hips, fromHips(0.0, hipHeight, 0.0);
  const Real scale = desc.scale;
  return {
      q, [hips, q, fromHips, scale](const Vec3& layout) { return hips + q * ((layout - fromHips) * scale); }};
}

void buildInEmptyWorld(const World& world, const RagdollDesc& desc, const std::string& who,
                       const std::function<void(World&)>& build) {
  SolverSettings solver = world.solverSettings();
  solver.threads = 1;  // no worker threads for a world that never steps
  World empty(world.worldSettings(), solver);
  try {
    build(empty);
  } catch (const std::invalid_argument& refused) {
    throw std::invalid_argument(who + ": mass " + numberText(desc.mass) + " kg at scale " +
                                numberText(desc.scale) + ": " + refused.what());
  }
}

BodyDesc ragdollPart(const RagdollDesc& desc, std::string_view part) {
  BodyDesc box;
  box.name = (desc.name.empty() ? std::string("ragdoll") : desc.name) + "." + std::string(part);
  box.velocity = desc.velocity;
  switch (desc.model) {
    case RagdollModel::Seed:
      box.model = BodyModel::Corners;
      break;
    case RagdollModel::Lean:
      box.model = BodyModel::Tetra;
      break;
    case RagdollModel::Rigid:
      box.model = BodyModel::Rigid;
      box.inertiaFloor = desc.inertiaFloor;
      break;
  }
  box.material = desc.material;
  box.collisionGroup = desc.collisionGroup;
  box.collisionMask = desc.collisionMask;
  return box;
}

// The stiffness is set at every strength, 0 too: a character given the ragdoll drives its joints
// at their own stiffness and its own strengths, and a heavy ragdoll's joints left at the 70 kg
// default could not carry its limbs (700 kg on the run cycle: 10 degrees RMS where 70 kg tracks
// within 1.3).
void driveRagdollJoints(World& world, const RagdollDesc& desc, std::size_t firstJoint) {
  const Real stiffness =
      desc.driveStiffness.value_or(kDriveStiffness * desc.mass / kRagdollDriveMass * desc.scale);
  if (desc.model != RagdollModel::Rigid) {
    for (std::size_t k = firstJoint; k < world.particleJoints().size(); ++k) {
      JointDrive drive = world.particleJointDrive(k);
      drive.strength = desc.strength;
      drive.stiffness = stiffness;
      world.setParticleJointDrive(k, drive);
    }
    return;
  }
  for (std::size_t k = firstJoint; k < world.rigidJoints().size(); ++k) {
    JointDrive drive = world.jointDrive(k);
    drive.strength = desc.strength;
    drive.stiffness = stiffness;
    world.setJointDrive(k, drive);
  }
}

void driveRagdollRoot(World& world, const RagdollDesc& desc, BodyId root) {
  if (desc.rootStrength == 0.0) return;
  const BodyPose pose = world.bodyPose(root);
  const Real mass = desc.mass / kRagdollDriveMass;
  world.setBodyDrive(root,
                     BodyDrive{pose.center, pose.orientation, desc.rootStrength,
                               kBodyDriveStiffness * mass / desc.scale, kDriveStiffness * mass * desc.scale});
}

Real jointDamping(const RagdollDesc& desc) {
  return desc.jointDamping.value_or(desc.model == RagdollModel::Rigid ? kRagdollJointDamping : 0.0);
}

Vec3 rotateAbout(const Vec3& v, const Vec3& axis, Real angle) {
  const Real c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0 - c));
}

namespace {

bool bothRigid(const World& world, BodyId a, BodyId b) {
  return world.bodies()[a].model == BodyModel::Rigid && world.bodies()[b].model == BodyModel::Rigid;
}

// A layout direction as it lies in the world: place() is a turn, a scale and a shift.
Vec3 directionOf(const PlaceFn& place, const Vec3& direction) {
  return glm::normalize(place(direction) - place(Vec3(0.0)));
}

// A rigid joint's pivot, axis and reference in the world; the caller adds its limits.
JointDesc rigidJoint(JointKind kind, BodyId parent, BodyId child, const Vec3& pivot, const Vec3& axis,
                     const Vec3& reference, Real damping, const PlaceFn& place) {
  JointDesc d;
  d.kind = kind;
  d.a = parent;
  d.b = child;
  d.pivot = place(pivot);
  d.axis = directionOf(place, axis);
  d.reference = directionOf(place, reference);
  d.damping = damping;
  return d;
}

}  // namespace

void addHinge(World& world, BodyId parent, BodyId child, const HingeSpec& spec, const PlaceFn& place,
              Real scale) {
  if (bothRigid(world, parent, child)) {
    JointDesc d = rigidJoint(JointKind::Hinge, parent, child, spec.pivot, spec.axis, spec.reference,
                             spec.damping, place);
    d.minAngle = spec.minAngle;
    d.maxAngle = spec.maxAngle;
    world.addJoint(d);
    return;
  }
  if (spec.damping > 0.0) world.addJointFriction(parent, child, spec.damping);
  world.addParticleJoint(parent, child, place(spec.pivot));  // what a drive needs of it
  // Two pins on the axis make the hinge.
  for (const Real side : {-1.0, 1.0}) {
    const Vec3 pin = place(spec.pivot + spec.axis * (side * spec.halfSpan));
    world.addLink(world.anchor(parent, pin), world.anchor(child, pin));
  }
  // The limits: one one-sided range link at each stop. Q is fixed in the child at `radius`
  // along the reference direction; P is fixed in the parent where Q would be had the hinge
  // turned kStopReach past the stop. Seen from the pivot P and Q are |theta - phi| apart, so
  // |P - Q| = 2 r sin(|theta - phi| / 2), which is r at the stop and less only within
  // kStopReach beyond it: the link pushes P and Q apart to r there, turning the hinge back.
  // Its push meets the arc of Q at kStopReach / 2 = 30 degrees, so most of it turns the
  // hinge; a single link with both bounds would have to work near 180 degrees, where its
  // push is almost all along the arm and a hard landing carries the hinge past it.
  const Vec3 inChild = place(spec.pivot + spec.reference * spec.radius);
  for (const Real stop : {spec.minAngle - kStopReach, spec.maxAngle + kStopReach}) {
    const Vec3 inParent = place(spec.pivot + rotateAbout(spec.reference, spec.axis, stop) * spec.radius);
    world.addLink(world.anchor(parent, inParent), world.anchor(child, inChild), spec.radius * scale,
                  kNoMaxLength);
  }
}

void addCone(World& world, BodyId parent, BodyId child, const ConeSpec& spec, const PlaceFn& place,
             Real scale) {
  if (bothRigid(world, parent, child)) {
    JointDesc d =
        rigidJoint(JointKind::Cone, parent, child, spec.pivot, spec.axis, spec.side, spec.damping, place);
    d.swing = spec.swing;
    d.twist = spec.twist;
    world.addJoint(d);
    return;
  }
  if (spec.damping > 0.0) world.addJointFriction(parent, child, spec.damping);
  const Vec3 pivot = place(spec.pivot);
  world.addParticleJoint(parent, child, pivot);  // what a drive needs of it
  world.addLink(world.anchor(parent, pivot), world.anchor(child, pivot));
  // A point at `radius` along the limb's axis, fixed in both parts where it is laid out: after
  // the child swings by s (about any line through the pivot) the two copies are 2 r sin(s / 2)
  // apart, so bounding that chord bounds the swing in every direction at once, a round cone.
  // The same chord for a point to the side bounds how far that point moved, which is the twist
  // when the limb does not swing and at most swing + twist when it does: twist is held within
  // the cone's own span, not apart from it (a pin there would make a hinge of the ball joint).
  auto chordLink = [&](const Vec3& direction, Real angle) {
    const Vec3 point = place(spec.pivot + direction * spec.radius);
    const Real chord = 2.0 * spec.radius * scale * std::sin(std::min(angle, kLargestHeldAngle) / 2.0);
    world.addLink(world.anchor(parent, point), world.anchor(child, point), 0.0, chord);
  };
  chordLink(spec.axis, spec.swing);
  chordLink(spec.side, spec.swing + spec.twist);
}

}  // namespace phys::detail
