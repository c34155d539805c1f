#include <cmath>

#include <glm/geometric.hpp>

#include "passes.h"

namespace phys::detail {

void integrate(Particles& p, const WorldSettings& world, Real h, std::span<Vec3> checked) {
  const Real keep = std::exp(-world.damping * h);  // 1 - d
  const std::size_t n = p.size();
  if (world.gravityMode == GravityMode::Uniform) {
    const Vec3 gravityStep = world.gravity * (h * h);
    for (std::size_t i = 0; i < n; ++i) {
      if (p.inverseMass[i] == 0.0) continue;  // pinned
      const Vec3 x = p.position[i];
      p.position[i] = x + keep * (x - p.previous[i]) + gravityStep;
      p.previous[i] = checked[i] = x;
    }
    return;
  }
  // Point gravity: a pull of fixed strength towards the point (none at the point itself).
  const Real pull = world.gravityStrength * h * h;
  for (std::size_t i = 0; i < n; ++i) {
    if (p.inverseMass[i] == 0.0) continue;
    const Vec3 x = p.position[i];
    const Vec3 towards = world.gravityPoint - x;
    const Real distance = glm::length(towards);
    const Vec3 gravityStep = distance > 0.0 ? towards * (pull / distance) : Vec3(0.0);
    p.position[i] = x + keep * (x - p.previous[i]) + gravityStep;
    p.previous[i] = checked[i] = x;
  }
}

}  // namespace phys::detail
