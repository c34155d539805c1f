#pragma once
// A mesh in GPU buffers: one vertex array with interleaved position and normal, and indices.
#include "engine/mesh_data.h"

namespace engine {

class GpuMesh {
 public:
  /// Uploads the mesh; needs a current GL context.
  explicit GpuMesh(const MeshData& data);
  ~GpuMesh();
  GpuMesh(GpuMesh&& other) noexcept;
  GpuMesh& operator=(GpuMesh&& other) noexcept;
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;

  /// Draws the triangles with whatever program is bound (attribute 0 position, 1 normal).
  void draw() const;

 private:
  void release();

  unsigned vao_ = 0, vbo_ = 0, ebo_ = 0;
  int indexCount_ = 0;
};

}  // namespace engine
