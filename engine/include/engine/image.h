#pragma once
// RGBA8 images: read back from the framebuffer, encoded as PNG, and read from PNG files.
// Writing files is not the engine's job: the programs write the encoded bytes through their
// one atomic writer (app/fileio).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

namespace engine {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  ///< rows top to bottom, 4 bytes a pixel

  /// The pixel at column x, row y (row 0 at the top).
  glm::u8vec4 pixel(int x, int y) const;
};

/// Reads the bound read framebuffer's colour (GL_BACK of the default one unless changed).
Image readFramebuffer(const glm::ivec2& size);
/// The image as a PNG file's bytes; throws engine::Error if it cannot be encoded.
std::string encodePng(const Image& image);
/// Reads a PNG as RGBA8; throws engine::Error naming the file.
Image readPng(const std::filesystem::path& file);

}  // namespace engine
