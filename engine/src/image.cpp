#include "engine/image.h"

#include <cstdlib>
#include <system_error>

#include <glad/gl.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include "engine/error.h"

namespace engine {

glm::u8vec4 Image::pixel(int x, int y) const {
  const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 4;
  return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
}

Image readFramebuffer(const glm::ivec2& size) {
  Image image;
  image.width = size.x;
  image.height = size.y;
  image.rgba.resize(static_cast<std::size_t>(size.x) * size.y * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  // GL's row 0 is the bottom one; images put it on top.
  const std::size_t rowBytes = static_cast<std::size_t>(size.x) * 4;
  for (int y = 0; y < size.y / 2; ++y) {
    std::swap_ranges(image.rgba.begin() + static_cast<std::ptrdiff_t>(y * rowBytes),
                     image.rgba.begin() + static_cast<std::ptrdiff_t>((y + 1) * rowBytes),
                     image.rgba.begin() + static_cast<std::ptrdiff_t>((size.y - 1 - y) * rowBytes));
  }
  return image;
}

void writePng(const std::filesystem::path& file, const Image& image) {
  const std::filesystem::path temp = file.string() + ".tmp";
  if (stbi_write_png(temp.string().c_str(), image.width, image.height, 4, image.rgba.data(),
                     image.width * 4) == 0) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    throw Error(file.string() + ": cannot write PNG (is the folder there and writable?)");
  }
  std::error_code ec;
  std::filesystem::rename(temp, file, ec);
  if (ec) throw Error(file.string() + ": cannot move the written PNG into place: " + ec.message());
}

Image readPng(const std::filesystem::path& file) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(file.string().c_str(), &w, &h, &channels, 4);
  if (data == nullptr) throw Error(file.string() + ": cannot read PNG: " + stbi_failure_reason());
  Image image;
  image.width = w;
  image.height = h;
  image.rgba.assign(data, data + static_cast<std::size_t>(w) * h * 4);
  stbi_image_free(data);
  return image;
}

}  // namespace engine
