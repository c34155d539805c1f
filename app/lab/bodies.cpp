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
  const std::vector<std::size_t> body = particleBodies(world);
  std::vector<phys::ParticleId> out;
  for (phys::ParticleId p{}; p < body.size(); ++p) {
    if (body[p] >= world.bodies().size()) out.push_back(p);
  }
  return out;
}

std::vector<std::size_t> particleBodies(const phys::World& world) {
  const std::size_t boxes = world.bodies().size();
  std::vector<std::size_t> body(world.particles().size(), boxes);
  for (phys::BodyId id{}; id < boxes; ++id) {
    const phys::Body& box = world.bodies()[id];
    for (int k = 0; k < box.particleCount; ++k) body[box.firstParticle + k] = id;
  }
  // Loose particles (still marked `boxes`) take their places after the boxes, in id order.
  std::size_t next = boxes;
  for (std::size_t& b : body) {
    if (b == boxes) b = next++;
  }
  return body;
}

}  // namespace lab
