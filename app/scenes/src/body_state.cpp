#include "body_state.h"

#include <tuple>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace scenes::detail {

phys::Vec3 loadVelocity(const phys::World& world, phys::ParticleId id) {
  const phys::SolverSettings& solver = world.solverSettings();
  const double h = solver.dt / solver.substeps;
  return world.velocity(id) + world.gravityAt(world.particles().position[id]) * (h / 2);
}

RigidState rigidState(const phys::World& world, phys::BodyId id) {
  const phys::Body& box = world.bodies()[id];
  const phys::Particles& particles = world.particles();
  RigidState state;
  state.pose = world.bodyPose(id);
  if (box.model == phys::BodyModel::Rigid) {
    // Its own velocities, of the last substep's middle, moved to the pose's time as addBody reads
    // them back.
    const phys::RigidBodies& rigid = world.rigidBodies();
    if (rigid.inverseMass[box.rigid] == 0.0) {  // frozen by the guard
      state.frozen = true;
      state.mass = phys::BodyDesc{}.mass;
      return state;
    }
    std::tie(state.velocity, state.angularVelocity) = world.rigidDescVelocity(id);
    state.mass = 1.0 / rigid.inverseMass[box.rigid];
    return state;
  }
  state.mass = 0.0;
  for (int j = 0; j < box.particleCount; ++j) {
    const double inverseMass = particles.inverseMass[box.firstParticle + j];
    // The guard freezes a box whole (inverse mass 0 on every particle): its mass is gone.
    if (inverseMass == 0.0) {
      state.frozen = true;
    } else {
      state.mass += 1.0 / inverseMass;
    }
  }
  if (state.frozen) {
    state.mass = phys::BodyDesc{}.mass;
    return state;
  }

  // addBody gives particle j the velocity v + w x r_j, with r_j its offset at the pose. The
  // offsets sum to zero for both models, so the least-squares v is the mean velocity, and w
  // solves I w = sum r_j x (v_j - v) with I = sum (|r_j|^2 1 - r_j r_j^T) (equal masses): the
  // fit keeps the box's momentum and angular momentum.
  phys::Vec3 velocities[8];
  for (int j = 0; j < box.particleCount; ++j) {
    velocities[j] = loadVelocity(world, box.firstParticle + j);
    state.velocity += velocities[j];
  }
  state.velocity /= static_cast<double>(box.particleCount);
  glm::dmat3 inertia(0.0);
  phys::Vec3 angularMomentum(0.0);
  for (int j = 0; j < box.particleCount; ++j) {
    const phys::Vec3 r = state.pose.orientation * phys::boxParticleLocal(box.model, box.halfExtents, j);
    inertia += glm::dmat3(glm::dot(r, r)) - glm::outerProduct(r, r);
    angularMomentum += glm::cross(r, velocities[j] - state.velocity);
  }
  // Not singular: both models' particles span all three axes for sizes > 0.
  state.angularVelocity = glm::inverse(inertia) * angularMomentum;
  return state;
}

}  // namespace scenes::detail
