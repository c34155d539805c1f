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
  // The window shows every pixel opaque, whatever alpha blending left in the framebuffer (the
  // overlay's translucent runs, the shadows): so does the picture, or a viewer would show the
  // page through those pixels.
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
  // GL's row 0 is the bottom one; images put it on top.
  const std::size_t rowBytes = static_cast<std::size_t>(size.x) * 4;
  for (int y = 0; y < size.y / 2; ++y) {
    std::swap_ranges(image.rgba.begin() + static_cast<std::ptrdiff_t>(y * rowBytes),
                     image.rgba.begin() + static_cast<std::ptrdiff_t>((y + 1) * rowBytes),
                     image.rgba.begin() + static_cast<std::ptrdiff_t>((size.y - 1 - y) * rowBytes));
  }
  return image;
}

std::string encodePng(const Image& image) {
  // stb's file writer ignores fwrite's and fclose's errors (a full disk gave a truncated PNG
  // and success); encoded into memory, the bytes are whole and the caller's writer checks.
  std::string png;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<std::size_t>(size));
  };
  if (image.width <= 0 || image.height <= 0 ||
      stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(),
                             image.width * 4) == 0) {
    throw Error("cannot encode a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                " image as PNG");
  }
  return png;
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
