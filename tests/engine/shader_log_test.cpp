// Compiler logs from each driver family become "file:line: message".
#include <gtest/gtest.h>

#include "engine/shader_log.h"

namespace {

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

}  // namespace
