#pragma once
// What assimp takes on trust in the clip formats other than BVH (docs/physics.md, "Animation"):
// each check refuses, with a ClipError naming the line or the item, a file that would make one of
// assimp 5.2's readers recurse past the stack, allocate what a count claims, or crash, before that
// reader sees it.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace clips::detail {

/// A skeleton nests tens of nodes deep; the readers recurse once a level (BVH's limit too).
constexpr int kMaxDepth = 256;

/// A count written as digits alone, nullopt otherwise (a sign, a point, a space): assimp reads a
/// count as a float and truncates it ("Frames: 2.7" was 2 frames, "-1" more than any memory
/// holds), so anything else is refused, not read its way. A count past 64 bits is the largest.
std::optional<std::uint64_t> wholeNumber(std::string_view word);

/// glTF as text (.gltf): its JSON nested no deeper than kMaxDepth, its nodes' children no deeper.
void checkGltf(std::string_view json, const std::string& name);
/// Binary glTF (.glb): the JSON chunk as checkGltf checks a .gltf; what is not a .glb is left to
/// assimp's reader.
void checkGlb(std::string_view content, const std::string& name);
/// COLLADA (.dae): elements nested no deeper than kMaxDepth, every array holding the values its
/// count says, every accessor within its array.
void checkCollada(std::string_view content, const std::string& name);
/// FBX as text: braces nested no deeper than kMaxDepth, every array (`*N { a: ... }`) holding the
/// N values it declares, no animation curve of no keys. A binary FBX is left to assimp's reader.
void checkFbx(std::string_view content, const std::string& name);
/// DirectX .x as text: braces nested no deeper than kMaxDepth, no count at the start of a block
/// (a Mesh's vertices, ...) larger than the bytes that follow it.
void checkX(std::string_view content, const std::string& name);

}  // namespace clips::detail
