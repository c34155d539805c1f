#pragma once
// A world's motion: everything that changes as it steps and that its state hash covers (particle
// positions and previous positions, rigid bodies' poses and velocities, characters' clips, strengths
// and reactions) and its clock. Saved and
// given back to a world of the same structure that has not stepped (World::setMotion), it lets a
// run go on from a state kept in a file: the sandbox's recordings (docs/sandbox.md, "Recording
// files").
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "physics/character.h"
#include "physics/types.h"

namespace phys {

/// What of a character changes as the world steps or as it is told to (World::playClip,
/// setCharacterStrength, ...): Character less its binding to the ragdoll and the settings it was
/// added with (scale, root offset, root stiffness). The fields mean what Character's of the same
/// names mean.
struct CharacterMotion {
  Playback now;
  Playback before;  ///< its clip may be none (no clip was faded out of yet)
  Real blend = 1.0;
  Real blendTime = 0.0;
  Real strength = 1.0;
  std::vector<Real> partStrength;  ///< per bone
  Real rootStrength = 0.0;
  Real balance = 0.0;
  Real goalStrength = 1.0;
  Real goalRootStrength = 0.0;
  Real goalBalance = 0.0;
  Reaction reaction;
  CharacterState state = CharacterState::Active;
  Real stateTime = 0.0;
  Real fromStrength = 0.0;
  Real fromBalance = 0.0;
  Real lastImpact = 0.0;
  Real stillTime = 0.0;
  Vec3 lastRootVelocity{0.0};
  bool supported = false;  ///< the balance acts in the next step only if so (Character::supported)
  std::optional<QueuedClip> queued;
  Real turnInTime = kTurnInTime;  ///< unit: s; Character::turnInTime
  Real turnIn = 0.0;              ///< unit: s; what is left of a turn-in (Character::turnIn)
  bool turnInDue = false;         ///< Character::turnInDue
  Quat frame{1.0, 0.0, 0.0, 0.0};
  Vec3 origin{0.0};
  Vec3 beforeShift{0.0};
  ClipPose pose;  ///< the last substep's target pose
  ClipPose held;  ///< read only while `holding` (until then its turns may be zeros)
  bool holding = false;
};

struct Motion {
  std::vector<Vec3> position;               ///< per particle, unit: m
  std::vector<Vec3> previous;               ///< per particle, unit: m; position a substep back
  std::vector<Vec3> rigidPosition;          ///< per rigid body (RigidId), unit: m
  std::vector<Quat> rigidOrientation;       ///< per rigid body, unit quaternion
  std::vector<Vec3> rigidVelocity;          ///< per rigid body, unit: m/s
  std::vector<Vec3> rigidAngularVelocity;   ///< per rigid body, unit: rad/s, world frame
  std::vector<CharacterMotion> characters;  ///< per character (World::characters)
  Real time = 0.0;                          ///< unit: s; World::time()
  long steps = 0;                           ///< World::stepCount(); from 0 to kMaxSteps

  /// World::stateHash of a world in this motion: FNV-1a over the bytes of every array above, then
  /// over each character's fields (its clips by their names' file part, without the folder).
  std::uint64_t hash() const;
  /// "" or what World::setMotion would refuse in it whatever the world: a non-finite or negative
  /// number, a step count over kMaxSteps, an orientation not of unit length (within kUnitTolerance), a
  /// character's playback without a clip or a strength out of [0, 1]. Sizes and skeletons are the world's to
  /// judge.
  std::string problem() const;

  static constexpr Real kUnitTolerance = 1e-6;
  /// The most steps a motion may have taken, 2^53 (9.0e15, every count to it exact in a double): a
  /// world given more could count past the largest long (9.2e18, signed overflow) as it steps, and
  /// one given 2^53 would need 9.2e18 more steps, 290,000 years at a million steps a second.
  static constexpr long kMaxSteps = 1L << 53;
};

}  // namespace phys
