// Joints between bodies: links between embedded points. The correction is the weighted
// projection of REFERENCES.md for a point in each body, as for box-box contacts: with
// S = sum_A c_i^2 w_i + sum_B c_j^2 w_j and C the vector the gap must shrink by, A's particles
// move by +c_i w_i C / S and B's by -c_j w_j C / S. For a pin C is the whole gap, so one
// projection closes it exactly whatever its direction.
#include <glm/geometric.hpp>

#include "passes.h"

namespace phys::detail {

void solveLinks(Particles& p, std::span<const Link> links) {
  for (const Link& link : links) {
    const Vec3 gap = embeddedPosition(p.position, link.b) - embeddedPosition(p.position, link.a);
    Vec3 correction = gap;  // a pin closes the whole gap
    if (!link.isPin()) {
      const Real length = glm::length(gap);
      const Real target =
          length < link.minLength ? link.minLength : (length > link.maxLength ? link.maxLength : -1.0);
      if (target < 0.0 || length == 0.0) continue;  // within its bounds, or no direction to push along
      correction = gap * ((length - target) / length);
    }
    const Real denominator = embeddedWeight(p.inverseMass, link.a) + embeddedWeight(p.inverseMass, link.b);
    if (denominator == 0.0) continue;  // both ends pinned or frozen
    const Vec3 step = correction / denominator;
    shiftEmbedded(p.position, p.inverseMass, link.a, step);
    shiftEmbedded(p.position, p.inverseMass, link.b, -step);
  }
}

}  // namespace phys::detail
