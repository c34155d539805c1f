// Damping of each box's internal motion (Müller et al., "Position Based Dynamics", 2007,
// section 3.5): the particles' velocities are pulled towards the rigid motion of their box,
// the velocity of its centre of mass plus its angular velocity about it, which keeps the box's
// linear and angular momentum. A box made of particles has no business vibrating inside, but
// a few relaxation passes leave some deformation in each substep, and Verlet turns it into
// velocity: contacts carried by weights of both signs (tetra boxes) and parts squeezed between
// heavier ones then never come to rest. Removing that motion leaves the rigid one untouched.
// The box's mass properties and rigid motion live here; restitution and the drag use them too.
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "passes.h"
#include "relax_lanes.h"

namespace phys::detail {

bool massProperties(const Particles& p, const Body& box, MassProperties& out) {
  const ParticleId first = box.firstParticle, end = first + box.particleCount;
  out = {};
  if (box.particleCount == 0) return false;  // a rigid body: its own model has its mass
  for (ParticleId i = first; i < end; ++i) {
    if (p.inverseMass[i] == 0.0) return false;  // pinned or frozen
    const Real m = 1.0 / p.inverseMass[i];
    out.mass += m;
    out.centre += m * p.position[i];
  }
  out.centre /= out.mass;
  for (ParticleId i = first; i < end; ++i) {
    const Vec3 r = p.position[i] - out.centre;
    out.inertia += (1.0 / p.inverseMass[i]) * (glm::dot(r, r) * glm::dmat3(1.0) - glm::outerProduct(r, r));
  }
  return std::abs(glm::determinant(out.inertia)) > 0.0;
}

void addBoxVelocity(Particles& p, const Body& box, const Vec3& centre, const Vec3& dv, const Vec3& dw,
                    Real h) {
  for (int j = 0; j < box.particleCount; ++j) {
    const ParticleId i = box.firstParticle + j;
    if (p.inverseMass[i] == 0.0) continue;
    p.position[i] += (dv + glm::cross(dw, p.position[i] - centre)) * h;
  }
}

RigidMotion rigidMotion(const Particles& p, const Body& box, const MassProperties& m) {
  const ParticleId first = box.firstParticle, end = first + box.particleCount;
  Vec3 momentum(0.0), angularMomentum(0.0);
  for (ParticleId i = first; i < end; ++i) {
    const Real mass = 1.0 / p.inverseMass[i];
    momentum += mass * (p.position[i] - p.previous[i]);
    angularMomentum += mass * glm::cross(p.position[i] - m.centre, p.position[i] - p.previous[i]);
  }
  return {momentum / m.mass, glm::inverse(m.inertia) * angularMomentum};
}

void dampBodyMotion(Particles& p, std::span<const Body> boxes, const BodyLayout& layout, Real fraction,
                    const Workers* workers) {
  if (fraction <= 0.0) return;
  // The same, eight bodies at a time.
  inLanePieces(dampLaneArguments(p, layout, fraction), workers,
               [](const DampLaneArguments& a) { dampBodyLanes(a); });
  MassProperties m;
  for (const BodyId b : layout.others()) {
    const Body& box = boxes[b];
    if (!massProperties(p, box, m)) continue;  // pinned, frozen or crushed flat: left alone
    // Motions are per substep (x - x*), so no h is needed: velocity times h throughout.
    const RigidMotion rigid = rigidMotion(p, box, m);
    for (ParticleId i = box.firstParticle; i < box.firstParticle + box.particleCount; ++i) {
      const Vec3 target = rigid.linear + glm::cross(rigid.angular, p.position[i] - m.centre);
      const Vec3 motion = p.position[i] - p.previous[i];
      p.previous[i] = p.position[i] - (motion + fraction * (target - motion));
    }
  }
}

}  // namespace phys::detail
