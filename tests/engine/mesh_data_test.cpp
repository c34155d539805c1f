// The project's box model loads through assimp as a closed unit cube with outward normals.
#include <filesystem>
#include <fstream>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "engine/error.h"
#include "engine/mesh_data.h"

namespace {

const std::filesystem::path kBoxModel = std::filesystem::path(DATA_DIR) / "assets/models/box.obj";

// A closed mesh with outward faces encloses a positive volume (divergence theorem).
float signedVolume(const engine::MeshData& m) {
  float v = 0.0f;
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                    c = m.positions[m.indices[i + 2]];
    v += glm::dot(a, glm::cross(b, c)) / 6.0f;
  }
  return v;
}

void expectUnitCube(const engine::MeshData& m) {
  EXPECT_EQ(m.indices.size(), 36u);  // 12 triangles
  EXPECT_EQ(m.positions.size(), m.normals.size());
  EXPECT_EQ(m.boundsMin, glm::vec3(-0.5f));
  EXPECT_EQ(m.boundsMax, glm::vec3(0.5f));
  EXPECT_NEAR(signedVolume(m), 1.0f, 1e-5f);
  // Each triangle's winding agrees with its vertices' normals (so back-face culling is right).
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                    c = m.positions[m.indices[i + 2]];
    const glm::vec3 faceNormal = glm::normalize(glm::cross(b - a, c - a));
    for (int k = 0; k < 3; ++k) EXPECT_GT(glm::dot(faceNormal, m.normals[m.indices[i + k]]), 0.99f);
  }
}

TEST(MeshData, ProjectBoxModelIsAUnitCube) { expectUnitCube(engine::loadMeshData(kBoxModel)); }

TEST(MeshData, BuiltInFallbackCubeIsAUnitCube) { expectUnitCube(engine::unitCubeMesh()); }

TEST(MeshData, MissingFileNamesThePath) {
  try {
    engine::loadMeshData("/nonexistent/thing.obj");
    FAIL() << "no error";
  } catch (const engine::Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/thing.obj"), std::string::npos) << e.what();
  }
}

TEST(MeshData, BrokenFileIsAnErrorNotACrash) {
  const auto file = std::filesystem::temp_directory_path() / "sandbox_broken_model.obj";
  std::ofstream(file) << "v 0 0 0\nf 1 2 3 4 5\nthis is not obj\n";
  EXPECT_THROW(engine::loadMeshData(file), engine::Error);
  std::filesystem::remove(file);
}

}  // namespace
