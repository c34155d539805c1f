// Contact features and points of two overlapping boxes, along the normal the SAT found.
// One function per feature case; each fills onA / onB so that n . (onB - onA) = -depth.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry.h"
#include "physics/collision.h"
#include "require.h"

namespace phys {
namespace {

using detail::clip;
using detail::closestPointsOfSegments;
using detail::Polygon;

int faceAxis(const Obb& box, const Vec3& direction, Real& sign) {
  int best = 0;
  Real bestDot = -1.0;
  for (int i = 0; i < 3; ++i) {
    const Real d = glm::dot(box.axes[i], direction);
    if (std::abs(d) > bestDot) {
      bestDot = std::abs(d);
      best = i;
      sign = d >= 0.0 ? 1.0 : -1.0;
    }
  }
  return best;
}

// The 4 corners of the face of `box` on side `sign` of `axis`, in order around the face.
std::array<int, 4> faceCorners(int axis, Real sign) {
  const int bit = 1 << axis, u = 1 << ((axis + 1) % 3), v = 1 << ((axis + 2) % 3);
  const int base = sign > 0.0 ? bit : 0;
  return {base, base | u, base | u | v, base | v};
}

Polygon featurePolygon(const Obb& box, const SupportFeature& f) {
  Polygon p;
  p.n = static_cast<int>(f.feature);
  for (int i = 0; i < p.n; ++i) p.v[i] = box.corner(f.corners[i]);
  return p;
}

// Face cases: clip the incident feature against the reference face's four side planes; each
// point below the reference plane is a contact, with its partner on that plane.
void faceContact(const Obb& reference, const Vec3& referenceNormal, const Polygon& incident,
                 bool referenceIsA, Real margin, BoxContact& out) {
  Real sign = 1.0;
  const int axis = faceAxis(reference, referenceNormal, sign);
  const Vec3 n = reference.axes[axis] * sign;  // outward normal of the reference face
  const Real planeOffset = glm::dot(n, reference.center) + reference.halfExtents[axis];
  Polygon p = incident;
  for (int k = 1; k <= 2; ++k) {
    const int side = (axis + k) % 3;
    const Vec3& s = reference.axes[side];
    const Real c = glm::dot(s, reference.center);
    p = clip(p, s, c + reference.halfExtents[side]);
    p = clip(p, -s, -c + reference.halfExtents[side]);
  }
  out.count = 0;
  auto add = [&](const Vec3& point) {
    const Real depth = planeOffset - glm::dot(n, point);
    if (depth < -margin || out.count >= 8) return;
    const Vec3 onReference = point + depth * n;
    ContactPoint& c = out.points[out.count++];
    c.depth = depth;
    c.onA = referenceIsA ? onReference : point;
    c.onB = referenceIsA ? point : onReference;
  };
  // Clipping may leave nothing: the incident feature lies beside the reference face (a corner
  // poking in near its edge). Its deepest corner is kept if it is within the margin of the face's
  // sides. Farther out it is below the face's plane only where the plane extends past the face,
  // and a point there would push where the boxes do not touch; the caller then looks at the edges
  // (collideBoxes).
  if (p.n == 0) {
    int deepest = 0;
    for (int i = 1; i < incident.n; ++i) {
      if (glm::dot(n, incident.v[i]) < glm::dot(n, incident.v[deepest])) deepest = i;
    }
    const Vec3 offset = incident.v[deepest] - reference.center;
    bool nearFace = true;
    for (int k = 1; k <= 2; ++k) {
      const int side = (axis + k) % 3;
      nearFace = nearFace &&
                 std::abs(glm::dot(reference.axes[side], offset)) <= reference.halfExtents[side] + margin;
    }
    if (nearFace) p.v[p.n++] = incident.v[deepest];
  }
  for (int i = 0; i < p.n; ++i) add(p.v[i]);
  out.sat.normal = referenceIsA ? n : -n;  // keep "from A towards B"
}

// Edge and vertex cases: one point, the closest points of the two features.
void closestFeatureContact(const Obb& a, const SupportFeature& fa, const Obb& b, const SupportFeature& fb,
                           BoxContact& out) {
  const Vec3 a0 = a.corner(fa.corners[0]), a1 = fa.feature == Feature::Edge ? a.corner(fa.corners[1]) : a0;
  const Vec3 b0 = b.corner(fb.corners[0]), b1 = fb.feature == Feature::Edge ? b.corner(fb.corners[1]) : b0;
  ContactPoint& c = out.points[0];
  closestPointsOfSegments(a0, a1, b0, b1, c.onA, c.onB);
  c.depth = -glm::dot(out.sat.normal, c.onB - c.onA);
  out.count = 1;
}

}  // namespace

const char* toString(ContactKind kind) {
  static constexpr std::array<const char*, 6> kNames = {"face-face", "face-edge",   "face-vertex",
                                                        "edge-edge", "edge-vertex", "vertex-vertex"};
  detail::requireEnum(static_cast<int>(kind), static_cast<int>(kNames.size()), "toString(ContactKind)",
                      "kind", "ContactKind");
  return kNames[static_cast<std::size_t>(kind)];
}

SupportFeature supportFeature(const Obb& box, const Vec3& direction, Real epsilon) {
  Real extreme = -1e300;
  std::array<Real, 8> along{};
  for (int k = 0; k < 8; ++k) {
    along[k] = glm::dot(box.corner(k), direction);
    extreme = std::max(extreme, along[k]);
  }
  SupportFeature f;
  std::array<int, 8> near{};
  for (int k = 0; k < 8; ++k) {
    if (along[k] >= extreme - epsilon) near[f.count++] = k;
  }
  if (f.count >= 3 || (f.count == 2 && std::popcount(static_cast<unsigned>(near[0] ^ near[1])) != 1)) {
    Real sign = 1.0;
    const int axis = faceAxis(box, direction, sign);  // sets sign: not inside the call below
    f.feature = Feature::Face;
    f.corners = faceCorners(axis, sign);
  } else {
    f.feature = f.count == 2 ? Feature::Edge : Feature::Vertex;
    f.corners = {near[0], near[1], 0, 0};
  }
  return f;
}

ContactKind classify(Feature a, Feature b) {
  const Feature hi = std::max(a, b), lo = std::min(a, b);
  if (hi == Feature::Face)
    return lo == Feature::Face   ? ContactKind::FaceFace
           : lo == Feature::Edge ? ContactKind::FaceEdge
                                 : ContactKind::FaceVertex;
  if (hi == Feature::Edge) return lo == Feature::Edge ? ContactKind::EdgeEdge : ContactKind::EdgeVertex;
  return ContactKind::VertexVertex;
}

bool collideBoxes(const Obb& a, const Obb& b, Real featureEpsilon, BoxContact& out) {
  return collideBoxes(a, b, featureEpsilon, featureEpsilon, out);
}

namespace {

// The contact points along the normal out.sat holds (from A towards B).
void contactAlong(const Obb& a, const Obb& b, Real featureEpsilon, Real margin, BoxContact& out) {
  const Vec3 n = out.sat.normal;
  // The features are told apart by the feature epsilon, not the margin: a feature that took in
  // every corner within a speculative margin made a resting part of a ragdoll tilted a centimetre
  // a face contact, and a lean ragdoll dropped at (0, 30, 8) degrees never came to rest.
  const SupportFeature fa = supportFeature(a, n, featureEpsilon);
  const SupportFeature fb = supportFeature(b, -n, featureEpsilon);
  out.kind = classify(fa.feature, fb.feature);
  if (fa.feature == Feature::Face || fb.feature == Feature::Face) {
    // Both faces: the reference is the one whose normal the SAT chose (or the better aligned).
    Real signA = 1.0, signB = 1.0;
    const Real alignA = std::abs(glm::dot(a.axes[faceAxis(a, n, signA)], n));
    const Real alignB = std::abs(glm::dot(b.axes[faceAxis(b, -n, signB)], n));
    const bool referenceIsA =
        fa.feature == Feature::Face &&
        (fb.feature != Feature::Face || (out.sat.axis < 3) || (out.sat.axis >= 6 && alignA >= alignB));
    if (referenceIsA)
      faceContact(a, n, featurePolygon(b, fb), true, margin, out);
    else
      faceContact(b, -n, featurePolygon(a, fa), false, margin, out);
  } else {
    closestFeatureContact(a, fa, b, fb, out);
  }
}

}  // namespace

bool collideBoxes(const Obb& a, const Obb& b, Real featureEpsilon, Real margin, BoxContact& out,
                  int previousAxis, PreferFaces prefer) {
  out.sat = satTest(a, b, margin, previousAxis, prefer);
  out.count = 0;
  if (!out.sat.overlap) return false;
  contactAlong(a, b, featureEpsilon, margin, out);
  if (out.count == 0 && out.sat.edgeAxis >= 0 && out.sat.axis != out.sat.edgeAxis) {
    // The face the SAT chose has nothing of the other box over it, nor near it (limbs crossed at
    // their edges, the other box's corner far beside the face): the contact is where the edges of
    // the edge-edge axis meet, measured along the face's normal still, so that the normal does not
    // turn from step to step with the choice (docs/physics.md, "Box-box contact").
    const SatResult face = out.sat;
    out.sat.axis = face.edgeAxis;
    out.sat.depth = face.edgeDepth;
    out.sat.normal = face.edgeNormal;
    contactAlong(a, b, featureEpsilon, margin, out);
    out.sat = face;
    int kept = 0;
    for (int i = 0; i < out.count; ++i) {
      ContactPoint c = out.points[i];
      c.depth = -glm::dot(face.normal, c.onB - c.onA);
      if (c.depth >= -margin) out.points[kept++] = c;
    }
    out.count = kept;
  }
  return out.count > 0;
}

// The deepest, the one farthest from it, then the two that span the largest area with those
// (the choice Bullet makes).
namespace {

void reduce(BoxContact& c, Real touching) {
  if (c.count <= 4) return;
  // The touching points first, in their order (std::stable_partition would allocate).
  std::array<ContactPoint, 8> sorted;
  int next = 0;
  for (int i = 0; i < c.count; ++i) {
    if (c.points[i].depth >= -touching) sorted[next++] = c.points[i];
  }
  const int touchingCount = next;
  for (int i = 0; i < c.count; ++i) {
    if (c.points[i].depth < -touching) sorted[next++] = c.points[i];
  }
  std::copy(sorted.begin(), sorted.begin() + c.count, c.points.begin());
  if (touchingCount < 4) {
    // Every touching point, then the speculative ones that come nearest.
    std::sort(c.points.begin() + touchingCount, c.points.begin() + c.count,
              [](const ContactPoint& a, const ContactPoint& b) { return a.depth > b.depth; });
    c.count = 4;
    return;
  }
  c.count = touchingCount;
  if (c.count <= 4) return;
  const Vec3 n = c.sat.normal;
  std::array<int, 4> keep{};
  keep[0] = 0;
  for (int i = 1; i < c.count; ++i) {
    if (c.points[i].depth > c.points[keep[0]].depth) keep[0] = i;
  }
  auto at = [&c](int i) { return c.points[i].onB; };
  Real best = -1.0;
  for (int i = 0; i < c.count; ++i) {
    const Real d = glm::length(at(i) - at(keep[0]));
    if (d > best) best = d, keep[1] = i;
  }
  best = -1.0;
  for (int i = 0; i < c.count; ++i) {
    const Real area = std::abs(glm::dot(glm::cross(at(i) - at(keep[0]), at(keep[1]) - at(keep[0])), n));
    if (area > best) best = area, keep[2] = i;
  }
  // The fourth on the other side of the line from keep[0] to keep[1] than keep[2].
  const Vec3 side = glm::cross(at(keep[1]) - at(keep[0]), n);
  const Real sideOfThird = glm::dot(at(keep[2]) - at(keep[0]), side);
  best = -1.0;
  keep[3] = keep[2];
  for (int i = 0; i < c.count; ++i) {
    const Real s = glm::dot(at(i) - at(keep[0]), side);
    if (s * sideOfThird < 0.0 && std::abs(s) > best) best = std::abs(s), keep[3] = i;
  }
  std::array<ContactPoint, 4> kept;
  int count = 0;
  for (int k = 0; k < 4; ++k) {
    if (std::find(keep.begin(), keep.begin() + k, keep[k]) == keep.begin() + k)
      kept[count++] = c.points[keep[k]];
  }
  for (int k = 0; k < count; ++k) c.points[k] = kept[k];
  c.count = count;
}

}  // namespace

void reduceToFourPoints(BoxContact& c, Real touching) {
  const int before = c.count;
  reduce(c, touching);
  c.dropped = before - c.count;
}

}  // namespace phys
