#pragma once
// The points that collide with the ground (loose particles, box corners, capsules' lowest points)
// and what the passes keep for each. World owns one; the passes (ground.cpp) read and write its
// arrays.
#include <cstdint>
#include <span>
#include <vector>

#include "physics/body.h"
#include "physics/collision.h"
#include "physics/constraints.h"
#include "physics/particles.h"
#include "physics/workers.h"

namespace phys {

struct Manifold;

/// Per ground contact point, index for index with GroundContacts::points().
struct GroundContactState {
  std::vector<Real> push;             ///< unit: m; the ground's correction in the last pass
  std::vector<std::uint8_t> hit;      ///< pushed in this substep (restitution reads it)
  std::vector<std::uint8_t> touched;  ///< pushed in the last step
  std::vector<Real> approach;         ///< unit: m/s; approach speed at the substep's start
  std::vector<Real> allowance;        ///< unit: m; depth at x*, then the depth it may keep
};

class GroundContacts {
 public:
  /// Adds a point of `body` (kNoBody for a loose particle), whose friction is the geometric mean of
  /// its material and the ground's (the ground's alone for a loose particle).
  void add(const Embedding& point, const Material& material, BodyId body, const Material& ground);
  /// A capsule's point that follows the lowest point of one end sphere (end -1 or +1 along the
  /// body's y axis): the point added last.
  void followCapsuleEnd(Real end);
  /// The 8 points added last are a tetra box's corners (World::addBody): markFreeTetraBoxes
  /// looks at them.
  void followTetraBox();
  /// Marks the 8 corners of each tetra box that is a free body (nothing joined to it: `joined`, per
  /// body, 1 for one a stick, link or joint acts on, empty for none; in none of this step's
  /// `manifolds`) with its box whole as one rigid block (GroundContact::rigidBlock 8 on its first
  /// corner): each pass's pushes and cuts of them move its 4 particles as one rigid body. Every other
  /// tetra box's are 0. Defined in ground_tetra_boxes.cpp, which says why.
  void markFreeTetraBoxes(std::span<const Body> bodies, const Particles& particles,
                          std::span<const Manifold> manifolds, std::span<const std::uint8_t> joined);
  /// Whether markFreeTetraBoxes marked any box in this step.
  bool anyFreeTetraBox() const { return anyFreeTetraBox_; }
  /// Drops the points from `count` on (a box's particles' own points, replaced by its corners).
  void truncate(std::size_t count);
  /// The ground's material changed: every point's friction again.
  void combineMaterials(const Material& ground);
  /// Re-embeds each capsule's points at the lowest points of its end spheres, at its frame of this
  /// substep (they move over its surface as it turns), on the step's threads (null: on this one).
  /// An end further above the ground (at groundHeight along groundNormal) than the capsule's half
  /// length keeps the point it had, which no pass pushes from there, and is marked far. `position`
  /// (the particles') tells a capsule turned inside out, whose points go on the face its particles
  /// lie on, not the one its frame names (see the definition). A corners capsule resting on the ground
  /// (its particles' mean move of this substep no more than `restingMove` towards it, and its box
  /// whole) has its two points paired, pushed as one block (GroundContact::pairedWithNext); a
  /// capsule that is a free body, its box whole (a corners one also paired), as one rigid block
  /// (GroundContact::rigidBlock): free, when nothing is joined to it (`joined`, per body: 1 for one a
  /// stick, link or joint acts on; empty for none) and it is in none of this step's `manifolds`.
  void placeCapsulePoints(std::span<const Body> bodies, std::span<const Obb> frames,
                          const Particles& particles, std::span<const Manifold> manifolds,
                          std::span<const std::uint8_t> joined, const Vec3& groundNormal, Real groundHeight,
                          Real restingMove, const Workers* workers);
  /// Per point, 1 for a capsule's end that placeCapsulePoints left far above the ground in this
  /// substep: the collision pass skips it (no push) as it would find it above the ground. Its depth at
  /// x* is still measured: the parting reads it.
  /// Empty without capsules.
  std::span<const std::uint8_t> far() const {
    return capsuleEnds_.empty() ? std::span<const std::uint8_t>() : std::span<const std::uint8_t>(far_);
  }
  bool hasCapsules() const { return !capsuleEnds_.empty(); }
  /// Marks the points whose every particle has inverse mass 0 in this step and had in the last
  /// one (a sleeping body's, from its second step asleep): nothing of them moves, so what the
  /// passes found for them in the last step is what they would find again, and the passes leave
  /// them and their push and flags as they are (their depths at x* are still measured: the
  /// parting reads them). clearStill marks none.
  void markStill(std::span<const Real> inverseMass);
  /// In the step, after islands woke and got their masses back (World::wakeTouched): their points are
  /// no longer still, and their flags start from none, as an awake body's do at the step's start.
  void unmarkMoving(std::span<const Real> inverseMass);
  void clearStill();
  /// Per point, 1 when marked still; empty when none is.
  std::span<const std::uint8_t> still() const {
    return anyStill_ ? std::span<const std::uint8_t>(still_) : std::span<const std::uint8_t>();
  }

  std::span<const GroundContact> points() const { return points_; }
  std::size_t size() const { return points_.size(); }
  GroundContactState& state() { return state_; }
  const GroundContactState& state() const { return state_; }

 private:
  /// touching_: per body, 1 for one in any of `manifolds` (speculative ones too), for the rigid
  /// blocks of capsules and tetra boxes, which only a body nothing else touches gets.
  void markTouching(std::size_t bodyCount, std::span<const Manifold> manifolds);

  struct CapsuleEnd {
    std::uint32_t point;  // which point
    BodyId body;          // the capsule: a far end reads its frame, not its point
    Real end;             // -1 or +1 along the body's y axis
  };
  std::vector<GroundContact> points_;
  GroundContactState state_;
  std::vector<CapsuleEnd> capsuleEnds_;
  struct TetraBox {
    std::uint32_t firstPoint;  // the first of its 8 corners
    BodyId body;
  };
  std::vector<TetraBox> tetraBoxes_;
  std::vector<std::uint8_t> still_;     // per point: 1 to leave it in this step
  std::vector<std::uint8_t> far_;       // per point: 1 for a capsule's end far above the ground
  std::vector<std::uint8_t> wasStill_;  // per point: its particles had inverse mass 0 last step
  std::vector<std::uint8_t> touching_;  // per body: in one of the step's manifolds (markTouching)
  bool anyStill_ = false;
  bool anyFreeTetraBox_ = false;
  bool anyMarked_ = false;  // markStill ran since the last clearStill
};

}  // namespace phys
