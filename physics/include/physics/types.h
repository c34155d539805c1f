#pragma once
// Scalar and vector types of the physics library, in one place.
//
// Double precision on purpose: Verlet keeps velocity as the difference of two positions
// (x - x*), so every step loses about ulp(x) / dt of velocity. In float a body 100 m from the
// origin is already off by 1e-3 relative after 10 s of free fall, and the stability suite puts
// scenes 1e5 m out. Doubles keep both within 1e-12. Rendering converts to float at the edge.
#include <cmath>
#include <cstdint>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace phys {

using Real = double;
using Vec3 = glm::dvec3;
using Quat = glm::dquat;

/// True when every component is finite.
inline bool finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Index of a particle in the world's particle arrays.
using ParticleId = std::uint32_t;
/// Index of a box in the world's box list.
using BodyId = std::uint32_t;

}  // namespace phys
