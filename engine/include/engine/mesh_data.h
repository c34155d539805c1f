#pragma once
// A triangle mesh on the CPU, loaded by assimp from any format it reads (the project's own
// models are Wavefront OBJ in assets/models/).
#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

namespace engine {

struct MeshData {
  std::vector<glm::vec3> positions;    ///< unit: model units (ours: m)
  std::vector<glm::vec3> normals;      ///< one per position, unit length
  std::vector<std::uint32_t> indices;  ///< three per triangle
  glm::vec3 boundsMin{0.0f};
  glm::vec3 boundsMax{0.0f};
};

/// Loads every mesh of the file into one, triangulated, with unit normals (made flat where the
/// file has none, and for each corner whose normal has zero length, which has no direction to
/// light: that corner gets its triangle's own normal); points and lines are left out with their
/// vertices, and so are triangles whose corners are in line where a corner has no normal (they
/// cover no pixel, and have no normal to give it). Throws engine::Error naming the
/// file and why: the OS's reason when it cannot be opened, a folder, a pipe or device, assimp's
/// reason, or a position or normal that is not finite, with the face and corner (counted from 1
/// in the file's order) or, for a normal computed from corners too far apart, the triangle.
MeshData loadMeshData(const std::filesystem::path& file);

/// A unit cube centred on the origin with flat normals, built in code: the fallback when a
/// model file is missing or broken.
MeshData unitCubeMesh();

/// A capsule centred on the origin, built in code: the points within `radius` of the core
/// segment from (0, -halfSegment, 0) to (0, halfSegment, 0) (the physics' capsules lie along
/// their body's y axis). Two hemispherical caps of `rings` rows each, from the pole to the
/// equator, and between them a cylinder, all `segments` columns around; smooth normals, one
/// vertex at each pole, triangles counter-clockwise seen from outside. Every vertex lies on the
/// surface, so the mesh is inscribed in the capsule, and it is closed. 2 + 2 * rings * segments
/// vertices and 4 * rings * segments triangles; when halfSegment is 0 (a sphere: no cylinder,
/// the caps share their equator) `segments` fewer vertices and 2 * segments fewer triangles.
/// A capsule cannot be scaled from another without squashing its caps, so each size needs its
/// own. Throws engine::Error unless radius > 0, halfSegment >= 0 (both finite), segments >= 3
/// and rings >= 1.
MeshData makeCapsuleMesh(float radius, float halfSegment, int segments = 24, int rings = 6);

}  // namespace engine
