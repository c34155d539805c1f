#pragma once
// The bodies of a world as the lab compares them, ours and the peers' alike: every box by its
// centre (World::bodies() order), then every loose particle, one that belongs to no box (id
// order). A peer engine builds one rigid body for each, in the same order, so one list of
// positions serves both.
#include <vector>

#include "physics/world.h"

namespace lab {

std::vector<phys::Vec3> bodyPositions(const phys::World& world);
/// The same bodies' orientations: a box's fitted pose (World::bodyPose), identity for a particle.
std::vector<phys::Quat> bodyOrientations(const phys::World& world);

/// The loose particles, in id order: the k-th of them is body bodies().size() + k of the list.
std::vector<phys::ParticleId> looseParticles(const phys::World& world);

/// Each particle's body, its place in the list: its box's id, or for a loose particle
/// bodies().size() + k as above.
std::vector<std::size_t> particleBodies(const phys::World& world);

}  // namespace lab
