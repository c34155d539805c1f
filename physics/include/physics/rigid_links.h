#pragma once
// Links with a rigid body at one end or both (docs/physics.md, "Rigid bodies"): the pins and range
// links of constraints.h (Link) with each end either a point fixed in a rigid body's frame or a
// point carried by a particle body's particles, so that a scene's <link> joins bodies of any model
// and a rigid body can hang from a particle body. (Ragdolls of rigid parts use rigid_joints.h.)
// Solved in the position passes by XPBD's positional impulses (Müller et al. 2020, 3.3.1), hard
// (no compliance), as Links are rigid projections in every method.
#include <span>

#include "physics/constraints.h"
#include "physics/rigid_bodies.h"
#include "physics/rigid_contacts.h"

namespace phys {

/// A point a joint holds: fixed in a rigid body (side Rigid: `rigid` and `local`, m, in its frame
/// from its centre) or carried by particles (side Particles: `point`). World::pointOn makes one
/// for any body.
struct BodyPoint {
  ContactSide side = ContactSide::Particles;
  RigidId rigid{};
  Vec3 local{0.0};
  Embedding point;

  static BodyPoint embedded(const Embedding& e) {
    BodyPoint p;
    p.point = e;
    return p;
  }
  static BodyPoint onRigid(RigidId rigid, const Vec3& local) {
    BodyPoint p;
    p.side = ContactSide::Rigid;
    p.rigid = rigid;
    p.local = local;
    return p;
  }
};

/// A link (a pin when maxLength is 0, else a range; the same meaning as Link) with a rigid end.
struct RigidLink {
  BodyPoint a;
  BodyPoint b;
  Real minLength = 0.0;  ///< unit: m
  Real maxLength = 0.0;  ///< unit: m; may be infinite (kNoMaxLength)

  bool isPin() const { return maxLength == 0.0; }
};

namespace detail {
/// One pass over the links: each pulls its two points to within its bounds by a positional impulse
/// along the line between them, shared by the two sides' inverse masses along it.
void solveRigidLinks(const RigidPassInput& in, std::span<const RigidLink> links);
}  // namespace detail

}  // namespace phys
