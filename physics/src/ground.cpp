#include <algorithm>
#include <cmath>

#include "passes.h"

namespace phys::detail {

void collideGround(Particles& p, Real groundHeight, std::span<Real> depth) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Real penetration = groundHeight - p.position[i].y;
    if (penetration <= 0.0 || p.inverseMass[i] == 0.0) continue;
    p.position[i].y = groundHeight;
    depth[i] = std::max(depth[i], penetration);
  }
}

// Jakobsen 2001, "Friction": the tangential part of this substep's motion (x - x*) is cut in
// proportion to how deep the particle went, by editing x* so the velocity changes and the
// position does not.
void applyGroundFriction(Particles& p, std::span<const Real> depth, Real staticFriction,
                         Real dynamicFriction) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (depth[i] <= 0.0) continue;
    Vec3 slide = p.position[i] - p.previous[i];
    slide.y = 0.0;
    const Real slideLength = std::sqrt(slide.x * slide.x + slide.z * slide.z);
    if (slideLength == 0.0) continue;
    Real cut = 1.0;  // static: stop the slide entirely
    if (slideLength > staticFriction * depth[i]) {
      cut = std::min(1.0, dynamicFriction * depth[i] / slideLength);
    }
    p.previous[i] += cut * slide;
  }
}

}  // namespace phys::detail
