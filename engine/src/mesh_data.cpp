#include "engine/mesh_data.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/error.h"
#include "fileio/files.h"

namespace engine {
namespace {

bool isFinite(const aiVector3D& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// As the file would write it, "(nan, 0, 1e+39)": what finds the vertex in the file.
std::string coordinates(const aiVector3D& v) {
  std::ostringstream text;
  text << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return text.str();
}

// "FILE: " or, when the file holds several meshes, "FILE: mesh 'name' (2 of 3), ".
std::string meshPlace(const std::filesystem::path& file, const aiScene& scene, unsigned m) {
  if (scene.mNumMeshes == 1) return file.string() + ": ";
  return file.string() + ": mesh '" + scene.mMeshes[m]->mName.C_Str() + "' (" + std::to_string(m + 1) +
         " of " + std::to_string(scene.mNumMeshes) + "), ";
}

[[noreturn]] void refuseCorner(const std::string& place, unsigned face, unsigned corner, const char* what,
                               const aiVector3D& value) {
  throw Error(place + "face " + std::to_string(face + 1) + ", corner " + std::to_string(corner + 1) +
              ": the " + what + " " + coordinates(value) + " is not finite");
}

// A NaN or an infinity in the file ("v nan 0 0", or "v 1e39 0 0", beyond a float's range) would
// reach the GPU, make the bounds infinite and the light NaN. Checked as the file gives them,
// before assimp's steps compute with them, so the face and corner (counting from 1, in the file's
// order within the mesh: an OBJ's "f" lines) say where: assimp's vertex numbers are not the file's.
// Points and lines are not drawn, so theirs are not checked.
void checkFileVertices(const std::filesystem::path& file, const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices < 3) continue;
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        const unsigned v = face.mIndices[k];
        if (!isFinite(mesh.mVertices[v])) {
          refuseCorner(meshPlace(file, scene, m), f, k, "position", mesh.mVertices[v]);
        }
        if (mesh.HasNormals() && !isFinite(mesh.mNormals[v])) {
          refuseCorner(meshPlace(file, scene, m), f, k, "normal", mesh.mNormals[v]);
        }
      }
    }
  }
}

// Normals that assimp computes (the file gives none) from finite positions can still overflow: a
// triangle whose corners lie some 1e19 apart has edges whose cross product is beyond a float's
// range. There is no such normal in the file to look for, so the message gives the triangle's
// corners (its number is not the file's once polygons are cut into triangles) and says where
// the normal came from.
void checkComputedNormals(const std::filesystem::path& file, const aiScene& scene,
                          const std::vector<bool>& fileHasNormals) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    if (fileHasNormals[m] || !mesh.HasNormals()) continue;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines: not drawn, and assimp gives them NaN
      std::string corners;
      bool finite = true;
      for (unsigned k = 0; k < 3; ++k) {
        corners += (k == 0 ? "" : ", ") + coordinates(mesh.mVertices[face.mIndices[k]]);
        finite = finite && isFinite(mesh.mNormals[face.mIndices[k]]);
      }
      if (finite) continue;
      throw Error(meshPlace(file, scene, m) + "the triangle " + corners +
                  ": its normal, computed from its corners as the file gives none, is not finite: the "
                  "corners are too far apart for float arithmetic");
    }
  }
}

// assimp says only "Unable to open file" for a file it cannot open, reads a folder as a file
// with no mesh in it, and would wait for ever on a named pipe; checkRegularFile says which, with
// the OS's reason.
const aiScene& importFile(Assimp::Importer& importer, const std::filesystem::path& file) {
  try {
    fileio::checkRegularFile(file, "model file");
  } catch (const fileio::FileError& e) {
    throw Error(e.what());
  }
  const aiScene* scene = importer.ReadFile(file.string(), aiProcess_ValidateDataStructure);
  if (scene == nullptr) throw Error(file.string() + ": cannot load mesh: " + importer.GetErrorString());
  if (scene->mNumMeshes == 0) throw Error(file.string() + ": the file holds no mesh");
  return *scene;
}

// The steps ReadFile would run with these flags, run apart so that the file's own numbers are
// checked (checkFileVertices) before anything is computed with them.
const aiScene& triangulate(Assimp::Importer& importer, const std::filesystem::path& file) {
  const aiScene* scene = importer.ApplyPostProcessing(aiProcess_Triangulate |
                                                      aiProcess_JoinIdenticalVertices | aiProcess_GenNormals);
  if (scene == nullptr) throw Error(file.string() + ": cannot load mesh: " + importer.GetErrorString());
  return *scene;
}

glm::dvec3 asDouble(const aiVector3D& v) {
  return {v.x, v.y, v.z};
}

bool isZero(const aiVector3D& v) {
  return v.x == 0.0f && v.y == 0.0f && v.z == 0.0f;
}

// The triangle's own normal, from its corners in the order that makes it face out (assimp's
// GenNormals makes the same one), in double so that neither corners far apart overflow nor
// corners close together underflow: zero only when the corners are in line.
glm::dvec3 triangleNormal(const aiMesh& mesh, const aiFace& face) {
  const glm::dvec3 a = asDouble(mesh.mVertices[face.mIndices[0]]);
  const glm::dvec3 b = asDouble(mesh.mVertices[face.mIndices[1]]);
  const glm::dvec3 c = asDouble(mesh.mVertices[face.mIndices[2]]);
  const glm::dvec3 n = glm::cross(b - a, c - a);
  return n == glm::dvec3(0.0) ? n : glm::normalize(n);
}

// The mesh's triangles and the vertices they use, added to `out`. The points and lines that
// triangulation leaves are not drawn; their vertices are left out too, so they do not widen the
// bounds, and the NaN normals assimp gives them do not reach the GPU.
//
// A normal of zero length (`vn 0 0 0`, or assimp's normal of a triangle whose corners are in
// line) gives the shader's normalize() nothing to work with: the light is undefined there. Such a
// corner is given its triangle's own normal, as a file that gives no normals gets them all (a
// zero normal is no normal), on a vertex of its own, since the triangles that share it face
// different ways. A triangle whose corners are in line has none to give; it covers no pixel, so
// it is left out. Every other normal is made unit length, as MeshData promises (OBJ allows any).
void appendTriangles(const std::filesystem::path& file, const aiMesh& mesh, unsigned m, MeshData& out) {
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> index(mesh.mNumVertices, kUnused);
  auto addVertex = [&](unsigned v, const glm::dvec3& normal) {
    const aiVector3D& p = mesh.mVertices[v];
    out.positions.emplace_back(p.x, p.y, p.z);
    out.normals.emplace_back(normal);
    return static_cast<std::uint32_t>(out.positions.size() - 1);
  };
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;
    if (!mesh.HasNormals()) throw Error(file.string() + ": mesh " + std::to_string(m) + " has no normals");
    const bool noNormal = isZero(mesh.mNormals[face.mIndices[0]]) ||
                          isZero(mesh.mNormals[face.mIndices[1]]) || isZero(mesh.mNormals[face.mIndices[2]]);
    const glm::dvec3 own = noNormal ? triangleNormal(mesh, face) : glm::dvec3(0.0);
    if (noNormal && own == glm::dvec3(0.0)) continue;
    for (unsigned k = 0; k < 3; ++k) {
      const unsigned v = face.mIndices[k];
      if (isZero(mesh.mNormals[v])) {
        out.indices.push_back(addVertex(v, own));
        continue;
      }
      if (index[v] == kUnused) index[v] = addVertex(v, glm::normalize(asDouble(mesh.mNormals[v])));
      out.indices.push_back(index[v]);
    }
  }
}

}  // namespace

MeshData loadMeshData(const std::filesystem::path& file) {
  Assimp::Importer importer;
  const aiScene& imported = importFile(importer, file);
  checkFileVertices(file, imported);
  std::vector<bool> fileHasNormals(imported.mNumMeshes);
  for (unsigned m = 0; m < imported.mNumMeshes; ++m) fileHasNormals[m] = imported.mMeshes[m]->HasNormals();
  const aiScene& scene = triangulate(importer, file);
  checkComputedNormals(file, scene, fileHasNormals);

  MeshData out;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) appendTriangles(file, *scene.mMeshes[m], m, out);
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
