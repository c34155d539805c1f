#include "bodies.h"

#include <algorithm>

namespace lab {

std::vector<phys::Vec3> bodyPositions(const phys::World& world) {
  std::vector<phys::Vec3> out;
  for (phys::BodyId id{}; id < world.bodies().size(); ++id) out.push_back(world.bodyPose(id).center);
  for (phys::ParticleId p : looseParticles(world)) out.push_back(world.particles().position[p]);
  return out;
}

std::vector<phys::Quat> bodyOrientations(const phys::World& world) {
  std::vector<phys::Quat> out;
  std::size_t inBoxes = 0;
  for (phys::BodyId id{}; id < world.bodies().size(); ++id) {
    out.push_back(world.bodyPose(id).orientation);
    inBoxes += static_cast<std::size_t>(world.bodies()[id].particleCount);
  }
  // Then the loose particles, as bodyPositions lists them: boxes share no particle.
  out.resize(out.size() + world.particles().size() - inBoxes, phys::Quat(1.0, 0.0, 0.0, 0.0));
  return out;
}

std::vector<phys::ParticleId> looseParticles(const phys::World& world) {
  std::vector<bool> inBox(world.particles().size(), false);
  for (const phys::Body& box : world.bodies()) {
    for (int k = 0; k < box.particleCount; ++k) inBox[box.firstParticle + k] = true;
  }
  std::vector<phys::ParticleId> out;
  for (phys::ParticleId p{}; p < inBox.size(); ++p) {
    if (!inBox[p]) out.push_back(p);
  }
  return out;
}

std::optional<std::size_t> particleSlot(const phys::World& world, phys::ParticleId particle) {
  const std::vector<phys::ParticleId> loose = looseParticles(world);
  const auto it = std::lower_bound(loose.begin(), loose.end(), particle);
  if (it == loose.end() || *it != particle) return std::nullopt;
  return world.bodies().size() + static_cast<std::size_t>(it - loose.begin());
}

}  // namespace lab
