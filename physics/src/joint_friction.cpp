// Friction in the joints of particle bodies (JointFriction). A ragdoll's particle parts keep no
// spin of their own that their passes would take away: a head lying loosely in a pile, turning
// about its own axis, goes on turning while friction with what it lies on, bounded by mu times a
// small push, slows it by a tenth a second. The joint's friction takes the two parts' relative
// spin away as a rigid joint's JointDesc::damping does (Mueller et al. 2020, section 3.6): an
// angular impulse L between their rigid motions along the relative spin d,
// L = share |w_rel| / (d.Ia^-1 d + d.Ib^-1 d), given to one and taken from the other, so their
// momentum and angular momentum are kept. Each body's change of spin dw turns its particles'
// motion by dw x r, which x* carries (motion = x - x*), and its rigid motion by exactly dw, so a
// body's spin is found once a step and kept up to date as each of its joints turns it. Once a
// step, not every substep: the share is small, and the spins cost more than the rest of it.
#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "passes.h"

namespace phys::detail {
namespace {

// A body's rigid motion over the last substep, as massProperties and rigidMotion give it, in one
// pass over its particles: sums taken from its first particle (so that a body far from the origin
// keeps its digits), its inertia from the second moments by the parallel axis theorem.
BodySpin spinOf(const Particles& p, const Body& body) {
  BodySpin out;
  out.state = BodySpin::State::Immovable;
  const ParticleId first = body.firstParticle, end = first + body.particleCount;
  if (body.particleCount == 0) return out;
  const Vec3 origin = p.position[first];
  Real mass = 0.0;
  Vec3 moment(0.0), momentum(0.0), angularMomentum(0.0);
  glm::dmat3 second(0.0);  // sum of m r r^T about the first particle
  for (ParticleId i = first; i < end; ++i) {
    if (p.inverseMass[i] == 0.0) return out;  // pinned, frozen or asleep
    const Real m = 1.0 / p.inverseMass[i];
    const Vec3 r = p.position[i] - origin, motion = p.position[i] - p.previous[i];
    mass += m;
    moment += m * r;
    momentum += m * motion;
    angularMomentum += m * glm::cross(r, motion);
    second += m * glm::outerProduct(r, r);
  }
  const Vec3 c = moment / mass;
  const glm::dmat3 spread = second - mass * glm::outerProduct(c, c);  // about the centre
  const glm::dmat3 inertia = (spread[0][0] + spread[1][1] + spread[2][2]) * glm::dmat3(1.0) - spread;
  if (!(std::abs(glm::determinant(inertia)) > 0.0)) return out;  // crushed flat
  out.state = BodySpin::State::Known;
  out.centre = origin + c;
  out.inverseInertia = glm::inverse(inertia);
  out.angular = out.inverseInertia * (angularMomentum - glm::cross(c, momentum));
  return out;
}

// Turns the body's particles' motion by `by` about its centre, and its spin with them.
void turn(Particles& p, const Body& body, BodySpin& spin, const Vec3& by) {
  for (ParticleId i = body.firstParticle; i < body.firstParticle + body.particleCount; ++i)
    p.previous[i] -= glm::cross(by, p.position[i] - spin.centre);
  spin.angular += by;
}

}  // namespace

void dampJointFriction(Particles& p, std::span<const Body> bodies, std::span<const JointFriction> frictions,
                       Real dt, std::span<BodySpin> spins) {
  for (const JointFriction& f : frictions) spins[f.a].state = spins[f.b].state = BodySpin::State::Unknown;
  auto spin = [&](BodyId id) -> BodySpin& {
    if (spins[id].state == BodySpin::State::Unknown) spins[id] = spinOf(p, bodies[id]);
    return spins[id];
  };
  for (const JointFriction& f : frictions) {
    const Real share = std::min(f.rate * dt, 1.0);
    if (share <= 0.0) continue;
    BodySpin &a = spin(f.a), &b = spin(f.b);
    // A pinned, frozen or sleeping part (inverse mass 0) or one crushed flat is left alone.
    if (a.state != BodySpin::State::Known || b.state != BodySpin::State::Known) continue;
    const Vec3 relative = b.angular - a.angular;
    const Real speed = glm::length(relative);
    if (!(speed > 0.0)) continue;
    const Vec3 d = relative / speed;
    const Real w = glm::dot(d, a.inverseInertia * d) + glm::dot(d, b.inverseInertia * d);
    if (!(w > 0.0)) continue;
    const Vec3 impulse = (share * speed / w) * d;
    turn(p, bodies[f.a], a, a.inverseInertia * impulse);
    turn(p, bodies[f.b], b, -(b.inverseInertia * impulse));
  }
}

}  // namespace phys::detail
