#include <stdexcept>

#include <glm/gtc/quaternion.hpp>
#include <glm/trigonometric.hpp>

#include "scenes/scene.h"

namespace scenes {
namespace {

// The skeleton's scene: one tilted box and four loose particles fall onto the ground, so the
// first frames show the integrator, the box's sticks and ground contact with friction.
Scene fallingBox() {
  Scene scene{"falling-box", "a tilted 1 m box and four particles dropped onto the ground",
              phys::World{}, CameraStart{{0.0f, 2.5f, 7.0f}, {0.0f, 1.0f, 0.0f}}};
  phys::BoxDesc box;
  box.center = {0.0, 3.0, 0.0};
  box.size = {1.0, 1.0, 1.0};
  box.orientation = glm::dquat(glm::radians(glm::dvec3(20.0, 35.0, 10.0)));
  box.mass = 8.0;
  scene.world.addBox(box);
  const phys::Vec3 particleStarts[] = {{-1.5, 2.0, 0.5}, {1.5, 2.5, 0.5}, {-1.0, 3.5, -1.0}, {1.0, 4.0, -1.0}};
  for (const phys::Vec3& p : particleStarts) scene.world.addParticle({p, phys::Vec3(0.0), 0.1});
  return scene;
}

struct Entry {
  const char* name;
  Scene (*make)();
};
constexpr Entry kScenes[] = {{"falling-box", fallingBox}};

}  // namespace

std::vector<std::string> builtinSceneNames() {
  std::vector<std::string> names;
  for (const Entry& e : kScenes) names.emplace_back(e.name);
  return names;
}

std::string defaultSceneName() { return kScenes[0].name; }

Scene makeBuiltinScene(std::string_view name) {
  for (const Entry& e : kScenes) {
    if (name == e.name) return e.make();
  }
  std::string known;
  for (const Entry& e : kScenes) known += std::string(known.empty() ? "" : ", ") + e.name;
  throw std::invalid_argument("unknown scene '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace scenes
