#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "passes.h"

namespace phys::detail {

// Integration reads and writes each particle once, so it is bound by memory, and many small pieces
// cost more than they save: one piece a thread, of at least this many particles
// (docs/performance.md, "Integration in one piece a thread").
constexpr std::size_t kFewestParticlesPerPiece = 2048;

void integrateRange(Particles& p, const WorldSettings& world, Real h, std::span<Vec3> checked,
                    std::size_t begin, std::size_t end) {
  const Real keep = std::exp(-world.damping * h);  // 1 - d
  const bool uniform = world.gravityMode == GravityMode::Uniform;
  const Vec3 gravityStep = world.gravity * (h * h);
  // Point gravity: a pull of fixed strength towards the point (none at the point itself).
  const Real pull = world.gravityStrength * h * h;
  for (std::size_t i = begin; i < end; ++i) {
    if (p.inverseMass[i] == 0.0) continue;  // pinned
    const Vec3 x = p.position[i];
    Vec3 step = gravityStep;
    if (!uniform) {
      const Vec3 towards = world.gravityPoint - x;
      const Real distance = glm::length(towards);
      step = distance > 0.0 ? towards * (pull / distance) : Vec3(0.0);
    }
    p.position[i] = x + keep * (x - p.previous[i]) + step;
    p.previous[i] = checked[i] = x;
  }
}

void integrate(Particles& p, const WorldSettings& world, Real h, std::span<Vec3> checked,
               const Workers* workers) {
  auto range = [&](std::size_t begin, std::size_t end) { integrateRange(p, world, h, checked, begin, end); };
  const std::size_t threads = workers == nullptr ? 1 : static_cast<std::size_t>(workers->threads());
  forEachRange(workers, p.size(), std::max(kFewestParticlesPerPiece, (p.size() + threads - 1) / threads),
               range);
}

}  // namespace phys::detail
