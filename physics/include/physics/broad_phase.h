#pragma once
// The broad phase (Stage::BroadPhase): which pairs of bodies may touch within a step, from each
// body's bounds grown by how far it can go in the step, and the collision filters that keep pairs
// out (groups and masks, and the pairs told to ignore each other). The bodies' bounds, enlarged
// further by a margin, sit in a dynamic tree with the pairs they overlap in; a step moves only
// the bodies that left their enlarged bounds. It owns its arrays; World hands it the bodies,
// their frames and their particles.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "physics/aabb_tree.h"
#include "physics/body.h"
#include "physics/collision.h"
#include "physics/particles.h"
#include "physics/settings.h"

namespace phys {

/// What the broad phase reads of the solver settings and the world for one step.
struct BroadPhaseStep {
  Real dt = 0.0;              ///< unit: s; the step
  Real h = 0.0;               ///< unit: s; the substep whose particle motion gives the speeds
  Real featureEpsilon = 0.0;  ///< unit: m; added to every body's bounds
  Real gravity = 0.0;         ///< unit: m/s^2; |g|, whose g dt^2 a body held still can still travel
  BroadPhaseSettings settings;
};

/// How a body moves over a step at the speeds of the broad phase's substep: its particles' mean
/// displacement, and the most one's differs from that (turning and bending).
struct BodyMotion {
  Vec3 shift{0.0};  ///< unit: m
  Real turn = 0.0;  ///< unit: m
};

class BroadPhase {
 public:
  using Pair = std::pair<BodyId, BodyId>;

  /// Makes room for one more body, whose id is the number of bodies before it.
  void addBody();
  /// Keeps the two bodies from colliding; ids must exist and differ (World checks them).
  void ignore(BodyId a, BodyId b);
  /// Every pair ignore() was given, as (smaller id, larger id), sorted.
  std::vector<Pair> ignoredPairs() const;
  /// Indexes the ignored pairs by body; after ignore(), before collides(). Allocates.
  void indexFilters();
  /// Whether the filters let the two bodies collide: each one's group has a bit in the other's
  /// mask, and they were not told to ignore each other.
  bool collides(std::span<const Body> bodies, BodyId a, BodyId b) const;

  /// The pairs must be found again at the next update (bodies or filters changed).
  void markStale() { stale_ = true; }
  /// True when the pairs are stale, or some body has gone further since they were found than its
  /// bounds allowed (an impact or a joint gave it speed within the step).
  bool needsUpdate(std::span<const Obb> frames) const;
  /// Finds the pairs from the bodies' frames now and their particles' motion over the last
  /// substep; allocates only when the world has gathered many more pairs than it ever had.
  void update(const Particles& particles, std::span<const Body> bodies, std::span<const Obb> frames,
              const BroadPhaseStep& step);

  /// The pairs whose grown bounds overlapped at the last update, (lower id, higher id), in body
  /// order: by lower id, then higher.
  std::span<const Pair> pairs() const { return pairs_; }
  /// A body's motion over a step, measured at the last update.
  const BodyMotion& motion(BodyId id) const { return motion_[id]; }
  /// How many bodies the last update moved in the tree (left their enlarged bounds, or all of
  /// them when the pairs were stale).
  std::size_t movedBodies() const { return moved_.size(); }
  /// The pairs whose enlarged bounds overlap, which pairs() is taken from.
  std::size_t candidatePairs() const { return candidates_.size(); }
  const AabbTree& tree() const { return tree_; }

 private:
  void measureBounds(const Particles& particles, std::span<const Body> bodies, std::span<const Obb> frames,
                     const BroadPhaseStep& step);
  void moveEscapedBodies(Real margin);
  void updateCandidates(std::span<const Body> bodies);
  void sortByBody(std::vector<Pair>& from, std::vector<Pair>& to);

  AabbTree tree_;
  std::vector<AabbTree::NodeId> leaf_;  // per body: its leaf in tree_
  std::vector<Aabb> bounds_;            // per body: AABB grown by its reach over a step
  std::vector<Real> travel_;            // per body: that reach (m)
  std::vector<BodyMotion> motion_;      // per body
  std::vector<Obb> pairFrames_;         // per body: its frame when pairs_ was found
  std::vector<BodyId> moved_;           // the bodies the last update moved in the tree
  std::vector<std::uint8_t> isMoved_;   // per body: in moved_
  bool stale_ = true;
  std::vector<Pair> candidates_;             // pairs whose enlarged bounds overlap, in body order
  std::vector<Pair> unsortedPairs_;          // the candidates kept and found, before sortByBody
  std::vector<Pair> pairs_;                  // candidates whose bounds overlap
  std::vector<std::uint32_t> pairStart_;     // per body and one more: its pairs as the lower id
  std::vector<std::uint64_t> ignored_;       // sorted keys (min << 32 | max)
  std::vector<std::uint32_t> ignoredStart_;  // per body and one more: its keys as min (indexFilters)
};

}  // namespace phys
