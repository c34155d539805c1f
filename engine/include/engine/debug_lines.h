#pragma once
// Batched debug lines: collect any number of coloured segments during a frame, then draw them
// all with one buffer upload and one draw call.
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "engine/shader.h"

namespace engine {

class DebugLines {
 public:
  /// Needs a current GL context; loads lines.vert and lines.frag from shaderDir.
  explicit DebugLines(const std::filesystem::path& shaderDir);
  ~DebugLines();
  DebugLines(const DebugLines&) = delete;
  DebugLines& operator=(const DebugLines&) = delete;

  void addLine(const glm::vec3& a, const glm::vec3& b, const glm::vec3& color);
  /// The 12 edges of a box with the given centre, rotation (columns = body axes) and half size.
  void addBody(const glm::vec3& center, const glm::mat3& rotation, const glm::vec3& halfExtents,
               const glm::vec3& color);
  /// Three short crossing segments around p.
  void addPoint(const glm::vec3& p, float size, const glm::vec3& color);

  std::size_t lineCount() const { return vertices_.size() / 2; }
  /// Draws every line added since the last flush, then forgets them.
  void flush(const glm::mat4& viewProjection);

 private:
  struct Vertex {
    glm::vec3 position;
    glm::vec3 color;
  };
  std::vector<Vertex> vertices_;  // capacity kept between frames: no allocation once warm
  ShaderProgram program_;
  unsigned vao_ = 0, vbo_ = 0;
  std::size_t gpuCapacity_ = 0;  // vertices the GPU buffer holds
};

}  // namespace engine
