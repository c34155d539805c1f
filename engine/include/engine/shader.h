#pragma once
// A linked GLSL program built from a vertex and a fragment shader file.
#include <cstddef>
#include <filesystem>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace engine {

/// The most a shader file may hold. The project's shaders are under 1 KiB each, so a thousand
/// times that leaves room for any shader written or generated; a bigger file is a wrong path (a
/// model, a log, /dev/zero), better refused at once than read into memory, /dev/zero until
/// memory runs out, and handed to the driver to reject.
inline constexpr std::size_t kMaxShaderBytes = std::size_t{1} << 20;

/// The text of a shader file, read whole. Throws engine::Error naming the file: with the OS's
/// reason when it cannot be opened or read ("mesh.frag: cannot open shader file: No such file
/// or directory"), for a folder, for more than kMaxShaderBytes, and for a NUL byte, naming its
/// line (GL would end the text there).
std::string readShaderSource(const std::filesystem::path& file);

class ShaderProgram {
 public:
  /// Reads (readShaderSource), compiles and links; throws engine::Error whose message names each
  /// failing file and line with the driver's words (see shader_log.h), or the file and why it
  /// could not be read.
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
