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

}  // namespace lab
