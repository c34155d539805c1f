// The separating-axis test for two oriented boxes (Gottschalk, Lin, Manocha 1996, "OBBTree";
// the face bias follows qu3e's q3Collide.cpp and Box2D). One small function per axis kind.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "physics/collision.h"

namespace phys {

Real projectedRadius(const Obb& box, const Vec3& axis) {
  return box.halfExtents.x * std::abs(glm::dot(box.axes[0], axis)) +
         box.halfExtents.y * std::abs(glm::dot(box.axes[1], axis)) +
         box.halfExtents.z * std::abs(glm::dot(box.axes[2], axis));
}

namespace {

// Penetration along a unit axis (negative: separated along it).
Real penetration(const Obb& a, const Obb& b, const Vec3& axis, const Vec3& t) {
  return projectedRadius(a, axis) + projectedRadius(b, axis) - std::abs(glm::dot(t, axis));
}

constexpr Real kParallelEdges = 1e-3;  // sin of the angle: 0.06 degrees

struct Best {
  Real depth = 1e300;
  int axis = -1;
  Vec3 normal{0.0};
};

// A face axis: keep the shallowest.
bool testFace(const Obb& a, const Obb& b, const Vec3& axis, int index, const Vec3& t, Real margin,
              Best& best) {
  const Real depth = penetration(a, b, axis, t);
  if (depth < -margin) return false;
  if (depth < best.depth) best = {depth, index, axis};
  return true;
}

// An edge-edge axis: only taken over the best face axis when clearly shallower, so resting
// contacts keep a face normal. Edges within kParallelEdges of parallel give no axis: their
// cross product points anywhere in the plane across them, and a stack of boxes a few
// hundredths of a degree apart would be pushed sideways along it.
bool testEdge(const Obb& a, const Obb& b, const Vec3& edgeA, const Vec3& edgeB, int index, const Vec3& t,
              Real margin, Best& bestEdge) {
  const Vec3 cross = glm::cross(edgeA, edgeB);
  const Real length = glm::length(cross);
  if (length < kParallelEdges) return true;
  const Vec3 axis = cross / length;
  const Real depth = penetration(a, b, axis, t);
  if (depth < -margin) return false;
  if (depth < bestEdge.depth) bestEdge = {depth, index, axis};
  return true;
}

}  // namespace

Vec3 Obb::corner(int k) const {
  return center + axes[0] * ((k & 1) ? halfExtents.x : -halfExtents.x) +
         axes[1] * ((k & 2) ? halfExtents.y : -halfExtents.y) +
         axes[2] * ((k & 4) ? halfExtents.z : -halfExtents.z);
}

SatResult satTest(const Obb& a, const Obb& b, Real margin, int previousAxis, PreferFaces prefer) {
  const Vec3 t = b.center - a.center;
  Best faceA, faceB, edge;
  for (int i = 0; i < 3; ++i) {
    if (!testFace(a, b, a.axes[i], i, t, margin, faceA)) return {};
  }
  for (int j = 0; j < 3; ++j) {
    if (!testFace(a, b, b.axes[j], 3 + j, t, margin, faceB)) return {};
  }
  // The shallowest of the six, A's on a tie (as when the six were one list), unless the preferred
  // box's shallowest is within the tolerance of it.
  Best face = faceB.depth < faceA.depth ? faceB : faceA;
  if (prefer == PreferFaces::OfA && faceA.depth <= face.depth + kPreferredFaceTolerance) face = faceA;
  if (prefer == PreferFaces::OfB && faceB.depth <= face.depth + kPreferredFaceTolerance) face = faceB;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (!testEdge(a, b, a.axes[i], b.axes[j], 6 + 3 * i + j, t, margin, edge)) return {};
    }
  }
  const bool wasEdge = previousAxis >= 6;
  const Best& best = edge.axis >= 0 && (edge.depth < kFaceBiasRelative * face.depth - kFaceBiasAbsolute ||
                                        (wasEdge && edge.depth < face.depth))
                         ? edge
                         : face;
  SatResult r;
  r.overlap = true;
  r.axis = best.axis;
  r.depth = best.depth;
  r.normal = glm::dot(best.normal, t) < 0.0 ? -best.normal : best.normal;  // from A towards B
  r.edgeAxis = edge.axis;
  r.edgeDepth = edge.depth;
  r.edgeNormal = glm::dot(edge.normal, t) < 0.0 ? -edge.normal : edge.normal;
  return r;
}

namespace {

// Where along the move (as fractions of it) B's projection on the unit axis overlaps A's; narrows
// [enter, exit] to it and keeps the axis whose entry is latest. False when they never overlap
// along it.
bool sweepAxis(const Obb& a, const Obb& b, const Vec3& axis, const Vec3& t, const Vec3& moved, SweptSat& best,
               Real& exit) {
  const Real reach = projectedRadius(a, axis) + projectedRadius(b, axis);
  const Real start = glm::dot(t, axis), speed = glm::dot(moved, axis);
  if (speed == 0.0) return std::abs(start) <= reach;  // still along it: overlapping throughout, or never
  const Real s1 = (-reach - start) / speed, s2 = (reach - start) / speed;
  const Real enter = std::min(s1, s2);
  exit = std::min(exit, std::max(s1, s2));
  if (!best.hit || enter > best.time) {
    best.hit = true;
    best.time = enter;
    best.normal = speed > 0.0 ? -axis : axis;  // B comes from the side it moves away from
    best.gap = glm::dot(t, best.normal) - reach;
  }
  return best.time <= exit;
}

}  // namespace

SweptSat sweptSat(const Obb& a, const Obb& b, const Vec3& moved) {
  const Vec3 t = b.center - a.center;
  SweptSat best;
  Real exit = std::numeric_limits<Real>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (!sweepAxis(a, b, a.axes[i], t, moved, best, exit)) return {};
    if (!sweepAxis(a, b, b.axes[i], t, moved, best, exit)) return {};
  }
  // Edge pairs within kParallelEdges of parallel give no axis, as in satTest: leaving one out can
  // only report a touch that a finer test would call a near miss.
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Vec3 cross = glm::cross(a.axes[i], b.axes[j]);
      const Real length = glm::length(cross);
      if (length < kParallelEdges) continue;
      if (!sweepAxis(a, b, cross / length, t, moved, best, exit)) return {};
    }
  }
  // Met within the move, or overlapping at its start (entered before it, not left by then).
  return best.hit && best.time <= 1.0 && exit >= 0.0 ? best : SweptSat{};
}

}  // namespace phys
