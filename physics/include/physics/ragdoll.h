#pragma once
// Ragdolls: ten boxes joined by nine hinges, each hinge two pins on its axis (World::addLink)
// and two one-sided range links, one at each stop of its angle. Three models a scene chooses:
// `seed` builds the parts as corners boxes (80 particles, the seed's), `lean` as tetra boxes
// (40 particles: the fewest of our box models that carry the same joints and limits), `rigid` as
// rigid bodies (ten poses; the same links, their ends fixed in the parts' frames).
// docs/physics.md, "Joints and ragdolls", draws the layout and lists the limits.
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "physics/world.h"

namespace phys {

enum class RagdollModel {
  Seed,   ///< corners boxes: 8 particles and 22 sticks a part
  Lean,   ///< tetra boxes: 4 particles and 6 sticks a part
  Rigid,  ///< rigid bodies: one pose a part, the joints' ends fixed in their frames
};

std::string_view toString(RagdollModel model);  ///< "seed", "lean", "rigid"
std::optional<RagdollModel> parseRagdollModel(std::string_view name);
/// The ragdoll model whose parts are boxes of `model`: corners -> seed, tetra -> lean, rigid -> rigid.
RagdollModel ragdollModelOf(BodyModel model);

/// The ten parts, in the order Ragdoll::parts holds them. Left is the ragdoll's own left (+x
/// when it stands facing +z).
enum class RagdollPart {
  Head,
  Torso,
  UpperArmLeft,
  LowerArmLeft,
  UpperArmRight,
  LowerArmRight,
  UpperLegLeft,
  LowerLegLeft,
  UpperLegRight,
  LowerLegRight,
};
inline constexpr int kRagdollParts = 10;
inline constexpr int kRagdollHinges = 9;
/// "head", "upper-arm-left", ...; throws std::invalid_argument for a value outside RagdollPart.
std::string_view toString(RagdollPart part);

/// Default friction of a rigid ragdoll's joints (RagdollDesc::jointDamping). Without it a limb of
/// rigid parts swings on its joint as a pendulum, slowed only by the air (docs/physics.md, "Rigid
/// bodies"), where the particle models' limbs come to rest within a few seconds.
inline constexpr Real kRagdollJointDamping = 2.0;  ///< unit: 1/s

/// Default inertia floor of a rigid ragdoll's parts (RagdollDesc::inertiaFloor, BodyDesc::inertiaFloor).
/// With each part's true inertia a rigid pile at 4 substeps never rests: the forearms, at their
/// elbows' stops, turn about their long axes and back every substep (docs/physics.md, "Inertia floor").
inline constexpr Real kRagdollInertiaFloor = 2.0 / 3.0;  ///< unitless

/// The mass a ragdoll's default drive stiffness is kDriveStiffness for (RagdollDesc::driveStiffness).
inline constexpr Real kRagdollDriveMass = 70.0;  ///< unit: kg

/// A ragdoll when it is created. At the identity orientation it stands upright on its feet,
/// facing +z, 1.72 m tall at scale 1.
struct RagdollDesc {
  std::string name;  ///< its parts are named "<name>.head", "<name>.torso", ...
  Vec3 hips{0.0};    ///< unit: m; where the bottom of the torso is (the hinge line of the hips)
  Quat orientation{1.0, 0.0, 0.0, 0.0};
  Real scale = 1.0;  ///< unitless; multiplies every length
  Real mass = 70.0;  ///< unit: kg; the whole body's, split over the parts as in a person
  RagdollModel model = RagdollModel::Seed;
  /// unit: 1/s; friction in the joints: the parts' relative spin decays as exp(-jointDamping t)
  /// (JointDesc::damping between rigid parts, World::addJointFriction between particle parts).
  /// Unset: kRagdollJointDamping for rigid parts, none for particle parts, whose passes take most
  /// of that motion away (a pile's loosely held heads keep turning: docs/physics.md, "Islands and
  /// sleeping").
  std::optional<Real> jointDamping;
  /// unitless, 0 to 1; rigid parts' BodyDesc::inertiaFloor (0: each part's solid inertia). Particle
  /// parts ignore it: their inertia is their particles'.
  Real inertiaFloor = kRagdollInertiaFloor;
  Vec3 velocity{0.0};  ///< unit: m/s; of every part at creation
  /// unitless, 0 to 1: every joint's drive (JointDrive::strength) holds the pose the ragdoll is made
  /// in; 0 is a limp ragdoll. A particle ragdoll's joints are driven through their particle joints.
  Real strength = 0.0;
  /// unit: N m / rad; the drives' stiffness at strength 1/2 (JointDrive::stiffness). Unset:
  /// kDriveStiffness for a 70 kg ragdoll at scale 1, in proportion to mass times scale, so that a
  /// ragdoll of any size leans as far under its own weight. Set at any strength, 0 too: a character
  /// on the ragdoll drives its joints at it.
  std::optional<Real> driveStiffness;
  /// unitless, 0 to 1: the root's drive (BodyDrive, the hand of god) holds the root part (the box
  /// ragdoll's torso, the capsule ragdoll's pelvis) at the pose it is made in; 0 is none. Rigid parts
  /// only, as strength. Its stiffnesses: kBodyDriveStiffness and kDriveStiffness for a 70 kg ragdoll
  /// at scale 1, the first in proportion to mass over scale (the root sags as far for its size), the
  /// second to mass times scale.
  Real rootStrength = 0.0;
  Material material;
  std::uint32_t collisionGroup = 1;
  std::uint32_t collisionMask = 0xffffffffu;
};

/// One hinge: the child part turns about `axis` relative to the parent, by an angle that is 0
/// in the standing pose and positive by the right-hand rule (for the x axis: a part pointing
/// down swings backwards).
struct RagdollHinge {
  RagdollPart parent = RagdollPart::Torso;
  RagdollPart child = RagdollPart::Head;
  Vec3 axis{1.0, 0.0, 0.0};        ///< unit vector in the parent's frame (the same in the child's at rest)
  Vec3 reference{0.0, -1.0, 0.0};  ///< unit vector normal to axis, in both frames at rest
  Real minAngle = 0.0;             ///< unit: rad
  Real maxAngle = 0.0;             ///< unit: rad
};

/// What addRagdoll built.
struct Ragdoll {
  std::string name;
  RagdollModel model = RagdollModel::Seed;
  std::array<BodyId, kRagdollParts> parts{};
  std::array<RagdollHinge, kRagdollHinges> hinges{};
  /// Hinge h is World joint firstJoint + h: a rigid joint (World::jointDrive, setJointDrive) for the
  /// rigid model, a particle joint (World::particleJointDrive, setParticleJointDrive) for the others.
  std::size_t firstJoint = 0;
  /// The body of a part; throws std::invalid_argument for a value outside RagdollPart.
  BodyId part(RagdollPart p) const;
};

/// Adds a ragdoll's boxes, pins and limits to the world, and keeps the parts that share a
/// hinge from colliding with each other (the others do). Throws std::invalid_argument on bad
/// input and adds nothing.
Ragdoll addRagdoll(World& world, const RagdollDesc& desc);

/// The hinge's angle now, from its two parts' poses. unit: rad, in (-pi, pi]. Throws
/// std::invalid_argument, naming itself, for a part outside RagdollPart or a body the world does not
/// have (a ragdoll of another world).
Real hingeAngle(const World& world, const Ragdoll& ragdoll, const RagdollHinge& hinge);

}  // namespace phys
