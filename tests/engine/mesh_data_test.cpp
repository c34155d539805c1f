// The project's box model loads through assimp as a closed unit cube with outward normals; a file
// that cannot be read, or whose numbers are not finite, is refused saying what and where; the
// capsule built in code lies on its surface, smooth, closed and facing out.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <utility>

#include <glm/common.hpp>
#include <glm/gtc/constants.hpp>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "../app/temp_folder.h"
#include "engine/error.h"
#include "engine/mesh_data.h"

namespace {

namespace fs = std::filesystem;
using testing_app::TempFolder;

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

TEST(MeshData, ProjectBoxModelIsAUnitCube) {
  expectUnitCube(engine::loadMeshData(kBoxModel));
}

TEST(MeshData, BuiltInFallbackCubeIsAUnitCube) {
  expectUnitCube(engine::unitCubeMesh());
}

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

// The engine::Error's message, or "(no error)".
std::string loadError(const fs::path& file) {
  try {
    engine::loadMeshData(file);
  } catch (const engine::Error& e) {
    return e.what();
  }
  return "(no error)";
}

fs::path writeModel(const TempFolder& folder, const std::string& name, const std::string& text) {
  std::ofstream(folder.path / name, std::ios::binary) << text;
  return folder.path / name;
}

// assimp alone said `Unable to open file "missing.obj".`, without why.
TEST(MeshData, AFileThatCannotBeOpenedGivesTheSystemsReason) {
  const TempFolder folder;
  const fs::path missing = folder.path / "missing.obj";
  EXPECT_EQ(loadError(missing), missing.string() + ": cannot open model file: No such file or directory");
}

// assimp read a folder as a file with no mesh in it ("aiScene::mNumMeshes is 0").
TEST(MeshData, AFolderIsRefusedAsAFolder) {
  const TempFolder folder;
  fs::create_directory(folder.path / "box.obj");
  EXPECT_EQ(loadError(folder.path / "box.obj"),
            (folder.path / "box.obj").string() + ": is a folder, not a model file");
}

// assimp's fopen would wait for ever on a pipe nobody writes to. This one is held open for
// writing by the test, so that a loader that opens it anyway fails rather than hangs.
TEST(MeshData, APipeIsRefusedNotWaitedFor) {
  const TempFolder folder;
  const fs::path pipe = folder.path / "box.obj";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  const int writer = ::open(pipe.c_str(), O_RDWR | O_NONBLOCK);
  ASSERT_GE(writer, 0);
  EXPECT_EQ(loadError(pipe),
            pipe.string() +
                ": is not a regular file (a device, pipe or socket), so it is not read as a model file");
  ::close(writer);
}

// Each was loaded, and NaN or infinite positions and normals reached the GPU (the bounds became
// infinite). The face and corner are counted from 1 in the file's order: "f 2 4 3" is face 2,
// and its corner 2 is vertex 4.
TEST(MeshData, ANonFinitePositionIsRefusedNamingItsFaceAndCorner) {
  const TempFolder folder;
  const fs::path nan =
      writeModel(folder, "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nf 1 2 3\nf 2 4 3\n");
  EXPECT_EQ(loadError(nan), nan.string() + ": face 2, corner 2: the position (nan, 0, 0) is not finite");
  // 1e39 is beyond a float's range, so it is read as infinity.
  const fs::path big =
      writeModel(folder, "big.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1e39 0 0\nf 1 2 3\nf 2 4 3\n");
  EXPECT_EQ(loadError(big), big.string() + ": face 2, corner 2: the position (inf, 0, 0) is not finite");
}

TEST(MeshData, ANonFiniteNormalInTheFileIsRefused) {
  const TempFolder folder;
  const fs::path file =
      writeModel(folder, "n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 nan\nf 1//1 2//1 3//2\n");
  EXPECT_EQ(loadError(file), file.string() + ": face 1, corner 3: the normal (0, 0, nan) is not finite");
}

// With several meshes in the file, the mesh is named too.
TEST(MeshData, ANonFiniteNumberInTheSecondMeshNamesTheMesh) {
  const TempFolder folder;
  const fs::path file = writeModel(folder, "two.obj",
                                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 -inf\n"
                                   "o first\nf 1 2 3\no second\nf 1 2 4\n");
  EXPECT_EQ(
      loadError(file),
      file.string() + ": mesh 'second' (2 of 2), face 1, corner 3: the position (0, 0, -inf) is not finite");
}

// Every position is finite, but the edges' cross product, from which assimp computes the
// normal of a file that gives none, is beyond a float's range: there is no normal in the file
// to look for, so the message gives the triangle and says where its normal came from.
TEST(MeshData, ANormalComputedFromAHugeTriangleIsRefusedAsComputed) {
  const TempFolder folder;
  const fs::path file = writeModel(folder, "huge.obj", "v -3e38 0 0\nv 3e38 0 0\nv 0 3e38 0\nf 1 2 3\n");
  EXPECT_EQ(loadError(file),
            file.string() +
                ": the triangle (-3e+38, 0, 0), (3e+38, 0, 0), (0, 3e+38, 0): its normal, computed "
                "from its corners as the file gives none, is not finite: the corners are too far "
                "apart for float arithmetic");
}

// A line is not drawn: assimp gives its vertices NaN normals, which stayed in the vertex buffer,
// and its far end widened the bounds.
TEST(MeshData, PointsAndLinesAreLeftOutWithTheirVertices) {
  const TempFolder folder;
  const engine::MeshData m = engine::loadMeshData(
      writeModel(folder, "line.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\nl 3 4\np 4\n"));
  EXPECT_EQ(m.indices.size(), 3u);
  EXPECT_EQ(m.positions.size(), 3u);
  for (const glm::vec3& n : m.normals) EXPECT_EQ(n, glm::vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(m.boundsMin, glm::vec3(0.0f));
  EXPECT_EQ(m.boundsMax, glm::vec3(1.0f, 1.0f, 0.0f));
}

// Each triangle's normal from its corners, wound as it is drawn (counter-clockwise seen from the
// side it faces).
glm::vec3 windingNormal(const engine::MeshData& m, std::size_t triangle) {
  const glm::vec3 a = m.positions[m.indices[3 * triangle]], b = m.positions[m.indices[3 * triangle + 1]],
                  c = m.positions[m.indices[3 * triangle + 2]];
  return glm::normalize(glm::cross(b - a, c - a));
}

// `vn 0 0 0` was loaded as it is, and mesh.frag's normalize() of a zero vector is undefined (NaN
// light on Mesa). A zero normal is no normal: each corner that has one gets its own triangle's,
// as a file without normals gets them all, even where two triangles facing different ways share
// the vertex (here the fold of a quad bent at right angles).
TEST(MeshData, AZeroNormalInTheFileBecomesItsTrianglesNormal) {
  const TempFolder folder;
  const engine::MeshData m = engine::loadMeshData(writeModel(folder, "zero.obj",
                                                             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                                             "v 1 0 -1\nv 1 1 -1\nvn 0 0 0\n"
                                                             "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n"
                                                             "f 2//1 5//1 6//1\nf 2//1 6//1 3//1\n"));
  ASSERT_EQ(m.indices.size(), 12u);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  const glm::vec3 expected[] = {{0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {1, 0, 0}};
  for (std::size_t t = 0; t < 4; ++t) {
    EXPECT_LT(glm::length(windingNormal(m, t) - expected[t]), 1e-6f) << "triangle " << t + 1;
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(m.normals[m.indices[3 * t + k]], expected[t]) << "triangle " << t + 1 << ", corner " << k + 1;
    }
  }
}

// Only the corner without a normal gets the triangle's; the file's other normals stay, made unit
// length as MeshData promises (OBJ allows any length; the shader does not need it, the CPU's
// users of MeshData may).
TEST(MeshData, OnlyTheZeroNormalIsReplacedAndTheOthersAreMadeUnitLength) {
  const TempFolder folder;
  const engine::MeshData m =
      engine::loadMeshData(writeModel(folder, "mixed.obj",
                                      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0.6 0.8\nvn 0 0 5\nvn 0 0 0\n"
                                      "f 1//1 2//2 3//3\n"));
  ASSERT_EQ(m.indices.size(), 3u);
  EXPECT_LT(glm::length(m.normals[m.indices[0]] - glm::vec3(0.0f, 0.6f, 0.8f)), 1e-6f);
  EXPECT_EQ(m.normals[m.indices[1]], glm::vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(m.normals[m.indices[2]], glm::vec3(0.0f, 0.0f, 1.0f));
}

// Through assimp from another format: a PLY whose normals are zero, as some exporters write for
// vertices they have none for.
TEST(MeshData, AZeroNormalFromAnyFormatBecomesItsTrianglesNormal) {
  const TempFolder folder;
  const engine::MeshData m = engine::loadMeshData(
      writeModel(folder, "zero.ply",
                 "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                 "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                 "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                 "0 0 0 0 0 0\n0 1 0 0 0 0\n0 0 1 0 0 0\n3 0 1 2\n"));
  ASSERT_EQ(m.indices.size(), 3u);
  for (const glm::vec3& n : m.normals) EXPECT_EQ(n, glm::vec3(1.0f, 0.0f, 0.0f));
}

// A triangle whose corners are in line has no normal to give a zero-normal corner (assimp gives
// its corners zero when the file has no normals): it covers no pixel, so it is left out with its
// vertices. One with normals of its own is kept as it is.
TEST(MeshData, ATriangleInALineWithoutANormalIsLeftOut) {
  const TempFolder folder;
  for (const char* normals : {"", "vn 0 0 0\n"}) {
    SCOPED_TRACE(normals);
    const std::string n = *normals == '\0' ? "" : "//1";
    const engine::MeshData m = engine::loadMeshData(
        writeModel(folder, "line.obj",
                   std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\n") + normals + "f 1" + n + " 2" + n +
                       " 3" + n + "\nf 1" + n + " 2" + n + " 4" + n + "\n"));
    EXPECT_EQ(m.indices.size(), 3u);
    EXPECT_EQ(m.positions.size(), 3u);
    for (const glm::vec3& v : m.normals) EXPECT_EQ(v, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(m.boundsMax, glm::vec3(1.0f, 1.0f, 0.0f));
  }
  const engine::MeshData kept = engine::loadMeshData(
      writeModel(folder, "kept.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nvn 0 1 0\nf 1//1 2//1 3//1\n"));
  EXPECT_EQ(kept.indices.size(), 3u);
}

// The capsules the sandbox draws: long and thin, short and fat, a sphere, a ragdoll's limb.
struct CapsuleCase {
  float radius, halfSegment;
  int segments, rings;
};
constexpr CapsuleCase kCapsules[] = {{0.3f, 0.7f, 24, 6},  {1.5f, 0.25f, 24, 6}, {0.5f, 0.0f, 24, 6},
                                     {0.08f, 0.17f, 3, 1}, {0.25f, 0.0f, 5, 1},  {2.0f, 5.0f, 32, 8}};

// The point of the core segment, (0, -h, 0) to (0, h, 0), nearest p.
glm::vec3 nearestOnCore(const glm::vec3& p, float halfSegment) {
  return {0.0f, std::clamp(p.y, -halfSegment, halfSegment), 0.0f};
}

TEST(CapsuleMesh, HasTheVertexAndTriangleCountsItSays) {
  for (const CapsuleCase& c : kCapsules) {
    SCOPED_TRACE(testing::Message() << "r " << c.radius << " h " << c.halfSegment << " " << c.segments << "x"
                                    << c.rings);
    const engine::MeshData m = engine::makeCapsuleMesh(c.radius, c.halfSegment, c.segments, c.rings);
    const std::size_t quads = std::size_t(c.rings) * std::size_t(c.segments);
    const bool sphere = c.halfSegment == 0.0f;
    EXPECT_EQ(m.positions.size(), 2 + 2 * quads - (sphere ? std::size_t(c.segments) : 0));
    EXPECT_EQ(m.normals.size(), m.positions.size());
    const std::size_t triangles = 4 * quads - (sphere ? 2 * std::size_t(c.segments) : 0);
    EXPECT_EQ(m.indices.size(), 3 * triangles);
    for (std::uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
  }
  // The sizes the sandbox uses.
  EXPECT_EQ(engine::makeCapsuleMesh(0.2f, 0.5f).positions.size(), 2u + 2u * 24u * 6u);
}

TEST(CapsuleMesh, EveryVertexLiesOnTheSurfaceWithAnOutwardUnitNormal) {
  for (const CapsuleCase& c : kCapsules) {
    SCOPED_TRACE(testing::Message() << "r " << c.radius << " h " << c.halfSegment);
    const engine::MeshData m = engine::makeCapsuleMesh(c.radius, c.halfSegment, c.segments, c.rings);
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      const glm::vec3 p = m.positions[i], n = m.normals[i];
      const glm::vec3 out = p - nearestOnCore(p, c.halfSegment);
      ASSERT_NEAR(glm::length(out), c.radius, 1e-5f) << "vertex " << i;
      ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f) << "vertex " << i;
      // Smooth: the normal is the surface's own, straight out from the core.
      ASSERT_GT(glm::dot(n, out / c.radius), 1.0f - 1e-5f) << "vertex " << i;
    }
    EXPECT_NEAR(m.boundsMin.y, -(c.halfSegment + c.radius), 1e-5f);
    EXPECT_NEAR(m.boundsMax.y, c.halfSegment + c.radius, 1e-5f);
    EXPECT_LE(m.boundsMax.x, c.radius + 1e-5f);
    EXPECT_GE(m.boundsMin.z, -c.radius - 1e-5f);
  }
}

TEST(CapsuleMesh, IsClosedWithTrianglesFacingOut) {
  for (const CapsuleCase& c : kCapsules) {
    SCOPED_TRACE(testing::Message() << "r " << c.radius << " h " << c.halfSegment);
    const engine::MeshData m = engine::makeCapsuleMesh(c.radius, c.halfSegment, c.segments, c.rings);
    // Closed and consistently wound: each directed edge once, and its reverse once.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
      for (int k = 0; k < 3; ++k) ++edges[{m.indices[t + k], m.indices[t + (k + 1) % 3]}];
    }
    for (const auto& [edge, count] : edges) {
      ASSERT_EQ(count, 1) << edge.first << "-" << edge.second;
      ASSERT_EQ(edges.count({edge.second, edge.first}), 1u) << edge.first << "-" << edge.second;
    }
    // Counter-clockwise seen from outside: each face's normal agrees with its vertices' (back
    // faces are culled), and the enclosed volume is positive, a little under the capsule's.
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
      const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                      d = m.positions[m.indices[t + 2]];
      const glm::vec3 face = glm::normalize(glm::cross(b - a, d - a));
      for (int k = 0; k < 3; ++k) {
        ASSERT_GT(glm::dot(face, m.normals[m.indices[t + k]]), 0.0f) << "triangle " << t / 3;
      }
    }
    const float exact =
        glm::pi<float>() * c.radius * c.radius * (2.0f * c.halfSegment + 4.0f / 3.0f * c.radius);
    EXPECT_LT(signedVolume(m), exact);
    if (c.segments >= 24) {
      EXPECT_GT(signedVolume(m), 0.95f * exact);
    }
  }
}

TEST(CapsuleMesh, RefusesSizesThatAreNoCapsule) {
  EXPECT_THROW(engine::makeCapsuleMesh(0.0f, 1.0f), engine::Error);
  EXPECT_THROW(engine::makeCapsuleMesh(-0.1f, 1.0f), engine::Error);
  EXPECT_THROW(engine::makeCapsuleMesh(0.1f, -1.0f), engine::Error);
  EXPECT_THROW(engine::makeCapsuleMesh(std::nanf(""), 1.0f), engine::Error);
  EXPECT_THROW(engine::makeCapsuleMesh(0.1f, INFINITY), engine::Error);
  EXPECT_THROW(engine::makeCapsuleMesh(0.1f, 1.0f, 2, 4), engine::Error);
  EXPECT_THROW(engine::makeCapsuleMesh(0.1f, 1.0f, 8, 0), engine::Error);
}

}  // namespace
