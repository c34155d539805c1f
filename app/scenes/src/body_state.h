#pragma once
// A world's bodies read back as a scene file describes them: the velocity a particle is given
// at load time, and a box as one rigid body (pose, velocity, spin, mass) fitted to its particles.
#include "physics/world.h"

namespace scenes::detail {

/// The velocity that, given to World::addParticle at the particle's position, rebuilds its
/// Verlet state exactly: addParticle sets x* = x - (v - g h / 2) h, so v = (x - x*) / h + g h / 2.
phys::Vec3 loadVelocity(const phys::World& world, phys::ParticleId id);

/// A box as a <box> element holds it.
struct RigidState {
  phys::BodyPose pose;              ///< World::bodyPose: the rigid fit of the particles' positions
  phys::Vec3 velocity{0.0};         ///< unit: m/s; of the centre, at load time
  phys::Vec3 angularVelocity{0.0};  ///< unit: rad/s; world frame
  phys::Real mass = 1.0;            ///< unit: kg; the sum of the particles' masses
  bool frozen = false;              ///< the guard froze it: no mass left, saved at rest
};

/// A rigid body's own pose and velocities. A particle body: fits one rigid motion to its
/// particles, the velocity and spin that addBody, at the fitted pose, turns into particle
/// velocities nearest (least squares) to loadVelocity's. For a box that keeps its shape this is
/// exact; what deformation there is, is dropped.
RigidState rigidState(const phys::World& world, phys::BodyId id);

}  // namespace scenes::detail
