#pragma once
// A linked GLSL program built from a vertex and a fragment shader file.
#include <filesystem>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace engine {

class ShaderProgram {
 public:
  /// Compiles and links; throws engine::Error whose message names each failing file and line
  /// with the driver's words (see shader_log.h).
  ShaderProgram(const std::filesystem::path& vertexFile, const std::filesystem::path& fragmentFile);
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  void use() const;
  /// Uniform setters; a name the program does not use is ignored (GL's rule for location -1).
  void set(const char* name, const glm::mat4& value) const;
  void set(const char* name, const glm::vec3& value) const;
  void set(const char* name, float value) const;

 private:
  unsigned id_ = 0;
};

}  // namespace engine
