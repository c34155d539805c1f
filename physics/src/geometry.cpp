#include "geometry.h"

#include <algorithm>

#include <glm/geometric.hpp>

namespace phys::detail {

// Sutherland-Hodgman: keep the part of the polygon with dot(plane, p) <= offset. Works for a
// segment (2 points) and a point (1) as well.
Polygon clip(const Polygon& in, const Vec3& plane, Real offset) {
  Polygon out;
  if (in.n == 1) {
    if (glm::dot(plane, in.v[0]) <= offset) out.v[out.n++] = in.v[0];
    return out;
  }
  const int edges = in.n == 2 ? 1 : in.n;  // a segment is one edge, not a closed loop
  for (int i = 0; i < edges; ++i) {
    const Vec3& p = in.v[i];
    const Vec3& q = in.v[(i + 1) % in.n];
    const Real dp = glm::dot(plane, p) - offset, dq = glm::dot(plane, q) - offset;
    if (dp <= 0.0 && out.n < 8) out.v[out.n++] = p;
    // A crossing strictly inside the edge only: an end on the plane is kept as itself.
    if (((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) && out.n < 8)
      out.v[out.n++] = p + (q - p) * (dp / (dp - dq));
    if (in.n == 2 && dq <= 0.0 && out.n < 8) out.v[out.n++] = q;
  }
  return out;
}

// Closest points of segments p1-q1 and p2-q2 (Ericson, "Real-Time Collision Detection" 5.1.9).
void closestPointsOfSegments(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2, Vec3& c1,
                             Vec3& c2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const Real a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
  Real s = 0.0, t = 0.0;
  if (a <= 1e-18 && e <= 1e-18) {
    c1 = p1;
    c2 = p2;
    return;
  }
  if (a <= 1e-18) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const Real c = glm::dot(d1, r);
    if (e <= 1e-18) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const Real b = glm::dot(d1, d2), denom = a * e - b * b;
      s = denom > 1e-18 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  c1 = p1 + d1 * s;
  c2 = p2 + d2 * t;
}

}  // namespace phys::detail
