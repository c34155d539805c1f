// Friction in the joints of particle bodies (JointFriction). A ragdoll's particle parts keep no
// spin of their own that their passes would take away: a head lying loosely in a pile, turning
// about its own axis, goes on turning while friction with what it lies on, bounded by mu times a
// small push, slows it by a tenth a second. The joint's friction takes the two parts' relative
// spin away as a rigid joint's JointDesc::damping does (Mueller et al. 2020, section 3.6): an
// angular impulse L between their rigid motions along the relative spin d,
// L = share |w_rel| / (d.Ia^-1 d + d.Ib^-1 d), given to one and taken from the other, so their
// momentum and angular momentum are kept. Each body's change of spin dw turns its particles'
// motion by dw x r, which x* carries (motion = x - x*). Once a step, not every substep: the share
// is small, and the bodies' mass properties and rigid motions cost more than the rest of it.
#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "passes.h"

namespace phys::detail {
namespace {

void turnParticles(Particles& p, const Body& body, const Vec3& centre, const Vec3& turn) {
  for (ParticleId i = body.firstParticle; i < body.firstParticle + body.particleCount; ++i)
    p.previous[i] -= glm::cross(turn, p.position[i] - centre);
}

}  // namespace

void dampJointFriction(Particles& p, std::span<const Body> bodies, std::span<const JointFriction> frictions,
                       Real dt) {
  MassProperties ma, mb;
  for (const JointFriction& f : frictions) {
    const Real share = std::min(f.rate * dt, 1.0);
    if (share <= 0.0) continue;
    const Body &a = bodies[f.a], &b = bodies[f.b];
    // A pinned, frozen or sleeping part (inverse mass 0) or one crushed flat is left alone.
    if (!massProperties(p, a, ma) || !massProperties(p, b, mb)) continue;
    const Vec3 relative = rigidMotion(p, b, mb).angular - rigidMotion(p, a, ma).angular;
    const Real spin = glm::length(relative);
    if (!(spin > 0.0)) continue;
    const Vec3 d = relative / spin;
    const glm::dmat3 inverseA = glm::inverse(ma.inertia), inverseB = glm::inverse(mb.inertia);
    const Real w = glm::dot(d, inverseA * d) + glm::dot(d, inverseB * d);
    if (!(w > 0.0)) continue;
    const Vec3 impulse = (share * spin / w) * d;
    turnParticles(p, a, ma.centre, inverseA * impulse);
    turnParticles(p, b, mb.centre, -(inverseB * impulse));
  }
}

}  // namespace phys::detail
