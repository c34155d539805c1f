// The capsule built in code (mesh_data.h): rows of vertices from the top pole to the bottom one,
// each row a ring of `segments` vertices around the y axis.
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include <glm/common.hpp>
#include <glm/gtc/constants.hpp>

#include "engine/error.h"
#include "engine/mesh_data.h"

namespace engine {

MeshData makeCapsuleMesh(float radius, float halfSegment, int segments, int rings) {
  if (!(radius > 0.0f) || !std::isfinite(radius) || !(halfSegment >= 0.0f) || !std::isfinite(halfSegment) ||
      segments < 3 || rings < 1) {
    throw Error("capsule mesh: radius " + std::to_string(radius) + ", half segment " +
                std::to_string(halfSegment) + ", " + std::to_string(segments) + " segments, " +
                std::to_string(rings) +
                " rings: needs radius > 0, half segment >= 0, segments >= 3, rings >= 1");
  }
  MeshData mesh;
  const auto columns = static_cast<std::uint32_t>(segments);
  const auto capRows = static_cast<std::uint32_t>(rings);
  // The rows between the poles: each cap's, with the equator in both unless the capsule is a
  // sphere, whose caps share theirs (a cylinder of no height would leave the mesh open there).
  const bool sphere = halfSegment == 0.0f;
  const std::uint32_t rows = 2u * capRows - (sphere ? 1u : 0u);
  mesh.positions.reserve(2 + rows * columns);
  mesh.normals.reserve(2 + rows * columns);

  auto add = [&](const glm::vec3& normal, float centreY) {
    mesh.normals.push_back(normal);
    mesh.positions.push_back(glm::vec3(0.0f, centreY, 0.0f) + radius * normal);
  };
  // Row r (0-based, top to bottom) lies at polar angle a = (r + 1) / rings * pi/2 from +y: the
  // top cap's rows (a <= pi/2) around (0, +h, 0), the bottom cap's (a >= pi/2) around (0, -h, 0),
  // where the bottom cap's numbering starts again at the equator unless it is shared. Column c
  // is at angle t = 2 pi c / segments, direction (sin t, 0, cos t), so that going up a column
  // and along a row from c to c + 1 turns counter-clockwise seen from outside.
  add(glm::vec3(0.0f, 1.0f, 0.0f), halfSegment);  // vertex 0: the top pole
  for (std::uint32_t r = 0; r < rows; ++r) {
    const bool top = r < capRows;
    const std::uint32_t step = top || sphere ? r + 1 : r;  // quarter turns of pi/2 / rings
    const float a = glm::half_pi<float>() * static_cast<float>(step) / static_cast<float>(capRows);
    // The equator gets exactly 0 for y and 1 for the ring's radius, not cos(pi/2)'s 4e-8.
    const bool equator = step == capRows;
    const float ringRadius = equator ? 1.0f : std::sin(a);
    const float y = equator ? 0.0f : std::cos(a);
    for (std::uint32_t c = 0; c < columns; ++c) {
      const float t = glm::two_pi<float>() * static_cast<float>(c) / static_cast<float>(segments);
      add(glm::vec3(ringRadius * std::sin(t), y, ringRadius * std::cos(t)), top ? halfSegment : -halfSegment);
    }
  }
  const auto bottomPole = static_cast<std::uint32_t>(mesh.positions.size());
  add(glm::vec3(0.0f, -1.0f, 0.0f), -halfSegment);

  auto at = [&](std::uint32_t row, std::uint32_t column) { return 1u + row * columns + column % columns; };
  mesh.indices.reserve(std::size_t{6} * columns * rows);
  for (std::uint32_t c = 0; c < columns; ++c) {
    mesh.indices.insert(mesh.indices.end(), {at(0, c), at(0, c + 1), 0u});
  }
  for (std::uint32_t r = 0; r + 1 < rows; ++r) {
    for (std::uint32_t c = 0; c < columns; ++c) {
      const std::uint32_t upper0 = at(r, c), upper1 = at(r, c + 1), lower0 = at(r + 1, c),
                          lower1 = at(r + 1, c + 1);
      mesh.indices.insert(mesh.indices.end(), {lower0, lower1, upper1, lower0, upper1, upper0});
    }
  }
  for (std::uint32_t c = 0; c < columns; ++c) {
    mesh.indices.insert(mesh.indices.end(), {bottomPole, at(rows - 1, c + 1), at(rows - 1, c)});
  }

  mesh.boundsMin = glm::vec3(std::numeric_limits<float>::max());
  mesh.boundsMax = -mesh.boundsMin;
  for (const glm::vec3& p : mesh.positions) {
    mesh.boundsMin = glm::min(mesh.boundsMin, p);
    mesh.boundsMax = glm::max(mesh.boundsMax, p);
  }
  return mesh;
}

}  // namespace engine
