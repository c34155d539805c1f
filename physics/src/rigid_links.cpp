// The position pass of links with a rigid end (physics/rigid_links.h).
#include "physics/rigid_links.h"

#include <glm/geometric.hpp>

#include "rigid_sides.h"

namespace phys::detail {

// XPBD's positional constraint with zero compliance (Müller et al. 2020, eqs. 2-5): the correction
// c along n = (pB - pA) / |pB - pA| is shared by the sides' generalised inverse masses along n, a
// rigid side's point both moving and turning its body. A pin's c is the whole distance: its
// direction is the gap's own, so a pin closes in any direction, as a particle pin does.
void solveRigidLinks(const RigidPassInput& input, std::span<const RigidLink> links) {
  RigidPassInput in = input;
  for (const RigidLink& link : links) {
    const SideView a = viewOf(in, link.a.side, link.a.rigid, link.a.local, link.a.point);
    const SideView b = viewOf(in, link.b.side, link.b.rigid, link.b.local, link.b.point);
    const Vec3 d = positionOf(in, b) - positionOf(in, a);
    const Real length = glm::length(d);
    Real c = 0.0;  // unit: m; positive when the points must come closer
    if (length > link.maxLength)
      c = length - link.maxLength;
    else if (length < link.minLength)
      c = length - link.minLength;
    if (c == 0.0 || length == 0.0) continue;  // within bounds; or at 0, no direction (and a pin holds)
    const Vec3 n = d / length;
    const Real w = inverseMassAlong(in, a, n) + inverseMassAlong(in, b, n);
    if (w <= 0.0) continue;
    const Vec3 p = (c / w) * n;
    push(in, a, p);
    push(in, b, -p);
  }
}

}  // namespace phys::detail
