#pragma once
// A particle box's edges along one of its axes, summed as its particles lie: World::fitFrame makes
// its x and y axes from them, and the contacts' embedding tells a body turned inside out by its z
// edges against its frame's z (detail::embeddingFrame, surface_points.cpp).
#include <span>

#include <glm/geometric.hpp>

#include "physics/body.h"
#include "physics/types.h"

namespace phys::detail {

/// The sum of the 4 edges along `axis` (0, 1, 2: x, y, z) of the corners box or of the box a tetra
/// body's 4 particles (at corners 0, 3, 5, 6) stand for: corner k is sum_j (1 + s_j . s_k) / 4 p_j,
/// so a tetra body's edges along x sum to 2 sum_j s_jx p_j, a third of the work of embedding 8 corners.
/// `p` is the body's first particle.
inline Vec3 edgeSum(BodyModel model, const Vec3* p, int axis) {
  if (model == BodyModel::Tetra) {
    if (axis == 0) return (p[1] + p[2] - p[0] - p[3]) * 2.0;
    if (axis == 1) return (p[1] + p[3] - p[0] - p[2]) * 2.0;
    return (p[2] + p[3] - p[0] - p[1]) * 2.0;
  }
  if (axis == 0) return (p[1] - p[0]) + (p[3] - p[2]) + (p[5] - p[4]) + (p[7] - p[6]);
  if (axis == 1) return (p[2] - p[0]) + (p[3] - p[1]) + (p[6] - p[4]) + (p[7] - p[5]);
  return (p[4] - p[0]) + (p[5] - p[1]) + (p[6] - p[2]) + (p[7] - p[3]);
}

/// Whether a particle body keeps more than half its volume right side out: the triple product of
/// its edge sums along x, y and z against its rest one's. One turned inside out is not a rigid body
/// that the ground could push as one; its volume floor (TetraVolumes) turns it back.
inline bool keepsItsVolume(const Body& box, std::span<const Vec3> position) {
  const Vec3* p = &position[box.firstParticle];
  const Vec3 ex = edgeSum(box.model, p, 0), ey = edgeSum(box.model, p, 1), ez = edgeSum(box.model, p, 2);
  const Vec3& h = box.halfExtents;
  const Real rest = 512.0 * h.x * h.y * h.z;  // each axis's 4 edges sum to 8 half extents
  return glm::dot(glm::cross(ex, ey), ez) > 0.5 * rest;
}

}  // namespace phys::detail
