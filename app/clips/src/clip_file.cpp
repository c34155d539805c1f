// Clips from files through assimp (clips/clip_file.h).
#include "clips/clip_file.h"

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <system_error>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/scene.h>

#include "fileio/files.h"

namespace clips {
namespace {

// Larger than any clip we would play: minutes of motion capture of a full skeleton.
constexpr std::size_t kMaxClipBytes = 64u << 20;

const aiNodeAnim* channelOf(const aiAnimation& a, const aiString& node) {
  for (unsigned c = 0; c < a.mNumChannels; ++c) {
    if (a.mChannels[c]->mNodeName == node) return a.mChannels[c];
  }
  return nullptr;
}

phys::Quat toQuat(const aiQuaternion& q) {
  return phys::Quat(q.w, q.x, q.y, q.z);
}

phys::Quat rotationOf(const aiMatrix4x4& m) {
  aiVector3D scaling, position;
  aiQuaternion rotation;
  m.Decompose(scaling, rotation, position);
  return glm::normalize(toQuat(rotation));
}

// An animated node: its channel, its rotation in the file's rest pose (the node's own transform,
// relative to its parent node), and its parent node's rest transform in the file's frame (animated
// or not: FBX and glTF put whole armatures, turned and scaled, under the scene's root).
struct Animated {
  const aiNodeAnim* channel;
  phys::Quat rest;
  aiMatrix4x4 parentRest;
  phys::Quat parentTurn;  // parentRest's rotation
};

// The animated nodes in depth-first order, each with the nearest animated ancestor as its parent.
void collectBones(const aiNode& node, const aiMatrix4x4& parentRest, int parent, const aiAnimation& a,
                  phys::Clip& clip, std::vector<Animated>& bones) {
  int self = parent;
  if (const aiNodeAnim* channel = channelOf(a, node.mName)) {
    self = static_cast<int>(clip.bones.size());
    clip.bones.emplace_back(node.mName.C_Str());
    clip.parents.push_back(parent);
    bones.push_back({channel, rotationOf(node.mTransformation), parentRest, rotationOf(parentRest)});
  }
  const aiMatrix4x4 rest = parentRest * node.mTransformation;
  for (unsigned i = 0; i < node.mNumChildren; ++i)
    collectBones(*node.mChildren[i], rest, self, a, clip, bones);
}

// A key's local rotation K taken back to the turn from rest a clip holds. A bone turned by K from
// its parent node, whose rest is P in the file's frame and whose own rest rotation is R, is turned
// from rest by P K R^-1 P^-1 relative to its parent's turn, in the file's frame (docs/physics.md,
// "Animation"). In BVH every rest rotation is the identity, and the key is the turn. Only rotations
// are composed: a node scaled unevenly above a bone is taken as if its scale were even.
phys::Quat turnFromRest(const Animated& bone, const aiQuaternion& key) {
  const phys::Quat& parent = bone.parentTurn;
  return glm::normalize(parent * toQuat(key) * glm::conjugate(bone.rest) * glm::conjugate(parent));
}

}  // namespace

ClipError::ClipError(const std::filesystem::path& file, const std::string& why)
    : std::runtime_error(file.string() + ": " + why) {}

phys::Clip parseClip(std::string_view content, const std::string& name, const std::string& format) {
  Assimp::Importer importer;
  // FBX's pivots as the nodes' own transforms, not as helper nodes the animation would key instead.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
  const aiScene* scene = importer.ReadFileFromMemory(content.data(), content.size(), 0, format.c_str());
  if (scene == nullptr) {
    // Read from memory, assimp names the file after its placeholder ("$$$___magic___$$$.sh"),
    // which the message has already said before the colon: the placeholder goes.
    std::string why = importer.GetErrorString();
    const std::string placeholder =
        std::string(" of file \"") + AI_MEMORYIO_MAGIC_FILENAME + "." + format + "\"";
    if (const std::size_t at = why.find(placeholder); at != std::string::npos)
      why.erase(at, placeholder.size());
    throw ClipError(name, "not a clip assimp can read: " + why);
  }
  if (scene->mNumAnimations == 0 || scene->mRootNode == nullptr)
    throw ClipError(name, "it holds no animation");
  const aiAnimation& anim = *scene->mAnimations[0];
  phys::Clip clip;
  clip.name = name;
  std::vector<Animated> bones;
  collectBones(*scene->mRootNode, aiMatrix4x4(), -1, anim, clip, bones);
  if (clip.bones.empty()) throw ClipError(name, "its animation moves no node of its skeleton");
  for (std::size_t b = 1; b < clip.bones.size(); ++b) {
    if (clip.parents[b] < 0)
      throw ClipError(name, "bones '" + clip.bones[0] + "' and '" + clip.bones[b] + "' are two roots");
  }
  const aiNodeAnim& root = *bones[0].channel;
  const unsigned frames = root.mNumRotationKeys;
  // assimp gives 0 ticks a second for a file that does not say, and then takes 25 itself; a BVH
  // always says (1 / its Frame Time), so there a tick rate that is not a finite number > 0 is a
  // Frame Time that is not one (-1 gave -1, nan nan), refused rather than guessed.
  const bool bvh = format == "bvh" || format == "BVH";
  const double ticksGiven = anim.mTicksPerSecond;
  if (!(ticksGiven >= 0.0 && std::isfinite(ticksGiven)) || (bvh && ticksGiven == 0.0))
    throw ClipError(name, bvh ? "its Frame Time is not a finite number of seconds > 0"
                              : "its animation's ticks per second are negative or not a finite number");
  const double ticks = ticksGiven > 0.0 ? ticksGiven : 25.0;  // assimp's own default
  // A BVH's animation lasts its Frames less one; assimp keys "Frames: 0" once, with a duration of
  // 2^32 - 1, and that lone key is no frame of the file's.
  if (frames == 0 || (bvh && anim.mDuration + 1.0 != static_cast<double>(frames)))
    throw ClipError(name, "it has no frames");
  // Frames evenly spaced, every bone keyed at every frame, the root's position too: what a BVH file
  // holds, and all a clip keeps.
  clip.frameTime =
      frames > 1 ? (root.mRotationKeys[1].mTime - root.mRotationKeys[0].mTime) / ticks : 1.0 / ticks;
  for (std::size_t b = 0; b < bones.size(); ++b) {
    const aiNodeAnim& ch = *bones[b].channel;
    if (ch.mNumRotationKeys != frames)
      throw ClipError(name, "bone '" + clip.bones[b] + "' has " + std::to_string(ch.mNumRotationKeys) +
                                " turns where the root has " + std::to_string(frames) + " frames");
    for (unsigned f = 0; f < frames; ++f) {
      const double expected = root.mRotationKeys[0].mTime + f * clip.frameTime * ticks;
      if (std::abs(ch.mRotationKeys[f].mTime - expected) > 1e-6 * (1.0 + std::abs(expected)))
        throw ClipError(name,
                        "bone '" + clip.bones[b] + "': frame " + std::to_string(f) + " is not evenly spaced");
    }
  }
  if (root.mNumPositionKeys != frames)
    throw ClipError(name, "the root '" + clip.bones[0] + "' has " + std::to_string(root.mNumPositionKeys) +
                              " positions for " + std::to_string(frames) + " frames");
  clip.root.resize(frames);
  clip.turns.resize(static_cast<std::size_t>(frames) * clip.bones.size());
  for (unsigned f = 0; f < frames; ++f) {
    // The root's position is in its parent node's space: put in the file's frame.
    const aiVector3D p = bones[0].parentRest * root.mPositionKeys[f].mValue;
    clip.root[f] = phys::Vec3(p.x, p.y, p.z);
    for (std::size_t b = 0; b < bones.size(); ++b) {
      const aiQuaternion& key = bones[b].channel->mRotationKeys[f].mValue;
      // A key of no length or not finite is kept as it is for clipProblem to name: glm::normalize
      // would make it the identity or NaN.
      const double length = std::sqrt(key.w * key.w + key.x * key.x + key.y * key.y + key.z * key.z);
      clip.turns[f * clip.bones.size() + b] =
          std::isfinite(length) && length > 0.0 ? turnFromRest(bones[b], key) : toQuat(key);
    }
  }
  if (const std::string problem = phys::clipProblem(clip); !problem.empty()) throw ClipError(name, problem);
  return clip;
}

phys::Clip loadClip(const std::filesystem::path& file) {
  // Only a regular file: a clip is named by a scene, and a pipe there with no writer would block
  // the loader in open() for good (a scene file itself may come from a pipe the user opens).
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(file, error);
  if (!error && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw ClipError(file, "is not a regular file (a folder, pipe, device or socket)");
  std::string content;
  try {
    content = fileio::readWhole(file, kMaxClipBytes);
  } catch (const fileio::FileError& e) {
    throw ClipError(file, e.message());
  }
  std::string format = file.extension().string();
  if (!format.empty()) format.erase(0, 1);
  return parseClip(content, file.string(), format);
}

}  // namespace clips
