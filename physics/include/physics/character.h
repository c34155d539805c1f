#pragma once
// Characters: a ragdoll whose joints' drives follow an animation clip (docs/physics.md,
// "Animation"). A clip's bones are the ragdoll's parts by name ("<ragdoll>.<bone>"), each joined
// to its parent's part by a rigid joint (rigid parts) or a particle joint (particle parts); every step the
// character samples its clip (blending from the clip before while a change of clip fades in) and sets each
// joint's drive target, and, with a root strength, the root part's body drive (the hand of god) to carry it
// along the clip's path.
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "physics/animation.h"
#include "physics/types.h"

namespace phys {

class World;

/// A clip playing: which, from when, how fast, looping or not.
struct Playback {
  std::shared_ptr<const Clip> clip;
  Real time = 0.0;   ///< unit: s; into the clip; |time| <= kMaxClipTime
  Real speed = 1.0;  ///< unitless; finite, >= 0
  bool loop = true;
};

/// unit: rad; the most the balance leans a character (20 degrees)
inline constexpr Real kMaxBalanceLean = 0.35;
/// unitless; the balance acts only while the character's centre of mass stands over its support at
/// least this share of its standing height (Character::standingHeight): a body tipped 60 degrees
/// about its feet, far past the 20 degrees the balance leans it, is falling, and lying it is down.
inline constexpr Real kStandingShare = 0.5;

/// unit: s; how long a character turns in (CharacterDesc::turnInTime) unless told: the first 0.1 s
/// of a turn from a far pose is what folds a particle part (docs/physics.md, "Turn-in")
inline constexpr Real kTurnInTime = 0.1;
/// unitless; during a turn-in, the most of a particle joint drive's gap one pass closes: from 0.3
/// down no setting of the seed ragdoll folded (docs/physics.md, "Turn-in")
inline constexpr Real kTurnInShare = 0.25;
/// unit: rad; a turn-in starts only for a character some part of which is further than this from
/// its target: one already in its clip's pose (CharacterDesc::startInPose, a fade) is left alone
inline constexpr Real kTurnInGap = 0.35;

/// How a character answers a blow: past the threshold it goes limp over fallTime, falls as a
/// ragdoll and, with a get-up clip, once it has lain still for restTime, is lifted back onto its
/// feet over getUpTime by its root's drive, playing the clip, and let go again.
struct Reaction {
  /// unit: m/s; the blow that makes it go limp (Character::lastImpact): another body striking one
  /// of its parts this fast, or its root part's speed changing this much in a step (a push, a
  /// fall); 0 never does
  Real threshold = 0.0;
  Real fallTime = 0.25;  ///< unit: s, >= 0; from its strengths to none
  Real restSpeed = 0.2;  ///< unit: m/s; every part slower than this is lying still
  Real restTime = 1.0;   ///< unit: s; lying still this long, it gets up
  Real getUpTime = 1.5;  ///< unit: s, > 0; lifted over this long, then let go over as long
  /// unit: s, >= 0; how long it must have been active (since it was added, set or got up) before a
  /// blow counts: its own start, a run begun from standing at full speed, is not a blow
  Real armTime = 0.5;
  Playback getUp;  ///< the clip it gets up on (its bones the character's); none stays down
};

/// Where a character is in its reaction.
enum class CharacterState {
  Active,     ///< following its clip at its strengths
  Falling,    ///< hit: its strengths fading to none
  Down,       ///< limp, waiting to lie still
  GettingUp,  ///< lifted by its root towards the get-up clip's pose
  LettingGo,  ///< on its feet; the root's lift fading to the root strength it had
};

/// "active", "falling", "down", "getting-up", "letting-go" (the scene format's names)
std::string_view toString(CharacterState state);
std::optional<CharacterState> parseCharacterState(std::string_view name);

/// A clip to change to once the one playing reaches a time (World::queueClip).
struct QueuedClip {
  Playback playback;
  Real at = 0.0;         ///< unit: s; on the playing clip's clock
  Real blendTime = 0.0;  ///< unit: s
};

/// What World::addCharacter takes.
struct CharacterDesc {
  std::string ragdoll;  ///< its parts are the bodies named "<ragdoll>.<bone>"
  Playback playback;
  Real strength = 1.0;      ///< unitless, 0 to 1: every joint's drive (JointDrive::strength)
  Real rootStrength = 0.0;  ///< unitless, 0 to 1: the root's body drive; 0 is none
  Real scale = 1.0;         ///< unitless, > 0: the ragdoll's; multiplies the clip's root path
  /// unitless, 0 to 1: the balance's strength, a turn of the root towards its clip's orientation
  /// leaned so as to bring the capture point back over the feet (docs/physics.md, "Balance"); used
  /// while the root is not carried (rootStrength 0)
  Real balance = 0.0;
  Reaction reaction;
  /// Put the ragdoll in the clip's pose at playback.time when the character is added, at rest: the
  /// root on the clip's path (its feet on the clip's floor), each part turned to its target and
  /// moved so that its joint meets its parent's. Without it the ragdoll starts in the pose it is
  /// in, and the drives turn it into the clip's over the first steps.
  bool startInPose = false;
  /// Per bone by name, 0 to 1: its joint's share of the character's strength (1 for a bone not
  /// named): an arm held loosely, a stiff neck. Not the root's, which has no joint.
  std::vector<std::pair<std::string, Real>> partStrengths;
  /// unit: m, in the clip's root bone's frame, times `scale`: where the root part's centre is from
  /// the clip's root position. 0 for the project's clips, whose root is the root part's centre; a
  /// clip whose root is the hip joint (most motion capture) needs the centre's offset from it.
  Vec3 rootOffset{0.0};
  /// unit: N/m, >= 0, and N m/rad, > 0: the root's body drive's stiffnesses at strength 1/2
  /// (Character::rootStiffness). Unset: the drive the root has when the character is added, else
  /// kBodyDriveStiffness and kDriveStiffness for a 70 kg ragdoll at scale 1, the first in proportion
  /// to mass over scale, the second to mass times scale.
  std::optional<Real> rootStiffness, rootAngularStiffness;
  /// unit: s, >= 0: the turn-in (docs/physics.md, "Turn-in"): for this long after the character is
  /// added, its clip is cut to another or its strength rises, if some part is further than
  /// kTurnInGap from its target, each pass of a particle joint's drive closes at most kTurnInShare of
  /// its gap, so that a stiff drive cannot fold a particle part on the way. 0 never does. Rigid
  /// parts, which cannot fold, are not held.
  Real turnInTime = kTurnInTime;
};

/// One part of a character, bound to a clip's bone.
struct CharacterBone {
  BodyId body{};
  int clipBone = 0;  ///< its index in the clip
  int parent = -1;   ///< the parent's index in Character::bones; -1 for the root
  /// the joint to its parent (not for the root): World::rigidJoints()' index, or
  /// World::particleJoints()' for a character of particle parts
  std::size_t joint = 0;
  bool reversed = false;          ///< the joint's first body is this part, not its parent
  Quat rest{1.0, 0.0, 0.0, 0.0};  ///< its orientation in the character's frame at rest
};

/// A character as the world holds it.
struct Character {
  std::string ragdoll;
  bool particleParts = false;        ///< its parts are particle bodies (CharacterBone::joint)
  std::vector<CharacterBone> bones;  ///< the root first, parents before children
  Playback now;                      ///< the clip playing
  Playback before;                   ///< the clip faded out of while `blend` < 1
  Real blend = 1.0;                  ///< unitless, 0 to 1: how far the fade to `now` has gone
  Real blendTime = 0.0;              ///< unit: s; how long the fade takes
  Real strength = 1.0;               ///< the joints' drives' strength now (the reaction changes it)
  /// Per bone (Character::bones' order), 0 to 1: its joint's drive has strength * this; 1 unless set
  /// (the root's, which has no joint, stays 1)
  std::vector<Real> partStrength;
  Real rootStrength = 0.0;  ///< the root's drive's strength now
  Real balance = 0.0;       ///< the balance's strength now
  Real goalStrength = 1.0;  ///< what the reaction gives back: the strengths last set
  Real goalRootStrength = 0.0;
  Real goalBalance = 0.0;
  Real scale = 1.0;
  Vec3 rootOffset{0.0};  ///< unit: m; CharacterDesc::rootOffset
  Reaction reaction;
  CharacterState state = CharacterState::Active;
  Real stateTime = 0.0;     ///< unit: s; since the state began
  Real fromStrength = 0.0;  ///< the strengths the state began with, what its ramp starts from
  Real fromBalance = 0.0;
  /// unit: m/s; the last step's blow, what the threshold is held against: the fastest closing
  /// speed at which another body struck one of its parts, or its root part's speed change over
  /// the step, whichever is larger
  Real lastImpact = 0.0;
  /// Whether it stood on its support in the last step (World::react): a support part touched the
  /// ground or a body not its own, and its centre of mass stood over the support at least
  /// kStandingShare of its height in the rest pose. The balance acts only then. A torque from the
  /// world on a body that nothing carries, hung or thrown, is energy from nowhere, and on one lying
  /// on the ground it lifts and flings it. False until a step has found it so.
  bool supported = false;
  /// Its support parts (Character::bones' indices): its two lowest in the rest pose, its feet,
  /// found when it is added; what the balance stands it on.
  std::array<std::size_t, 2> support{0, 0};
  /// unit: m; its centre of mass's height over the support's middle in the rest pose, standing
  Real standingHeight = 0.0;
  Real stepBlow = 0.0;         ///< unit: m/s; the fastest strike so far in this step
  Real stillTime = 0.0;        ///< unit: s; how long every part has been slower than restSpeed
  Vec3 lastRootVelocity{0.0};  ///< unit: m/s; the root part's at the last step's end
  std::optional<QueuedClip> queued;
  Real turnInTime = kTurnInTime;  ///< unit: s; CharacterDesc::turnInTime
  /// unit: s; how much of a turn-in is left (0: none under way); a particle character's joint drives
  /// close at most kTurnInShare of their gap a pass while it is above 0
  Real turnIn = 0.0;
  /// A turn-in may be due (added, its clip cut to another, its strength risen): the next substep
  /// starts one if some part is further than kTurnInGap from its target, and clears this
  bool turnInDue = false;
  Real rootStiffness = 0.0;         ///< unit: N/m; of the root's body drive at strength 1/2
  Real rootAngularStiffness = 0.0;  ///< unit: N m/rad; the same for its turn
  Quat frame{1.0, 0.0, 0.0, 0.0};   ///< the clip's frame in the world
  Vec3 origin{0.0};                 ///< unit: m; the clip frame's origin in the world
  /// unit: m, clip frame; what `before`'s root path is moved by to meet `now`'s (playClip starts
  /// the new clip where the old one has got to).
  Vec3 beforeShift{0.0};
  ClipPose pose;    ///< the target pose, as of the last substep
  ClipPose fading;  ///< scratch: the pose of `before`
  /// The target pose a change of clip found a fade still under way at, held still and faded out of
  /// (`before` would cut that fade short); used while `holding`
  ClipPose held;
  bool holding = false;
  ClipPose starting;  ///< scratch: the first pose of a clip changed to
};

/// Calls f(const Playback&) for every playback a character, or its motion (CharacterMotion), holds:
/// the clip playing, the one faded out of, the get-up and the queued one, if any (a playback's clip
/// may be none).
template <class CharacterOrMotion, class F>
void forEachPlayback(const CharacterOrMotion& c, F&& f) {
  f(c.now);
  f(c.before);
  f(c.reaction.getUp);
  if (c.queued) f(c.queued->playback);
}

/// Binds a clip's bones to the ragdoll's parts by name: every part "<ragdoll>.<bone>" a bone of the
/// clip, every bone a part, all rigid or all of particles, each joined to its parent's by a rigid
/// joint or a particle joint (World::addParticleJoint). Throws std::invalid_argument naming the
/// bones that do not match. `rest` of each bone is from the joints'
/// rests, so the binding does not depend on the pose the ragdoll is in.
std::vector<CharacterBone> bindClip(const World& world, const std::string& ragdoll, const Clip& clip);

/// Where `pose` puts the root part's centre in the world: the clip's root position and the root
/// offset turned with the root bone, in the character's frame. unit: m
Vec3 rootCentre(const Character& c, const ClipPose& pose);

/// Each part's target orientation in the world for `pose`: frame * (the bones' turns down the
/// chain) * rest, into the first c.bones.size() elements of `out` (at least that long).
void targetOrientations(const Character& c, const ClipPose& pose, std::span<Quat> out);

/// Bone b's joint's two pivots, each in its own body's frame (unit: m): the parent part's first, then
/// the bone's own; of its rigid joint, or its particle joint for a character of particle parts. Not
/// for the root, which has no joint.
std::pair<Vec3, Vec3> bonePivots(const World& world, const Character& c, std::size_t b);

/// Where each part's centre is with the parts turned to `orientations` (as targetOrientations gives
/// them): the root's at `rootCentre`, every other part's where its joint's two pivots meet, parents
/// first; into the first c.bones.size() elements of `out` (at least that long). The ghost of the
/// target pose (DebugDrawFlags::targets) and CharacterDesc::startInPose place the parts so.
void targetCentres(const World& world, const Character& c, std::span<const Quat> orientations,
                   const Vec3& rootCentre, std::span<Vec3> out);

/// The way character k faces now, a unit vector across the world's up: its root part's forward
/// (the clip's +z, turned by the part's rest) taken about the up alone, so a leaning or lying body
/// faces where its heading points. Not the clip frame's (Character::frame), which stays where the
/// clip's path was laid while the body turns away from it: limp, fallen, dragged round, or on a
/// clip that turns.
Vec3 facing(const World& world, std::size_t k);

/// How far character k's parts are from its target pose (Character::pose, the last substep's): the
/// root mean square, over its parts, of the angle between each part's orientation and its target.
/// unit: rad
Real trackingError(const World& world, std::size_t k);

}  // namespace phys
