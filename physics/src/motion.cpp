// Motion: a world's moving state, taken out (World::motion) and given back (World::setMotion).
#include "physics/motion.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "physics/world.h"
#include "require.h"
#include "state_hash.h"

namespace phys {

namespace {

bool allFinite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string sizes(std::size_t given, std::size_t wanted) {
  return std::to_string(given) + " given for " + std::to_string(wanted);
}

bool finitePlayback(const Playback& p) {
  return std::isfinite(p.time) && std::isfinite(p.speed) && p.speed >= 0.0;
}

// Reaction's ranges, as World::addCharacter checks them.
bool validReaction(const Reaction& r) {
  const auto atLeast0 = [](Real v) { return std::isfinite(v) && v >= 0.0; };
  const auto over0 = [](Real v) { return std::isfinite(v) && v > 0.0; };
  return atLeast0(r.threshold) && atLeast0(r.fallTime) && over0(r.restSpeed) && atLeast0(r.restTime) &&
         over0(r.getUpTime) && atLeast0(r.armTime);
}

bool unitLength(const Quat& q) {
  const Real length = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return std::abs(length - 1.0) < Motion::kUnitTolerance;
}

bool unitTurns(const ClipPose& pose) {
  return allFinite(pose.root) && std::all_of(pose.turns.begin(), pose.turns.end(), unitLength);
}

// What Motion::problem finds in one character; "" for nothing.
std::string characterProblem(const CharacterMotion& c) {
  if (c.now.clip == nullptr) return "no clip playing";
  if (c.blend < 1.0 && !c.holding && c.before.clip == nullptr) return "a fade from no clip";
  if (c.queued && c.queued->playback.clip == nullptr) return "a queued change to no clip";
  const bool finite = finitePlayback(c.now) && finitePlayback(c.before) && finitePlayback(c.reaction.getUp) &&
                      (!c.queued || (finitePlayback(c.queued->playback) && std::isfinite(c.queued->at) &&
                                     std::isfinite(c.queued->blendTime))) &&
                      std::isfinite(c.blendTime) && std::isfinite(c.stateTime) &&
                      std::isfinite(c.lastImpact) && std::isfinite(c.stillTime) &&
                      allFinite(c.lastRootVelocity) && allFinite(c.origin) && allFinite(c.beforeShift);
  if (!finite) return "a non-finite clock, impact or position, or a negative speed";
  const auto onClock = [](const Playback& p) { return std::abs(p.time) <= kMaxClipTime; };
  if (!onClock(c.now) || !onClock(c.before) || !onClock(c.reaction.getUp) ||
      (c.queued && (!onClock(c.queued->playback) || std::abs(c.queued->at) > kMaxClipTime)))
    return "a clip's time beyond +-1e9 s";
  for (const Real span :
       {c.blendTime, c.stateTime, c.stillTime, c.lastImpact, c.queued ? c.queued->blendTime : 0.0}) {
    if (span < 0.0) return "a negative blend time, time in a state, time lain still or blow";
  }
  if (!(std::isfinite(c.turnInTime) && c.turnInTime >= 0.0 && c.turnIn >= 0.0 && c.turnIn <= c.turnInTime))
    return "a turn-in time non-finite or negative, or a turn-in left beyond it";
  if (!validReaction(c.reaction)) return "a reaction's threshold or time non-finite or out of range";
  for (const Real unit : {c.blend, c.strength, c.rootStrength, c.balance, c.goalStrength, c.goalRootStrength,
                          c.goalBalance, c.fromStrength, c.fromBalance}) {
    if (!(unit >= 0.0 && unit <= 1.0)) return "a strength, balance or blend out of [0, 1]";
  }
  if (!std::all_of(c.partStrength.begin(), c.partStrength.end(), [](Real s) { return s >= 0.0 && s <= 1.0; }))
    return "a part's strength out of [0, 1]";
  if (static_cast<unsigned>(c.state) > static_cast<unsigned>(CharacterState::LettingGo))
    return "no such state";
  if (!unitLength(c.frame) || !unitTurns(c.pose) || (c.holding && !unitTurns(c.held)))
    return "a frame or a pose's turn not of unit length, or a pose's root not finite";
  return {};
}

// The same-named fields of a Character and a CharacterMotion, either way.
template <class From, class To>
void copyCharacterMotion(const From& from, To& to) {
  to.now = from.now;
  to.before = from.before;
  to.blend = from.blend;
  to.blendTime = from.blendTime;
  to.strength = from.strength;
  to.partStrength = from.partStrength;
  to.rootStrength = from.rootStrength;
  to.balance = from.balance;
  to.goalStrength = from.goalStrength;
  to.goalRootStrength = from.goalRootStrength;
  to.goalBalance = from.goalBalance;
  to.reaction = from.reaction;
  to.state = from.state;
  to.stateTime = from.stateTime;
  to.fromStrength = from.fromStrength;
  to.fromBalance = from.fromBalance;
  to.lastImpact = from.lastImpact;
  to.stillTime = from.stillTime;
  to.lastRootVelocity = from.lastRootVelocity;
  to.supported = from.supported;
  to.queued = from.queued;
  to.turnInTime = from.turnInTime;
  to.turnIn = from.turnIn;
  to.turnInDue = from.turnInDue;
  to.frame = from.frame;
  to.origin = from.origin;
  to.beforeShift = from.beforeShift;
  to.pose = from.pose;
  to.held = from.held;
  to.holding = from.holding;
}

// Why character `c` of a motion cannot be given to the world's `w` ("" when it can): its per-bone
// arrays must be the character's size and every clip it names of the character's skeleton.
std::string characterMismatch(const CharacterMotion& c, const Character& w) {
  const std::size_t bones = w.bones.size();
  if (c.partStrength.size() != bones || c.pose.turns.size() != w.pose.turns.size() ||
      c.held.turns.size() != w.held.turns.size())
    return "part strengths or pose turns for " + std::to_string(c.partStrength.size()) +
           " bones, the character has " + std::to_string(bones);
  const auto held = [&w](const Clip* clip) {
    bool found = false;
    forEachPlayback(w, [&](const Playback& p) { found = found || p.clip.get() == clip; });
    return found;
  };
  std::string why;  // the first playback's problem
  forEachPlayback(c, [&](const Playback& p) {
    if (!why.empty() || p.clip == nullptr) return;
    if (std::string difference = skeletonDifference(*p.clip, *w.now.clip); !difference.empty()) {
      why = std::move(difference);
      return;
    }
    // A clip the character holds was checked when it was given; another is checked as addCharacter would.
    if (std::string problem = held(p.clip.get()) ? "" : clipProblem(*p.clip); !problem.empty())
      why = "clip '" + p.clip->name + "': " + problem;
  });
  return why;
}

}  // namespace

std::string Motion::problem() const {
  if (!std::isfinite(time) || time < 0.0 || steps < 0) return "a non-finite or negative time or step count";
  if (steps > kMaxSteps)
    return "step count " + std::to_string(steps) + " over " + std::to_string(kMaxSteps) +
           " (2^53): stepping on would count past the largest long";
  for (const auto* values : {&position, &previous, &rigidPosition, &rigidVelocity, &rigidAngularVelocity}) {
    for (const Vec3& v : *values) {
      if (!allFinite(v)) return "a non-finite position or velocity";
    }
  }
  if (!std::all_of(rigidOrientation.begin(), rigidOrientation.end(), unitLength))
    return "an orientation not of unit length";
  for (std::size_t k = 0; k < characters.size(); ++k) {
    if (std::string problem = characterProblem(characters[k]); !problem.empty())
      return "character " + std::to_string(k) + ": " + problem;
  }
  return {};
}

std::uint64_t Motion::hash() const {
  return detail::stateHash(position, previous, rigidPosition, rigidVelocity, rigidAngularVelocity,
                           rigidOrientation, std::span<const CharacterMotion>(characters));
}

Motion World::motion() const {
  Motion m;
  m.position = particles_.position;
  m.previous = particles_.previous;
  m.rigidPosition = rigidBodies_.position;
  m.rigidOrientation = rigidBodies_.orientation;
  m.rigidVelocity = rigidBodies_.velocity;
  m.rigidAngularVelocity = rigidBodies_.angularVelocity;
  m.characters.resize(characters_.size());
  for (std::size_t k = 0; k < characters_.size(); ++k) copyCharacterMotion(characters_[k], m.characters[k]);
  m.time = time_;
  m.steps = steps_;
  return m;
}

std::string World::motionProblem(const Motion& m) const {
  const std::size_t n = particles_.size(), r = rigidBodies_.size();
  if (m.position.size() != n || m.previous.size() != n)
    return "particle positions " + sizes(m.position.size(), n) + " particles, previous " +
           sizes(m.previous.size(), n);
  if (m.rigidPosition.size() != r || m.rigidOrientation.size() != r || m.rigidVelocity.size() != r ||
      m.rigidAngularVelocity.size() != r)
    return "rigid body poses or velocities for " + std::to_string(m.rigidPosition.size()) +
           " bodies, the world has " + std::to_string(r);
  if (m.characters.size() != characters_.size())
    return std::to_string(m.characters.size()) + " characters given, the world has " +
           std::to_string(characters_.size());
  if (std::string problem = m.problem(); !problem.empty()) return problem;
  for (std::size_t k = 0; k < characters_.size(); ++k) {
    if (std::string mismatch = characterMismatch(m.characters[k], characters_[k]); !mismatch.empty())
      return "character " + std::to_string(k) + ": " + mismatch;
  }
  return {};
}

void World::setMotion(const Motion& m) {
  using detail::require;
  // A world that has stepped keeps contacts, warm starts, rest timers and the guard's last good
  // positions from its own motion; none of them would belong to the one given.
  require(steps_ == 0 && time_ == 0.0, "setMotion: the world has stepped (" + std::to_string(steps_) +
                                           " steps); give the motion to a world that has not");
  const std::string problem = motionProblem(m);
  require(problem.empty(), "setMotion: " + problem);
  particles_.position = m.position;
  particles_.previous = m.previous;
  std::copy(m.position.begin(), m.position.end(), guard_.checked().begin());
  rigidBodies_.position = rigidBodies_.previousPosition = m.rigidPosition;
  rigidBodies_.orientation = rigidBodies_.previousOrientation = m.rigidOrientation;
  rigidBodies_.velocity = m.rigidVelocity;
  rigidBodies_.angularVelocity = m.rigidAngularVelocity;
  for (std::size_t k = 0; k < characters_.size(); ++k) {
    Character& c = characters_[k];
    copyCharacterMotion(m.characters[k], c);
    makeRootDriveIfNeeded(c);
  }
  time_ = m.time;
  steps_ = m.steps;
  updateBodyFrames();  // what raycast and the drawing read between steps
}

CharacterMotion World::characterMotion(std::size_t k) const {
  detail::requireIndex(k, characters_.size(), "characterMotion", "character");
  CharacterMotion m;
  copyCharacterMotion(characters_[k], m);
  return m;
}

void World::setCharacterMotion(std::size_t k, const CharacterMotion& m) {
  using detail::require;
  detail::requireIndex(k, characters_.size(), "setCharacterMotion", "character");
  const std::string problem = characterProblem(m);
  require(problem.empty(), "setCharacterMotion: " + problem);
  const std::string mismatch = characterMismatch(m, characters_[k]);
  require(mismatch.empty(), "setCharacterMotion: " + mismatch);
  Character& c = characters_[k];
  copyCharacterMotion(m, c);
  makeRootDriveIfNeeded(c);
  islands_.wake(islands_.nodeOf(c.bones[0].body));
}

}  // namespace phys
