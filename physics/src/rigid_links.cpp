// The position pass of links with a rigid end (physics/rigid_links.h).
#include "physics/rigid_links.h"

#include <glm/geometric.hpp>

#include "rigid_sides.h"

namespace phys::detail {
namespace {

// A pin's end as it is corrected: a rigid body is turned about the lever its point had as the
// substep started (pinLever; docs/physics.md, "Joints"), so that the pin's two impulses act at one
// point, the pin where the substep started, and keep the bodies' angular momentum. A range link's
// ends keep the levers they have now: its two points are apart, and its direction turns with them.
struct LinkEnd {
  SideView view;
  Vec3 lever{0.0};

  LinkEnd(const RigidPassInput& in, const BodyPoint& end, const SideView& s, const Vec3& n, bool pin)
      : view(s), lever(s.at) {
    if (pin && s.side == ContactSide::Rigid)
      lever = pinLever(in.rigid, s.rigid, s.at, in.rigid.previousOrientation[s.rigid] * end.local, n);
  }
  Real inverseMass(const RigidPassInput& in, const Vec3& n) const {
    if (view.side == ContactSide::Rigid) return leveredInverseMass(in.rigid, view.rigid, view.at, lever, n);
    return inverseMassAlong(in, view, n);
  }
  void push(RigidPassInput& in, const Vec3& p) const {
    if (view.side == ContactSide::Rigid) {
      applyPositionalImpulse(in.rigid, view.rigid, lever, p);
      return;
    }
    detail::push(in, view, p);
  }
};

}  // namespace

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
    const LinkEnd endA(in, link.a, a, n, link.isPin()), endB(in, link.b, b, n, link.isPin());
    const Real w = endA.inverseMass(in, n) + endB.inverseMass(in, n);
    if (w <= 0.0) continue;
    const Vec3 p = (c / w) * n;
    endA.push(in, p);
    endB.push(in, -p);
  }
}

}  // namespace phys::detail
