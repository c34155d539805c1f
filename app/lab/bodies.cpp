#include "bodies.h"

namespace lab {

std::vector<phys::Vec3> bodyPositions(const phys::World& world) {
  std::vector<phys::Vec3> out;
  for (phys::BodyId id{}; id < world.bodies().size(); ++id) out.push_back(world.bodyPose(id).center);
  for (phys::ParticleId p : looseParticles(world)) out.push_back(world.particles().position[p]);
  return out;
}

std::vector<phys::Quat> bodyOrientations(const phys::World& world) {
  std::vector<phys::Quat> out;
  for (phys::BodyId id{}; id < world.bodies().size(); ++id) out.push_back(world.bodyPose(id).orientation);
  out.resize(out.size() + looseParticles(world).size(), phys::Quat(1.0, 0.0, 0.0, 0.0));
  return out;
}

std::vector<phys::ParticleId> looseParticles(const phys::World& world) {
  const std::span<const phys::BodyId> owner = world.particleBodies();
  std::vector<phys::ParticleId> out;
  for (phys::ParticleId p{}; p < owner.size(); ++p) {
    if (owner[p] == phys::kNoBody) out.push_back(p);
  }
  return out;
}

std::vector<std::size_t> particleBodies(const phys::World& world) {
  // Loose particles take their places after the boxes, in id order.
  std::size_t next = world.bodies().size();
  std::vector<std::size_t> out;
  out.reserve(world.particleBodies().size());
  for (const phys::BodyId owner : world.particleBodies())
    out.push_back(owner == phys::kNoBody ? next++ : owner);
  return out;
}

}  // namespace lab
