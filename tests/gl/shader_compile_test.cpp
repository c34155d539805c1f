// Shaders compiled by the real driver (Mesa llvmpipe under Xvfb): the project's own compile,
// and a broken one is reported as file:line with the driver's words.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "engine/error.h"
#include "engine/renderer.h"
#include "engine/shader.h"
#include "gl_context.h"

namespace {

namespace fs = std::filesystem;
const fs::path kShaders = fs::path(DATA_DIR) / "shaders";

fs::path writeFile(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(OUTPUT_DIR) / "shaders";
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

std::string errorOf(const fs::path& vert, const fs::path& frag) {
  try {
    engine::ShaderProgram program(vert, frag);
  } catch (const engine::Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ShaderCompile, ProjectShadersCompileAndLink) {
  testing_gl::context();
  EXPECT_NO_THROW(engine::ShaderProgram(kShaders / "mesh.vert", kShaders / "mesh.frag"));
  EXPECT_NO_THROW(engine::ShaderProgram(kShaders / "ground.vert", kShaders / "ground.frag"));
  EXPECT_NO_THROW(engine::ShaderProgram(kShaders / "lines.vert", kShaders / "lines.frag"));
  EXPECT_NO_THROW(engine::Renderer renderer(kShaders));
}

TEST(ShaderCompile, BrokenShaderNamesFileAndLine) {
  testing_gl::context();
  const fs::path broken = writeFile("broken.frag",
                                    "#version 330 core\n"
                                    "out vec4 fragColor;\n"
                                    "void main() {\n"
                                    "  fragColor = vec4(undeclaredThing, 1.0);\n"
                                    "}\n");
  const std::string message = errorOf(kShaders / "lines.vert", broken);
  EXPECT_EQ(message.rfind(broken.string() + ":4: ", 0), 0u) << message;
  EXPECT_NE(message.find("undeclaredThing"), std::string::npos) << "the driver's words are kept: " << message;
}

TEST(ShaderCompile, EveryErrorOfAVertexShaderIsReported) {
  testing_gl::context();
  const fs::path broken = writeFile("broken.vert",
                                    "#version 330 core\n"
                                    "layout(location = 0) in vec3 aPosition;\n"
                                    "void main() {\n"
                                    "  gl_Position = vec4(aPosition, 1.0) +;\n"
                                    "}\n");
  const std::string message = errorOf(broken, kShaders / "lines.frag");
  EXPECT_NE(message.find(broken.string() + ":4: "), std::string::npos) << message;
}

TEST(ShaderCompile, MissingFileIsNamed) {
  testing_gl::context();
  const std::string message = errorOf(kShaders / "no-such.vert", kShaders / "lines.frag");
  EXPECT_NE(message.find("no-such.vert: cannot open shader file"), std::string::npos) << message;
}

}  // namespace
