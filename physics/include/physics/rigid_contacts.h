#pragma once
// Contacts that involve a rigid body (docs/physics.md, "Rigid bodies"): a rigid body on the
// ground, on another rigid body, or on a particle body. Each side of a contact is the ground, a
// point fixed in a rigid body's frame, or a point embedded in a particle body; the passes correct
// both sides by XPBD's positional impulses (Müller et al. 2020), with static friction as a
// positional constraint, and a velocity pass after the substep for dynamic friction and restitution.
#include <array>
#include <cstddef>
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
  /// One of the two points of a capsule lying along the ground (its two ends' lowest points) or
  /// along another rigid body (its core along a face or a core): such a patch of two is solved as
  /// one block (solvesAsBlock in rigid_contacts.cpp).
  bool capsuleLying = false;
};

/// The points of one pair of bodies (or of one body on the ground), consecutive in their list: the
/// passes push each point along the normal, then hold the patch by friction as a whole (its centre's
/// tangential motion and its twist about the normal, against mu times the patch's normal impulse).
struct ContactPatch {
  std::uint32_t first = 0, count = 0;
  /// unit: m; of the upper body along the ground's normal (-infinity on the ground): the passes'
  /// order, so that a body's patches with the bodies under it come one after another
  Real height = 0.0;
  std::uint32_t anchor = 0;  ///< its PatchAnchor: the patch's place in the contacts' order
  BodyId upper = kNoBody;    ///< the upper body (B on the ground)
};

/// Where static friction holds a patch, kept from substep to substep and from step to step while it
/// holds and the same points press: one point, where the patch's centre on B was when it stuck,
/// fixed in each body (in the world for the ground). Static friction pulls the two back together,
/// so a slip left over in one substep is undone in the next instead of adding up: held only against
/// each substep's own motion, as the 2020 paper has it, the top of a rigid pyramid of 20 rows went
/// 0.57 m in 60 s, and 0.29 m with anchors alone (docs/physics.md, "Standing for a minute"). A
/// patch with a particle body on a side keeps no anchor, nor does one of one or two points between
/// two bodies (solved point by point); a box's such patch on the ground does (a capsule's points
/// are placed anew before each pass, so its patch is anchored anew each pass).
struct PatchAnchor {
  /// The most points whose impulses a patch keeps for the next substep (a block's most points).
  static constexpr std::size_t kKeptPoints = 8;

  BodyId bodyA = kNoBody, bodyB = kNoBody;  ///< the patch's pair, to find it again
  Vec3 onA{0.0}, onB{0.0};                  ///< unit: m; in A's frame (the world's for the ground), in B's
  bool held = false;
  /// unit: kg m; each point's normal impulse over the patch's last substep, where its block's solve
  /// starts the next substep (a warm start). A resting patch needs the same impulses substep after
  /// substep, so started there its block converges in a sweep or two instead of running out of
  /// sweeps. Kept only for a patch solved as a block; used while it has as many points.
  std::array<Real, kKeptPoints> normal{};
  std::uint8_t points = 0;  ///< how many of `normal` hold a point's impulse; 0: none kept
  bool fresh = false;       ///< not yet solved in this substep: its impulses are the last substep's
};

/// What the passes keep per contact for one substep, index for index with the contacts, and each
/// patch's anchor, which outlives the substep.
struct RigidContactState {
  std::vector<Real> lambdaNormal;         ///< unit: kg m; the substep's normal positional impulse so far
  std::vector<Real> lambdaTangent;        ///< unit: kg m; static friction's, per patch (on its first point)
  std::vector<Real> twist;                ///< unit: kg m^2; static friction's against twisting, per patch
  std::vector<Real> approach;             ///< unit: m/s; separation speed before the passes (< 0 closing)
  std::vector<Real> allowance;            ///< unit: m; the overlap the point may keep in this substep
  std::vector<std::uint8_t> touched;      ///< pushed in the last substep
  std::vector<PatchAnchor> anchors;       ///< per patch, in the contacts' order (ContactPatch::anchor)
  std::vector<PatchAnchor> spareAnchors;  ///< the last substep's, while they are carried over

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
/// A contact's overlap at the substep's start (m; < 0 apart): along its normal between its sides at
/// their previous poses, or below the ground plane n . x = groundHeight.
Real startOverlap(const Particles& particles, const RigidBodies& rigidBodies, const RigidContact& c,
                  Real groundHeight);
/// Each ground contact's overlap at the substep's start (the body's previous pose) into
/// state.allowance, where the parting moves it with the body (NarrowPhase::measureStarts does the
/// same for the contacts between bodies).
void measureRigidGroundStarts(const RigidPassInput& in, std::span<const RigidContact> contacts,
                              RigidContactState& state);
/// From the start overlaps in state.allowance, what each point may keep: all but
/// `depenetration` (m, SolverSettings::maxDepenetrationSpeed h) of it; the approach speeds, and no
/// impulse yet.
void startRigidContacts(const RigidPassInput& in, std::span<const RigidContact> contacts,
                        RigidContactState& state, Real depenetration);
/// The contacts' patches in the order the passes take them: the ground's first, then from the lowest
/// body up, so that each body is set on what is below it after that has been set.
void findPatches(const RigidPassInput& in, std::span<const RigidContact> contacts,
                 std::vector<ContactPatch>& out);
/// Each patch's anchor from the last substep's, found by its pair; a new patch's is not held yet.
void carryAnchors(std::span<const RigidContact> contacts, std::span<const ContactPatch> patches,
                  RigidContactState& state);
/// One position pass over the patches: each point pushed apart along its normal by positional
/// impulses, and the patch held at its anchor by static friction while its tangential impulse stays
/// within mu_s times its normal one. A resting patch between two bodies one above the other is
/// solved by shock propagation: the lower body is held still (Guendelman, Bridson, Fedkiw 2003).
/// A patch of 3 to 8 points between rigid bodies or on the ground is one block, points and friction
/// together, and a body resting on several held bodies takes all of those patches in one block
/// (rigid_block.h).
void solveRigidContacts(const RigidPassInput& in, std::span<const RigidContact> contacts,
                        std::span<const ContactPatch> patches, RigidContactState& state);
/// After the velocities are derived: restitution (a point that approached faster than
/// `in.restingSpeed` leaves at e times that speed; any other stops closing), then dynamic friction
/// at each patch's centre (an impulse against the sliding of at most mu_d times the patch's normal
/// impulse), with the same shock propagation. A patch that pressed in none of the substep's passes
/// lets go of its anchor.
void rigidVelocityPass(const RigidPassInput& in, std::span<const RigidContact> contacts,
                       std::span<const ContactPatch> patches, RigidContactState& state, Real restitution);
}  // namespace detail

}  // namespace phys
