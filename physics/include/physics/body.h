#pragma once
// Rigid bodies made of particles, in two models a scene chooses per body, and in two shapes: a
// box, or the capsule inscribed in one. Either way the particles sit on the box (its corners, or
// a tetrahedron of them), so everything the solver does with a body (poses, joints, friction,
// restitution, picking) is the same for both shapes; only collision knows the difference.
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include <glm/mat3x3.hpp>

#include "physics/rigid_bodies.h"
#include "physics/settings.h"
#include "physics/types.h"

namespace phys {

enum class BodyModel {
  /// The seed's: 8 corner particles braced by 22 sticks (docs/physics.md says which and why).
  Corners,
  /// Jakobsen's: 4 particles and 6 sticks forming a tetrahedron; the 8 corners are embedded by
  /// fixed barycentric weights.
  Tetra,
  /// One pose and its velocities, solved by XPBD (Müller et al. 2020): no particles, no sticks;
  /// mass and inertia are a solid box's or capsule's (docs/physics.md, "Rigid bodies").
  Rigid,
};

std::string_view toString(BodyModel model);  ///< "corners", "tetra", "rigid"
std::optional<BodyModel> parseBodyModel(std::string_view name);

/// What collides: the box itself, or a capsule along the body's y axis inscribed in the box:
/// radius size.x / 2 (size.z must equal size.x), whole length size.y from cap to cap (>= size.x).
/// A capsule's mass sits on its box's particles, so it turns like that box (docs/physics.md,
/// "Capsules"), and the peers are given the same moments of inertia.
enum class Shape { Box, Capsule };

std::string_view toString(Shape shape);  ///< "box", "capsule"

/// What a body (a box, or the capsule inscribed in one) is when it is created.
struct BodyDesc {
  std::string name;  ///< for reports and dumps; may be empty
  Vec3 center{0.0};  ///< unit: m
  Vec3 size{1.0};    ///< unit: m; full edge lengths, each > 0
  Quat orientation{1.0, 0.0, 0.0, 0.0};
  Vec3 velocity{0.0};         ///< unit: m/s; of the centre at creation
  Vec3 angularVelocity{0.0};  ///< unit: rad/s; world frame, at creation
  Real mass = 1.0;            ///< unit: kg; spread evenly over the particles
  BodyModel model = BodyModel::Corners;
  Shape shape = Shape::Box;
  Material material;
  /// Rigid model only; unitless, from 0 to 1: each principal moment of inertia is raised to at least
  /// this fraction of the largest, and 0 keeps the solid shape's. A joint's angular correction turns
  /// a thin limb mostly about its long axis, which moves the joint's axis again; a rounder inertia
  /// lets jointed limbs come to rest at a few substeps (docs/physics.md, "Inertia floor"). It changes
  /// how a free body tumbles, so bodies default to 0 and only ragdolls raise it.
  Real inertiaFloor = 0.0;
  /// Collision filtering: two bodies collide when each one's group has a bit in the other's mask.
  std::uint32_t collisionGroup = 1;
  std::uint32_t collisionMask = 0xffffffffu;
};

/// Where a body is: its pose (rigid), or read back from its particles.
struct BodyPose {
  Vec3 center{0.0};  ///< unit: m
  Quat orientation{1.0, 0.0, 0.0, 0.0};
};

/// A body's mass properties, for whoever models it elsewhere (the lab's peer engines): its mass
/// and its principal moments of inertia about its centre, in its own frame. A rigid body's are its
/// solid shape's; a particle body's are its particles' at their rest places. A body held by a
/// pinned or frozen particle is fixed: mass and inertia 0, as engines write a body nothing moves.
struct BodyMass {
  Real mass = 0.0;    ///< unit: kg; 0 when fixed
  Vec3 inertia{0.0};  ///< unit: kg m^2, about the body's x, y and z axes
  bool fixed() const { return mass == 0.0; }
};

/// A body in the world: a box, or a capsule inscribed in its box. Its particles are consecutive from
/// firstParticle; its 8 corners are embeddings from firstCorner in World::corners(). Corner k sits at (+-hx,
/// +-hy, +-hz) in the body frame, bit 0 of k choosing the sign of x, bit 1 of y and bit 2 of z (set =
/// positive).
struct Body {
  std::string name;
  BodyModel model = BodyModel::Corners;
  ParticleId firstParticle{};
  int particleCount = 0;          ///< 8 (corners), 4 (tetra) or 0 (rigid)
  std::uint32_t firstStick = 0;   ///< its own sticks are consecutive in World::sticks() from here
  int stickCount = 0;             ///< 22 (corners) or 6 (tetra)
  std::uint32_t firstCorner = 0;  ///< particle models only: a rigid body has no embedded corners
  RigidId rigid{};                ///< rigid model only: its pose and velocities in World::rigidBodies()
  Vec3 halfExtents{0.5};          ///< unit: m; of the box, or of the box a capsule is inscribed in
  Shape shape = Shape::Box;
  Material material;
  Real inertiaFloor = 0.0;  ///< unitless; a rigid body's BodyDesc::inertiaFloor (0 for particle models)
  std::uint32_t collisionGroup = 1;
  std::uint32_t collisionMask = 0xffffffffu;

  /// A capsule's radius (unit: m): halfExtents.x.
  Real capsuleRadius() const { return halfExtents.x; }
  /// Half the length of a capsule's core segment, which runs along the body's y axis between
  /// its caps' centres (unit: m; 0 for a sphere).
  Real capsuleHalfSegment() const { return halfExtents.y - halfExtents.x; }
};

/// A box seen as a rigid body, from its particles at one instant: the scratch of restitution's
/// velocity pass, which changes the velocities by impulses and then writes the changes into the
/// particles' x* (World keeps one per box).
struct RigidState {
  Real inverseMass = 0.0;          ///< unit: 1/kg; 0 when the box cannot move (pinned, frozen, crushed flat)
  Vec3 centre{0.0};                ///< unit: m; of mass
  glm::dmat3 inverseInertia{0.0};  ///< unit: 1/(kg m^2); about the centre, world axes
  Vec3 velocity{0.0};              ///< unit: m/s; of the centre
  Vec3 spin{0.0};                  ///< unit: rad/s; about the centre
  Vec3 velocityChange{0.0};        ///< unit: m/s; what the impulses added to velocity
  Vec3 spinChange{0.0};            ///< unit: rad/s; what the impulses added to spin
};

/// A particle body's scratch for keeping its angular momentum through its sticks' passes
/// (SolverSettings::keepSpin), set at the start of each substep's passes.
struct StickSpin {
  bool kept = false;  ///< false: left alone (a particle pinned, frozen or asleep, or a rigid body)
  Vec3 moment{0.0};   ///< unit: kg m^2; sum m s_i x x_i before the pass over the sticks
};
/// keepSpin's scratch per particle of a body whose sticks are relaxed in the world's arrays
/// (StickLayout::runBodies): m (x* - c*) (unit: kg m) and m (kg); zeros for a body left alone. The
/// lanes and blocks keep their own levers (ConstraintGraph's lane-major copy, the blocks' locals).
struct SpinLever {
  Vec3 lever{0.0};
  Real mass = 0.0;
};

/// The corners the tetra model's particles sit at: alternate corners, a regular tetrahedron for
/// a cube. Their second moment is m diag(hx^2, hy^2, hz^2), three times a solid box's, as for the
/// corners model; the ratios, hence a free body's tumbling, are a solid box's. Pulled in to
/// 1/sqrt(3) they would match a solid box exactly, but the corners' embedding weights would grow
/// to 1.55 and -1.05 and a resting box would not settle (docs/physics.md).
inline constexpr int kTetraCorner[4] = {0, 3, 5, 6};

/// Body-frame position of corner k of a box with the given half extents.
Vec3 boxCornerLocal(const Vec3& halfExtents, int k);
/// The lowest point, as a height along the unit vector `up`, of a solid box with these half
/// extents (Shape::Box) or of the capsule inscribed in it (Shape::Capsule: Body::capsuleRadius
/// and capsuleHalfSegment's) placed at `pose`: the height of its support point in direction
/// -up. The world's penetration metric measures its capsules by it, and the lab's peer engines
/// their boxes and capsules.
Real lowestAlong(Shape shape, const Vec3& halfExtents, const BodyPose& pose, const Vec3& up);
/// Body-frame rest position of particle j of a box of the given model.
Vec3 boxParticleLocal(BodyModel model, const Vec3& halfExtents, int j);
/// Particles per box of the given model.
int boxParticleCount(BodyModel model);
/// Barycentric weights, over a tetra box's 4 particles, of the point at u in the box's frame
/// (u in units of the half extents: the corners are at +-1). Closed form (1 + s_j . u) / 4 with
/// s_j the particles' corner signs: those four sign vectors sum to zero and sum s_j s_j^T = 4 I.
/// No matrix is inverted; the weights of a corner outside the tetrahedron are (1/2, 1/2, 1/2, -1/2).
std::array<Real, 4> tetraWeights(const Vec3& u);

}  // namespace phys
