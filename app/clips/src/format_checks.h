#pragma once
// What assimp takes on trust in the clip formats (docs/physics.md, "Animation"):
// each check refuses, with a ClipError naming the line or the item, a file that would make one of
// assimp 5.2's readers recurse past the stack, allocate what a count claims, or crash, before that
// reader sees it.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace clips::detail {

/// Larger than any clip we would play: minutes of motion capture of a full skeleton.
constexpr std::size_t kMaxClipBytes = 64u << 20;

/// Whether assimp reads `content` as a BVH: a file named so (`format`, its extension in lower
/// case), or one of another name that starts as a BVH does (a .txt or a file with no extension).
bool isBvh(std::string_view content, const std::string& format);

/// BVH (bvh_checks.cpp): joints no deeper than kMaxDepth and no more than a skeleton has, a frame
/// count the file holds, and every number (OFFSET, Frame Time, each channel's value) one assimp
/// reads into a float in the range the clip keeps, each refused with its line.
void checkBvh(std::string_view content, const std::string& name);

/// A skeleton nests tens of nodes deep; the readers recurse once a level (BVH's limit too).
constexpr int kMaxDepth = 256;
/// A skeleton has tens of nodes; COLLADA and FBX readers copy a node once for each place it is put,
/// so a few nodes each put twice under the next unfold to billions.
constexpr std::uint64_t kMaxUnfoldedNodes = 100000;

/// The little-endian number of `width` bytes (at most 8) at byte `at` of `bytes`: binary FBX and
/// glTF store their lengths so, whatever the machine's order.
inline std::uint64_t readLittle(std::string_view bytes, std::size_t at, std::size_t width) {
  std::uint64_t value = 0;
  for (std::size_t i = width; i-- > 0;) value = value << 8 | static_cast<unsigned char>(bytes[at + i]);
  return value;
}

/// A count written as digits alone, nullopt otherwise (a sign, a point, a space): assimp reads a
/// count as a float and truncates it ("Frames: 2.7" was 2 frames, "-1" more than any memory
/// holds), so anything else is refused, not read its way. A count past 64 bits is the largest.
std::optional<std::uint64_t> wholeNumber(std::string_view word);

/// glTF as text (.gltf): its JSON nested no deeper than kMaxDepth, its nodes no deeper once
/// unfolded and no more than kMaxUnfoldedNodes.
void checkGltf(std::string_view json, const std::string& name);
/// Binary glTF (.glb): the lengths in its header and chunks within the file, and the JSON chunk as
/// checkGltf checks a .gltf; what is not a .glb is left to assimp's reader.
void checkGlb(std::string_view content, const std::string& name);
/// COLLADA (.dae): elements nested no deeper than kMaxDepth, every array holding the values its
/// count says, every accessor within its array, every mesh's primitives and skin's weights holding
/// the indices their counts need, no node instancing a node it is within or unfolding to more than
/// 100,000.
void checkCollada(std::string_view content, const std::string& name);
/// FBX as text: braces nested no deeper than kMaxDepth, every array (`*N { a: ... }`) holding the
/// N values it declares, no animation curve of no keys, every curve's keys in time order. A binary
/// FBX is checked by checkBinaryFbx.
void checkFbx(std::string_view content, const std::string& name);
/// Binary FBX: every node record within its parent and the file, its properties within its property
/// list, records nested no deeper than kMaxDepth, every array's count within what its bytes hold
/// (and its size within 32 bits, where assimp computes it), every curve's keys in time order.
void checkBinaryFbx(std::string_view content, const std::string& name);
/// DirectX .x as text: braces nested no deeper than kMaxDepth, no count at the start of a block
/// (a Mesh's vertices, ...) larger than the bytes that follow it, a tick rate (AnimTicksPerSecond) a
/// whole number > 0. A binary or compressed .x is refused.
void checkX(std::string_view content, const std::string& name);

/// Why a model's property `property` of FBX type `type` (a `P` under a Model's Properties70) cannot
/// be read, or "" if it can. assimp 5.2 copies each model property it does not itself read into the
/// node's metadata, and stops the program (an assert, abort()) on one of a type it has no metadata
/// for: KTime and ColorAndAlpha.
std::string modelPropertyProblem(std::string_view property, std::string_view type);

/// An FBX's models, the links between them and its animation curves, gathered from either form of
/// the file. A model that is its own ancestor, or models that unfold to more than kMaxUnfoldedNodes,
/// are refused: assimp converts a model once under each model it is linked to, recursing once a
/// level, and a cycle overflowed the stack. A curve whose keys are out of time order is refused
/// naming what it moves: assimp 5.2 drops such a curve with a warning no caller sees, and a file of
/// them read as one of no animation.
class FbxCurves {
 public:
  /// A model (a node of the scene) and its name.
  void model(std::int64_t id, std::string name);
  /// A link from object `source` to object `target` (a model to its parent model, or to 0, the
  /// root), or to its `property` (a curve to "d|X" of a curve node, a curve node to "Lcl Rotation"
  /// of a model; the first such link from an object is kept); at `line`, or at `byte` of a binary
  /// file.
  void link(std::int64_t source, std::int64_t target, std::string property, std::size_t line,
            std::size_t byte);
  /// A curve's key times, at `line` (0 if the file has no lines) or at `where` ("byte N: ").
  void keyTimes(std::int64_t curve, const std::vector<std::int64_t>& times, std::size_t line,
                const std::string& where);
  /// Throws ClipError for models that nest without end or unfold past kMaxUnfoldedNodes, then for
  /// the first curve whose keys do not rise in time, naming what it moves.
  void check(const std::string& name) const;

 private:
  struct Child {
    std::int64_t id;
    std::size_t line, byte;
  };
  void checkModels(const std::string& name) const;
  std::string modelName(std::int64_t id) const;

  struct Link {
    std::int64_t target;
    std::string property;
  };
  struct Unordered {
    std::int64_t curve;
    std::size_t line;
    std::string where;
    std::string why;
  };
  std::map<std::int64_t, std::string> models_;
  std::map<std::int64_t, Link> links_;
  std::map<std::int64_t, std::vector<Child>> children_;  // by the parent's id
  std::optional<Unordered> unordered_;
};

}  // namespace clips::detail
