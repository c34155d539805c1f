#pragma once
// Constraint definitions, kept apart from particle state.
#include <array>
#include <cstdint>
#include <limits>

#include <glm/mat3x3.hpp>

#include "physics/settings.h"
#include "physics/types.h"

namespace phys {

/// Keeps the distance between two particles within [minLength, maxLength]. A stick proper
/// (Jakobsen's) has minLength == maxLength; a range stick (the softer joint the seed wished
/// for) has minLength < maxLength, and is one-sided when minLength is 0 or maxLength infinite.
struct Stick {
  ParticleId a{};
  ParticleId b{};
  Real minLength = 0.0;  ///< unit: m
  Real maxLength = 0.0;  ///< unit: m; may be infinite
  /// Inverse stiffness (XPBD's alpha), honoured by SolverMethod::Xpbd; 0 is rigid.
  Real compliance = 0.0;  ///< unit: m/N

  bool isRange() const { return minLength != maxLength; }
};

inline constexpr Real kNoMaxLength = std::numeric_limits<Real>::infinity();

/// A point carried by up to 4 particles as the affine combination sum(weight[i] * x[i]), with
/// weights summing to 1: a particle itself (one weight of 1), a box corner embedded in a
/// tetrahedron (four barycentric weights). Moving the point by D moves particle i by
/// weight[i] * w_i * D / sum_j(weight[j]^2 w_j) (REFERENCES.md, Jakobsen): no matrix inverse,
/// and it cannot blow up for a point inside the body.
struct Embedding {
  std::array<ParticleId, 4> particle{};
  std::array<Real, 4> weight{};
  int count = 0;
};

/// The embedding of a particle itself: one weight of 1.
inline Embedding embedParticle(ParticleId id) {
  Embedding e;
  e.particle[0] = id;
  e.weight[0] = 1.0;
  e.count = 1;
  return e;
}

/// Keeps two embedded points, usually of two bodies, within [minLength, maxLength] of each
/// other: a joint. maxLength 0 makes a pin, which holds the points together (a ball joint; two
/// pins on a line make a hinge); a range link with minLength > 0 or a finite maxLength is a joint
/// limit. A pin is a linear constraint, so its projection is exact for any direction, even
/// when the two points coincide, where a stick's direction is undefined.
struct Link {
  Embedding a;
  Embedding b;
  Real minLength = 0.0;  ///< unit: m
  Real maxLength = 0.0;  ///< unit: m; may be infinite (kNoMaxLength)

  bool isPin() const { return maxLength == 0.0; }
};

/// Friction in the joint between two particle bodies (a ragdoll's jointed parts): once a step the
/// share min(rate dt, 1) of their relative spin is taken away by an angular impulse between them,
/// which keeps their momentum and angular momentum. The rigid joints' JointDesc::damping does the
/// same for rigid parts.
struct JointFriction {
  BodyId a{};
  BodyId b{};
  Real rate = 0.0;  ///< unit: 1/s; the relative spin decays as exp(-rate t)
};

/// Scratch of the joint friction's pass: a body's rigid motion over the last substep, found once a
/// step and kept up to date as its joints turn it.
struct BodySpin {
  enum class State : std::uint8_t { Unknown, Known, Immovable };
  State state = State::Unknown;
  Vec3 centre{0.0};                ///< unit: m
  glm::dmat3 inverseInertia{0.0};  ///< unit: 1/(kg m^2)
  Vec3 angular{0.0};               ///< unit: rad over the substep
};

/// What friction did to an anchored contact point in the last pass of the substep that pushed it
/// (docs/physics.md, "Friction anchors"): none pushed it, held it, or let it slip.
enum class Grip : std::uint8_t { None, Held, Slipped };

/// A contact between two boxes for one substep: a point embedded in each, kept apart along the
/// normal (from A towards B): n . (pointB - pointA) >= 0. Only what the contact and friction passes
/// read of every point is here, what the push reads first: the rest is in a BodyContactExtra of
/// the same index (NarrowPhase::contactExtras), so that the passes, which are bound by loading
/// their points, load 224 bytes a point instead of 368 (docs/performance.md, "The contact's
/// seldom read part apart").
struct BodyContact {
  Embedding pointA;
  Embedding pointB;
  Vec3 normal{0.0};
  /// The least n . (pointB - pointA) (unit: m): 0 when both points are on the surfaces. A point
  /// of a corners-model capsule is carried by the box face nearest it (its own 4 particles,
  /// which hold it as they hold a box's contact), off the round surface: this is by how much.
  Real offset = 0.0;
  Material combined;  ///< geometric mean of the two boxes' materials
  /// Static friction's anchor (unit: m), for a point of a face-on-face manifold between particle
  /// boxes: the tangential part of pointB - pointA that friction holds the two to. Set from x* at
  /// the point's first substep and after a substep in which it did not touch; set to slipEnd after
  /// one that ended in a slip; fixed within a substep; turned with its manifold's reference face
  /// (docs/physics.md, "Friction anchors").
  Vec3 anchor{0.0};
  /// unit: m; where the pair's last slip left the tangential part of pointB - pointA, friction's
  /// cut made: the next substep's anchor if the substep's last push slipped.
  Vec3 slipEnd{0.0};
  BodyId bodyA = kNoBody;  ///< for debug drawing and reports
  BodyId bodyB = kNoBody;
  std::uint8_t kind = 0;   ///< ContactKind, for debug drawing
  bool anchored = false;   ///< of a kept manifold: friction holds it to `anchor`
  Grip grip = Grip::None;  ///< what the substep's last pass that pushed it did
  /// Friction acts at BodyContactExtra::surfaceA (surfaceB) instead of pointA (pointB): a side
  /// that is a corners capsule.
  bool frictionAtSurfaceA = false;
  bool frictionAtSurfaceB = false;
};

/// What a BodyContact carries that the passes do not read of every point, at the same index as
/// the contact (NarrowPhase::contactExtras): read only where a flag of the contact says, or once a
/// substep.
struct BodyContactExtra {
  /// Where friction acts on a corners capsule (count 0 for any other body): its true surface
  /// point, carried rigidly, as GroundContact::surface (BodyContact::frictionAtSurfaceA, B).
  Embedding surfaceA;
  Embedding surfaceB;
  /// unit: m; when its face-on-face manifold was clipped again, what the old point at the same
  /// place on both bodies had slid from its anchor while friction held it, taken off this point's
  /// first anchor so that the slide is not forgotten; 0 for any other point. Only between a tetra
  /// box and a box (NarrowPhase::carrySlide; docs/physics.md, "A tetra box walking on a box").
  Vec3 carriedSlide{0.0};
};

/// A point that collides with the ground: a loose particle or a box corner.
struct GroundContact {
  Embedding point;
  Material material;      ///< the body's own
  Material combined;      ///< geometric mean with the ground's, kept current by the world
  BodyId body = kNoBody;  ///< kNoBody for a loose particle
  /// How far above the plane the point is held (unit: m): 0 for a point on the surface; for a
  /// corners-model capsule, whose point is carried by a face of its box where the ground's normal
  /// through its lowest point leaves the box, the height of that face point over the capsule's
  /// lowest point: 0 or negative, the face point lying on that line below it (see
  /// BodyContact::offset).
  Real lift = 0.0;
  /// Where friction acts when it is not `point` (count 0 otherwise): a corners capsule's true
  /// surface point, carried rigidly. Held at the face point, up to 0.29 r off the surface, friction
  /// stopped it slipping there, and the capsule rolled as on a larger radius, 11% fast.
  Embedding surface;
  /// For the first of a corners capsule's two points (its ends' lowest points; the next point is
  /// the other), set where they are placed each substep while it rests with its box whole: the two
  /// share their particles, and the ground pass pushes them as one block (collideGround), by their
  /// weights unless rigidBlock says rigidly. Never for a tetra capsule (GroundContacts::placeCapsulePoints
  /// says why; see rigidBlock).
  bool pairedWithNext = false;
  /// How many points from this one on (this one's body's) are pushed as one block moving its
  /// particles (a tetra capsule's 4, a corners capsule's 8) as one rigid body, not by the points'
  /// weights (collideGround): a capsule's 2 while it is a free body (nothing joined to it, no other
  /// body touching it in the step) with its box whole, a corners one also only while its points are
  /// paired (resting; GroundContacts::placeCapsulePoints); 8 on the first corner of a tetra box
  /// under the capsules' rule: its 8 corners are pushed and cut by their weights, and each pass's
  /// moves of its 4 particles made a rigid body's (GroundContacts::markFreeTetraBoxes); 0 for none.
  std::uint8_t rigidBlock = 0;
};

/// A tetra box's ground points: its 8 corners, added one after the other (GroundContact::rigidBlock).
inline constexpr std::uint8_t kTetraBoxCorners = 8;

}  // namespace phys
