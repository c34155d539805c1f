// Clips from files through assimp (clips/clip_file.h).
#include "clips/clip_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include <assimp/BaseImporter.h>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/scene.h>

#include "fileio/files.h"
#include "fileio/printable.h"
#include "format_checks.h"
#include "skeleton_only.h"

namespace clips {
namespace {

// Larger than any clip we would play: minutes of motion capture of a full skeleton.

// Ticks a second of an animation whose file does not say: a .x file's (DirectX's default), any
// other's (assimp's).
constexpr double kXDefaultTicks = 4800.0;
constexpr double kAssimpDefaultTicks = 25.0;

// The animation's channels by the name of the node each moves, the first where two name one node
// (as assimp's own lookups take it). A node's channel was looked for among all of them, once a node:
// 20,000 channels and nodes took seconds.
class ChannelsByNode {
 public:
  explicit ChannelsByNode(const aiAnimation& a) {
    byName_.reserve(a.mNumChannels);
    for (unsigned c = 0; c < a.mNumChannels; ++c)
      byName_.emplace(nameOf(a.mChannels[c]->mNodeName), a.mChannels[c]);
  }
  /// The channel that moves `node`, nullptr if none does.
  const aiNodeAnim* of(const aiString& node) const {
    const auto found = byName_.find(nameOf(node));
    return found == byName_.end() ? nullptr : found->second;
  }

 private:
  static std::string_view nameOf(const aiString& s) { return {s.data, s.length}; }
  std::unordered_map<std::string_view, const aiNodeAnim*> byName_;
};

phys::Quat toQuat(const aiQuaternion& q) {
  return phys::Quat(q.w, q.x, q.y, q.z);
}

phys::Quat rotationOf(const aiMatrix4x4& m) {
  aiVector3D scaling, position;
  aiQuaternion rotation;
  m.Decompose(scaling, rotation, position);
  return glm::normalize(toQuat(rotation));
}

// The formats a clip is read from, by extension (a BVH also by its first word), and the check each
// is given before assimp reads it. assimp reads some forty more, most of them meshes with no
// skeleton; each is a reader more for a hostile file to reach, so none of them is asked.
struct ClipFormat {
  const char* extension;
  void (*check)(std::string_view content, const std::string& name);
  // The file as assimp is given it (skeleton_only.h), if not as it is.
  std::optional<std::string> (*skeletonOnly)(std::string_view content, const std::string& name);
};
constexpr ClipFormat kClipFormats[] = {{"bvh", detail::checkBvh, nullptr},
                                       {"fbx", detail::checkFbx, detail::fbxSkeletonOnly},
                                       {"gltf", detail::checkGltf, detail::gltfSkeletonOnly},
                                       {"glb", detail::checkGlb, detail::glbSkeletonOnly},
                                       {"dae", detail::checkCollada, detail::colladaSkeletonOnly},
                                       {"x", detail::checkX, detail::xSkeletonOnly}};

// No file but the one in memory: a glTF names its buffers by path, which assimp opened from the
// working folder (not the clip's), and any path at all: a pipe there held the reader for good.
class NoOtherFiles : public Assimp::IOSystem {
 public:
  bool Exists(const char* /*file*/) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* /*file*/, const char* /*mode*/) override { return nullptr; }
  void Close(Assimp::IOStream* file) override { delete file; }
};

// assimp keeps a reader of glTF 1.0 beside glTF 2.0's, both for .gltf and .glb. Exporters have
// written 2.0 since 2017, and the 1.0 reader recursed once a level of a binary file's JSON
// unchecked (300,000 '[' overflowed the stack): a clip is read as glTF 2.0 or not at all.
bool isGltf1Reader(const Assimp::BaseImporter& reader) {
  return std::string_view(reader.GetInfo()->mName) == "glTF Importer";
}

// Leaves `importer` only the reader of `extension`, so that the file is read as the format its
// check assumed, whatever its bytes look like to the other readers.
void keepOnlyReaderOf(Assimp::Importer& importer, const std::string& extension) {
  for (std::size_t i = importer.GetImporterCount(); i-- > 0;) {
    Assimp::BaseImporter* reader = importer.GetImporter(i);
    std::set<std::string> extensions;
    reader->GetExtensionList(extensions);
    if (extensions.contains(extension) && !isGltf1Reader(*reader)) continue;
    importer.UnregisterLoader(reader);
    delete reader;  // unregistered, it is ours
  }
}

// What a clip reads of an FBX: its nodes and their animation. Its skins' weights (a cluster's
// vertex index is taken unchecked: 99 on a mesh of 3 failed an assertion that aborts), materials,
// textures, cameras and lights are left unread.
void readOnlySkeletons(Assimp::Importer& importer) {
  // FBX's pivots as the nodes' own transforms, not as helper nodes the animation would key instead.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
  for (const char* part : {AI_CONFIG_IMPORT_FBX_READ_WEIGHTS, AI_CONFIG_IMPORT_FBX_READ_MATERIALS,
                           AI_CONFIG_IMPORT_FBX_READ_TEXTURES, AI_CONFIG_IMPORT_FBX_READ_CAMERAS,
                           AI_CONFIG_IMPORT_FBX_READ_LIGHTS})
    importer.SetPropertyBool(part, false);
}

// assimp's reason for refusing a file read from memory, and the line it names (0 if none). assimp
// names the file after its placeholder ("$$$___magic___$$$.bvh"), which the message has already
// said before the colon: the placeholder goes, and a line it gives is kept.
struct AssimpReason {
  std::string why;
  std::size_t line = 0;
};

AssimpReason assimpReason(std::string why, const std::string& format) {
  const std::string placeholder = std::string(AI_MEMORYIO_MAGIC_FILENAME) + "." + format;
  // Most readers: "... of file \"PLACEHOLDER\"".
  const std::string ofFile = " of file \"" + placeholder + "\"";
  if (const std::size_t at = why.find(ofFile); at != std::string::npos) why.erase(at, ofFile.size());
  // BVH's: "PLACEHOLDER:LINE - why".
  if (why.starts_with(placeholder + ":")) {
    const char* const begin = why.data() + placeholder.size() + 1;
    std::size_t line = 0;
    const auto [end, error] = std::from_chars(begin, why.data() + why.size(), line);
    const std::string_view rest(end, static_cast<std::size_t>(why.data() + why.size() - end));
    if (error == std::errc() && rest.starts_with(" - ")) return {std::string(rest.substr(3)), line};
  }
  return {why, 0};
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
void collectBones(const aiNode& node, const aiMatrix4x4& parentRest, int parent,
                  const ChannelsByNode& channels, phys::Clip& clip, std::vector<Animated>& bones) {
  int self = parent;
  if (const aiNodeAnim* channel = channels.of(node.mName)) {
    self = static_cast<int>(clip.bones.size());
    clip.bones.emplace_back(node.mName.C_Str());
    clip.parents.push_back(parent);
    bones.push_back({channel, rotationOf(node.mTransformation), parentRest, rotationOf(parentRest)});
  }
  const aiMatrix4x4 rest = parentRest * node.mTransformation;
  for (unsigned i = 0; i < node.mNumChildren; ++i)
    collectBones(*node.mChildren[i], rest, self, channels, clip, bones);
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
    : std::runtime_error(file.string() + ": " + fileio::printableReason(why)) {}

ClipError::ClipError(const std::filesystem::path& file, std::size_t line, const std::string& why)
    : std::runtime_error(file.string() + ":" + std::to_string(line) + ": " + fileio::printableReason(why)) {}

phys::Clip parseClip(std::string_view content, const std::string& name, const std::string& givenFormat) {
  // An extension in any case: "Bvh" is a BVH file too.
  std::string format = givenFormat;
  std::transform(format.begin(), format.end(), format.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const bool bvh = detail::isBvh(content, format);
  if (bvh) format = "bvh";
  const auto* known = std::find_if(std::begin(kClipFormats), std::end(kClipFormats),
                                   [&](const ClipFormat& f) { return format == f.extension; });
  if (known == std::end(kClipFormats))
    throw ClipError(name,
                    "not a clip file: clips are read from BVH (.bvh), FBX (.fbx), glTF (.gltf, .glb), "
                    "COLLADA (.dae) and DirectX (.x) files");
  // assimp refuses no bytes as "Invalid parameters passed to ReadFileFromMemory()", which says
  // nothing of the file.
  if (content.empty()) throw ClipError(name, "is empty: a clip file holds a skeleton and its motion");
  known->check(content, name);
  const std::optional<std::string> skeleton =
      known->skeletonOnly == nullptr ? std::nullopt : known->skeletonOnly(content, name);
  const std::string_view given = skeleton ? std::string_view(*skeleton) : content;
  Assimp::Importer importer;
  importer.SetIOHandler(new NoOtherFiles);  // the importer owns it
  keepOnlyReaderOf(importer, format);
  readOnlySkeletons(importer);
  const aiScene* scene = importer.ReadFileFromMemory(given.data(), given.size(), 0, format.c_str());
  if (scene == nullptr) {
    const AssimpReason reason = assimpReason(importer.GetErrorString(), format);
    const std::string why = "not a clip assimp can read: " + reason.why;
    if (reason.line > 0) throw ClipError(name, reason.line, why);
    throw ClipError(name, why);
  }
  if (scene->mNumAnimations == 0 || scene->mRootNode == nullptr)
    throw ClipError(name, "it holds no animation");
  const aiAnimation& anim = *scene->mAnimations[0];
  phys::Clip clip;
  clip.name = name;
  std::vector<Animated> bones;
  collectBones(*scene->mRootNode, aiMatrix4x4(), -1, ChannelsByNode(anim), clip, bones);
  if (clip.bones.empty()) throw ClipError(name, "its animation moves no node of its skeleton");
  for (std::size_t b = 1; b < clip.bones.size(); ++b) {
    if (clip.parents[b] < 0)
      throw ClipError(name, "bones '" + clip.bones[0] + "' and '" + clip.bones[b] + "' are two roots");
  }
  const aiNodeAnim& root = *bones[0].channel;
  const unsigned frames = root.mNumRotationKeys;
  // assimp gives 0 ticks a second for a file that does not say, and would then take 25. A .x that
  // gives no AnimTicksPerSecond is DirectX's default of 4800, as D3DX and the exporters that write
  // it take it (one that says 0 is refused by checkX, since assimp reads it as one that does not
  // say); other formats, assimp's 25. A BVH always says (1 / its Frame Time), so there a tick rate
  // that is not a finite number > 0 is a Frame Time that is not one (-1 gave -1, nan nan), refused
  // rather than guessed.
  const double ticksGiven = anim.mTicksPerSecond;
  if (!(ticksGiven >= 0.0 && std::isfinite(ticksGiven)) || (bvh && ticksGiven == 0.0))
    throw ClipError(name, bvh ? "its Frame Time is not a finite number of seconds > 0"
                              : "its animation's ticks per second are negative or not a finite number");
  const double ticks = ticksGiven > 0.0 ? ticksGiven : format == "x" ? kXDefaultTicks : kAssimpDefaultTicks;
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
    content = fileio::readWhole(file, detail::kMaxClipBytes);
  } catch (const fileio::FileError& e) {
    throw ClipError(file, e.message());
  }
  std::string format = file.extension().string();
  if (!format.empty()) format.erase(0, 1);
  return parseClip(content, file.string(), format);
}

}  // namespace clips
