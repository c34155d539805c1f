#pragma once
// Geometry shared by the narrow phases (box_contacts.cpp, capsule_collision.cpp).
#include <array>

#include "physics/types.h"

namespace phys::detail {

/// A convex polygon, a segment (n = 2) or a point (n = 1), of at most 8 vertices.
struct Polygon {
  std::array<Vec3, 8> v;
  int n = 0;
};

/// Sutherland-Hodgman: the part of the polygon with dot(plane, p) <= offset.
Polygon clip(const Polygon& in, const Vec3& plane, Real offset);

/// Closest points c1 of segment p1-q1 and c2 of segment p2-q2.
void closestPointsOfSegments(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2, Vec3& c1,
                             Vec3& c2);

}  // namespace phys::detail
