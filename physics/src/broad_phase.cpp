// The broad phase (Stage::BroadPhase): the pairs of bodies whose bounds, grown by how far each
// can go in a step, overlap, found once per step by sweep and prune within strips; and the room the
// narrow phase's arrays keep.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "passes.h"
#include "physics/world.h"

namespace phys {
namespace {

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();
// At most this many strips (a world of boxes spread far apart along t), and a box across more
// than kMaxStripsPerBox of them is tested against every box instead.
constexpr std::size_t kMaxStrips = std::size_t{1} << 16;
constexpr std::size_t kMaxStripsPerBox = 8;
constexpr std::size_t kStripsPerBox = 4;  // at most this many strips a box

// Makes room in v for `room` elements (what the bodies are given), and for twice what was used
// last once that passes two thirds of the room there is, so that a step allocates only when the
// world gathers half as many pairs or contact points again as it ever had (docs/performance.md,
// "No allocation in the step").
template <typename T>
void keepRoom(std::vector<T>& v, std::size_t used, std::size_t room) {
  if (3 * used > 2 * v.capacity()) room = std::max(room, 2 * used);
  if (v.capacity() < room) v.reserve(room);
}

}  // namespace

// Sweep and prune along one axis: the list stays sorted from one step to the next, so
// insertion sort costs about one pass while boxes move little; the sweep then runs within strips
// across a second axis (findPairsInStrips), whose width comes from the boxes' mean size. The
// axis is the one the boxes' centres spread most along (Ericson, "Real-Time Collision Detection",
// 7.5.2): along x, a stack or Bullet's pile of ragdolls (rows 7 m apart in y, each ragdoll 6 m
// wide) overlaps everywhere and the sweep tests nearly every pair. It changes only when another
// axis spreads 1.5 times as much, so it does not flip back and forth. True when it changed.
bool World::chooseSweepAxis() {
  Vec3 sum(0.0), sumSquares(0.0);
  for (const Obb& f : frames_) {
    sum += f.center;
    sumSquares += f.center * f.center;
  }
  const Real n = static_cast<Real>(frames_.size());
  const Vec3 variance = sumSquares / n - (sum / n) * (sum / n);
  int widest = 0;
  for (int k = 1; k < 3; ++k) {
    if (variance[k] > variance[widest]) widest = k;
  }
  if (!(variance[widest] > 1.5 * variance[sweepAxis_])) return false;
  sweepAxis_ = widest;
  return true;
}

// Once per step, for all its substeps: each box's bounds are its AABB grown by how far it can go
// in the step at its speed of the first substep (its fastest particle's speed times dt, and
// gravity's g dt^2, twice what free fall adds); the narrow phase still runs every substep on these
// pairs. A box that goes further within the step (an impact, a joint, a drag gave it speed) makes
// the next substep find them again (World::step, outgrewPairBounds). Found every substep, the
// pairs of Bullet's 136-ragdoll pile (each ragdoll's bounds overlap ~200 others' along any one
// axis) cost a fifth of the step.
void World::findBoxPairs() {
  const Real margin = solver_.featureEpsilon;
  const Real dt = solver_.dt, h = substepDt();
  const Real g = gravityMagnitude();
  for (BoxId id = 0; id < boxes_.size(); ++id) {
    const Box& box = boxes_[id];
    Real fastest = 0.0;  // squared displacement over the last substep
    Vec3 mean(0.0);
    for (int j = 0; j < box.particleCount; ++j) {
      const Vec3 d = particles_.position[box.firstParticle + j] - particles_.previous[box.firstParticle + j];
      fastest = std::max(fastest, glm::dot(d, d));
      mean += d;
    }
    mean /= static_cast<Real>(box.particleCount);
    Real turning = 0.0;  // squared, the most a particle's displacement differs from the mean
    for (int j = 0; j < box.particleCount; ++j) {
      const Vec3 d =
          particles_.position[box.firstParticle + j] - particles_.previous[box.firstParticle + j] - mean;
      turning = std::max(turning, glm::dot(d, d));
    }
    const Real travel = std::sqrt(fastest) / h * dt + g * dt * dt;
    motion_[id] = {mean / h * dt, std::sqrt(turning) / h * dt};
    const Obb& f = frames_[id];
    Vec3 reach(margin + travel);
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) reach[k] += std::abs(f.axes[j][k]) * f.halfExtents[j];
    }
    bounds_[id] = {f.center - reach, f.center + reach};
    travel_[id] = travel;
  }
  const bool newAxis = chooseSweepAxis();
  const int s = sweepAxis_;
  for (Interval& it : sweep_) {
    it.min = bounds_[it.box].lo[s];
    it.max = bounds_[it.box].hi[s];
  }
  if (newAxis) {
    // The order along a new axis is unrelated to the old one's, too far for insertion sort.
    std::sort(sweep_.begin(), sweep_.end(),
              [](const Interval& a, const Interval& b) { return a.min < b.min; });
  }
  for (std::size_t i = 1; i < sweep_.size(); ++i) {
    const Interval moving = sweep_[i];
    std::size_t j = i;
    while (j > 0 && sweep_[j - 1].min > moving.min) {
      sweep_[j] = sweep_[j - 1];
      --j;
    }
    sweep_[j] = moving;
  }
  unsortedPairs_.clear();
  findPairsInStrips();
  sortPairsByBody();
  for (BoxId id = 0; id < boxes_.size(); ++id) pairFrames_[id] = frames_[id];
  pairsStale_ = false;
  // Contact points are made in every substep: their room is checked here, in each step's first
  // substep, from the last substep's count, before any is made.
  reserveContacts();
}

void World::reserveContacts() {
  const std::size_t room = kRoomPerBody * boxes_.size();
  const std::size_t pairs = pairs_.size(), points = bodyContacts_.size();
  keepRoom(pairs_, pairs, room);
  keepRoom(unsortedPairs_, pairs, room);
  keepRoom(partPairs_, pairs, room);
  keepRoom(spareParts_, pairs, room);
  keepRoom(bodyContacts_, points, room);
  keepRoom(spareContacts_, points, room);
  keepRoom(bodyAllowance_, points, room);
  keepRoom(bodyPush_, points, room);
  keepRoom(bodyTouched_, points, room);
  keepRoom(bodyApproach_, points, room);
}

// Whether some box has gone further since the pairs were found than its bounds allowed (an impact
// or a joint gave it speed within the step): its corners moved at most |dc| + sum_k |da_k| h_k.
bool World::outgrewPairBounds() const {
  for (BoxId id = 0; id < boxes_.size(); ++id) {
    const Obb& now = frames_[id];
    const Obb& then = pairFrames_[id];
    Real moved = glm::length(now.center - then.center);
    for (int k = 0; k < 3; ++k) moved += glm::length(now.axes[k] - then.axes[k]) * now.halfExtents[k];
    if (moved > travel_[id]) return true;
  }
  return false;
}

// The pairs whose bounds overlap on all three axes. One sweep along one axis tests every box
// against all those its interval overlaps on that axis, wherever they are on the other two: for
// bodies spread over a floor, about sqrt(N) of them, and the broad phase grew as N^1.5 (a third of
// the step of 1024 ragdolls, `lab scale`). So the boxes are first dealt into strips across a
// second axis, t, each strip twice the boxes' mean extent along t wide, and swept one strip at a
// time: a box meets only the boxes of its own strips. Dealt in sweep order, each strip is already
// sorted. A box in several strips meets a neighbour in each strip they share; the pair is kept in
// the one strip where their overlap along t begins, so each is found once. A box whose bounds
// cross more than kMaxStripsPerBox strips (a floor, or bounds grown by a huge speed) is left out of
// the strips and tested against every box. The pairs found are the same set, in the same sorted
// order, as one sweep finds: the state after a step does not depend on the strips.
void World::findPairsInStrips() {
  const std::size_t n = boxes_.size();
  const int s = sweepAxis_;
  const int other1 = (s + 1) % 3, other2 = (s + 2) % 3;
  Real lo1 = kInfinity, hi1 = -kInfinity, lo2 = kInfinity, hi2 = -kInfinity, extent = 0.0;
  for (const Bounds& b : bounds_) {
    lo1 = std::min(lo1, b.lo[other1]), hi1 = std::max(hi1, b.hi[other1]);
    lo2 = std::min(lo2, b.lo[other2]), hi2 = std::max(hi2, b.hi[other2]);
  }
  // Across the wider of the other two axes; u is the last one.
  const bool firstWider = hi1 - lo1 >= hi2 - lo2;
  const int t = firstWider ? other1 : other2, u = firstWider ? other2 : other1;
  const Real lo = firstWider ? lo1 : lo2, hi = firstWider ? hi1 : hi2;
  for (const Bounds& b : bounds_) extent += b.hi[t] - b.lo[t];
  // How many strips: 1 when the figures are not finite (bounds grown without limit) or all boxes
  // lie in one strip; at most kStripsPerBox a box, wider strips beyond that (boxes spread far
  // apart), so the strips' room is fixed by the number of boxes.
  const std::size_t most = std::min(kMaxStrips, kStripsPerBox * n);
  Real width = 2.0 * extent / static_cast<Real>(n);
  const Real count = (hi - lo) / width;
  std::size_t strips = 1;
  if (count >= static_cast<Real>(most)) {
    strips = most;
    width = (hi - lo) / static_cast<Real>(most);
  } else if (count >= 1.0) {
    strips = static_cast<std::size_t>(count) + 1;
  }
  auto stripOf = [&](Real v) -> std::size_t {
    if (strips == 1) return 0;
    const Real k = (v - lo) / width;
    if (!(k > 0.0)) return 0;  // also NaN
    return k >= static_cast<Real>(strips - 1) ? strips - 1 : static_cast<std::size_t>(k);
  };
  auto wide = [&](BoxId id) {
    return stripOf(bounds_[id].hi[t]) - stripOf(bounds_[id].lo[t]) >= kMaxStripsPerBox;
  };
  auto overlap = [&](const Bounds& a, const Bounds& b, int axis) {
    return a.lo[axis] <= b.hi[axis] && b.lo[axis] <= a.hi[axis];
  };

  // Deal the boxes into the strips, in sweep order: count, then starts, then fill. With room kept
  // as for the contacts (keepRoom), so that the step does not allocate.
  keepRoom(stripStart_, 0, most + 1);
  keepRoom(wideBoxes_, 0, n);
  stripStart_.assign(strips + 1, 0);
  wideBoxes_.clear();
  std::size_t entries = 0;
  for (const Interval& it : sweep_) {
    if (wide(it.box)) {
      wideBoxes_.push_back(it.box);
      continue;
    }
    const std::size_t first = stripOf(bounds_[it.box].lo[t]), last = stripOf(bounds_[it.box].hi[t]);
    for (std::size_t k = first; k <= last; ++k) ++stripStart_[k + 1];
    entries += last - first + 1;
  }
  for (std::size_t k = 0; k < strips; ++k) stripStart_[k + 1] += stripStart_[k];
  keepRoom(stripBoxes_, 0, kMaxStripsPerBox * n);  // what the boxes that are not wide can fill
  stripBoxes_.resize(entries);
  for (const Interval& it : sweep_) {
    if (wide(it.box)) continue;
    const std::size_t first = stripOf(bounds_[it.box].lo[t]), last = stripOf(bounds_[it.box].hi[t]);
    for (std::size_t k = first; k <= last; ++k) stripBoxes_[stripStart_[k]++] = it.box;
  }
  // The fill moved each start to the next strip's: move them back.
  for (std::size_t k = strips; k > 0; --k) stripStart_[k] = stripStart_[k - 1];
  stripStart_[0] = 0;

  for (std::size_t k = 0; k < strips; ++k) {
    const std::size_t end = stripStart_[k + 1];
    for (std::size_t i = stripStart_[k]; i < end; ++i) {
      const BoxId a = stripBoxes_[i];
      const Bounds& ba = bounds_[a];
      for (std::size_t j = i + 1; j < end && bounds_[stripBoxes_[j]].lo[s] <= ba.hi[s]; ++j) {
        const BoxId b = stripBoxes_[j];
        const Bounds& bb = bounds_[b];
        if (!overlap(ba, bb, t) || !overlap(ba, bb, u)) continue;
        if (stripOf(std::max(ba.lo[t], bb.lo[t])) != k) continue;  // kept in another strip
        if (collides(a, b)) unsortedPairs_.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
  }
  for (const BoxId w : wideBoxes_) {
    for (BoxId b = 0; b < n; ++b) {
      if (b == w || (b < w && wide(b))) continue;  // two wide boxes: once, from the lower id
      const Bounds &bw = bounds_[w], &bb = bounds_[b];
      if (overlap(bw, bb, s) && overlap(bw, bb, t) && overlap(bw, bb, u) && collides(w, b)) {
        unsortedPairs_.emplace_back(std::min(w, b), std::max(w, b));
      }
    }
  }
}

// Into body order, not sweep order: the contacts are solved in this order, which then depends on
// the state alone, not on the sweep axis the world's history chose (a saved and reloaded world
// steps as the original). By counting on the lower id, then by insertion on the higher within each
// body's few: linear in the pairs, where a sort of the whole list was N log N in them.
void World::sortPairsByBody() {
  pairStart_.assign(boxes_.size() + 1, 0);
  for (const auto& [a, b] : unsortedPairs_) ++pairStart_[a + 1];
  for (std::size_t k = 0; k < boxes_.size(); ++k) pairStart_[k + 1] += pairStart_[k];
  pairs_.resize(unsortedPairs_.size());
  for (const auto& pair : unsortedPairs_) pairs_[pairStart_[pair.first]++] = pair;
  // Each start has moved to the next body's: body k's pairs end at pairStart_[k].
  std::uint32_t begin = 0;
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    const std::uint32_t end = pairStart_[k];
    for (std::uint32_t i = begin + 1; i < end; ++i) {
      const auto moving = pairs_[i];
      std::uint32_t j = i;
      while (j > begin && pairs_[j - 1].second > moving.second) {
        pairs_[j] = pairs_[j - 1];
        --j;
      }
      pairs_[j] = moving;
    }
    begin = end;
  }
}

}  // namespace phys
