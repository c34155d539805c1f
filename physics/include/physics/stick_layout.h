#pragma once
// The sticks laid out by body for the relaxation passes (docs/performance.md, "Sticks by body").
// A body's particles are consecutive and its own sticks are consecutive, and no two bodies share
// a particle, so a pass can copy a body's few particles into locals, relax its sticks there in
// their usual order and write them back: no index reaches into the world's arrays and the
// compiler keeps the body in the first level of cache. Gauss-Seidel's result depends only on the
// order of sticks that share a particle, which this keeps, so the result is bit for bit the one of
// the plain loop over World::sticks() in creation order.
//
// Within a body the sticks depend on each other one after the other (each reads what the last
// wrote), so one body at a time is bound by the latency of a square root and a division per
// stick. Bodies of the same shape (the same particles and sticks, as every box of one model) are
// therefore also grouped kStickLanes at a time into lanes, relaxed together with SIMD, one body
// per lane: the same operations in the same order per body, so again the same result.
//
// A chain of loose particles (a rope) is one long run of such sticks, and a pass over it cannot go
// faster than one stick after the other. But a later pass only needs the earlier one to be two
// sticks ahead: pass j + 1 at stick i reads what pass j left at sticks i - 1 to i + 1 and nothing
// beyond, so a chain whose particles nothing else moves in the passes can have all of a substep's
// passes run at once, pass j at stick t - 2j for t = 0, 1, ..., which keeps every stick's inputs and
// so the bits of one pass after the other, with `passes` independent sticks in flight (a wavefront,
// as in temporal blocking). docs/performance.md, "A chain's passes at once".
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "physics/body.h"
#include "physics/constraints.h"

namespace phys {

/// A body whose particles only its own sticks touch: relaxed in locals.
struct StickBlock {
  ParticleId firstParticle{};
  std::uint32_t firstStick = 0;
  std::uint16_t particleCount = 0;
  std::uint16_t stickCount = 0;
};

/// Consecutive sticks, in creation order, relaxed straight in the world's arrays.
struct StickRun {
  std::uint32_t begin = 0, end = 0;
};

/// The fewest sticks of a chain run with all its passes at once: shorter ones are not worth it.
inline constexpr std::uint32_t kMinChainSticks = 8;

/// The most particles a block copies into locals: a corners box's 8.
inline constexpr int kMaxBlockParticles = 8;

/// Bodies relaxed together, one per SIMD lane.
inline constexpr int kStickLanes = 8;

/// A stick of a block, by the positions of its particles in the block.
struct LocalStick {
  std::uint8_t a = 0, b = 0;
};

/// kStickLanes blocks of one shape, relaxed together.
struct StickLanes {
  ParticleId firstParticle[kStickLanes]{};
  std::uint32_t firstStick[kStickLanes]{};
  std::uint16_t particleCount = 0;
  std::uint16_t stickCount = 0;
  std::uint32_t firstLocal = 0;  ///< the shape's sticks in StickLayout::localSticks()
  /// Each stick's bounds and compliance in StickLayout::laneValues(), stick by stick, one value
  /// per lane: so the lanes load them as vectors.
  std::uint32_t firstValue = 0;
};

class StickLayout {
 public:
  /// Every stick relaxed in the world's arrays, in creation order (no blocks).
  static StickLayout inOrder(std::size_t stickCount);
  /// The bodies whose particles no other stick touches become blocks; every other stick (loose
  /// particles' sticks, sticks a scene added between a body's particles and others) goes into
  /// runs, in creation order, but for the chains (chains()). `heldElsewhere`, if not empty, is 1
  /// per particle that some other constraint of the passes moves (a link's end): no chain has it.
  /// Allocates: called when sticks or bodies are added, not in the step.
  void build(std::span<const Stick> sticks, std::span<const Body> boxes, std::size_t particleCount,
             std::span<const std::uint8_t> heldElsewhere = {});

  /// Bodies relaxed one at a time: those of a shape with fewer than kStickLanes bodies left over.
  std::span<const StickBlock> blocks() const { return blocks_; }
  std::span<const StickLanes> lanes() const { return lanes_; }
  std::span<const StickRun> runs() const { return runs_; }
  /// Runs of at least kMinChainSticks sticks, in creation order, that make a whole simple path of
  /// loose particles: each stick shares one particle with the next, the path's two ends are in no
  /// other stick, and no particle of it is in a body or held elsewhere (build). Only sticks and the
  /// ground move their particles in the passes, so their passes can run at once
  /// (detail::relaxChainsAhead). Relaxed after the runs, as runs are, unless marked ahead.
  std::span<const StickRun> chains() const { return chains_; }
  /// Per chain, 1 when this substep's passes over it have all been run at once: the passes skip it.
  /// All 0 until setAhead, and again after clearAhead.
  std::span<const std::uint8_t> ahead() const { return ahead_; }
  std::span<std::uint8_t> setAhead() { return ahead_; }
  void clearAhead() { std::fill(ahead_.begin(), ahead_.end(), std::uint8_t{0}); }
  std::span<const LocalStick> localSticks() const { return localSticks_; }
  /// Per lane group and stick: kStickLanes min lengths, then max lengths, then compliances.
  std::span<const Real> laneValues() const { return laneValues_; }
  /// The particle bodies (indices into build's `boxes`) not laid out as blocks or lanes: their
  /// sticks are in the runs, relaxed in the world's arrays, so keepSpin brackets them around the
  /// whole pass (restoreStickSpin) rather than in the lanes. Empty for inOrder.
  std::span<const std::uint32_t> runBodies() const { return runBodies_; }
  /// Per lane group, 1 when every particle of its lanes has inverse mass 0 in this step (asleep,
  /// pinned or frozen), so that the passes skip it: they would move none of them. Empty unless
  /// markStill was called since the last clearStill.
  std::span<const std::uint8_t> still() const { return still_; }
  void markStill(std::span<const Real> inverseMass);
  void clearStill() { still_.clear(); }

 private:
  void addToRuns(std::uint32_t stick);
  void findChains(std::span<const Stick> sticks, std::span<const std::uint8_t> loose);
  void groupIntoLanes(std::span<const Stick> sticks);

  std::vector<StickBlock> blocks_;
  std::vector<StickLanes> lanes_;
  std::vector<StickRun> runs_;
  std::vector<StickRun> chains_;
  std::vector<std::uint8_t> ahead_;
  std::vector<LocalStick> localSticks_;
  std::vector<Real> laneValues_;
  std::vector<std::uint32_t> runBodies_;
  std::vector<std::uint8_t> still_;
};

}  // namespace phys
