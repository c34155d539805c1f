#pragma once
// Box-box narrow phase: the separating-axis test over the 15 axes of two oriented boxes, the
// contact feature on each side, and the contact points. Pure geometry on oriented boxes, so it
// is tested on its own; World turns the points into constraints on particles.
#include <array>
#include <cstdint>
#include <limits>

#include <glm/mat3x3.hpp>

#include "physics/types.h"

namespace phys {

/// An oriented box: centre, unit axes (columns) and half extents.
struct Obb {
  Vec3 center{0.0};
  glm::dmat3 axes{1.0};
  Vec3 halfExtents{0.5};

  Vec3 corner(int k) const;  ///< corner k, bits 0/1/2 choosing +x/+y/+z as in box.h
};

/// Which of the 15 axes separated least: 0-2 faces of A, 3-5 faces of B, 6 + 3 i + j the cross
/// product of A's axis i and B's axis j.
struct SatResult {
  bool overlap = false;  ///< true also when apart by less than the margin (depth < 0)
  int axis = -1;
  Real depth = 0.0;  ///< unit: m; penetration along the axis when overlapping
  Vec3 normal{0.0};  ///< unit vector from A towards B
  /// The shallowest edge-edge axis, which the face bias may have passed over (-1: none, every pair
  /// of edges near parallel), with its penetration (m) and its unit normal from A towards B.
  int edgeAxis = -1;
  Real edgeDepth = 0.0;
  Vec3 edgeNormal{0.0};
};

/// Tolerances that bias the choice towards face axes, so the contact normal does not flip
/// between a face and an edge axis of nearly equal depth from one step to the next
/// (the same idea as qu3e's and Box2D's relative and absolute tolerances).
inline constexpr Real kFaceBiasRelative = 0.95;
inline constexpr Real kFaceBiasAbsolute = 0.01;  ///< unit: m

/// Which box's face axes a pair's face-face choice prefers: one whose frame is exact (a rigid body)
/// against one whose frame is fitted to particles (a corners or tetra box), whose fitted axes wobble
/// by the passes' residue (1e-4 rad on a corners box at rest at 3 x 1). With no preference, the
/// shallower of two near-equal face axes was the particle box's every other step, and the normal
/// tilted with it by turns: the box rocked by 2e-5 m a step for good and crept off a rigid box
/// (docs/physics.md, "Failures at rest").
enum class PreferFaces : std::uint8_t { None, OfA, OfB };
/// unit: m; how much deeper the preferred box's face axis may be and still be taken.
inline constexpr Real kPreferredFaceTolerance = 1e-3;

/// The separating-axis test; stops at the first axis that separates. Boxes less than `margin`
/// apart count as touching (depth down to -margin), so a resting contact that a relaxation pass
/// left a hair open is still found in the next substep. `previousAxis` is the axis the pair's
/// last test chose (-1: none): after an edge-edge axis, the shallowest edge axis is taken whenever
/// it is shallower than every face axis (no bias), so that a pair between the biased and the
/// unbiased choice does not take a face axis and an edge axis by turns (a limb rocked against
/// another every other step: docs/physics.md, "Box-box contact").
/// `prefer` takes the preferred box's shallowest face axis over the other's when it is no more than
/// kPreferredFaceTolerance deeper.
SatResult satTest(const Obb& a, const Obb& b, Real margin = 0.0, int previousAxis = -1,
                  PreferFaces prefer = PreferFaces::None);

/// The first touch of two oriented boxes as B moves by `moved` relative to A, neither turning: the
/// separating-axis test swept over the move. On each of the 15 axes the projections overlap over
/// one stretch of the move; the boxes meet where all the stretches do, first at the latest entry,
/// along that entry's axis (a near miss past an edge overlaps on some axes but never on all).
struct SweptSat {
  bool hit = false;  ///< they meet within the move, or overlap at its start
  Real time = 0.0;   ///< fraction of the move at the first touch (< 0: they overlapped before it)
  Vec3 normal{0.0};  ///< unit axis of the first touch, from A towards B
  Real gap = 0.0;    ///< unit: m; apart along the normal at the start (< 0: overlapping so far)
};
SweptSat sweptSat(const Obb& a, const Obb& b, const Vec3& moved);

/// Half the box's thickness along the unit axis: its projected radius. unit: m
Real projectedRadius(const Obb& box, const Vec3& axis);

/// The feature each box meets the other with, seen along the contact normal.
enum class Feature { Vertex = 1, Edge = 2, Face = 4 };
enum class ContactKind { FaceFace, FaceEdge, FaceVertex, EdgeEdge, EdgeVertex, VertexVertex };
const char* toString(ContactKind kind);

/// The vertices of `box` within `epsilon` of its extreme in direction `direction`: 1 is a
/// vertex, 2 an edge, 3 or more a face (the seed's classification, with its epsilon).
struct SupportFeature {
  Feature feature = Feature::Vertex;
  int count = 0;
  std::array<int, 4> corners{};  ///< corner indices; for a face in winding order
};
SupportFeature supportFeature(const Obb& box, const Vec3& direction, Real epsilon);
ContactKind classify(Feature a, Feature b);

/// One point of contact: where it is on A and on B. n . (onB - onA) = -depth < 0 while they
/// overlap; the response pushes the two apart along the normal until that is 0.
struct ContactPoint {
  Vec3 onA{0.0};
  Vec3 onB{0.0};
  Real depth = 0.0;  ///< unit: m
};

struct BoxContact {
  ContactKind kind = ContactKind::FaceFace;
  SatResult sat;
  int count = 0;
  /// Points the last reduceToFourPoints on it dropped (set by it alone): a manifold that dropped
  /// none holds every corner of the faces' overlap.
  int dropped = 0;
  std::array<ContactPoint, 8> points;
};

/// Finds the contact of two boxes along the SAT normal: face-face and face-edge by clipping
/// the incident feature against the reference face's sides (up to 8 points), face-vertex by
/// projecting the vertex, edge-edge by the closest points of the two edges, edge-vertex and
/// vertex-vertex by the closest point to the vertex. Boxes within featureEpsilon count as
/// touching (see satTest). False when the boxes are apart.
bool collideBoxes(const Obb& a, const Obb& b, Real featureEpsilon, BoxContact& out);
/// The same, keeping boxes and points up to `margin` apart (>= featureEpsilon: a speculative
/// margin), while the features are still told apart by featureEpsilon.
/// `previousAxis` and `prefer` as satTest's.
bool collideBoxes(const Obb& a, const Obb& b, Real featureEpsilon, Real margin, BoxContact& out,
                  int previousAxis = -1, PreferFaces prefer = PreferFaces::None);

/// Keeps at most 4 of a contact's points: the deepest, the farthest from it, and the two that
/// span the largest area with them. The solver uses this, so a face contact has 4 points
/// whether the faces meet square (4 clipped) or turned (up to 8), and its stiffness does not
/// jump from one substep to the next as the clipped polygon gains and loses corners. Points more
/// than `touching` apart (speculative ones, depth < -touching) never displace a touching one:
/// with 4 or more touching points they are dropped, with fewer the nearest fill the 4.
void reduceToFourPoints(BoxContact& contact, Real touching = std::numeric_limits<Real>::infinity());

/// A capsule: the points within `radius` of the core segment p0-p1 (p0 == p1 makes a sphere).
struct Capsule {
  Vec3 p0{0.0};
  Vec3 p1{0.0};
  Real radius = 0.0;  ///< unit: m
};

/// The capsule inscribed in an oriented box (a body of Shape::Capsule): its core runs along the
/// box's y axis, radius halfExtents.x, ending halfExtents.y - radius either side of the centre.
Capsule capsuleInBox(const Obb& box);

/// Contact of two capsules, normal from A towards B: one point where the cores' closest points
/// are, or two (the ends of the stretch where they overlap lengthwise) when the cores lie side by
/// side, so that a capsule lying on another does not rock about one point. Capsules less than
/// `margin` apart count as touching (depth down to -margin). False when they are apart.
bool collideCapsules(const Capsule& a, const Capsule& b, Real margin, BoxContact& out);

/// Contact of a capsule (A) and a box (B), normal from A towards B: the core's point nearest the
/// box, or two points (the core clipped to the face) when the core lies along a face of the box.
/// A core that reaches inside the box is pushed out through the face it is least deep behind.
bool collideCapsuleBox(const Capsule& a, const Obb& b, Real margin, BoxContact& out);

}  // namespace phys
