#include "bodies.h"

namespace lab {

std::vector<phys::Vec3> bodyPositions(const phys::World& world) {
  const auto boxes = world.bodies();
  std::vector<phys::Vec3> out;
  std::vector<bool> inBox(world.particles().size(), false);
  for (phys::BodyId id{}; id < boxes.size(); ++id) {
    out.push_back(world.bodyPose(id).center);
    for (int k = 0; k < boxes[id].particleCount; ++k)
      inBox[boxes[id].firstParticle + static_cast<phys::ParticleId>(k)] = true;
  }
  for (std::size_t i = 0; i < world.particles().size(); ++i) {
    if (!inBox[i]) out.push_back(world.particles().position[i]);
  }
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

}  // namespace lab
