// Characters (physics/character.h): binding a clip to a ragdoll by name, and the step's first
// stage, which moves each character's drive targets along its clip.
#include "physics/character.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/quaternion.hpp>

#include "physics/ragdoll.h"
#include "physics/world.h"
#include "require.h"
#include "stage_timer.h"

namespace phys {
namespace {

using detail::require;

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
  return s;
}

// The rigid joint between two rigid bodies, either way round; false when there is none.
bool jointBetween(const World& world, RigidId parent, RigidId child, std::size_t& joint, bool& reversed) {
  const std::span<const RigidJoint> joints = world.rigidJoints();
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
  require(std::isfinite(p.time), who + ": the clip's time must be finite");
  require(std::isfinite(p.speed) && p.speed >= 0.0, who + ": the clip's speed must be finite and >= 0");
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

// The target pose: the clip playing, blended from the one before while it fades in.
void characterPose(Character& c) {
  samplePlayback(c.now, Vec3(0.0), c.pose);
  if (c.blend >= 1.0) return;
  samplePlayback(c.before, c.beforeShift, c.fading);
  blendPoses(c.fading, c.pose, c.blend, c.pose);
}

// The same bones, in the same order, with the same parents: a clip the binding fits.
bool sameSkeleton(const Clip& a, const Clip& b) {
  return a.bones == b.bones && a.parents == b.parents;
}

}  // namespace

std::vector<CharacterBone> bindClip(const World& world, const std::string& ragdoll, const Clip& clip) {
  const std::string who = "clip '" + clip.name + "' on ragdoll '" + ragdoll + "'";
  const std::string prefix = ragdoll + ".";
  std::vector<std::string> partNames;
  std::vector<BodyId> partIds;
  const std::span<const Body> bodies = world.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].name.size() > prefix.size() && bodies[i].name.starts_with(prefix)) {
      partNames.push_back(bodies[i].name.substr(prefix.size()));
      partIds.push_back(BodyId(static_cast<std::uint32_t>(i)));
    }
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
  for (std::size_t b = 0; b < clip.bones.size(); ++b) {
    const auto at = std::find(partNames.begin(), partNames.end(), clip.bones[b]) - partNames.begin();
    CharacterBone& bone = bones[b];
    bone.body = partIds[static_cast<std::size_t>(at)];
    bone.clipBone = static_cast<int>(b);
    bone.parent = clip.parents[b];
    require(bodies[bone.body].model == BodyModel::Rigid,
            who + ": part '" + clip.bones[b] + "' is not rigid (only rigid ragdolls have drives)");
    if (bone.parent < 0) continue;
    const CharacterBone& parent = bones[static_cast<std::size_t>(bone.parent)];
    require(
        jointBetween(world, bodies[parent.body].rigid, bodies[bone.body].rigid, bone.joint, bone.reversed),
        who + ": bone '" + clip.bones[b] + "': no rigid joint joins it to its parent '" +
            clip.bones[static_cast<std::size_t>(bone.parent)] + "'");
    const Quat rest = world.jointRest(bone.joint);
    bone.rest = parent.rest * (bone.reversed ? glm::conjugate(rest) : rest);
  }
  return bones;
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

Real trackingError(const World& world, std::size_t k) {
  require(k < world.characters().size(), "trackingError: character index must exist");
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

std::size_t World::addCharacter(const CharacterDesc& desc) {
  const std::string who = "addCharacter";
  checkPlayback(desc.playback, who);
  checkStrengths(desc.strength, desc.rootStrength, who);
  require(std::isfinite(desc.scale) && desc.scale > 0.0, who + ": scale must be finite and > 0");
  Character c;
  c.ragdoll = desc.ragdoll;
  c.bones = bindClip(*this, desc.ragdoll, *desc.playback.clip);
  c.now = desc.playback;
  c.strength = desc.strength;
  c.rootStrength = desc.rootStrength;
  c.scale = desc.scale;
  // The clip's frame is where the root is now: turned so that the clip's first pose puts the root
  // part as it is, with the clip's root path starting at its centre.
  const BodyId root = c.bones[0].body;
  const BodyPose pose = bodyPose(root);
  sampleClip(*c.now.clip, c.now.time, c.now.loop, c.pose);
  c.frame = glm::normalize(pose.orientation * glm::conjugate(c.pose.turns[0]));
  c.origin = pose.center - c.frame * (c.scale * c.pose.root);
  // The root's drive: as stiff as the one it has, else the ragdolls' default for this mass.
  Real mass = 0.0;
  for (const CharacterBone& bone : c.bones) mass += bodyMass(bone.body).mass;
  const std::optional<BodyDrive> had = bodyDrive(root);
  c.rootStiffness = had ? had->stiffness : kBodyDriveStiffness * mass / kRagdollDriveMass / c.scale;
  c.rootAngularStiffness = had ? had->angularStiffness : kDriveStiffness * mass / kRagdollDriveMass * c.scale;
  // Scratch sized now, not reserved: a copied World (the sandbox's rewind) keeps sizes, not capacities.
  c.fading.turns.resize(c.pose.turns.size());
  // The root's drive made now, so that the step only aims it and never allocates for it.
  if (c.rootStrength > 0.0)
    constraints_.setBodyDrive(bodies_[root].rigid, BodyDrive{pose.center, pose.orientation, c.rootStrength,
                                                             c.rootStiffness, c.rootAngularStiffness});
  characterTargets_.resize(std::max(characterTargets_.size(), c.bones.size()));
  characters_.push_back(std::move(c));
  return characters_.size() - 1;
}

void World::playClip(std::size_t k, const Playback& playback, Real blendTime) {
  const std::string who = "playClip";
  require(k < characters_.size(), who + ": character index must exist");
  checkPlayback(playback, who);
  require(std::isfinite(blendTime) && blendTime >= 0.0, who + ": blend time must be finite and >= 0");
  Character& c = characters_[k];
  require(sameSkeleton(*playback.clip, *c.now.clip),
          who + ": clip '" + playback.clip->name + "' has other bones than '" + c.now.clip->name + "'");
  // The new clip's root path starts where the target is now, across the ground (the clip frame's
  // x and z); its height stays the clip's own.
  characterPose(c);
  ClipPose start;
  sampleClip(*playback.clip, playback.time, playback.loop, start);
  Vec3 shift = c.pose.root - start.root;
  shift.y = 0.0;
  c.origin += c.frame * (c.scale * shift);
  c.before = c.now;
  c.beforeShift = shift;
  c.now = playback;
  c.blendTime = blendTime;
  c.blend = blendTime > 0.0 ? 0.0 : 1.0;
  islands_.wake(islands_.bodyNode(c.bones[0].body));
}

void World::setCharacterStrength(std::size_t k, Real strength, Real rootStrength) {
  require(k < characters_.size(), "setCharacterStrength: character index must exist");
  checkStrengths(strength, rootStrength, "setCharacterStrength");
  Character& c = characters_[k];
  c.strength = strength;
  c.rootStrength = rootStrength;
  const BodyId root = c.bones[0].body;
  if (rootStrength > 0.0 && !bodyDrive(root)) {
    const BodyPose pose = bodyPose(root);
    constraints_.setBodyDrive(bodies_[root].rigid, BodyDrive{pose.center, pose.orientation, rootStrength,
                                                             c.rootStiffness, c.rootAngularStiffness});
  }
  islands_.wake(islands_.bodyNode(characters_[k].bones[0].body));
}

// Each substep: the clips move on by h and every character's drives are aimed at the pose for the
// substep's end, so that the drives pull towards where the part should be when they are solved.
void World::animate(Real h) {
  if (characters_.empty()) return;
  const detail::StageTimer timer(profile_, Stage::Animate);
  for (Character& c : characters_) {
    c.now.time += h * c.now.speed;
    if (c.blend < 1.0) {
      c.before.time += h * c.before.speed;
      c.blend = c.blendTime > 0.0 ? std::min(1.0, c.blend + h / c.blendTime) : 1.0;
    }
    characterPose(c);
    targetOrientations(c, c.pose, characterTargets_);
    for (std::size_t b = 1; b < c.bones.size(); ++b) {
      const CharacterBone& bone = c.bones[b];
      JointDrive drive = constraints_.drives()[bone.joint];
      const Quat& parent = characterTargets_[static_cast<std::size_t>(bone.parent)];
      const Quat target = glm::normalize(glm::conjugate(parent) * characterTargets_[b]);
      drive.target = bone.reversed ? glm::conjugate(target) : target;
      drive.strength = c.strength;
      constraints_.setDrive(bone.joint, drive);
    }
    const Body& root = bodies_[c.bones[0].body];
    if (c.rootStrength > 0.0) {
      const BodyDrive drive{c.origin + c.frame * (c.scale * c.pose.root), characterTargets_[0],
                            c.rootStrength, c.rootStiffness, c.rootAngularStiffness};
      constraints_.setBodyDrive(root.rigid, drive);
    } else {
      constraints_.clearBodyDrive(root.rigid);
    }
    if (c.strength > 0.0 || c.rootStrength > 0.0) islands_.wake(islands_.bodyNode(c.bones[0].body));
  }
}

bool World::anyCharacterActive() const {
  return std::any_of(characters_.begin(), characters_.end(),
                     [](const Character& c) { return c.strength > 0.0 || c.rootStrength > 0.0; });
}

}  // namespace phys
