// The loader's line index: what it costs and what it answers.
#include <gtest/gtest.h>

#include <string>

#include "element_reader.h"

// Offsets are 32 bits (a scene is at most 512 MiB): a file of newlines costs 4 bytes of index a
// byte, not the 8 a size_t would.
TEST(SceneLineIndex, HoldsFourBytesANewline) {
  const std::string newlines(100000, '\n');
  const scenes::detail::LineIndex lines(newlines.data(), newlines.size());
  EXPECT_LE(lines.bytes(), 4 * newlines.size());
  EXPECT_EQ(lines.lineOf(newlines.data()), 1);
  EXPECT_EQ(lines.lineOf(newlines.data() + 1), 2);
  EXPECT_EQ(lines.lineOf(newlines.data() + newlines.size() - 1), 100000);
}
