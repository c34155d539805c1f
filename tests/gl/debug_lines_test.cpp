// The batched line renderer draws what it is given, where it is given, in its colour.
#include <glad/gl.h>
#include <glm/mat4x4.hpp>
#include <gtest/gtest.h>

#include "engine/debug_lines.h"
#include "engine/image.h"
#include "gl_context.h"

namespace {

// A colour target of its own, so the window's framebuffer size and visibility do not matter.
class OffscreenTarget {
 public:
  OffscreenTarget(int w, int h) {
    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
    glViewport(0, 0, w, h);
  }
  ~OffscreenTarget() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &texture_);
  }
  bool complete() const { return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE; }

 private:
  unsigned fbo_ = 0, texture_ = 0;
};

TEST(DebugLines, DrawsEachLineInItsColourInOneBatch) {
  testing_gl::context();
  OffscreenTarget target(64, 64);
  ASSERT_TRUE(target.complete());
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  engine::DebugLines lines(std::filesystem::path(DATA_DIR) / "shaders");
  // Clip space directly (identity view-projection): a horizontal red line through the middle
  // row and a vertical green one through the middle column.
  lines.addLine({-1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f});
  lines.addLine({0.5f, -1.0f, 0.0f}, {0.5f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
  EXPECT_EQ(lines.lineCount(), 2u);
  lines.flush(glm::mat4(1.0f));
  EXPECT_EQ(lines.lineCount(), 0u);
  const engine::Image image = engine::readFramebuffer({64, 64});
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

  int redInMiddleRows = 0, greenInColumn = 0, lit = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const glm::u8vec4 p = image.pixel(x, y);
      if (p.r > 200 && p.g < 50) redInMiddleRows += (y == 31 || y == 32) ? 1 : 0;
      if (p.g > 200 && p.r < 50) greenInColumn += (x == 47 || x == 48) ? 1 : 0;
      if (p.r + p.g + p.b > 0) ++lit;
    }
  }
  EXPECT_GE(redInMiddleRows, 60);  // the whole row but where the green line crosses
  EXPECT_GE(greenInColumn, 60);
  EXPECT_LE(lit, 64 * 2 + 64 * 2);  // nothing drawn anywhere else
}

}  // namespace
