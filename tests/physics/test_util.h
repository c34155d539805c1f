#pragma once
// Small helpers shared by the physics tests.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "physics/world.h"

namespace testing_phys {

/// Angle between two orientations, in radians.
inline double angleBetween(const phys::Quat& a, const phys::Quat& b) {
  const double d = std::min(1.0, std::abs(glm::dot(glm::normalize(a), glm::normalize(b))));
  return 2.0 * std::acos(d);
}

/// A world with no ground and the given gravity and solver.
inline phys::World openSpace(const phys::SolverSettings& solver = {},
                             phys::Vec3 gravity = {0.0, -9.81, 0.0}) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.gravity = gravity;
  return phys::World(ws, solver);
}

inline phys::SolverSettings solver(phys::SolverMethod method, int substeps, int iterations) {
  phys::SolverSettings s;
  s.method = method;
  s.substeps = substeps;
  s.iterations = iterations;
  return s;
}

}  // namespace testing_phys
