// Compiler logs from each driver family become "file:line: message"; a shader file that cannot
// be read is refused naming the file and why, before any GL call (so no context is needed).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "../app/temp_folder.h"
#include "engine/error.h"
#include "engine/shader.h"
#include "engine/shader_log.h"

namespace {

namespace fs = std::filesystem;
using testing_app::TempFolder;

TEST(ShaderLog, MesaForm) {
  EXPECT_EQ(engine::formatShaderLog("shaders/a.frag", "0:12(5): error: syntax error, unexpected '}'\n"),
            "shaders/a.frag:12: error: syntax error, unexpected '}'\n");
}

TEST(ShaderLog, NvidiaForm) {
  EXPECT_EQ(engine::formatShaderLog("a.vert", "0(7) : error C0000: syntax error, unexpected ';'\n"),
            "a.vert:7: error C0000: syntax error, unexpected ';'\n");
}

TEST(ShaderLog, AmdIntelForm) {
  EXPECT_EQ(engine::formatShaderLog("a.vert",
                                    "ERROR: 0:3: 'foo' : undeclared identifier\n"
                                    "WARNING: 0:9: 'x' : unused\n"),
            "a.vert:3: error: 'foo' : undeclared identifier\na.vert:9: warning: 'x' : unused\n");
}

TEST(ShaderLog, UnknownLinesAreKeptAndBlankOnesDropped) {
  EXPECT_EQ(engine::formatShaderLog("x.frag", "something odd\n\n  \n"), "x.frag: something odd\n");
  EXPECT_EQ(engine::formatShaderLog("x.frag", ""), "");
}

TEST(ShaderLog, MultipleErrorsKeepTheirOwnLines) {
  const std::string log = "0:2(1): error: one\r\n0:40(3): error: two\0";
  EXPECT_EQ(engine::formatShaderLog("m.frag", log), "m.frag:2: error: one\nm.frag:40: error: two\n");
}

// The engine::Error's message, or "(no error)".
std::string readError(const fs::path& file) {
  try {
    engine::readShaderSource(file);
  } catch (const engine::Error& e) {
    return e.what();
  }
  return "(no error)";
}

fs::path writeShader(const TempFolder& folder, const std::string& name, const std::string& text) {
  std::ofstream(folder.path / name, std::ios::binary) << text;
  return folder.path / name;
}

TEST(ShaderSource, TheProjectsShadersAreReadWhole) {
  const fs::path file = fs::path(DATA_DIR) / "shaders/mesh.frag";
  std::ifstream in(file, std::ios::binary);
  std::stringstream whole;
  whole << in.rdbuf();
  ASSERT_FALSE(whole.str().empty());
  EXPECT_EQ(engine::readShaderSource(file), whole.str());
}

// It said "cannot open shader file", without why.
TEST(ShaderSource, AFileThatCannotBeOpenedGivesTheSystemsReason) {
  const TempFolder folder;
  const fs::path missing = folder.path / "mesh.frag";
  EXPECT_EQ(readError(missing), missing.string() + ": cannot open shader file: No such file or directory");
}

// A folder was read as an empty shader, which then failed to compile with
// "mesh.frag:1: error: syntax error, unexpected end of file".
TEST(ShaderSource, AFolderIsRefusedAsAFolder) {
  const TempFolder folder;
  fs::create_directory(folder.path / "mesh.frag");
  EXPECT_EQ(readError(folder.path / "mesh.frag"),
            (folder.path / "mesh.frag").string() + ": is a folder, not a shader file");
}

// Any size was read into memory and handed to the driver, /dev/zero until memory ran out (a
// file one byte over the limit stands for it: without the limit, /dev/zero would take the test).
TEST(ShaderSource, AFileOverTheLimitIsRefusedAndOneAtTheLimitReadWhole) {
  const TempFolder folder;
  const std::string atLimit(engine::kMaxShaderBytes, ' ');
  EXPECT_EQ(engine::readShaderSource(writeShader(folder, "big.frag", atLimit)), atLimit);
  const fs::path over = writeShader(folder, "over.frag", atLimit + " ");
  EXPECT_EQ(readError(over), over.string() + ": is larger than " + std::to_string(engine::kMaxShaderBytes) +
                                 " bytes, the most a shader file may hold");
}

// GL reads the source up to its first NUL byte: what followed was left out without a word.
TEST(ShaderSource, ANulByteIsRefusedNamingItsLine) {
  using namespace std::string_literals;
  const TempFolder folder;
  const fs::path file = writeShader(folder, "nul.frag", "#version 330 core\nvoid main() {\n\0}\n"s);
  EXPECT_EQ(readError(file),
            file.string() +
                ":3: the shader file holds a NUL byte, which GLSL text cannot (GL would stop "
                "reading there)");
}

}  // namespace
