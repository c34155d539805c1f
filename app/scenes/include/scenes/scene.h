#pragma once
// A scene: a world ready to step, plus where a viewer's camera starts.
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "physics/world.h"

namespace scenes {

/// Where the camera starts, in metres.
struct CameraStart {
  glm::vec3 eye{0.0f, 2.0f, 8.0f};
  glm::vec3 target{0.0f, 1.0f, 0.0f};
};

struct Scene {
  std::string name;
  std::string description;  ///< one line, shown by the sandbox
  phys::World world;
  CameraStart camera;
};

/// Names of the scenes built in code, default first.
std::vector<std::string> builtinSceneNames();
/// The scene the sandbox opens with no argument.
std::string defaultSceneName();
/// Builds a built-in scene; throws std::invalid_argument naming the known scenes if unknown.
Scene makeBuiltinScene(std::string_view name);

}  // namespace scenes
