#include "sandbox_run.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "panels.h"

namespace testing_gl {

engine::Image runSandbox(const std::string& args, const std::string& png, int frames) {
  namespace fs = std::filesystem;
  fs::create_directories(OUTPUT_DIR);
  const fs::path file = fs::path(OUTPUT_DIR) / png;
  fs::remove(file);
  const std::string command = std::string("'") + SANDBOX_EXE + "' " + args + " --screenshot '" +
                              file.string() + "' --frames " + std::to_string(frames) + " --data '" +
                              DATA_DIR + "' > /dev/null";
  if (std::system(command.c_str()) != 0) throw std::runtime_error("sandbox failed: " + command);
  return engine::readPng(file);
}

namespace {

// `view` in pixels from the top-left corner, as sandbox::ScreenRect counts them.
glm::ivec2 project(const engine::Image& image, const engine::FirstPersonCamera& camera,
                   const glm::vec3& world, const sandbox::ScreenRect& view) {
  const float h = static_cast<float>(image.height);
  const glm::vec4 viewport(view.x, h - view.y - view.height, view.width, view.height);
  const glm::vec3 p =
      glm::project(world, camera.view(), camera.projection(view.width / view.height), viewport);
  return {static_cast<int>(p.x), static_cast<int>(h - p.y)};
}

}  // namespace

glm::ivec2 toPixel(const engine::Image& image, const engine::FirstPersonCamera& camera,
                   const glm::vec3& world) {
  const sandbox::ScreenRect all{0.0f, 0.0f, static_cast<float>(image.width),
                                static_cast<float>(image.height)};
  return project(image, camera, world, all);
}

glm::ivec2 toSandboxPixel(const engine::Image& image, const engine::FirstPersonCamera& camera,
                          const glm::vec3& world, bool panelsShown) {
  return project(
      image, camera, world,
      sandbox::sceneView(static_cast<float>(image.width), static_cast<float>(image.height), panelsShown));
}

}  // namespace testing_gl
