// Damping of each box's internal motion (Müller et al., "Position Based Dynamics", 2007,
// section 3.5): the particles' velocities are pulled towards the rigid motion of their box,
// the velocity of its centre of mass plus its angular velocity about it, which keeps the box's
// linear and angular momentum. A box made of particles has no business vibrating inside, but
// a few relaxation passes leave some deformation in each substep, and Verlet turns it into
// velocity: contacts carried by weights of both signs (tetra boxes) and parts squeezed between
// heavier ones then never come to rest. Removing that motion leaves the rigid one untouched.
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "passes.h"

namespace phys::detail {

namespace {

bool movable(const Particles& p, const Box& box) {
  for (int j = 0; j < box.particleCount; ++j) {
    if (p.inverseMass[box.firstParticle + j] == 0.0) return false;  // pinned or frozen
  }
  return true;
}

}  // namespace

void dampBodyMotion(Particles& p, std::span<const Box> boxes, Real fraction) {
  if (fraction <= 0.0) return;
  for (const Box& box : boxes) {
    if (!movable(p, box)) continue;
    const ParticleId first = box.firstParticle, end = first + static_cast<ParticleId>(box.particleCount);
    // Motions are per substep (x - x*), so no h is needed: velocity times h throughout.
    Real mass = 0.0;
    Vec3 centre(0.0), momentum(0.0);
    for (ParticleId i = first; i < end; ++i) {
      const Real m = 1.0 / p.inverseMass[i];
      mass += m;
      centre += m * p.position[i];
      momentum += m * (p.position[i] - p.previous[i]);
    }
    centre /= mass;
    const Vec3 linear = momentum / mass;
    Vec3 angular(0.0);
    glm::dmat3 inertia(0.0);
    for (ParticleId i = first; i < end; ++i) {
      const Real m = 1.0 / p.inverseMass[i];
      const Vec3 r = p.position[i] - centre;
      angular += m * glm::cross(r, p.position[i] - p.previous[i]);
      inertia += m * (glm::dot(r, r) * glm::dmat3(1.0) - glm::outerProduct(r, r));
    }
    // Four or more particles not in one plane make the inertia positive definite; a box
    // crushed flat does not, and is left alone.
    if (!(std::abs(glm::determinant(inertia)) > 0.0)) continue;
    const Vec3 omega = glm::inverse(inertia) * angular;
    for (ParticleId i = first; i < end; ++i) {
      const Vec3 rigid = linear + glm::cross(omega, p.position[i] - centre);
      const Vec3 motion = p.position[i] - p.previous[i];
      p.previous[i] = p.position[i] - (motion + fraction * (rigid - motion));
    }
  }
}

}  // namespace phys::detail
