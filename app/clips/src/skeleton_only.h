#pragma once
// What assimp is given of a clip file: its skeleton and animation alone. A clip reads nodes and
// their keys; meshes, skins, materials, cameras and the like are where assimp's readers take the
// most on trust (a mesh's face count allocated before its faces, a skin's vertex index written
// unchecked, a sparse accessor read past its buffer: docs/physics.md, "Animation"), so they are
// taken out before assimp reads the file rather than checked one by one. Each runs after the
// format's checks (format_checks.h), which bound the nesting and the counts these walk.
#include <optional>
#include <string>
#include <string_view>

namespace clips::detail {

/// glTF as text: the JSON with its nodes, animations and what their keys are read from alone.
std::optional<std::string> gltfSkeletonOnly(std::string_view json, const std::string& name);
/// Binary glTF: the same, its JSON chunk rewritten, its binary chunk kept.
std::optional<std::string> glbSkeletonOnly(std::string_view content, const std::string& name);
/// FBX, text or binary: the file with every Geometry object renamed to a type assimp does not read.
std::optional<std::string> fbxSkeletonOnly(std::string_view content, const std::string& name);
/// COLLADA: the document without its geometries, controllers, materials, effects, images, cameras
/// and lights, or any instance of them.
std::optional<std::string> colladaSkeletonOnly(std::string_view content, const std::string& name);
/// DirectX .x as text: the file with every Mesh block blanked out, lines kept.
std::optional<std::string> xSkeletonOnly(std::string_view content, const std::string& name);

}  // namespace clips::detail
