#pragma once
// A triangle mesh on the CPU, loaded by assimp from any format it reads (the project's own
// models are Wavefront OBJ in assets/models/).
#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

namespace engine {

struct MeshData {
  std::vector<glm::vec3> positions;  ///< unit: model units (ours: m)
  std::vector<glm::vec3> normals;    ///< one per position, unit length
  std::vector<std::uint32_t> indices;  ///< three per triangle
  glm::vec3 boundsMin{0.0f};
  glm::vec3 boundsMax{0.0f};
};

/// Loads every mesh of the file into one, triangulated, with normals (made flat where the file
/// has none). Throws engine::Error naming the file and assimp's reason.
MeshData loadMeshData(const std::filesystem::path& file);

/// A unit cube centred on the origin with flat normals, built in code: the fallback when a
/// model file is missing or broken.
MeshData unitCubeMesh();

}  // namespace engine
