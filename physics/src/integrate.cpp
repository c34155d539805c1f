#include <cmath>

#include "passes.h"

namespace phys::detail {

void integrate(Particles& p, const Vec3& gravity, Real damping, Real h) {
  const Real keep = std::exp(-damping * h);  // 1 - d
  const Vec3 gravityStep = gravity * (h * h);
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (p.inverseMass[i] == 0.0) continue;  // pinned
    const Vec3 x = p.position[i];
    p.position[i] = x + keep * (x - p.previous[i]) + gravityStep;
    p.previous[i] = x;
  }
}

}  // namespace phys::detail
