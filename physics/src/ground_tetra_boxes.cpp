// Which tetra boxes' ground corners move the box as a rigid body (physics/ground_contacts.h).
//
// A tetra box's bottom corners are 2 of its particles and 2 points embedded with weights 1/2, 1/2,
// 1/2 and -1/2, so pushed by their weights they lift its bottom particles and leave its top two
// where gravity took them, and every substep its sticks lift the top two in the passes after the
// push. Jakobsen's projection along a stick's present direction does not keep angular momentum
// (docs/physics.md, "Keeping a body's spin through its sticks"), and the 4-particle body is chiral,
// so a 1.4 x 0.4 x 0.4 m box lying alone gained the same spin about the vertical every step: with
// friction 0 it turned 2 rad in 30 s at 10 x 1, faster and faster; with friction, what friction took
// of that spin and of the sticks' sideways moves of its corners left it walking 6.4 cm in 30 s
// (docs/physics.md, "A tetra box lying still"). The ground's passes now make what they do to a free
// box a rigid body's move (collideGround, applyGroundFriction), and a resting box's sticks have
// nothing to undo.
//
// Only a free box (the rule of a tetra capsule's rigid block, GroundContacts::placeCapsulePoints):
// one with a link or joint is not a free rigid body, and the bottom box of a stack pushed as a rigid
// block under a top one pushed by weights lost stability runs (the 8 corners as one block, tried
// before: docs/physics.md, the same section).
#include <glm/geometric.hpp>

#include "particle_edges.h"
#include "physics/ground_contacts.h"
#include "physics/narrow_phase.h"

namespace phys {

void GroundContacts::followTetraBox() {
  tetraBoxes_.push_back({static_cast<std::uint32_t>(points_.size() - kTetraBoxCorners), points_.back().body});
}

void GroundContacts::markFreeTetraBoxes(std::span<const Body> bodies, const Particles& particles,
                                        std::span<const Manifold> manifolds,
                                        std::span<const std::uint8_t> joined) {
  anyFreeTetraBox_ = false;
  if (tetraBoxes_.empty()) return;
  markTouching(bodies.size(), manifolds);
  for (const TetraBox& t : tetraBoxes_) {
    if (anyStill_ && still_[t.firstPoint] != 0) continue;  // asleep: not pushed at all
    const Body& box = bodies[t.body];
    const bool free = (joined.empty() || joined[t.body] == 0) && touching_[t.body] == 0;
    // one inside out is left to its weights and its volume floor, which a rigid push would never turn back
    const bool block = free && detail::keepsItsVolume(box, particles.position);
    for (std::uint32_t k = 0; k < kTetraBoxCorners; ++k) points_[t.firstPoint + k].rigidBlock = 0;
    if (block) points_[t.firstPoint].rigidBlock = kTetraBoxCorners;
    anyFreeTetraBox_ = anyFreeTetraBox_ || block;
  }
}

}  // namespace phys
