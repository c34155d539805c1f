// Characters (physics/character.h): binding a clip to a ragdoll by name, and the step's first
// stage, which moves each character's drive targets along its clip.
#include "physics/character.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/gtc/quaternion.hpp>

#include "passes.h"
#include "physics/ragdoll.h"
#include "physics/world.h"
#include "require.h"
#include "stage_timer.h"

namespace phys {
namespace {

using detail::numberText;
using detail::require;
using detail::requireIndex;

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
  return s;
}

// The joint between two bodies among `joints` (rigid joints by RigidId, particle joints by BodyId),
// either way round; false when there is none.
template <typename Joint, typename Id>
bool jointBetween(std::span<const Joint> joints, Id parent, Id child, std::size_t& joint, bool& reversed) {
  for (std::size_t k = 0; k < joints.size(); ++k) {
    if ((joints[k].a == parent && joints[k].b == child) || (joints[k].a == child && joints[k].b == parent)) {
      joint = k;
      reversed = joints[k].a == child;
      return true;
    }
  }
  return false;
}

void checkPlayback(const Playback& p, const std::string& who) {
  require(p.clip != nullptr, who + ": no clip");
  const std::string problem = clipProblem(*p.clip);
  require(problem.empty(), who + ": clip '" + p.clip->name + "': " + problem);
  require(std::isfinite(p.time) && std::abs(p.time) <= kMaxClipTime,
          who + ": the clip's time must be finite and within +-1e9 s");
  require(std::isfinite(p.speed) && p.speed >= 0.0, who + ": the clip's speed must be finite and >= 0");
}

void checkTurnInTime(Real seconds, const std::string& who) {
  require(std::isfinite(seconds) && seconds >= 0.0, who + ": the turn-in time must be finite and >= 0 (s)");
}

void checkStrengths(Real strength, Real rootStrength, const std::string& who) {
  require(strength >= 0.0 && strength <= 1.0, who + ": strength must be in [0, 1]");
  require(rootStrength >= 0.0 && rootStrength <= 1.0, who + ": root strength must be in [0, 1]");
}

// The clip's pose for the playback's time; `shift` moves its root (clip frame).
void samplePlayback(const Playback& p, const Vec3& shift, ClipPose& out) {
  sampleClip(*p.clip, p.time, p.loop, out);
  out.root -= shift;
}

// The target pose: the clip playing, blended from the one before (or from the pose held when the
// change came during a fade) while it fades in.
void characterPose(Character& c) {
  samplePlayback(c.now, Vec3(0.0), c.pose);
  if (c.blend >= 1.0) return;
  if (c.holding) {
    blendPoses(c.held, c.pose, c.blend, c.pose);
    return;
  }
  samplePlayback(c.before, c.beforeShift, c.fading);
  blendPoses(c.fading, c.pose, c.blend, c.pose);
}

// The part of a turn about the world's up (+y): its twist, as a unit quaternion.
Quat headingOf(const Quat& q) {
  const Real norm = std::sqrt(q.w * q.w + q.y * q.y);
  if (norm < 1e-12) return Quat(1.0, 0.0, 0.0, 0.0);  // upside down: every heading is as good
  return Quat(q.w / norm, 0.0, q.y / norm, 0.0);
}

void checkReaction(const Reaction& r, const Clip& clip, const std::string& who) {
  require(std::isfinite(r.threshold) && r.threshold >= 0.0,
          who + ": the reaction threshold must be finite and >= 0");
  require(std::isfinite(r.fallTime) && r.fallTime >= 0.0, who + ": the fall time must be finite and >= 0");
  require(std::isfinite(r.restSpeed) && r.restSpeed > 0.0, who + ": the rest speed must be finite and > 0");
  require(std::isfinite(r.restTime) && r.restTime >= 0.0, who + ": the rest time must be finite and >= 0");
  require(std::isfinite(r.getUpTime) && r.getUpTime > 0.0, who + ": the get-up time must be finite and > 0");
  require(std::isfinite(r.armTime) && r.armTime >= 0.0, who + ": the arm time must be finite and >= 0");
  if (r.getUp.clip == nullptr) return;
  checkPlayback(r.getUp, who + ": get-up");
  const std::string difference = skeletonDifference(*r.getUp.clip, clip);
  require(difference.empty(), who + ": get-up " + difference);
}

// Changes the character's clip to `playback`, faded in over blendTime, its root path moved across
// the ground (the clip frame's x and z; the height stays the clip's own) to start at `from`, in the
// clip frame. A fade still under way is not cut short: the pose it has reached (c.pose, which the
// callers have just made) is held and faded out of. Allocates nothing: the step calls it for a
// queued clip.
void changeClip(Character& c, const Playback& playback, Real blendTime, const Vec3& from) {
  sampleClip(*playback.clip, playback.time, playback.loop, c.starting);
  Vec3 shift = from - c.starting.root;
  shift.y = 0.0;
  c.holding = c.blend < 1.0 && blendTime > 0.0;
  if (c.holding) {
    c.held.turns = c.pose.turns;  // sized alike at addCharacter: no allocation
    c.held.root = c.pose.root - shift;
  }
  c.origin += c.frame * (c.scale * shift);
  c.before = c.now;
  c.beforeShift = shift;
  c.now = playback;
  c.blendTime = blendTime;
  c.blend = blendTime > 0.0 ? 0.0 : 1.0;
  // A cut may leave the parts far from the new clip's pose; a fade starts from the pose it leaves,
  // and the next substep finds it near, with no turn-in.
  c.turnInDue = true;
}

// Where the clip's bone `bone` is among the character's bones, checked with the share to give it:
// a bone of the clip, not the root, a share in [0, 1].
std::size_t partOf(const Character& c, const Clip& clip, const std::string& bone, Real share,
                   const std::string& who) {
  require(share >= 0.0 && share <= 1.0, who + ": part '" + bone + "': strength must be in [0, 1]");
  for (std::size_t b = 0; b < c.bones.size(); ++b) {
    if (clip.bones[static_cast<std::size_t>(c.bones[b].clipBone)] != bone) continue;
    require(
        c.bones[b].parent >= 0,
        who + ": part '" + bone + "' is the root, which has no joint (its strength is the root strength)");
    return b;
  }
  throw std::invalid_argument(who + ": clip '" + clip.name + "' has no bone '" + bone + "'");
}

// Whether the character moves its ragdoll, or will: a drive with strength, or a reaction under way
// (a limp character that lies still waiting to get up still counts its rest). A limp one that
// stays down lets its island sleep.
bool characterMoves(const Character& c) {
  if (c.strength > 0.0 || c.rootStrength > 0.0 || c.balance > 0.0) return true;
  if (c.state == CharacterState::Down) return c.reaction.getUp.clip != nullptr;
  return c.state != CharacterState::Active;
}

// Whether the character keeps its root's drive while the root is not carried: for the balance, or
// at strength 0 so that balancing or lifting it again allocates nothing in the step (a character
// given a get-up under way, as a saved scene can, lifts with it too).
bool keepsRootDrive(const Character& c) {
  return c.balance > 0.0 || c.goalBalance > 0.0 || c.reaction.getUp.clip != nullptr ||
         c.state == CharacterState::GettingUp || c.state == CharacterState::LettingGo;
}

void enter(Character& c, CharacterState state) {
  c.state = state;
  c.stateTime = 0.0;
  c.fromStrength = c.strength;
  c.fromBalance = c.balance;
}

// The strengths the character's state gives after `h` more of it: ramps from the strengths the
// state began with (Reaction).
void rampStrengths(Character& c, Real h) {
  c.stateTime += h;
  if (c.state == CharacterState::Active || c.state == CharacterState::Down) return;
  const Reaction& r = c.reaction;
  switch (c.state) {
    case CharacterState::Falling: {
      const Real left = r.fallTime > 0.0 ? std::max(0.0, 1.0 - c.stateTime / r.fallTime) : 0.0;
      c.strength = c.fromStrength * left;
      c.balance = c.fromBalance * left;
      c.rootStrength = 0.0;  // the hand of god lets go at once: a blow is not to be held against
      if (left == 0.0) enter(c, CharacterState::Down);
      break;
    }
    case CharacterState::GettingUp: {
      const Real done = std::min(1.0, c.stateTime / r.getUpTime);
      c.strength = c.goalStrength * done;
      c.balance = c.goalBalance * done;
      c.rootStrength = done;
      if (done == 1.0) enter(c, CharacterState::LettingGo);
      break;
    }
    case CharacterState::LettingGo: {
      const Real done = std::min(1.0, c.stateTime / r.getUpTime);
      c.rootStrength = 1.0 + (c.goalRootStrength - 1.0) * done;
      if (done == 1.0) enter(c, CharacterState::Active);
      break;
    }
    default:
      break;
  }
}

// Where the root part's centre is from the clip's root position in `pose`, in the clip's frame
// (before the character's scale): the root offset turned with the root bone.
Vec3 turnedRootOffset(const Character& c, const ClipPose& pose) {
  return pose.turns[static_cast<std::size_t>(c.bones[0].clipBone)] * c.rootOffset;
}

constexpr std::string_view kStateNames[] = {"active", "falling", "down", "getting-up", "letting-go"};

}  // namespace

std::string_view toString(CharacterState state) {
  detail::requireEnum(static_cast<int>(state), static_cast<int>(std::size(kStateNames)),
                      "toString(CharacterState)", "state", "CharacterState");
  return kStateNames[static_cast<std::size_t>(state)];
}

std::optional<CharacterState> parseCharacterState(std::string_view name) {
  for (std::size_t k = 0; k < std::size(kStateNames); ++k) {
    if (kStateNames[k] == name) return static_cast<CharacterState>(k);
  }
  return std::nullopt;
}

std::vector<CharacterBone> bindClip(const World& world, const std::string& ragdoll, const Clip& clip) {
  const std::string who = "clip '" + clip.name + "' on ragdoll '" + ragdoll + "'";
  const std::string prefix = ragdoll + ".";
  std::vector<std::string> partNames;
  std::vector<BodyId> partIds;
  const std::span<const Body> bodies = world.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].name.size() <= prefix.size() || !bodies[i].name.starts_with(prefix)) continue;
    std::string part = bodies[i].name.substr(prefix.size());
    // "a.b.torso" is ragdoll "a.b"'s torso, not ragdoll "a"'s part "b.torso": a dotted rest that is
    // not one of the clip's bones belongs to another ragdoll whose name starts with this one's.
    // Taken as a part, it was a part with no bone, and ragdoll "a" could have no character.
    if (part.find('.') != std::string::npos && clip.bone(part) < 0) continue;
    partNames.push_back(std::move(part));
    partIds.push_back(BodyId(static_cast<std::uint32_t>(i)));
  }
  require(!partNames.empty(), who + ": the world has no body named '" + prefix + "<bone>'");
  std::vector<std::string> noPart, noBone;
  for (const std::string& bone : clip.bones) {
    if (std::find(partNames.begin(), partNames.end(), bone) == partNames.end()) noPart.push_back(bone);
  }
  for (const std::string& part : partNames) {
    if (clip.bone(part) < 0) noBone.push_back(part);
  }
  if (!noPart.empty() || !noBone.empty()) {
    std::string why = who + " does not fit:";
    if (!noPart.empty()) why += " the ragdoll has no part for the bones " + joined(noPart) + ";";
    if (!noBone.empty()) why += " the clip has no bone for the parts " + joined(noBone) + ";";
    why.pop_back();
    throw std::invalid_argument(why);
  }

  std::vector<CharacterBone> bones(clip.bones.size());
  // Rigid parts are driven through rigid joints, particle parts through particle joints: the first
  // part's model says which the character is, and every other part must be of its kind.
  const bool rigid = bodies[partIds[0]].model == BodyModel::Rigid;
  for (std::size_t b = 0; b < clip.bones.size(); ++b) {
    const auto at = std::find(partNames.begin(), partNames.end(), clip.bones[b]) - partNames.begin();
    CharacterBone& bone = bones[b];
    bone.body = partIds[static_cast<std::size_t>(at)];
    bone.clipBone = static_cast<int>(b);
    bone.parent = clip.parents[b];
    require((bodies[bone.body].model == BodyModel::Rigid) == rigid,
            who + ": part '" + clip.bones[b] + "' is " + (rigid ? "not rigid" : "rigid") + " and part '" +
                partNames[0] + "' is " + (rigid ? "rigid " : "not ") +
                "(a character's parts are all rigid or all particle bodies)");
    if (bone.parent < 0) continue;
    const CharacterBone& parent = bones[static_cast<std::size_t>(bone.parent)];
    const bool joined =
        rigid ? jointBetween(world.rigidJoints(), bodies[parent.body].rigid, bodies[bone.body].rigid,
                             bone.joint, bone.reversed)
              : jointBetween(world.particleJoints(), parent.body, bone.body, bone.joint, bone.reversed);
    require(joined, who + ": bone '" + clip.bones[b] + "': no " + (rigid ? "rigid" : "particle") +
                        " joint joins it to its parent '" +
                        clip.bones[static_cast<std::size_t>(bone.parent)] + "'");
    const Quat rest = rigid ? world.jointRest(bone.joint) : world.particleJoints()[bone.joint].rest;
    bone.rest = parent.rest * (bone.reversed ? glm::conjugate(rest) : rest);
  }
  return bones;
}

Vec3 rootCentre(const Character& c, const ClipPose& pose) {
  return c.origin + c.frame * (c.scale * (pose.root + turnedRootOffset(c, pose)));
}

void targetOrientations(const Character& c, const ClipPose& pose, std::span<Quat> out) {
  // Checked before a message is made: this runs every substep, where nothing may allocate.
  if (out.size() < c.bones.size() || pose.turns.size() < c.bones.size())
    throw std::invalid_argument("targetOrientations: a pose or an output shorter than the skeleton");
  // First each bone's turn from rest in the clip's frame, down the chain, then the parts'.
  for (std::size_t b = 0; b < c.bones.size(); ++b) {
    const CharacterBone& bone = c.bones[b];
    const Quat turn = pose.turns[static_cast<std::size_t>(bone.clipBone)];
    out[b] = bone.parent < 0 ? turn : out[static_cast<std::size_t>(bone.parent)] * turn;
  }
  for (std::size_t b = 0; b < c.bones.size(); ++b)
    out[b] = glm::normalize(c.frame * out[b] * c.bones[b].rest);
}

namespace {

// bonePivots without its checks, for targetCentres, which runs it for every bone it places.
std::pair<Vec3, Vec3> pivotsOf(const World& world, const Character& c, std::size_t b) {
  const CharacterBone& bone = c.bones[b];
  Vec3 pivotA(0.0), pivotB(0.0);
  if (c.particleParts) {
    const ParticleJoint& j = world.particleJoints()[bone.joint];
    pivotA = j.pivotA, pivotB = j.pivotB;
  } else {
    const RigidJoint& j = world.rigidJoints()[bone.joint];
    pivotA = j.pivotA, pivotB = j.pivotB;
  }
  return bone.reversed ? std::pair{pivotB, pivotA} : std::pair{pivotA, pivotB};
}

}  // namespace

std::pair<Vec3, Vec3> bonePivots(const World& world, const Character& c, std::size_t b) {
  requireIndex(b, c.bones.size(), "bonePivots", "bone");
  // The root's joint index means nothing: it has none.
  if (c.bones[b].parent < 0) [[unlikely]]
    throw std::invalid_argument("bonePivots: bone " + std::to_string(b) + " is the root, which has no joint");
  const std::size_t joints = c.particleParts ? world.particleJoints().size() : world.rigidJoints().size();
  requireIndex(c.bones[b].joint, joints, "bonePivots", c.particleParts ? "particle joint" : "joint");
  return pivotsOf(world, c, b);
}

void targetCentres(const World& world, const Character& c, std::span<const Quat> orientations,
                   const Vec3& rootCentre, std::span<Vec3> out) {
  if (out.size() < c.bones.size() || orientations.size() < c.bones.size())
    throw std::invalid_argument("targetCentres: orientations or an output shorter than the skeleton");
  for (std::size_t b = 0; b < c.bones.size(); ++b) {
    const CharacterBone& bone = c.bones[b];
    if (bone.parent < 0) {
      out[b] = rootCentre;
      continue;
    }
    const auto parent = static_cast<std::size_t>(bone.parent);
    const auto [parents, own] = pivotsOf(world, c, b);
    out[b] = out[parent] + orientations[parent] * parents - orientations[b] * own;
  }
}

namespace {

// The character's support parts, its two lowest in the rest pose (the feet of a standing skeleton),
// and its centre of mass's height over their middle there: what the balance stands it on, and how
// high it stands. Of the rest, not of where the parts are now, so that a body lying on its forearms
// is not taken to stand on them.
void findSupport(const World& world, Character& c) {
  const std::size_t n = c.bones.size();
  if (n < 2) return;
  std::vector<Quat> rests(n);
  std::vector<Vec3> centres(n);
  for (std::size_t b = 0; b < n; ++b) rests[b] = c.bones[b].rest;
  targetCentres(world, c, rests, Vec3(0.0), centres);  // the character's frame: y is up
  std::vector<std::size_t> order(n);
  for (std::size_t b = 0; b < n; ++b) order[b] = b;
  std::partial_sort(order.begin(), order.begin() + 2, order.end(),
                    [&](std::size_t a, std::size_t b) { return centres[a].y < centres[b].y; });
  c.support = {order[0], order[1]};
  Real mass = 0.0, height = 0.0;
  for (std::size_t b = 0; b < n; ++b) {
    const Real m = world.bodyMass(c.bones[b].body).mass;
    mass += m;
    height += m * centres[b].y;
  }
  if (mass > 0.0) c.standingHeight = height / mass - 0.5 * (centres[order[0]].y + centres[order[1]].y);
}

}  // namespace

Real trackingError(const World& world, std::size_t k) {
  requireIndex(k, world.characters().size(), "trackingError", "character");
  const Character& c = world.characters()[k];
  std::vector<Quat> targets(c.bones.size());
  targetOrientations(c, c.pose, targets);
  Real sum = 0.0;
  for (std::size_t b = 0; b < c.bones.size(); ++b) {
    const Quat q = world.bodyPose(c.bones[b].body).orientation;
    const Real cosHalf = std::min(1.0, std::abs(glm::dot(q, targets[b])));
    const Real angle = 2.0 * std::acos(cosHalf);
    sum += angle * angle;
  }
  return std::sqrt(sum / static_cast<Real>(c.bones.size()));
}

Vec3 facing(const World& world, std::size_t k) {
  requireIndex(k, world.characters().size(), "facing", "character");
  const CharacterBone& root = world.characters()[k].bones[0];
  const Quat forward = world.bodyPose(root.body).orientation * glm::conjugate(root.rest);
  return headingOf(forward) * Vec3(0.0, 0.0, 1.0);  // clips face +z
}

std::size_t World::addCharacter(const CharacterDesc& desc) {
  const std::string who = "addCharacter";
  checkPlayback(desc.playback, who);
  checkStrengths(desc.strength, desc.rootStrength, who);
  require(desc.balance >= 0.0 && desc.balance <= 1.0, who + ": balance must be in [0, 1]");
  require(std::isfinite(desc.scale) && desc.scale > 0.0, who + ": scale must be finite and > 0");
  require(finite(desc.rootOffset) && glm::length(desc.rootOffset) <= kMaxClipReach,
          who + ": root offset must be finite and within " + std::to_string(kMaxClipReach) + " m");
  checkReaction(desc.reaction, *desc.playback.clip, who);
  checkTurnInTime(desc.turnInTime, who);
  Character c;
  c.ragdoll = desc.ragdoll;
  c.bones = bindClip(*this, desc.ragdoll, *desc.playback.clip);
  c.particleParts = bodies_[c.bones[0].body].model != BodyModel::Rigid;
  c.partStrength.assign(c.bones.size(), 1.0);
  for (const auto& [bone, share] : desc.partStrengths)
    c.partStrength[partOf(c, *desc.playback.clip, bone, share, who)] = share;
  for (const Character& other : characters_)
    require(other.ragdoll != desc.ragdoll, who + ": ragdoll '" + desc.ragdoll + "' already has a character");
  findSupport(*this, c);
  c.now = desc.playback;
  c.strength = c.goalStrength = desc.strength;
  c.rootStrength = c.goalRootStrength = desc.rootStrength;
  c.balance = c.goalBalance = desc.balance;
  c.scale = desc.scale;
  c.rootOffset = desc.rootOffset;
  c.reaction = desc.reaction;
  c.turnInTime = desc.turnInTime;
  c.turnInDue = true;  // from the pose it was made in: the first substep sees how far that is
  c.lastRootVelocity = bodyVelocity(c.bones[0].body).first;
  // The clip's frame is where the root is now: its root path starts at the root part's centre and
  // it faces the way the root part faces. Only the heading (the turn about the world's up) is
  // taken: a clip whose first pose leans would otherwise tilt its whole frame, and its path with
  // it, by the lean. A clip's y = 0 is its floor: on a ground, the frame stands on the ground, so
  // that a ragdoll placed a little into it or above it runs on it all the same.
  const BodyId root = c.bones[0].body;
  const BodyPose pose = bodyPose(root);
  sampleClip(*c.now.clip, c.now.time, c.now.loop, c.pose);
  c.frame = headingOf(pose.orientation * glm::conjugate(c.pose.turns[0]));
  c.origin = pose.center - c.frame * (c.scale * (c.pose.root + turnedRootOffset(c, c.pose)));
  if (world_.ground) {
    const Vec3& n = world_.groundNormal;
    c.origin -= n * (glm::dot(c.origin, n) - world_.groundHeight);
  }
  // The root's drive: as stiff as asked, else as the one it has, else the ragdolls' default for
  // this mass.
  Real mass = 0.0;
  for (const CharacterBone& bone : c.bones) mass += bodyMass(bone.body).mass;
  const std::optional<BodyDrive> had = bodyDrive(root);
  c.rootStiffness = desc.rootStiffness.value_or(
      had ? had->stiffness : kBodyDriveStiffness * mass / kRagdollDriveMass / c.scale);
  c.rootAngularStiffness = desc.rootAngularStiffness.value_or(
      had ? had->angularStiffness : kDriveStiffness * mass / kRagdollDriveMass * c.scale);
  require(!desc.rootStiffness || (std::isfinite(*desc.rootStiffness) && *desc.rootStiffness >= 0.0),
          who + ": root stiffness must be finite and >= 0 (N/m)");
  require(!desc.rootAngularStiffness ||
              (std::isfinite(*desc.rootAngularStiffness) && *desc.rootAngularStiffness > 0.0),
          who + ": root angular stiffness must be finite and > 0 (N m/rad)");
  // The step gives the root these without setBodyDrive's checks: a scale near 0 or 1e308 overflows one
  // to inf, which the drive turns into non-finite motion (the guard freezes the ragdoll at once).
  require(std::isfinite(c.rootStiffness) && std::isfinite(c.rootAngularStiffness),
          who + ": scale " + numberText(desc.scale) + " makes the root drive's stiffness " +
              numberText(c.rootStiffness) + " N/m and " + numberText(c.rootAngularStiffness) +
              " N m/rad for a ragdoll of " + numberText(mass) + " kg; both must be finite");
  // Scratch sized now, not reserved: a copied World (the sandbox's rewind) keeps sizes, not capacities.
  c.fading.turns.resize(c.pose.turns.size());
  c.held.turns.resize(c.pose.turns.size());
  c.starting.turns.resize(c.pose.turns.size());
  characterTargets_.resize(std::max(characterTargets_.size(), c.bones.size()));
  held_.resize(held_.size() + 1);
  bodyCharacter_.resize(bodies_.size(), -1);
  for (const CharacterBone& bone : c.bones) bodyCharacter_[bone.body] = static_cast<int>(characters_.size());
  characters_.push_back(std::move(c));
  // Made last, so that a refusal above leaves the world as it was.
  const Character& added = characters_.back();
  if (desc.startInPose) putInPose(added);
  makeRootDriveIfNeeded(added);
  return characters_.size() - 1;
}

void World::makeRootDriveIfNeeded(const Character& c) {
  if (c.rootStrength > 0.0 || keepsRootDrive(c)) makeRootDrive(c, c.rootStrength);
}

// Each part turned to its target in the character's pose, parents first, the root put on the clip's
// path (its feet on the clip's floor) and every other part moved so that its joint's pivot meets its
// parent's; all at rest, so that the first substep does not read the move as a speed.
void World::putInPose(const Character& c) {
  std::vector<Quat> targets(c.bones.size());
  std::vector<Vec3> centres(c.bones.size());
  targetOrientations(c, c.pose, targets);
  targetCentres(*this, c, targets, rootCentre(c, c.pose), centres);
  for (std::size_t b = 0; b < c.bones.size(); ++b)
    placeAtRest(c.bones[b].body, BodyPose{centres[b], targets[b]});
  islands_.wake(islands_.nodeOf(c.bones[0].body));
}

// The root's drive made now, at the pose the root is in, so that the step only aims it and never
// allocates for it; the step sets its target, strength and stiffness every substep.
void World::makeRootDrive(const Character& c, Real strength) {
  const BodyId root = c.bones[0].body;
  if (bodyDrive(root)) return;
  const BodyPose pose = bodyPose(root);
  setRootDrive(c,
               BodyDrive{pose.center, pose.orientation, strength, c.rootStiffness, c.rootAngularStiffness});
}

void World::setRootDrive(const Character& c, const BodyDrive& drive) {
  const BodyId root = c.bones[0].body;
  constraints_.setBodyDrive(DrivenBody{root, bodies_[root].rigid, c.particleParts, drive});
}

// A part's mass, centre and velocity, of the pose and velocities of a rigid part, or of a particle
// part's particles (their velocities over the last substep); mass 0 for a part that cannot move.
World::PartMotion World::partMotion(BodyId id) const {
  const Body& body = bodies_[id];
  if (body.model == BodyModel::Rigid) {
    const RigidId i = body.rigid;
    const Real inverseMass = rigidBodies_.inverseMass[i];
    return {inverseMass > 0.0 ? 1.0 / inverseMass : 0.0, rigidBodies_.position[i], rigidBodies_.velocity[i]};
  }
  detail::MassProperties m;
  if (!detail::massProperties(particles_, body, m)) return {0.0, poseOf(id).center, Vec3(0.0)};
  return {m.mass, m.centre, detail::rigidMotion(particles_, body, m).linear / substepDt()};
}

// Put where `pose` says at rest: a rigid body's pose and previous pose, or a particle body's particles
// at their places in the pose and their previous positions with them.
void World::placeAtRest(BodyId id, const BodyPose& pose) {
  const Body& body = bodies_[id];
  if (body.model == BodyModel::Rigid) {
    RigidBodies& r = rigidBodies_;
    const RigidId i = body.rigid;
    r.orientation[i] = r.previousOrientation[i] = pose.orientation;
    r.position[i] = r.previousPosition[i] = pose.center;
    r.velocity[i] = r.angularVelocity[i] = Vec3(0.0);
    return;
  }
  for (int j = 0; j < body.particleCount; ++j) {
    const ParticleId p = body.firstParticle + j;
    particles_.position[p] = particles_.previous[p] =
        pose.center + pose.orientation * boxParticleLocal(body.model, body.halfExtents, j);
  }
}

void World::playClip(std::size_t k, const Playback& playback, Real blendTime) {
  requireIndex(k, characters_.size(), "playClip", "character");
  const std::string who = "playClip";
  checkPlayback(playback, who);
  require(std::isfinite(blendTime) && blendTime >= 0.0, who + ": blend time must be finite and >= 0");
  Character& c = characters_[k];
  const std::string difference = skeletonDifference(*playback.clip, *c.now.clip);
  require(difference.empty(), who + ": " + difference);
  // The new clip's root path starts where the target is now.
  characterPose(c);
  changeClip(c, playback, blendTime, c.pose.root);
  c.queued.reset();
  islands_.wake(islands_.nodeOf(c.bones[0].body));
}

void World::queueClip(std::size_t k, const Playback& playback, Real at, Real blendTime) {
  requireIndex(k, characters_.size(), "queueClip", "character");
  const std::string who = "queueClip";
  checkPlayback(playback, who);
  require(std::isfinite(at) && std::abs(at) <= kMaxClipTime,
          who + ": the time must be finite and within +-1e9 s");
  require(std::isfinite(blendTime) && blendTime >= 0.0, who + ": blend time must be finite and >= 0");
  Character& c = characters_[k];
  const std::string difference = skeletonDifference(*playback.clip, *c.now.clip);
  require(difference.empty(), who + ": " + difference);
  c.queued = QueuedClip{playback, at, blendTime};
}

void World::setCharacterStrength(std::size_t k, Real strength, Real rootStrength) {
  requireIndex(k, characters_.size(), "setCharacterStrength", "character");
  checkStrengths(strength, rootStrength, "setCharacterStrength");
  Character& c = characters_[k];
  // A limp or weak character given its strength back turns from wherever it lies: a turn-in if far.
  if (strength > c.strength) c.turnInDue = true;
  c.strength = c.goalStrength = strength;
  c.rootStrength = c.goalRootStrength = rootStrength;
  // The balance the reaction ramped (to 0 once down) comes back with the strengths: Active never
  // ramps it again, so left as it was, a character set after a fall stood at balance 0 for good.
  c.balance = c.goalBalance;
  enter(c, CharacterState::Active);  // set by hand: whatever the reaction was doing stops
  if (rootStrength > 0.0) makeRootDrive(c, rootStrength);
  islands_.wake(islands_.nodeOf(c.bones[0].body));
}

void World::setPartStrength(std::size_t k, const std::string& bone, Real share) {
  requireIndex(k, characters_.size(), "setPartStrength", "character");
  Character& c = characters_[k];
  c.partStrength[partOf(c, *c.now.clip, bone, share, "setPartStrength")] = share;
  islands_.wake(islands_.nodeOf(c.bones[0].body));
}

void World::setCharacterBalance(std::size_t k, Real balance) {
  requireIndex(k, characters_.size(), "setCharacterBalance", "character");
  require(balance >= 0.0 && balance <= 1.0, "setCharacterBalance: balance must be in [0, 1]");
  Character& c = characters_[k];
  c.goalBalance = balance;
  if (c.state == CharacterState::Active || c.state == CharacterState::LettingGo) c.balance = balance;
  if (balance > 0.0) makeRootDrive(c, 0.0);
  islands_.wake(islands_.nodeOf(c.bones[0].body));
}

void World::setCharacterTurnIn(std::size_t k, Real seconds) {
  requireIndex(k, characters_.size(), "setCharacterTurnIn", "character");
  checkTurnInTime(seconds, "setCharacterTurnIn");
  Character& c = characters_[k];
  c.turnInTime = seconds;
  c.turnIn = std::min(c.turnIn, seconds);
}

void World::setCharacterReaction(std::size_t k, const Reaction& reaction) {
  requireIndex(k, characters_.size(), "setCharacterReaction", "character");
  Character& c = characters_[k];
  checkReaction(reaction, *c.now.clip, "setCharacterReaction");
  if (reaction.getUp.clip) makeRootDrive(c, 0.0);
  c.reaction = reaction;
  islands_.wake(islands_.nodeOf(c.bones[0].body));
}

// Each substep: the clips move on by h and every character's drives are aimed at the pose for the
// substep's end, so that the drives pull towards where the part should be when they are solved.
void World::animate(Real h) {
  if (characters_.empty()) return;
  const detail::StageTimer timer(stageProfile(), Stage::Animate);
  noteBlows();
  for (Character& c : characters_) {
    rampStrengths(c, h);
    c.now.time += h * c.now.speed;
    if (c.queued && c.now.time >= c.queued->at) {
      characterPose(c);
      changeClip(c, c.queued->playback, c.queued->blendTime, c.pose.root);
      c.queued.reset();
    }
    if (c.blend < 1.0) {
      c.before.time += h * c.before.speed;
      c.blend = c.blendTime > 0.0 ? std::min(1.0, c.blend + h / c.blendTime) : 1.0;
    }
    characterPose(c);
    targetOrientations(c, c.pose, characterTargets_);
    if (c.turnInDue) {
      c.turnInDue = false;
      if (c.particleParts && c.turnInTime > 0.0 && farFromTargets(c)) c.turnIn = c.turnInTime;
    }
    const Real share = c.turnIn > 0.0 ? kTurnInShare : 1.0;
    for (std::size_t b = 1; b < c.bones.size(); ++b) {
      const CharacterBone& bone = c.bones[b];
      JointDrive drive =
          c.particleParts ? constraints_.particleDrives()[bone.joint] : constraints_.drives()[bone.joint];
      const Quat& parent = characterTargets_[static_cast<std::size_t>(bone.parent)];
      const Quat target = glm::normalize(glm::conjugate(parent) * characterTargets_[b]);
      drive.target = bone.reversed ? glm::conjugate(target) : target;
      drive.strength = c.strength * c.partStrength[b];
      if (c.particleParts) {
        constraints_.setParticleDrive(bone.joint, drive);
        constraints_.setParticleDriveShare(bone.joint, share);
      } else {
        constraints_.setDrive(bone.joint, drive);
      }
    }
    // This substep's passes take the share; the turn-in ends after the last substep within it (a
    // remainder of rounding, under a billionth of a substep, is none).
    c.turnIn = c.turnIn - h > 1e-9 * h ? c.turnIn - h : 0.0;
    if (c.rootStrength > 0.0) {
      setRootDrive(c, BodyDrive{rootCentre(c, c.pose), characterTargets_[0], c.rootStrength, c.rootStiffness,
                                c.rootAngularStiffness});
    } else if (keepsRootDrive(c)) {
      // Stiffness 0: the balance only turns the root, wherever it is; and only while the feet touch
      // something (Character::supported). Strength 0 keeps the drive, so it allocates nothing.
      setRootDrive(c, BodyDrive{poseOf(c.bones[0].body).center, balanceTarget(c, characterTargets_[0]),
                                c.supported ? c.balance : 0.0, 0.0, c.rootAngularStiffness});
    } else {
      constraints_.clearBodyDrive(c.bones[0].body);
    }
    if (characterMoves(c)) islands_.wake(islands_.nodeOf(c.bones[0].body));
  }
}

// Whether some part of the character is further than kTurnInGap from its target (characterTargets_,
// just found): far enough from its clip's pose for a turn-in.
bool World::farFromTargets(const Character& c) const {
  for (std::size_t b = 0; b < c.bones.size(); ++b) {
    const Quat q = poseOf(c.bones[b].body).orientation;
    const Real cosHalf = std::min(1.0, std::abs(glm::dot(q, characterTargets_[b])));
    if (2.0 * std::acos(cosHalf) > kTurnInGap) return true;
  }
  return false;
}

// The balance (docs/physics.md, "Balance"): the root's clip orientation `upright`, leaned about the
// feet so as to move the capture point (Pratt et al. 2006: where the centre of mass comes to rest
// over a point foot, c + v sqrt(h / g)) back over the support, the middle of its two lowest parts.
// A turn of the whole body by a about the feet moves the centre of mass by a h towards the lean, so
// the lean is the capture point's distance from the support over h, at most kMaxBalanceLean.
Quat World::balanceTarget(const Character& c, const Quat& upright) const {
  Real mass = 0.0;
  Vec3 com(0.0), velocity(0.0);
  Real lowY[2] = {std::numeric_limits<Real>::infinity(), std::numeric_limits<Real>::infinity()};
  Vec3 lowCentre[2] = {Vec3(0.0), Vec3(0.0)};
  for (std::size_t b = 0; b < c.bones.size(); ++b) {
    const PartMotion part = partMotion(c.bones[b].body);
    if (part.mass == 0.0) return upright;  // frozen: nothing to balance
    mass += part.mass;
    com += part.mass * part.centre;
    velocity += part.mass * part.velocity;
    const Real y = part.centre.y;
    if (y < lowY[0]) {
      lowCentre[1] = lowCentre[0], lowY[1] = lowY[0];
      lowCentre[0] = part.centre, lowY[0] = y;
    } else if (y < lowY[1]) {
      lowCentre[1] = part.centre, lowY[1] = y;
    }
  }
  com /= mass;
  velocity /= mass;
  const Vec3 g = gravityAt(com);
  const Real gLength = glm::length(g);
  if (gLength == 0.0 || c.bones.size() < 2) return upright;
  const Vec3 up = -g / gLength;
  const Vec3 support = 0.5 * (lowCentre[0] + lowCentre[1]);
  const Real height = glm::dot(com - support, up);
  if (height <= 0.0) return upright;
  Vec3 off = support - (com + velocity * std::sqrt(height / gLength));
  off -= up * glm::dot(off, up);
  const Real distance = glm::length(off);
  if (distance < 1e-9) return upright;
  const Real lean = std::min(distance / height, kMaxBalanceLean);
  return glm::normalize(glm::angleAxis(lean, glm::cross(up, off / distance)) * upright);
}

// Once a step, for each balancing character: whether it stands on its support (Character::support,
// its feet): its centre of mass at least kStandingShare of its standing height over them, and one of
// them touching the ground or a body that is not one of its own parts, of the last substep's
// contacts and of the step's for the ground points of particle parts. One walk over the contacts for
// every character, as noteBlows.
void World::findSupports() {
  supportParts_.resize(characters_.size());  // sized again only when a character is added
  bool any = false;
  for (std::size_t k = 0; k < characters_.size(); ++k) {
    Character& c = characters_[k];
    std::array<BodyId, 2>& low = supportParts_[k];
    low = {kNoBody, kNoBody};
    if (c.balance <= 0.0 && c.goalBalance <= 0.0) continue;  // never read: left as it was
    c.supported = false;
    any = true;
    if (standsOverSupport(c)) low = {c.bones[c.support[0]].body, c.bones[c.support[1]].body};
  }
  if (!any) return;
  auto characterOf = [this](BodyId body) {
    return body != kNoBody && body < bodyCharacter_.size() ? bodyCharacter_[body] : -1;
  };
  // `part` touches `other` (kNoBody: the ground): a support part touching what is not its own.
  auto touch = [&](BodyId part, BodyId other) {
    const int k = characterOf(part);
    if (k < 0) return;
    const std::array<BodyId, 2>& low = supportParts_[static_cast<std::size_t>(k)];
    if ((part == low[0] || part == low[1]) && characterOf(other) != k)
      characters_[static_cast<std::size_t>(k)].supported = true;
  };
  // Rigid parts' contacts with bodies, and with the ground (their own list, the ground kNoBody).
  for (const auto& [rigid, state] :
       {std::pair{std::span<const RigidContact>(narrowPhase_.rigidContacts()),
                  static_cast<const RigidContactState*>(&narrowPhase_.rigidState())},
        std::pair{std::span<const RigidContact>(rigidGround_),
                  static_cast<const RigidContactState*>(&rigidGroundState_)}}) {
    for (std::size_t k = 0; k < std::min(rigid.size(), state->touched.size()); ++k) {
      if (state->touched[k] == 0) continue;
      touch(rigid[k].bodyA, rigid[k].bodyB);
      touch(rigid[k].bodyB, rigid[k].bodyA);
    }
  }
  const std::span<const BodyContact> bodies = narrowPhase_.contacts();
  const std::vector<std::uint8_t>& bodyTouched = narrowPhase_.state().touched;
  for (std::size_t k = 0; k < std::min(bodies.size(), bodyTouched.size()); ++k) {
    if (bodyTouched[k] == 0) continue;
    touch(bodies[k].bodyA, bodies[k].bodyB);
    touch(bodies[k].bodyB, bodies[k].bodyA);
  }
  const std::span<const GroundContact> ground = ground_.points();
  const std::vector<std::uint8_t>& groundTouched = ground_.state().touched;
  for (std::size_t k = 0; k < std::min(ground.size(), groundTouched.size()); ++k) {
    if (groundTouched[k] != 0) touch(ground[k].body, kNoBody);
  }
}

// Whether the character's centre of mass is over its support (Character::support) by at least
// kStandingShare of its standing height, along the world's up there: standing, or leaning as far
// as the balance can bring back, not fallen. Lying, its forearms or its torso touch the ground and
// its feet may too; the balance, which leans a standing body about its feet, then turned the whole
// body towards its clip's upright and flung it about.
bool World::standsOverSupport(const Character& c) const {
  if (c.bones.size() < 2) return false;
  Real mass = 0.0;
  Vec3 com(0.0);
  for (const CharacterBone& bone : c.bones) {
    const PartMotion part = partMotion(bone.body);
    mass += part.mass;
    com += part.mass * part.centre;
  }
  if (mass <= 0.0) return false;
  com /= mass;
  const Vec3 g = gravityAt(com);
  const Real gLength = glm::length(g);
  const Vec3 up = gLength > 0.0 ? -g / gLength : Vec3(0.0, 1.0, 0.0);
  const Vec3 support =
      0.5 * (poseOf(c.bones[c.support[0]].body).center + poseOf(c.bones[c.support[1]].body).center);
  return glm::dot(com - support, up) >= kStandingShare * c.standingHeight;
}

// Each substep, of the last one's contacts: a body that is not one of a character's parts striking
// one that is, at the closing speed its contact measured before the passes pushed it.
void World::noteBlows() {
  auto characterOf = [this](BodyId body) { return body < bodyCharacter_.size() ? bodyCharacter_[body] : -1; };
  auto note = [&](BodyId bodyA, BodyId bodyB, Real closing) {
    if (bodyA == kNoBody || bodyB == kNoBody) return;  // the ground is no blow
    const int a = characterOf(bodyA), b = characterOf(bodyB);
    if (a == b) return;  // its own parts, or two bodies of no character
    for (const int side : {a, b}) {
      if (side < 0) continue;
      Real& blow = characters_[static_cast<std::size_t>(side)].stepBlow;
      blow = std::max(blow, closing);
    }
  };
  const std::span<const RigidContact> contacts = narrowPhase_.rigidContacts();
  const RigidContactState& state = narrowPhase_.rigidState();
  const std::size_t n = std::min({contacts.size(), state.touched.size(), state.approach.size()});
  for (std::size_t k = 0; k < n; ++k) {
    // A rigid contact's approach is its separation speed: negative closing.
    if (state.touched[k] && state.approach[k] < 0.0)
      note(contacts[k].bodyA, contacts[k].bodyB, -state.approach[k]);
  }
  // Particle bodies' contacts, whose approach measureApproaches takes while a character has particle
  // parts: their points' closing speed, positive closing, as restitution reads it.
  const std::span<const BodyContact> particleContacts = narrowPhase_.contacts();
  const BodyContactState& particleState = narrowPhase_.state();
  const std::size_t m =
      std::min({particleContacts.size(), particleState.touched.size(), particleState.approach.size()});
  for (std::size_t k = 0; k < m; ++k) {
    if (particleState.touched[k] && particleState.approach[k] > 0.0)
      note(particleContacts[k].bodyA, particleContacts[k].bodyB, particleState.approach[k]);
  }
}

// Once a step, after its substeps: each character's blow (the fastest strike on its parts by
// another body, or its root part's speed change over the step: a push, a fall; free fall changes
// it by g dt, 0.16 m/s at 1/60 s) against its reaction's threshold; and how long it has lain still,
// to get up.
void World::react() {
  if (characters_.empty()) return;
  const detail::StageTimer timer(stageProfile(), Stage::Animate);
  findSupports();
  for (Character& c : characters_) {
    const PartMotion root = partMotion(c.bones[0].body);  // a particle part's is a pass over its particles
    const Real impact = std::max(c.stepBlow, glm::length(root.velocity - c.lastRootVelocity));
    c.lastRootVelocity = root.velocity;
    c.stepBlow = 0.0;
    bool still = glm::length(root.velocity) < c.reaction.restSpeed;
    for (std::size_t b = 1; b < c.bones.size(); ++b)
      still = still && glm::length(partMotion(c.bones[b].body).velocity) < c.reaction.restSpeed;
    c.lastImpact = impact;
    c.stillTime = still ? c.stillTime + solver_.dt : 0.0;
    // Only an active character reacts, and only once it has been so for armTime: getting up, or
    // starting a run from standing at full speed, its drives' own jolts are not blows.
    const bool armed = c.state == CharacterState::Active && c.stateTime >= c.reaction.armTime;
    if (armed && c.reaction.threshold > 0.0 && impact > c.reaction.threshold) {
      enter(c, CharacterState::Falling);
      c.queued.reset();
    } else if (c.state == CharacterState::Down && c.reaction.getUp.clip &&
               c.stillTime >= c.reaction.restTime) {
      // Up where it lies: the get-up clip's root path starts under the root part's centre.
      const Vec3 lying =
          glm::conjugate(c.frame) * (root.centre - c.origin) / c.scale - turnedRootOffset(c, c.pose);
      changeClip(c, c.reaction.getUp, 0.0, lying);
      enter(c, CharacterState::GettingUp);
    }
  }
}

// Each character whose drives move it (as animate wakes it for) is held awake by its root: at rest
// it would otherwise fall asleep at a step's end and be woken in the next step's first substep,
// after the masks, to stand pinned for that step (and for good with a sleep time under a step).
std::size_t World::holdMovingCharacters(std::span<NodeId> into) const {
  std::size_t n = 0;
  for (const Character& c : characters_) {
    if (characterMoves(c)) into[n++] = islands_.nodeOf(c.bones[0].body);
  }
  return n;
}

bool World::anyCharacterActive() const {
  return std::any_of(characters_.begin(), characters_.end(),
                     [](const Character& c) { return characterMoves(c); });
}

}  // namespace phys
