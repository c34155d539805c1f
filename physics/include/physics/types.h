#pragma once
// Scalar and vector types of the physics library, in one place.
//
// Double precision on purpose: Verlet keeps velocity as the difference of two positions
// (x - x*), so every step loses about ulp(x) / dt of velocity. In float a body 100 m from the
// origin is already off by 1e-3 relative after 10 s of free fall, and the stability suite puts
// scenes 1e5 m out. Doubles keep both within 1e-12. Rendering converts to float at the edge.
#include <cmath>
#include <compare>
#include <concepts>
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

/// True when v is within `bound` of the origin along every axis (false for NaN): the world's
/// bound (WorldSettings::bound) as a scene file may place a body, and any other reach held the same way.
inline bool insideBound(const Vec3& v, Real bound) {
  return std::abs(v.x) <= bound && std::abs(v.y) <= bound && std::abs(v.z) <= bound;
}

/// An index into one of the world's lists, of a type of its own for each list (Tag), so that a
/// particle's index is never passed where a body's is wanted: it is made from a number only
/// explicitly, and reads as its number wherever an index is wanted (arrays, comparisons, sums).
template <typename Tag>
struct Id {
  std::uint32_t index = 0;

  constexpr Id() = default;
  template <std::integral I>
  constexpr explicit Id(I i) : index(static_cast<std::uint32_t>(i)) {}
  constexpr operator std::uint32_t() const { return index; }  // NOLINT(google-explicit-constructor)
  friend constexpr bool operator==(Id, Id) = default;
  friend constexpr auto operator<=>(Id, Id) = default;
  constexpr Id& operator++() {
    ++index;
    return *this;
  }
  /// The id `offset` places on: a body's j-th particle is firstParticle + j.
  template <std::integral I>
  friend constexpr Id operator+(Id id, I offset) {
    return Id(id.index + static_cast<std::uint32_t>(offset));
  }
};

/// Index of a particle in the world's particle arrays.
using ParticleId = Id<struct ParticleTag>;
/// Index of a body (a box or a capsule) in the world's body list.
using BodyId = Id<struct BodyTag>;
/// No body: what a loose particle belongs to, and a contact point of the ground or of nothing.
inline constexpr BodyId kNoBody{0xffffffffu};

}  // namespace phys
