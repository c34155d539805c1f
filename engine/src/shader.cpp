#include "engine/shader.h"

#include <algorithm>
#include <utility>

#include <glad/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include "engine/error.h"
#include "engine/shader_log.h"
#include "fileio/files.h"

namespace engine {
namespace {

// GL takes the source as a C string and stops at its first NUL byte, so the rest would be left
// out without a word: say where the NUL is instead, as "file:line:" as a compiler's error.
void refuseNulBytes(const std::filesystem::path& file, const std::string& source) {
  const std::size_t nul = source.find('\0');
  if (nul == std::string::npos) return;
  const auto line = 1 + std::count(source.begin(), source.begin() + static_cast<std::ptrdiff_t>(nul), '\n');
  throw Error(file.string() + ":" + std::to_string(line) +
              ": the shader file holds a NUL byte, which GLSL text cannot (GL would stop reading there)");
}

std::string infoLog(GLuint object, bool isProgram) {
  GLint length = 0;
  if (isProgram)
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  else
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 0), '\0');
  if (length > 0) {
    if (isProgram)
      glGetProgramInfoLog(object, length, nullptr, log.data());
    else
      glGetShaderInfoLog(object, length, nullptr, log.data());
  }
  return log;
}

GLuint compile(GLenum stage, const std::filesystem::path& file) {
  const std::string source = readShaderSource(file);
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = infoLog(shader, false);
    glDeleteShader(shader);
    std::string message = formatShaderLog(file.string(), log);
    if (message.empty()) message = file.string() + ": compilation failed (the driver gave no log)\n";
    message.pop_back();  // the trailing newline
    throw Error(message);
  }
  return shader;
}

}  // namespace

std::string readShaderSource(const std::filesystem::path& file) {
  std::string source;
  try {
    source = fileio::readWhole(file, kMaxShaderBytes, "shader file");
  } catch (const fileio::FileError& e) {
    throw Error(e.what());
  }
  refuseNulBytes(file, source);
  return source;
}

ShaderProgram::ShaderProgram(const std::filesystem::path& vertexFile,
                             const std::filesystem::path& fragmentFile) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertexFile);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragmentFile);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = infoLog(id_, true);
    glDeleteProgram(id_);
    id_ = 0;
    throw Error(vertexFile.string() + " + " + fragmentFile.string() + ": link failed: " + log);
  }
}

ShaderProgram::~ShaderProgram() {
  if (id_ != 0) glDeleteProgram(id_);
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept : id_(std::exchange(other.id_, 0)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
  if (this != &other) {
    if (id_ != 0) glDeleteProgram(id_);
    id_ = std::exchange(other.id_, 0);
  }
  return *this;
}

void ShaderProgram::use() const {
  glUseProgram(id_);
}

void ShaderProgram::set(const char* name, const glm::mat4& value) const {
  glUniformMatrix4fv(glGetUniformLocation(id_, name), 1, GL_FALSE, glm::value_ptr(value));
}

void ShaderProgram::set(const char* name, const glm::vec3& value) const {
  glUniform3fv(glGetUniformLocation(id_, name), 1, glm::value_ptr(value));
}

void ShaderProgram::set(const char* name, float value) const {
  glUniform1f(glGetUniformLocation(id_, name), value);
}

}  // namespace engine
