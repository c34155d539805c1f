#pragma once
// Capsule ragdolls laid out like Bullet's benchmark ragdoll (the one its RagdollDemo builds and
// its benchmark piles 136 of): eleven capsules of Bullet's radii and lengths at Bullet's places,
// joined by ten joints: five hinges (spine, knees, elbows: two pins on the axis and a one-sided
// link at each stop, as in ragdoll.h) and five cones (neck, hips, shoulders: one pin, a link that
// keeps the limb's axis within the cone, and a link that bounds its twist). docs/physics.md, "Capsule
// ragdolls", lists the layout and where it differs from Bullet's.
#include <array>
#include <string>
#include <string_view>

#include "physics/ragdoll.h"
#include "physics/world.h"

namespace phys {

/// The eleven parts, in the order CapsuleRagdoll::parts holds them (Bullet's order). Left is the
/// ragdoll's own left (+x when it stands facing +z), as in ragdoll.h.
enum class CapsulePart {
  Pelvis,
  Spine,
  Head,
  UpperLegLeft,
  LowerLegLeft,
  UpperLegRight,
  LowerLegRight,
  UpperArmLeft,
  LowerArmLeft,
  UpperArmRight,
  LowerArmRight,
};
inline constexpr int kCapsuleParts = 11;
inline constexpr int kCapsuleJoints = 10;
/// "pelvis", "spine", "head", "upper-leg-left", ...; throws std::invalid_argument for a value
/// outside CapsulePart.
std::string_view toString(CapsulePart part);

/// What addCapsuleRagdoll built.
struct CapsuleRagdoll {
  std::string name;
  RagdollModel model = RagdollModel::Seed;
  std::array<BodyId, kCapsuleParts> parts{};
  /// Its joints are World joints firstJoint to firstJoint + kCapsuleJoints - 1 (rigid joints for the
  /// rigid model, particle joints for the others), the five hinges (spine, knees, elbows) and then
  /// the five cones (neck, hips, shoulders).
  std::size_t firstJoint = 0;
  /// The body of a part; throws std::invalid_argument for a value outside CapsulePart.
  BodyId part(CapsulePart p) const;
};

/// Adds a capsule ragdoll: its parts are capsules (Shape::Capsule) of the desc's model (seed:
/// corners boxes, lean: tetra boxes, rigid: rigid bodies), named "<name>.pelvis", ...; desc.hips is the
/// middle of the hip joints, and at the identity orientation it stands in a T pose on its feet, facing +z,
/// 1.76 m tall at scale 1 (arms out sideways, as Bullet builds it). The mass is split evenly over
/// the parts, as Bullet gives each part the same mass. Parts that share a joint do not collide.
/// Throws std::invalid_argument on bad input and adds nothing.
CapsuleRagdoll addCapsuleRagdoll(World& world, const RagdollDesc& desc);

}  // namespace phys
