#include "scene_bounds.h"

#include <vector>

#include <glm/common.hpp>

#include "body_colors.h"

namespace sandbox {

std::optional<std::pair<glm::vec3, glm::vec3>> sceneBounds(const phys::World& world) {
  std::optional<std::pair<glm::vec3, glm::vec3>> b;
  auto add = [&](const glm::vec3& lo, const glm::vec3& hi) {
    if (!b) {
      b.emplace(lo, hi);
      return;
    }
    b->first = glm::min(b->first, lo);
    b->second = glm::max(b->second, hi);
  };
  std::vector<bool> inBody(world.particles().size(), false);
  for (phys::BodyId id{}; id < world.bodies().size(); ++id) {
    for (int k = 0; k < 8; ++k) {
      const glm::vec3 c(world.cornerPosition(id, k));
      add(c, c);
    }
    const phys::Body& body = world.bodies()[id];
    for (int k = 0; k < body.particleCount; ++k) inBody[body.firstParticle + k] = true;
  }
  const glm::vec3 half(kParticleDrawSize * 0.5f);
  for (std::size_t i = 0; i < inBody.size(); ++i) {
    if (!inBody[i])
      add(glm::vec3(world.particles().position[i]) - half, glm::vec3(world.particles().position[i]) + half);
  }
  return b;
}

}  // namespace sandbox
