#include "engine/debug_lines.h"

#include <glad/gl.h>

namespace engine {

DebugLines::DebugLines(const std::filesystem::path& shaderDir)
    : program_(shaderDir / "lines.vert", shaderDir / "lines.frag") {
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                        reinterpret_cast<const void*>(sizeof(glm::vec3)));
  glBindVertexArray(0);
}

DebugLines::~DebugLines() {
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &vbo_);
}

void DebugLines::addLine(const glm::vec3& a, const glm::vec3& b, const glm::vec3& color) {
  vertices_.push_back({a, color});
  vertices_.push_back({b, color});
}

void DebugLines::addBody(const glm::vec3& center, const glm::mat3& rotation, const glm::vec3& halfExtents,
                         const glm::vec3& color) {
  glm::vec3 corner[8];
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 local{(k & 1) ? halfExtents.x : -halfExtents.x, (k & 2) ? halfExtents.y : -halfExtents.y,
                          (k & 4) ? halfExtents.z : -halfExtents.z};
    corner[k] = center + rotation * local;
  }
  for (int k = 0; k < 8; ++k) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      if ((k & bit) == 0) addLine(corner[k], corner[k | bit], color);
    }
  }
}

void DebugLines::addPoint(const glm::vec3& p, float size, const glm::vec3& color) {
  const float h = size * 0.5f;
  addLine(p - glm::vec3(h, 0, 0), p + glm::vec3(h, 0, 0), color);
  addLine(p - glm::vec3(0, h, 0), p + glm::vec3(0, h, 0), color);
  addLine(p - glm::vec3(0, 0, h), p + glm::vec3(0, 0, h), color);
}

void DebugLines::flush(const glm::mat4& viewProjection) {
  if (vertices_.empty()) return;
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  const auto bytes = static_cast<GLsizeiptr>(vertices_.size() * sizeof(Vertex));
  if (vertices_.size() > gpuCapacity_) {
    gpuCapacity_ = vertices_.capacity();
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(gpuCapacity_ * sizeof(Vertex)), nullptr,
                 GL_STREAM_DRAW);
  }
  glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, vertices_.data());
  program_.use();
  program_.set("uViewProjection", viewProjection);
  glBindVertexArray(vao_);
  glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(vertices_.size()));
  glBindVertexArray(0);
  vertices_.clear();
}

}  // namespace engine
