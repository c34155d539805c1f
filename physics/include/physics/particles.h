#pragma once
// Particle state as a structure of arrays: the integrator and the relaxation loop walk these
// arrays front to back, and each array can later be split into SIMD lanes without a copy.
#include <cstddef>
#include <vector>

#include "physics/types.h"

namespace phys {

/// Positions, previous positions and inverse masses of every particle, in id order.
struct Particles {
  std::vector<Vec3> position;     ///< unit: m; x at the current time
  std::vector<Vec3> previous;     ///< unit: m; x* at the previous substep (Verlet's velocity)
  std::vector<Real> inverseMass;  ///< unit: 1/kg; 0 means pinned (infinite mass)

  std::size_t size() const { return position.size(); }
};

}  // namespace phys
