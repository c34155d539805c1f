// Points of a body's surface embedded in its particles, as the body lies in its frame of this
// substep: where contacts between bodies and with the ground are carried.
#include <cmath>

#include <glm/geometric.hpp>

#include "particle_edges.h"
#include "passes.h"

namespace phys::detail {
namespace {

// How near an edge of its face, in face coordinates (-1 to 1), a point is taken to be on it: a
// billionth of the half extent, far above rounding and far below anything a contact resolves.
constexpr Real kEdgeSnap = 1e-9;

}  // namespace

Vec3 frameCoordinates(const Body& body, const Obb& f, const Vec3& point) {
  const Vec3 d = point - f.center;
  const Vec3& h = body.halfExtents;
  return {glm::dot(d, f.axes[0]) / h.x, glm::dot(d, f.axes[1]) / h.y, glm::dot(d, f.axes[2]) / h.z};
}

Embedding rigidPoint(const Body& body, const Obb& frame, const Vec3& point) {
  return rigidEmbedding(body, frameCoordinates(body, frame, point));
}

// A body's frame is a rotation, its z axis cross(x, y) of its particles' mean x and y edges
// (World::fitFrame); its sticks hold its mirror image as well as its shape, and a thin body landing
// deeper in a step than it is thick (a 0.1 m capsule at 7 m/s on the ground; a 0.05 m box thrown
// onto a box, or laid on it under Jacobi) has its bottom particles pushed up through its top ones,
// whole and inside out for good. Then the frame's z runs against the particles' z: a point at the
// frame's bottom was embedded in the particles on top, and the passes held those on the surface
// below, the body a thickness inside it (docs/physics.md, "Capsules", "Inside out"). With z along
// the particles' edges the point is on the face whose particles lie there. A box or a capsule is
// symmetric across its frame's planes, so inside out it is the same solid, and is left so.
// Only past half its thickness inside out (its 4 z edges sum to 8 half extents when whole): a capsule
// crushed flat has its z edges' sign at round-off's mercy, and flipping its points from face to
// face with it shook a capsule ragdoll with flat legs at 1 m/s.
Obb embeddingFrame(const Body& body, const Obb& frame, std::span<const Vec3> position) {
  if (body.model == BodyModel::Rigid) return frame;
  const Vec3 edgesZ = edgeSum(body.model, &position[body.firstParticle], 2);
  if (glm::dot(edgesZ, frame.axes[2]) > -4.0 * body.halfExtents.z) return frame;
  Obb mirrored = frame;
  mirrored.axes[2] = -frame.axes[2];
  return mirrored;
}

Embedding surfacePoint(const Body& box, const Obb& f, const Vec3& point, Vec3* moved) {
  Vec3 u = frameCoordinates(box, f, point);
  // A tetra capsule's points lie on its round surface, inside its box: carried rigidly by its
  // tetrahedron. A corners capsule's go onto the nearest face below, whose 4 particles then hold
  // it up as they hold a box (through the inscribed tetrahedron, the other 4 hang on sticks: a
  // capsule lying on the ground sagged 15 mm at 3 x 1). `moved` gets how far the embedding
  // carries the point, as the box lies in its frame: from its rest shape, not its particles',
  // since a correction reckoned from their sag would feed back into it.
  if (moved != nullptr) *moved = Vec3(0.0);
  if (box.shape == Shape::Capsule && box.model == BodyModel::Tetra) return rigidEmbedding(box, u);
  const Vec3 unclamped = u;
  u = glm::clamp(u, Vec3(-1.0), Vec3(1.0));
  Embedding e;
  e.count = 4;
  if (box.model == BodyModel::Tetra) {
    const std::array<Real, 4> w = tetraWeights(u);
    for (int j = 0; j < 4; ++j) {
      e.particle[j] = box.firstParticle + j;
      e.weight[j] = w[j];
    }
    return e;
  }
  // Corners model: contact points lie on the surface, so trilinear weights reduce to bilinear
  // ones on the face the point is nearest: put it on that face and weigh its 4 corners.
  int axis = 0;
  if (box.shape == Shape::Capsule) {
    // The face nearest in metres: by |u| alone, a side point of a long capsule near its end went
    // to the end face, 2.5 r along the capsule. (A box's points are on a face: either rule finds it.)
    for (int a = 1; a < 3; ++a) {
      if ((1.0 - std::abs(u[a])) * box.halfExtents[a] < (1.0 - std::abs(u[axis])) * box.halfExtents[axis])
        axis = a;
    }
  } else {
    for (int a = 1; a < 3; ++a) {
      if (std::abs(u[a]) > std::abs(u[axis])) axis = a;
    }
  }
  const int side = u[axis] >= 0.0 ? (1 << axis) : 0;
  const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
  if (moved != nullptr) {
    Vec3 carried = u;
    carried[axis] = u[axis] >= 0.0 ? 1.0 : -1.0;
    for (int k = 0; k < 3; ++k) *moved += f.axes[k] * ((carried[k] - unclamped[k]) * box.halfExtents[k]);
  }
  // A point on an edge or at a corner of its face, as most of a stack's are (a face's corner
  // resting on the face below), is carried by 2 corners or 1: snapped there from within kEdgeSnap
  // (rounding leaves it some 1e-16 off), its other corners weigh exactly 0 and are left out, so
  // each pass reads and moves 4.5 particles a contact point (both sides) in a pyramid, not 8.
  for (const int a : {ua, va}) {
    if (std::abs(u[a]) > 1.0 - kEdgeSnap) u[a] = u[a] > 0.0 ? 1.0 : -1.0;
  }
  e.count = 0;
  for (int j = 0; j < 4; ++j) {
    const bool plusU = (j & 1) != 0, plusV = (j & 2) != 0;
    const Real weight = 0.25 * (plusU ? 1.0 + u[ua] : 1.0 - u[ua]) * (plusV ? 1.0 + u[va] : 1.0 - u[va]);
    if (weight == 0.0) continue;
    const int corner = side | (plusU ? 1 << ua : 0) | (plusV ? 1 << va : 0);
    e.particle[e.count] = box.firstParticle + corner;
    e.weight[e.count] = weight;
    ++e.count;
  }
  return e;
}

}  // namespace phys::detail
