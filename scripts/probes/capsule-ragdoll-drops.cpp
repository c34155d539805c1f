// Probe for docs/physics.md, "A capsule lying on an edge": the capsule ragdoll of
// CapsuleRagdoll.FallsTumblesAndSettlesWithoutSliding (its world and solver: world damping 0.2,
// Gauss-Seidel 2 x 4, body damping 1) dropped at 12 speeds from 0.90 to 1.12 m/s, 64 s each; for
// each model and drop it prints the fastest particle's speed (m/s) at 8, 12, 15, 20, 30 and 64 s.
// The drop is chaotic, so one drop says little: the table in the docs counts these. Not part of the
// build. From the repository's root, after `cmake --build --preset release --target physics`:
//
//   g++ -std=c++20 -O2 -Iphysics/include -Itests/physics scripts/probes/capsule-ragdoll-drops.cpp \
//     build/release/physics/libphysics.a -ltbb -o /tmp/capsule-ragdoll-drops
//   /tmp/capsule-ragdoll-drops
#include <algorithm>
#include <cstdio>

#include <glm/geometric.hpp>

#include "physics/capsule_ragdoll.h"
#include "test_util.h"  // the ragdoll scenes' world, as the test's

int main() {
  const int checks[] = {8, 12, 15, 20, 30, 64};
  for (const phys::RagdollModel model :
       {phys::RagdollModel::Seed, phys::RagdollModel::Lean, phys::RagdollModel::Rigid}) {
    for (int drop = 0; drop < 12; ++drop) {
      const double speed = 0.90 + 0.02 * drop;
      phys::World world = testing_phys::ragdollWorld();
      phys::RagdollDesc d;
      d.hips = phys::Vec3(0.0, 2.0, 0.0);
      d.model = model;
      d.orientation = glm::angleAxis(0.6, glm::normalize(phys::Vec3(1.0, 0.3, 0.2)));
      d.velocity = phys::Vec3(speed, 0.0, 0.0);
      phys::addCapsuleRagdoll(world, d);
      std::printf("%-5s %.2f m/s:", std::string(phys::toString(model)).c_str(), speed);
      for (int i = 1, next = 0; i <= 64 * 60; ++i) {
        world.step();
        if (i != checks[next] * 60) continue;
        double fastest = 0.0;
        for (phys::ParticleId p{}; p < world.particles().size(); ++p)
          fastest = std::max(fastest, glm::length(world.velocity(p)));
        // the rigid model's parts are rigid bodies: their farthest corner's speed, as the test reads
        if (model == phys::RagdollModel::Rigid) fastest = world.metrics().maxSpeed;
        std::printf("  %2d s %.5f", checks[next], fastest);
        ++next;
      }
      std::printf("\n");
    }
  }
}
