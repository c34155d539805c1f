#pragma once
// The joints ragdolls are made of, built from pins and range links (World::addLink). Both
// ragdolls (ragdoll.cpp, capsule_ragdoll.cpp) describe their joints in a layout frame, a
// standing body at scale 1; `place` maps a layout point into the world and `scale` multiplies
// layout lengths, so a joint is built the same way whatever the ragdoll's pose and size.
#include <functional>

#include <string>
#include <string_view>

#include "physics/ragdoll.h"
#include "physics/world.h"

namespace phys::detail {

using PlaceFn = std::function<Vec3(const Vec3&)>;

/// Checks what both ragdoll builders take from a RagdollDesc (finite hips and velocity, a scale
/// in (0, 1e6), a positive mass, a finite non-zero orientation, valid friction, strengths from 0 to
/// 1, a finite positive drive stiffness), throwing
/// std::invalid_argument with `who` ("addRagdoll") in the message, and returns the orientation made
/// unit and the function that places a layout point: the layout's (0, hipHeight, 0) goes to desc.hips.
struct RagdollFrame {
  Quat orientation;
  PlaceFn place;
};
RagdollFrame ragdollFrame(const RagdollDesc& desc, Real hipHeight, const std::string& who);

/// Runs `build` on an empty world of `world`'s settings and rethrows what it refuses prefixed with
/// `who` and the desc's mass and scale: a builder adds part after part, and World takes nothing
/// back, so a part or a drive refused half way (a mass or size addBody cannot represent, a drive's
/// stiffness overflowing) would leave the parts before it in `world`. What a ragdoll's build
/// refuses does not depend on the bodies already in the world, only on its settings.
void buildInEmptyWorld(const World& world, const RagdollDesc& desc, const std::string& who,
                       const std::function<void(World&)>& build);
/// What every part of a ragdoll takes from it: the name "<ragdoll or 'ragdoll'>.<part>", the
/// velocity, the body model (seed: corners, lean: tetra, rigid: rigid), the material and the collision
/// filter. The caller sets the shape, place, size, orientation and mass.
BodyDesc ragdollPart(const RagdollDesc& desc, std::string_view part);

/// A hinge in the layout frame: the child turns about `axis` (unit) through `pivot`, by an angle
/// that is 0 as laid out and positive by the right-hand rule, between the two stops.
struct HingeSpec {
  Vec3 pivot{0.0};
  Vec3 axis{1.0, 0.0, 0.0};
  Vec3 reference{0.0, -1.0, 0.0};  ///< unit, normal to axis: where the limit links' points lie
  Real minAngle = 0.0;             ///< unit: rad
  Real maxAngle = 0.0;             ///< unit: rad
  Real halfSpan = 0.07;            ///< unit: m; the two pins sit this far either side of the pivot
  Real radius = 0.1;               ///< unit: m; of the limit links' points from the pivot
  Real damping = 0.0;              ///< unit: 1/s; JointDesc::damping, or World::addJointFriction
};

/// Two pins on the axis and a one-sided range link at each stop (the why is in the .cpp); between
/// two rigid parts, a hinge joint (World::addJoint).
void addHinge(World& world, BodyId parent, BodyId child, const HingeSpec& spec, const PlaceFn& place,
              Real scale);

/// A cone in the layout frame: a ball joint at `pivot` whose child keeps its `axis` within
/// `swing` of the parent's, and turns about it by at most about `twist` more.
struct ConeSpec {
  Vec3 pivot{0.0};
  Vec3 axis{0.0, -1.0, 0.0};  ///< unit: the limb's direction as laid out
  Vec3 side{0.0, 0.0, 1.0};   ///< unit, normal to axis: where the twist link's points lie
  Real swing = 0.0;           ///< unit: rad; half-angle of the cone, in (0, pi)
  Real twist = 0.0;           ///< unit: rad; >= 0
  Real radius = 0.1;          ///< unit: m; of the limit links' points from the pivot
  Real damping = 0.0;         ///< unit: 1/s; JointDesc::damping, or World::addJointFriction
};

/// One pin at the pivot, one range link holding a point on the axis within the cone, one range
/// link holding a point to the side within swing + twist (the why is in the .cpp); between two
/// rigid parts, a cone joint (World::addJoint), whose twist is bounded apart from its swing.
void addCone(World& world, BodyId parent, BodyId child, const ConeSpec& spec, const PlaceFn& place,
             Real scale);

/// A ragdoll (Ragdoll or CapsuleRagdoll) of no parts yet: the desc's name and model, and the index
/// its first joint will have in `world`, among the rigid joints for the rigid model and among the
/// particle joints for the others.
template <class AnyRagdoll>
AnyRagdoll startRagdoll(const World& world, const RagdollDesc& desc) {
  AnyRagdoll ragdoll;
  ragdoll.name = desc.name;
  ragdoll.model = desc.model;
  ragdoll.firstJoint =
      desc.model == RagdollModel::Rigid ? world.rigidJoints().size() : world.particleJoints().size();
  return ragdoll;
}

/// The joints' damping a ragdoll's parts take: desc.jointDamping if set, else kRagdollJointDamping
/// for rigid parts and 0 for particle ones (RagdollDesc::jointDamping).
Real jointDamping(const RagdollDesc& desc);

/// Gives each joint from `firstJoint` on (rigid, or particle joints for a particle ragdoll) its drive
/// at desc.strength, holding the pose it was made in, and its stiffness (RagdollDesc::strength,
/// driveStiffness): at strength 0 too, the stiffness a character driving the ragdoll takes.
void driveRagdollJoints(World& world, const RagdollDesc& desc, std::size_t firstJoint);
/// Gives the root its drive at desc.rootStrength, holding it where it is (RagdollDesc::rootStrength).
/// Nothing when the strength is 0.
void driveRagdollRoot(World& world, const RagdollDesc& desc, BodyId root);

/// v turned by `angle` (rad) about the unit `axis`, by Rodrigues' formula.
Vec3 rotateAbout(const Vec3& v, const Vec3& axis, Real angle);

}  // namespace phys::detail
