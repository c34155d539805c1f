// The mouse spring (World::setDrag): a damped spring from an embedded point to a target, stepped
// by backward Euler once per substep, before the passes, like any force.
//
// With F = k (T - p) - b v on the point and K the point's inverse mass (how its velocity answers an
// impulse there), the impulse J over the substep is taken with the force at the substep's end:
//   J = h (k (T - p - h K J) - b (v + K J)),  so  (1 + (h^2 k + h b) K) J = h (k (T - p) - b v).
// As k grows the point tends to land on the target, as b grows to stop: it never overshoots,
// whatever the stiffness. At rest it holds a weight m g at exactly m g / k below the target. For
// a lone point this is XPBD's damped compliant constraint (Macklin, Müller, Chentanez 2016,
// eq. 26) in closed form, compliance 1 / k.
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "passes.h"
#include "rigid_motion.h"

namespace phys::detail {
namespace {

// The point moved alone, through its carrier particles: K = sum c_i^2 w_i (REFERENCES.md).
void dragCarriers(Particles& p, const Embedding& point, const Vec3& force, Real stiffness, Real damping,
                  Real h) {
  const Real K = embeddedWeight(p.inverseMass, point);
  const Vec3 impulse = h * force / (1.0 + (h * h * stiffness + h * damping) * K);
  // The impulse moves the point by h K J; shiftEmbedded moves particle i by c_i w_i times the
  // step, which moves the point by K times it.
  shiftEmbedded(p.position, p.inverseMass, point, h * impulse);  // K = 0 (all pinned): nothing moves
}

}  // namespace

void applyDrag(Particles& p, const Body* box, const Embedding& point, const Vec3& target, Real stiffness,
               Real damping, Real h) {
  const Vec3 x = embeddedPosition(p.position, point);
  const Vec3 force = stiffness * (target - x) - damping * (x - embeddedPosition(p.previous, point)) / h;
  MassProperties m;
  if (box == nullptr || !massProperties(p, *box, m)) {
    // A loose particle; a box crushed flat, which has no inertia to answer with; or a frozen box,
    // which its carriers' zero inverse masses keep in place.
    dragCarriers(p, point, force, stiffness, damping, h);
    return;
  }
  // A box answers as a rigid body: K = 1/M + [r]x^T I^-1 [r]x at r from its centre. Through the
  // carriers alone (a quarter to an eighth of the box's mass) the spring would move the point
  // far, the box's sticks would pull it back, and the pull would come out far softer than k: a
  // 1 kg box held by a corner at 60 Hz sagged 81 mm below the target, not M g / k = 4.9 mm.
  const glm::dmat3 rx = crossMatrix(x - m.centre), inverseInertia = glm::inverse(m.inertia);
  const glm::dmat3 K = glm::dmat3(1.0 / m.mass) + glm::transpose(rx) * inverseInertia * rx;
  const Vec3 impulse = glm::inverse(glm::dmat3(1.0) + (h * h * stiffness + h * damping) * K) * (h * force);
  // massProperties succeeded, so no carrier is pinned: every particle takes dv + dw x r_i.
  addBoxVelocity(p, *box, m.centre, impulse / m.mass, inverseInertia * glm::cross(x - m.centre, impulse), h);
}

}  // namespace phys::detail
