#include "engine/mesh_data.h"

#include <limits>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <glm/common.hpp>
#include <glm/vec2.hpp>

#include "engine/error.h"

namespace engine {

MeshData loadMeshData(const std::filesystem::path& file) {
  Assimp::Importer importer;
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenNormals |
                         aiProcess_ValidateDataStructure;
  const aiScene* scene = importer.ReadFile(file.string(), flags);
  if (scene == nullptr) throw Error(file.string() + ": cannot load mesh: " + importer.GetErrorString());
  if (scene->mNumMeshes == 0) throw Error(file.string() + ": the file holds no mesh");

  MeshData out;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!mesh->HasNormals()) throw Error(file.string() + ": mesh " + std::to_string(m) + " has no normals");
    const auto base = static_cast<std::uint32_t>(out.positions.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const aiVector3D& n = mesh->mNormals[v];
      out.positions.emplace_back(p.x, p.y, p.z);
      out.normals.emplace_back(n.x, n.y, n.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by triangulation
      for (unsigned k = 0; k < 3; ++k) out.indices.push_back(base + face.mIndices[k]);
    }
  }
  if (out.indices.empty()) throw Error(file.string() + ": the mesh has no triangles");

  out.boundsMin = glm::vec3(std::numeric_limits<float>::max());
  out.boundsMax = -out.boundsMin;
  for (const glm::vec3& p : out.positions) {
    out.boundsMin = glm::min(out.boundsMin, p);
    out.boundsMax = glm::max(out.boundsMax, p);
  }
  return out;
}

MeshData unitCubeMesh() {
  MeshData cube;
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      glm::vec3 n(0.0f);
      n[axis] = sign;
      // u, v span the face so that u x v = n (counter-clockwise seen from outside).
      glm::vec3 u(0.0f), v(0.0f);
      u[(axis + 1) % 3] = 1.0f;
      v[(axis + 2) % 3] = sign;
      const auto base = static_cast<std::uint32_t>(cube.positions.size());
      for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        cube.positions.push_back(0.5f * (n + c.x * u + c.y * v));
        cube.normals.push_back(n);
      }
      cube.indices.insert(cube.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  }
  cube.boundsMin = glm::vec3(-0.5f);
  cube.boundsMax = glm::vec3(0.5f);
  return cube;
}

}  // namespace engine
