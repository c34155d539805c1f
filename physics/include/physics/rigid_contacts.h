#pragma once
// Contacts that involve a rigid body (docs/physics.md, "Rigid bodies"): a rigid body on the
// ground, on another rigid body, or on a particle body. Each side of a contact is the ground, a
// point fixed in a rigid body's frame, or a point embedded in a particle body; the passes correct
// both sides by XPBD's positional impulses (Müller et al. 2020), with static friction as a
// positional constraint, and a velocity pass after the substep for dynamic friction and restitution.
#include <cstdint>
#include <span>
#include <vector>

#include "physics/body.h"
#include "physics/constraints.h"
#include "physics/particles.h"
#include "physics/rigid_bodies.h"

namespace phys {

/// What one side of a RigidContact is.
enum class ContactSide : std::uint8_t { Ground, Rigid, Particles };

/// One contact point with a rigid body on at least one side, kept apart along `normal` (from A
/// towards B): n . (pB - pA) >= 0. No slop: a resting contact is pushed in every substep, so that
/// its friction and velocity pass act; with the particle models' 1 mm, a box resting on a box fell
/// freely within it in the substeps that did not push it (1.6 cm/s at the end of a step).
struct RigidContact {
  BodyId bodyA = kNoBody;  ///< kNoBody for the ground
  BodyId bodyB = kNoBody;
  ContactSide sideA = ContactSide::Ground;
  ContactSide sideB = ContactSide::Rigid;
  RigidId rigidA{}, rigidB{};     ///< Rigid sides: which body
  Vec3 localA{0.0}, localB{0.0};  ///< Rigid sides: the point in the body's frame, from its centre (m)
  Embedding pointA, pointB;       ///< Particles sides: the point carried by the body's particles
  Vec3 normal{0.0};               ///< unit; from A towards B; the ground's normal for a ground contact
  Material combined;
  std::uint8_t kind = 0;  ///< ContactKind, for debug drawing (0 on the ground)
  /// A capsule's point on the ground follows the lowest point of one end sphere (-1 or +1 along
  /// the body's y axis) as the capsule turns; 0 for a point fixed in its body.
  std::int8_t capsuleEnd = 0;
};

/// The points of one pair of bodies (or of one body on the ground), consecutive in their list: the
/// passes push each point along the normal, then hold the patch by friction as a whole (its centre's
/// tangential motion and its twist about the normal, against mu times the patch's normal impulse).
struct ContactPatch {
  std::uint32_t first = 0, count = 0;
  Real height = 0.0;  ///< unit: m; of the lower body along the ground's normal: the passes' order
};

/// What the passes keep per contact for one substep, index for index with the contacts.
struct RigidContactState {
  std::vector<Real> lambdaNormal;     ///< unit: kg m; the substep's normal positional impulse so far
  std::vector<Real> lambdaTangent;    ///< unit: kg m; static friction's, per patch (on its first point)
  std::vector<Real> twist;            ///< unit: kg m^2; static friction's against twisting, per patch
  std::vector<Real> approach;         ///< unit: m/s; separation speed before the passes (< 0 closing)
  std::vector<Real> allowance;        ///< unit: m; the overlap the point may keep in this substep
  std::vector<std::uint8_t> touched;  ///< pushed in the last substep

  void resize(std::size_t n);
};

/// What the rigid passes read of the world.
struct RigidPassInput {
  Particles& particles;
  RigidBodies& rigid;
  Vec3 groundNormal{0.0, 1.0, 0.0};  ///< also "up" for shock propagation, with or without a ground
  Real groundHeight = 0.0;           ///< unit: m
  Real h = 0.0;                      ///< unit: s; the substep
  /// unit: m/s; a contact closing no faster than this is resting (restitution's threshold too)
  Real restingSpeed = 0.0;
};

/// A contact between bodies whose normal is within 45 degrees of the ground's normal may be solved
/// by shock propagation (the lower body held still) when it is resting.
inline constexpr Real kShockMinUpright = 0.7071;  ///< unitless: |n . up|

namespace detail {
/// A contact side's point now, and where the same point was at the start of the substep.
Vec3 sidePosition(const Particles& particles, const RigidBodies& rigidBodies, ContactSide side, RigidId rigid,
                  const Vec3& local, const Embedding& point, bool previous);
/// The overlap at the substep's start, the approach speeds, and no impulse yet; `depenetration`
/// (m) is how much of a start overlap the substep may remove (SolverSettings::maxDepenetrationSpeed h).
void startRigidContacts(const RigidPassInput& in, std::span<const RigidContact> contacts,
                        RigidContactState& state, Real depenetration);
/// The contacts' patches in the order the passes take them: the ground's first, then from the lowest
/// body up, so that each body is set on what is below it after that has been set.
void findPatches(const RigidPassInput& in, std::span<const RigidContact> contacts,
                 std::vector<ContactPatch>& out);
/// One position pass over the patches: each point pushed apart along its normal by positional
/// impulses, then the patch held by static friction while its tangential impulse stays within mu_s
/// times its normal one. A resting patch between two bodies one above the other is solved by shock
/// propagation: the lower body is held still (Guendelman, Bridson, Fedkiw 2003).
void solveRigidContacts(const RigidPassInput& in, std::span<const RigidContact> contacts,
                        std::span<const ContactPatch> patches, RigidContactState& state);
/// After the velocities are derived: restitution (a point that approached faster than
/// `in.restingSpeed` leaves at e times that speed; any other stops closing), then dynamic friction
/// at each patch's centre (an impulse against the sliding of at most mu_d times the patch's normal
/// impulse), with the same shock propagation.
void rigidVelocityPass(const RigidPassInput& in, std::span<const RigidContact> contacts,
                       std::span<const ContactPatch> patches, const RigidContactState& state,
                       Real restitution);
}  // namespace detail

}  // namespace phys
