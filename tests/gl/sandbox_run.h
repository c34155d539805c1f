#pragma once
// Runs the real sandbox program under the test's Xvfb server to a PNG, and maps world points to
// the pixels a scene's starting camera puts them at.
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/camera.h"
#include "engine/image.h"

namespace testing_gl {

/// `sandbox ARGS --screenshot OUTPUT_DIR/<png> --frames N --data DATA_DIR`; throws if it fails.
engine::Image runSandbox(const std::string& args, const std::string& png, int frames);

/// Pixel (column, row from the top) where a world point lands in `image` seen by `camera`.
glm::ivec2 toPixel(const engine::Image& image, const engine::FirstPersonCamera& camera,
                   const glm::vec3& world);
/// The same in a sandbox screenshot, whose scene is drawn left of the panels' column unless they
/// are hidden (sandbox::sceneView).
glm::ivec2 toSandboxPixel(const engine::Image& image, const engine::FirstPersonCamera& camera,
                          const glm::vec3& world, bool panelsShown = true);

/// Pixels in the rectangle for which `test(r, g, b)` holds.
template <typename Test>
int countPixels(const engine::Image& image, int x0, int y0, int w, int h, Test test) {
  int n = 0;
  for (int y = y0; y < y0 + h && y < image.height; ++y) {
    for (int x = x0; x < x0 + w && x < image.width; ++x) {
      const glm::u8vec4 p = image.pixel(x, y);
      n += test(int(p.r), int(p.g), int(p.b)) ? 1 : 0;
    }
  }
  return n;
}

}  // namespace testing_gl
