// Clips from files through assimp (clips/clip_file.h).
#include "clips/clip_file.h"

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <system_error>
#include <vector>

#include <assimp/Importer.hpp>
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

// The animated nodes in depth-first order, each with the nearest animated ancestor as its parent.
void collectBones(const aiNode& node, int parent, const aiAnimation& a, phys::Clip& clip,
                  std::vector<const aiNodeAnim*>& channels) {
  int self = parent;
  if (const aiNodeAnim* channel = channelOf(a, node.mName)) {
    self = static_cast<int>(clip.bones.size());
    clip.bones.emplace_back(node.mName.C_Str());
    clip.parents.push_back(parent);
    channels.push_back(channel);
  }
  for (unsigned i = 0; i < node.mNumChildren; ++i) collectBones(*node.mChildren[i], self, a, clip, channels);
}

phys::Quat toQuat(const aiQuaternion& q) {
  return phys::Quat(q.w, q.x, q.y, q.z);
}

}  // namespace

ClipError::ClipError(const std::filesystem::path& file, const std::string& why)
    : std::runtime_error(file.string() + ": " + why) {}

phys::Clip parseClip(std::string_view content, const std::string& name, const std::string& format) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFileFromMemory(content.data(), content.size(), 0, format.c_str());
  if (scene == nullptr)
    throw ClipError(name, std::string("not a clip assimp can read: ") + importer.GetErrorString());
  if (scene->mNumAnimations == 0 || scene->mRootNode == nullptr)
    throw ClipError(name, "it holds no animation");
  const aiAnimation& anim = *scene->mAnimations[0];
  phys::Clip clip;
  clip.name = name;
  std::vector<const aiNodeAnim*> channels;
  collectBones(*scene->mRootNode, -1, anim, clip, channels);
  if (clip.bones.empty()) throw ClipError(name, "its animation moves no node of its skeleton");
  for (std::size_t b = 1; b < clip.bones.size(); ++b) {
    if (clip.parents[b] < 0)
      throw ClipError(name, "bones '" + clip.bones[0] + "' and '" + clip.bones[b] + "' are two roots");
  }
  const aiNodeAnim& root = *channels[0];
  const unsigned frames = root.mNumRotationKeys;
  const double ticks = anim.mTicksPerSecond > 0.0 ? anim.mTicksPerSecond : 25.0;  // assimp's own default
  if (frames == 0) throw ClipError(name, "it has no frames");
  // Frames evenly spaced, every bone keyed at every frame, the root's position too: what a BVH file
  // holds, and all a clip keeps.
  clip.frameTime =
      frames > 1 ? (root.mRotationKeys[1].mTime - root.mRotationKeys[0].mTime) / ticks : 1.0 / ticks;
  for (std::size_t b = 0; b < channels.size(); ++b) {
    const aiNodeAnim& ch = *channels[b];
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
    const aiVector3D& p = root.mPositionKeys[f].mValue;
    clip.root[f] = phys::Vec3(p.x, p.y, p.z);
    for (std::size_t b = 0; b < channels.size(); ++b) {
      phys::Quat q = toQuat(channels[b]->mRotationKeys[f].mValue);
      const double length = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
      if (std::isfinite(length) && length > 0.0) q /= length;  // assimp's are floats: made unit again
      clip.turns[f * clip.bones.size() + b] = q;
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
