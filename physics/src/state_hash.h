#pragma once
// The state hash World::stateHash and Motion::hash share, so that a motion saved from a world
// hashes as the world did. A world's characters (Character) and a motion's (CharacterMotion) have
// their fields under the same names, so one template hashes both.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "physics/animation.h"
#include "physics/character.h"
#include "physics/fnv1a.h"
#include "physics/types.h"

namespace phys::detail {

/// FNV-1a over a state: the arrays' bytes, then the characters' fields.
class StateHasher : public Fnv1a {
 public:
  /// A quaternion counts as (w, x, y, z).
  void quat(const Quat& q) {
    const Real wxyz[4] = {q.w, q.x, q.y, q.z};
    bytes(wxyz, sizeof(wxyz));
  }
  void text(std::string_view s) {
    value(s.size());
    bytes(s.data(), s.size());
  }
  /// A clip counts by its name's last part, the file it was read from without its folder: two loads
  /// of one file hash alike, and the same scene hashes alike from any checkout. Its frames are not
  /// read (a long clip would cost the recording's hash of every step); what it plays shows in the
  /// target pose.
  void clip(const Clip& c) {
    const std::string_view name = c.name;
    const std::size_t slash = name.find_last_of('/');
    text(slash == std::string_view::npos ? name : name.substr(slash + 1));
  }
  void playback(const Playback& p) {
    value(p.clip != nullptr);
    if (p.clip != nullptr) clip(*p.clip);
    value(p.time);
    value(p.speed);
    value(p.loop);
  }
  void pose(const ClipPose& p) {
    value(p.root);
    for (const Quat& q : p.turns) quat(q);
  }
};

/// Every field of a character that changes as it steps (CharacterMotion's), `C` a Character or a
/// CharacterMotion. The pose held for a fade counts only while it is held.
template <class C>
void hashCharacter(StateHasher& h, const C& c) {
  h.playback(c.now);
  h.playback(c.before);
  for (const Real v :
       {c.blend, c.blendTime, c.strength, c.rootStrength, c.balance, c.goalStrength, c.goalRootStrength,
        c.goalBalance, c.stateTime, c.fromStrength, c.fromBalance, c.lastImpact, c.stillTime})
    h.value(v);
  for (const Real share : c.partStrength) h.value(share);
  const Reaction& r = c.reaction;
  for (const Real v : {r.threshold, r.fallTime, r.restSpeed, r.restTime, r.getUpTime, r.armTime}) h.value(v);
  h.playback(r.getUp);
  h.value(c.state);
  h.value(c.lastRootVelocity);
  // Whether the balance may act in the next step. Hashed only when true: a world in which no
  // character stands on its support (every one without the balance, as the pinned tackle) hashes
  // as before the field was kept, and one whose reloaded character had lost it differs.
  if (c.supported) h.value(c.supported);
  // The turn-in (Character::turnIn), hashed only where it differs from a character that has none
  // and the default time: a world without one (the pinned tackle, whose parts are rigid) hashes as
  // before it was kept.
  if (c.turnInTime != kTurnInTime) h.value(c.turnInTime);
  if (c.turnIn > 0.0) h.value(c.turnIn);
  if (c.turnInDue) h.value(c.turnInDue);
  h.value(c.queued.has_value());
  if (c.queued) {
    h.playback(c.queued->playback);
    h.value(c.queued->at);
    h.value(c.queued->blendTime);
  }
  h.quat(c.frame);
  h.value(c.origin);
  h.value(c.beforeShift);
  h.pose(c.pose);
  h.value(c.holding);
  if (c.holding) h.pose(c.held);
}

/// The bytes of each array in turn, then each character's fields.
template <class C>
std::uint64_t stateHash(std::span<const Vec3> position, std::span<const Vec3> previous,
                        std::span<const Vec3> rigidPosition, std::span<const Vec3> rigidVelocity,
                        std::span<const Vec3> rigidAngularVelocity, std::span<const Quat> rigidOrientation,
                        std::span<const C> characters) {
  StateHasher h;
  for (const std::span<const Vec3> values :
       {position, previous, rigidPosition, rigidVelocity, rigidAngularVelocity})
    h.bytes(values.data(), values.size_bytes());
  for (const Quat& q : rigidOrientation) h.quat(q);
  for (const C& c : characters) hashCharacter(h, c);
  return h.hash();
}

}  // namespace phys::detail
