#pragma once
// The broad phase (Stage::BroadPhase): which pairs of bodies may touch within a step, found by
// sweep and prune within strips from each body's bounds grown by how far it can go in the step,
// and the collision filters that keep pairs out (groups and masks, and the pairs told to ignore
// each other). It owns its arrays; World hands it the bodies, their frames and their particles.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "physics/body.h"
#include "physics/collision.h"
#include "physics/particles.h"
#include "physics/rigid_bodies.h"
#include "physics/settings.h"
#include "physics/workers.h"

namespace phys {

/// What the broad phase reads of the solver settings and the world for one step.
struct BroadPhaseStep {
  Real dt = 0.0;              ///< unit: s; the step
  Real h = 0.0;               ///< unit: s; the substep whose particle motion gives the speeds
  Real featureEpsilon = 0.0;  ///< unit: m; added to every body's bounds
  Real gravity = 0.0;         ///< unit: m/s^2; |g|, whose g dt^2 a body held still can still travel
  BroadPhaseSettings strips;
  /// Per body, 1 when it sleeps (Islands::bodiesAsleep), or empty: two sleeping bodies make no pair,
  /// and a sleeping body's bounds, once found asleep, are kept (nothing of it moves). So a body must
  /// not sleep through a change of the other fields: World wakes every island when its settings
  /// change.
  std::span<const std::uint8_t> asleep;
  const Workers* workers = nullptr;  ///< the step's threads, which measure the bodies' bounds; null on one
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
  bool needsUpdate(std::span<const Obb> frames, std::span<const std::uint8_t> asleep = {},
                   const Workers* workers = nullptr) const;
  /// Finds the pairs from the bodies' frames now and their motion over the last substep (their
  /// particles', or a rigid body's velocities); allocates only when the world has gathered many
  /// more pairs than it ever had.
  void update(const Particles& particles, const RigidBodies& rigid, std::span<const Body> bodies,
              std::span<const Obb> frames, const BroadPhaseStep& step);

  /// The pairs whose grown bounds overlapped at the last update, (lower id, higher id), in body
  /// order: by lower id, then higher.
  std::span<const Pair> pairs() const { return pairs_; }
  /// A body's motion over a step, measured at the last update. The id must exist, unchecked: the
  /// narrow phase and the sweep read it for every pair of every substep, with the world's own ids,
  /// and World does not hand its broad phase out.
  const BodyMotion& motion(BodyId id) const { return motion_[id]; }

 private:
  struct Interval {
    Real min, max;  // extent of a body's bounds along the sweep axis
    BodyId body;
  };
  struct Bounds {
    Vec3 lo, hi;
  };
  /// A body's entry in a strip: its bounds along the sweep axis s and the strips' axes t and u
  /// (lo, hi), copied so that a strip's sweep reads them in order.
  struct StripEntry {
    Real s[2], t[2], u[2];
    BodyId body;
    std::uint32_t firstStrip;
  };
  void measure(const Particles& particles, const RigidBodies& rigid, const Body& box, const Obb& f, BodyId id,
               const BroadPhaseStep& step);
  bool chooseSweepAxis(std::span<const Obb> frames);
  void findPairsInStrips(std::span<const Body> bodies, const BroadPhaseSettings& settings,
                         std::span<const std::uint8_t> asleep, const Workers* workers);
  template <class Sweep>
  void sweepInPieces(std::size_t strips, std::size_t entries, const Workers* workers, Sweep&& sweep);
  void sortPairsByBody();

  std::vector<Interval> sweep_;           // sweep-and-prune list, kept sorted between steps
  std::vector<std::size_t> stripStart_;   // per strip and one more: where its bodies start in stripBodies_
  std::vector<BodyId> stripBodies_;       // the bodies of each strip, in sweep order
  std::vector<StripEntry> stripEntries_;  // the same entries with their bounds
  std::vector<BodyId> wideBodies_;        // bodies across too many strips, tested against all
  std::vector<std::pair<std::uint32_t, std::uint32_t>> stripsOf_;  // per body: its first and last strip
  std::vector<Real> sleepingReach_;       // per strip entry: the furthest hi of the sleeping ones up to it
  std::vector<Bounds> bounds_;            // per body: AABB grown by its reach over a step
  std::vector<Real> travel_;              // per body: that reach (m)
  std::vector<BodyMotion> motion_;        // per body
  std::vector<Obb> pairFrames_;           // per body: its frame when pairs_ was found
  std::vector<std::uint8_t> keptAsleep_;  // per body: 1 when its bounds were found while it slept
  bool stale_ = true;
  int sweepAxis_ = 0;  // the axis sweep_ is sorted along
  std::vector<Pair> pairs_;
  std::vector<Pair> unsortedPairs_;            // as the strips find them
  std::vector<std::vector<Pair>> stripPairs_;  // the second piece's on, when strips are swept at once
  std::vector<std::uint32_t> pairStart_;       // per body and one more: its pairs as the lower id
  std::vector<std::uint64_t> ignored_;         // sorted keys (min << 32 | max)
  std::vector<std::uint32_t> ignoredStart_;    // per body and one more: its keys as min (indexFilters)
};

}  // namespace phys
