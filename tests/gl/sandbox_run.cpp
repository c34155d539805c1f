#include "sandbox_run.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

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

glm::ivec2 toPixel(const engine::Image& image, const engine::FirstPersonCamera& camera,
                   const glm::vec3& world) {
  const float w = static_cast<float>(image.width), h = static_cast<float>(image.height);
  const glm::vec3 p = glm::project(world, camera.view(), camera.projection(w / h), glm::vec4(0, 0, w, h));
  return {static_cast<int>(p.x), static_cast<int>(h - p.y)};
}

}  // namespace testing_gl
