#include <glm/geometric.hpp>

#include "passes.h"

namespace phys::detail {

// Jakobsen 2001, "Advanced Character Physics", stick constraint, with the sign of the printed
// listing corrected (REFERENCES.md): diff = (|d| - r) / (|d| (w1 + w2)).
void relaxSticks(Particles& p, std::span<const Stick> sticks) {
  for (const Stick& s : sticks) {
    const Real w1 = p.inverseMass[s.a];
    const Real w2 = p.inverseMass[s.b];
    const Real wSum = w1 + w2;
    if (wSum == 0.0) continue;
    const Vec3 delta = p.position[s.b] - p.position[s.a];
    const Real len = glm::length(delta);
    if (len == 0.0) continue;  // direction undefined; another stick or step will separate them
    const Real diff = (len - s.length) / (len * wSum);
    p.position[s.a] += (w1 * diff) * delta;
    p.position[s.b] -= (w2 * diff) * delta;
  }
}

}  // namespace phys::detail
