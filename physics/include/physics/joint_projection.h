#pragma once
// Rigid joints closed exactly after each substep's passes, by a direct solve of every tree of
// jointed rigid bodies in time linear in its bodies (Baraff 1996). The passes end with the contacts,
// so wherever joints and contacts disagree (a part pressed into the ground by the bodies above it)
// the joints give way, and ragdolls landing in a pile come apart by centimetres. The projection moves
// the poses the least, weighted by mass and inertia, that brings every pin's two points together and
// every hinge's axes into line; the substep's velocities, taken from the change of pose afterwards,
// carry the correction (docs/physics.md, "Joint projection").
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat3x3.hpp>

#include "physics/rigid_bodies.h"
#include "physics/rigid_joints.h"
#include "physics/settings.h"

namespace phys {

/// What one projection did.
struct JointProjectionReport {
  int iterations = 0;      ///< linear solves made (0 when every joint was already within tolerance)
  Real errorBefore = 0.0;  ///< the widest pin (m) or hinge axes' misalignment (rad) before
  Real errorAfter = 0.0;   ///< the same after, over the joints of the trees
};

/// The projection's trees and its scratch, kept from step to step so that a step allocates nothing.
class JointProjection {
 public:
  /// Moves the rigid bodies' poses so that every joint's pin closes and every hinge's two axes
  /// align, by up to settings.iterations Newton steps, each an exact solve of those constraints
  /// linearised at the poses reached. Joints that would close a loop (or tie a tree to a second body
  /// that cannot move) are left to the passes; so are the stops, a cone's swing and the twists.
  JointProjectionReport project(RigidBodies& r, std::span<const RigidJoint> joints,
                                const JointProjectionSettings& settings);

 private:
  // Row-major, its first `rows` rows and columns used: a joint's block (its constraints: a pin's 3
  // rows and a hinge's 2 more).
  using Matrix6 = std::array<Real, 36>;
  using Vector6 = std::array<Real, 6>;
  // Symmetric 6x6 as [[a, b], [b^T, c]]: a body's block (translation, turn).
  struct Block6 {
    glm::dmat3 a{0.0}, b{0.0}, c{0.0};
  };
  // A joint's block and its Jacobians' parts: X = -[arm]x of each side's pivot arm, and the two
  // directions normal to a hinge's axis in which its axes' misalignment is measured (zero for a cone).
  struct JointRows {
    Matrix6 block{};
    glm::dmat3 xa{0.0}, xb{0.0};
    Vec3 u{0.0}, v{0.0};
  };
  struct Node {
    std::uint32_t index = 0;   // RigidId for a body, joint index for a joint
    std::int32_t parent = -1;  // node index; -1 for a tree's root
    std::uint8_t rows = 0;     // 6 for a body; a joint's constraints
    bool leaf = true;          // no children: a body's block is its mass and inertia alone
  };

  void buildTrees(const RigidBodies& r, std::span<const RigidJoint> joints);
  Real measure(const RigidBodies& r, std::span<const RigidJoint> joints) const;
  /// False, moving nothing, when a block could not be inverted or the result is not finite.
  bool solve(RigidBodies& r, std::span<const RigidJoint> joints);

  std::vector<Node> nodes_;  // parents before children
  std::vector<std::int32_t> bodyNode_;
  std::vector<std::uint32_t> treeJoints_;  // the joints in the trees
  // Union-find and the trees' adjacency, by body.
  std::vector<std::uint32_t> root_;
  std::vector<std::uint8_t> anchored_;
  std::vector<std::uint32_t> adjacencyStart_, adjacency_;
  // Per node: D, then D^-1 once eliminated (a body's in body_, a joint's in joint_); the
  // right-hand side, then the solution.
  std::vector<Block6> body_;
  std::vector<JointRows> joint_;
  std::vector<Vector6> rhs_;
};

}  // namespace phys
