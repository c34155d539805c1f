// Capsule narrow phase: capsule-capsule and capsule-box contacts. A capsule is its core segment
// swept by a sphere, so both reduce to the core's nearest points, pushed out by the radius.
// Every contact point is on the surfaces: onA on A's, onB on B's, n . (onB - onA) = -depth.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry.h"
#include "physics/collision.h"

namespace phys {
namespace {

// Cores closer to parallel than this (the sine of about 3 degrees) count as side by side.
constexpr Real kParallelSine = 0.05;
// A core whose nearest points to a box are within 3 degrees of a face's normal lies over that face.
constexpr Real kFaceCosine = 0.9986;
// A normal for cores that meet exactly, where the nearest points give none.
Vec3 anyNormalTo(const Vec3& direction) {
  const Vec3 other = std::abs(direction.x) < 0.9 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0);
  const Vec3 n = glm::cross(direction, other);
  const Real length = glm::length(n);
  return length > 0.0 ? n / length : Vec3(0.0, 1.0, 0.0);
}

void addPoint(BoxContact& out, const Vec3& onA, const Vec3& onB, Real depth) {
  if (out.count >= static_cast<int>(out.points.size())) return;
  ContactPoint& c = out.points[out.count++];
  c.onA = onA;
  c.onB = onB;
  c.depth = depth;
  out.sat.depth = out.count == 1 ? depth : std::max(out.sat.depth, depth);
}

Vec3 nearestOnSegment(const Vec3& p0, const Vec3& p1, const Vec3& x) {
  const Vec3 d = p1 - p0;
  const Real dd = glm::dot(d, d);
  if (dd <= 1e-18) return p0;
  return p0 + d * std::clamp(glm::dot(x - p0, d) / dd, 0.0, 1.0);
}

// The box's point nearest x, and in `clamped` how many of its axes x lies beyond.
Vec3 nearestOnBox(const Obb& box, const Vec3& x, int& clamped, int& lastAxis) {
  const Vec3 d = x - box.center;
  Vec3 q = box.center;
  clamped = 0;
  for (int k = 0; k < 3; ++k) {
    const Real along = glm::dot(d, box.axes[k]);
    const Real inside = std::clamp(along, -box.halfExtents[k], box.halfExtents[k]);
    if (inside != along) ++clamped, lastAxis = k;
    q += box.axes[k] * inside;
  }
  return q;
}

// The core's part over the face of `box` with outward normal n = axes[axis] * sign: the core
// clipped to the face's four side planes.
detail::Polygon coreOverFace(const Capsule& a, const Obb& box, int axis) {
  detail::Polygon p;
  p.v[0] = a.p0;
  p.v[1] = a.p1;
  p.n = glm::dot(a.p1 - a.p0, a.p1 - a.p0) > 1e-18 ? 2 : 1;
  for (int k = 1; k <= 2; ++k) {
    const int side = (axis + k) % 3;
    const Vec3& s = box.axes[side];
    const Real c = glm::dot(s, box.center);
    p = detail::clip(p, s, c + box.halfExtents[side]);
    p = detail::clip(p, -s, -c + box.halfExtents[side]);
  }
  return p;
}

// Contact through one face of the box: each point of the core over the face within radius +
// margin of its plane (a core below the plane is inside, and deeper). Normal from A into B.
void faceContact(const Capsule& a, const Obb& box, int axis, Real sign, Real margin, BoxContact& out) {
  const Vec3 n = box.axes[axis] * sign;  // outward, towards the capsule
  const Real plane = glm::dot(n, box.center) + box.halfExtents[axis];
  out.sat.normal = -n;
  out.sat.axis = axis;
  out.kind = ContactKind::FaceEdge;
  const detail::Polygon over = coreOverFace(a, box, axis);
  for (int i = 0; i < over.n; ++i) {
    const Real height = glm::dot(n, over.v[i]) - plane;
    const Real depth = a.radius - height;
    if (depth < -margin) continue;
    addPoint(out, over.v[i] - n * a.radius, over.v[i] - n * height, depth);
  }
}

}  // namespace

Capsule capsuleInBox(const Obb& box) {
  const Real halfSegment = std::max(0.0, box.halfExtents.y - box.halfExtents.x);
  const Vec3 along = box.axes[1] * halfSegment;
  return {box.center - along, box.center + along, box.halfExtents.x};
}

bool collideCapsules(const Capsule& a, const Capsule& b, Real margin, BoxContact& out) {
  out = BoxContact{};
  Vec3 ca, cb;
  detail::closestPointsOfSegments(a.p0, a.p1, b.p0, b.p1, ca, cb);
  const Vec3 d = cb - ca;
  const Real distance = glm::length(d);
  const Real reach = a.radius + b.radius;
  if (distance > reach + margin) return false;
  const Vec3 da = a.p1 - a.p0, db = b.p1 - b.p0;
  // Cores that meet exactly give no direction; across both cores is the one that parts them
  // without sliding either along itself.
  const Vec3 across = glm::cross(da, db);
  const Vec3 n = distance > 1e-12 ? d / distance
                 : glm::length(across) > 1e-12
                     ? across / glm::length(across)
                     : anyNormalTo(glm::length(da) > 0.0 ? da : Vec3(0.0, 1.0, 0.0));
  out.sat.overlap = true;
  out.sat.normal = n;
  out.kind = ContactKind::EdgeEdge;
  const Real la = glm::length(da), lb = glm::length(db);
  if (la > 1e-9 && lb > 1e-9 && glm::length(glm::cross(da / la, db / lb)) < kParallelSine) {
    // Side by side: the two ends of the stretch of A that B lies along, each with its nearest
    // point of B, so a capsule lying on another rests on two points and does not rock.
    const Vec3 ua = da / la;
    Real t0 = std::clamp(glm::dot(b.p0 - a.p0, ua), 0.0, la),
         t1 = std::clamp(glm::dot(b.p1 - a.p0, ua), 0.0, la);
    if (t0 > t1) std::swap(t0, t1);
    if (t1 - t0 > 1e-6 * la) {
      for (const Real t : {t0, t1}) {
        const Vec3 pa = a.p0 + ua * t, pb = nearestOnSegment(b.p0, b.p1, pa);
        const Real depth = reach - glm::dot(n, pb - pa);
        if (depth >= -margin) addPoint(out, pa + n * a.radius, pb - n * b.radius, depth);
      }
      out.kind = ContactKind::FaceFace;
      if (out.count > 0) return true;
    }
  }
  addPoint(out, ca + n * a.radius, cb - n * b.radius, reach - distance);
  return true;
}

bool collideCapsuleBox(const Capsule& a, const Obb& b, Real margin, BoxContact& out) {
  out = BoxContact{};
  // The core's point nearest the box: the distance from a convex set is convex along the core,
  // so a ternary search finds it (each round keeps 2/3; 48 rounds leave 4e-9 of the length).
  auto distanceAt = [&](Real t) {
    int clamped = 0, axis = 0;
    const Vec3 s = a.p0 + (a.p1 - a.p0) * t;
    return glm::length(s - nearestOnBox(b, s, clamped, axis));
  };
  Real lo = 0.0, hi = 1.0;
  for (int round = 0; round < 48; ++round) {
    const Real m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (distanceAt(m1) <= distanceAt(m2))
      hi = m2;
    else
      lo = m1;
  }
  const Vec3 s = a.p0 + (a.p1 - a.p0) * ((lo + hi) / 2.0);
  int clamped = 0, lastAxis = 0;
  const Vec3 q = nearestOnBox(b, s, clamped, lastAxis);
  const Real distance = glm::length(s - q);
  if (distance > a.radius + margin) return false;
  out.sat.overlap = true;
  if (distance > 1e-9) {
    // Over a face: the core clipped to it, one or two points (a capsule lying on the face). The
    // search ends anywhere along a level core's flat stretch of distance, at its end just past
    // the face's edge as likely as inside: the face is the one the nearest points' direction is
    // within 3 degrees of, not only the one the point lies beyond alone.
    int faceAxis = clamped == 1 ? lastAxis : -1;
    for (int k = 0; k < 3 && faceAxis < 0; ++k) {
      if (std::abs(glm::dot(s - q, b.axes[k])) >= kFaceCosine * distance) faceAxis = k;
    }
    if (faceAxis >= 0) {
      const Real sign = glm::dot(s - b.center, b.axes[faceAxis]) >= 0.0 ? 1.0 : -1.0;
      faceContact(a, b, faceAxis, sign, margin, out);
      if (out.count > 0) return true;
    }
  }
  if (distance > 1e-9) {
    // Beside an edge or a corner of the box: one point.
    const Vec3 outward = (s - q) / distance;
    out.sat.normal = -outward;
    out.kind = clamped == 2 ? ContactKind::EdgeEdge : ContactKind::EdgeVertex;
    addPoint(out, s - outward * a.radius, q, a.radius - distance);
    return true;
  }
  // The core reaches inside the box: out through the face it needs the least push to clear.
  int bestAxis = 0;
  Real bestSign = 1.0, bestPush = 1e300;
  for (int k = 0; k < 3; ++k) {
    const Real e0 = glm::dot(a.p0 - b.center, b.axes[k]), e1 = glm::dot(a.p1 - b.center, b.axes[k]);
    const Real pushUp = b.halfExtents[k] + a.radius - std::min(e0, e1);
    const Real pushDown = b.halfExtents[k] + a.radius + std::max(e0, e1);
    if (pushUp < bestPush) bestPush = pushUp, bestAxis = k, bestSign = 1.0;
    if (pushDown < bestPush) bestPush = pushDown, bestAxis = k, bestSign = -1.0;
  }
  faceContact(a, b, bestAxis, bestSign, margin, out);
  if (out.count == 0) {
    // The core's part inside lies off the face's rectangle: push its deepest point.
    const Vec3 n = b.axes[bestAxis] * bestSign;
    const Real plane = glm::dot(n, b.center) + b.halfExtents[bestAxis];
    const Real height = glm::dot(n, s) - plane;
    addPoint(out, s - n * a.radius, s - n * height, a.radius - height);
  }
  return true;
}

}  // namespace phys
