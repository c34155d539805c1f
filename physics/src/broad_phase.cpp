// The broad phase (Stage::BroadPhase): the pairs of bodies whose bounds, grown by how far each
// can go in a step, overlap, found once per step by sweep and prune within strips.
#include "physics/broad_phase.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "room.h"

namespace phys {
namespace {

using detail::keepRoom;
using detail::kRoomPerBody;

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

std::uint64_t pairKey(BodyId a, BodyId b) {
  const BodyId lo = std::min(a, b), hi = std::max(a, b);
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

}  // namespace

void BroadPhase::addBody() {
  const auto id = static_cast<BodyId>(sweep_.size());
  sweep_.push_back({0.0, 0.0, id});
  bounds_.emplace_back();
  travel_.push_back(0.0);
  motion_.emplace_back();
  pairFrames_.emplace_back();
  keptAsleep_.push_back(0);
  stale_ = true;
}

void BroadPhase::ignore(BodyId a, BodyId b) {
  const std::uint64_t key = pairKey(a, b);
  const auto at = std::lower_bound(ignored_.begin(), ignored_.end(), key);
  if (at == ignored_.end() || *at != key) ignored_.insert(at, key);
  stale_ = true;
}

std::vector<BroadPhase::Pair> BroadPhase::ignoredPairs() const {
  std::vector<Pair> out;
  out.reserve(ignored_.size());
  for (const std::uint64_t key : ignored_) {
    out.emplace_back(static_cast<BodyId>(key >> 32), static_cast<BodyId>(key & 0xffffffffu));
  }
  return out;
}

void BroadPhase::indexFilters() {
  const std::size_t n = sweep_.size();
  ignoredStart_.assign(n + 1, 0);
  for (const std::uint64_t key : ignored_) ++ignoredStart_[(key >> 32) + 1];
  for (std::size_t b = 0; b < n; ++b) ignoredStart_[b + 1] += ignoredStart_[b];
}

bool BroadPhase::collides(std::span<const Body> bodies, BodyId a, BodyId b) const {
  const Body& ba = bodies[a];
  const Body& bb = bodies[b];
  if ((ba.collisionGroup & bb.collisionMask) == 0 || (bb.collisionGroup & ba.collisionMask) == 0)
    return false;
  // The keys whose smaller id is `lo` are consecutive (sorted by it): a ragdoll part's few joints,
  // where a search of the whole world's list missed the cache at every step.
  const BodyId lo = std::min(a, b), hi = std::max(a, b);
  for (std::uint32_t k = ignoredStart_[lo]; k < ignoredStart_[lo + 1]; ++k) {
    if (static_cast<BodyId>(ignored_[k]) == hi) return false;
  }
  return true;
}

// Sweep and prune along one axis: the list stays sorted from one step to the next, so
// insertion sort costs about one pass while boxes move little; the sweep then runs within strips
// across a second axis (findPairsInStrips), whose width comes from the boxes' mean size. The
// axis is the one the boxes' centres spread most along (Ericson, "Real-Time Collision Detection",
// 7.5.2): along x, a stack or Bullet's pile of ragdolls (rows 7 m apart in y, each ragdoll 6 m
// wide) overlaps everywhere and the sweep tests nearly every pair. It changes only when another
// axis spreads 1.5 times as much, so it does not flip back and forth. True when it changed.
bool BroadPhase::chooseSweepAxis(std::span<const Obb> frames) {
  Vec3 sum(0.0), sumSquares(0.0);
  for (const Obb& f : frames) {
    sum += f.center;
    sumSquares += f.center * f.center;
  }
  const Real n = static_cast<Real>(frames.size());
  const Vec3 variance = sumSquares / n - (sum / n) * (sum / n);
  int widest = 0;
  for (int k = 1; k < 3; ++k) {
    if (variance[k] > variance[widest]) widest = k;
  }
  if (!(variance[widest] > 1.5 * variance[sweepAxis_])) return false;
  sweepAxis_ = widest;
  return true;
}

// Bodies whose bounds one thread measures at a time: a few microseconds of work.
constexpr std::size_t kBodiesPerPiece = 256;
// Runs of strips each thread sweeps (sweepInPieces).
constexpr std::size_t kSweepPiecesPerThread = 4;

// A body's bounds and motion for the step: its AABB grown by how far it can go in the step at its
// speed of the step's first substep (its fastest particle's speed times dt, and gravity's g dt^2,
// twice what free fall adds).
void BroadPhase::measure(const Particles& particles, const RigidBodies& rigid, const Body& box, const Obb& f,
                         BodyId id, const BroadPhaseStep& step) {
  const Real margin = step.featureEpsilon;
  const Real dt = step.dt, h = step.h;
  const Real g = step.gravity;
  const std::span<const std::uint8_t> asleep = step.asleep;
  pairFrames_[id] = f;
  // A sleeping body's particles and frame do not change, nor do the bounds found from them.
  const bool sleeps = !asleep.empty() && asleep[id] != 0;
  if (sleeps && keptAsleep_[id] != 0) return;
  keptAsleep_[id] = sleeps ? 1 : 0;
  Real fastest = 0.0;  // squared displacement over the last substep
  Vec3 mean(0.0);
  Real turning = 0.0;  // squared, the most a particle's displacement differs from the mean
  if (box.model == BodyModel::Rigid) {
    // A rigid body's centre moves v h, and no point of it turns further than |w| h times the
    // half diagonal.
    mean = rigid.velocity[box.rigid] * h;
    const Real turn = glm::length(rigid.angularVelocity[box.rigid]) * h * glm::length(box.halfExtents);
    turning = turn * turn;
    fastest = (glm::length(mean) + turn) * (glm::length(mean) + turn);
  }
  for (int j = 0; j < box.particleCount; ++j) {
    const Vec3 d = particles.position[box.firstParticle + j] - particles.previous[box.firstParticle + j];
    fastest = std::max(fastest, glm::dot(d, d));
    mean += d;
  }
  if (box.particleCount > 0) mean /= static_cast<Real>(box.particleCount);
  for (int j = 0; j < box.particleCount; ++j) {
    const Vec3 d =
        particles.position[box.firstParticle + j] - particles.previous[box.firstParticle + j] - mean;
    turning = std::max(turning, glm::dot(d, d));
  }
  const Real travel = std::sqrt(fastest) / h * dt + g * dt * dt;
  motion_[id] = {mean / h * dt, std::sqrt(turning) / h * dt};
  Vec3 reach(margin + travel);
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) reach[k] += std::abs(f.axes[j][k]) * f.halfExtents[j];
  }
  bounds_[id] = {f.center - reach, f.center + reach};
  travel_[id] = travel;
}

// Once per step, for all its substeps. A box that goes further within the step than its bounds
// allow (an impact, a joint, a drag gave it speed) makes the next substep find them again
// (needsUpdate). Found every substep, the pairs of Bullet's 136-ragdoll pile (each ragdoll's bounds
// overlap ~200 others' along any one axis) cost a fifth of the step.
void BroadPhase::update(const Particles& particles, const RigidBodies& rigid, std::span<const Body> bodies,
                        std::span<const Obb> frames, const BroadPhaseStep& step) {
  auto range = [&](std::size_t begin, std::size_t end) {
    for (BodyId id(begin); id < end; ++id) measure(particles, rigid, bodies[id], frames[id], id, step);
  };
  stripPairs_.resize(step.workers == nullptr
                         ? 0
                         : kSweepPiecesPerThread * static_cast<std::size_t>(step.workers->threads()) - 1);
  // Each body's bounds are its own: ranges of bodies at once on the step's threads.
  forEachRange(step.workers, bodies.size(), kBodiesPerPiece, range);
  const bool newAxis = chooseSweepAxis(frames);
  const int s = sweepAxis_;
  for (Interval& it : sweep_) {
    it.min = bounds_[it.body].lo[s];
    it.max = bounds_[it.body].hi[s];
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
  findPairsInStrips(bodies, step.strips, step.asleep, step.workers);
  sortPairsByBody();
  stale_ = false;
  const std::size_t room = kRoomPerBody * bodies.size();
  keepRoom(pairs_, pairs_.size(), room);
  keepRoom(unsortedPairs_, pairs_.size(), room);
  for (std::vector<Pair>& piece : stripPairs_) keepRoom(piece, pairs_.size(), room);
}

// A body's corners moved at most |dc| + sum_k |da_k| h_k since the pairs were found. Looked at every
// substep but the first: ranges of bodies at once, each stopping once any range found one.
bool BroadPhase::needsUpdate(std::span<const Obb> frames, std::span<const std::uint8_t> asleep,
                             const Workers* workers) const {
  if (stale_) return true;
  std::atomic<bool> found{false};
  auto range = [&](std::size_t begin, std::size_t end) {
    for (BodyId id(begin); id < end && !found.load(std::memory_order_relaxed); ++id) {
      if (!asleep.empty() && asleep[id] != 0) continue;  // its frame has not moved
      const Obb& now = frames[id];
      const Obb& then = pairFrames_[id];
      Real moved = glm::length(now.center - then.center);
      for (int k = 0; k < 3; ++k) moved += glm::length(now.axes[k] - then.axes[k]) * now.halfExtents[k];
      if (moved > travel_[id]) found.store(true, std::memory_order_relaxed);
    }
  };
  forEachRange(workers, frames.size(), kBodiesPerPiece, range);
  return found.load();
}

// The pairs whose bounds overlap on all three axes. One sweep along one axis tests every box
// against all those its interval overlaps on that axis, wherever they are on the other two: for
// bodies spread over a floor, about sqrt(N) of them, and the broad phase grew as N^1.5 (a third of
// the step of 1024 ragdolls, `lab scale`). So the boxes are first dealt into strips across a
// second axis, t, each strip twice the boxes' mean extent along t wide, and swept one strip at a
// time: a box meets only the boxes of its own strips. Dealt in sweep order, each strip is already
// sorted. A box in several strips meets a neighbour in each strip they share; the pair is kept in
// the one strip where their overlap along t begins, so each is found once. A box whose bounds
// cross more than settings.maxStripsPerBody strips (a floor, or bounds grown by a huge speed) is left out of
// the strips and tested against every box. The pairs found are the same set, in the same sorted
// order, as one sweep finds: the state after a step does not depend on the strips.
void BroadPhase::findPairsInStrips(std::span<const Body> bodies, const BroadPhaseSettings& settings,
                                   std::span<const std::uint8_t> asleep, const Workers* workers) {
  const std::size_t n = bodies.size();
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
  // lie in one strip; at most settings.stripsPerBody a body, wider strips beyond that (boxes spread far
  // apart), so the strips' room is fixed by the number of boxes.
  const std::size_t most = std::min(settings.maxStrips, settings.stripsPerBody * n);
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
  // Each body's strips, found once: the dealing and the sweep read them. stripOf is monotone, so
  // the strip where two bodies' overlap along t begins, stripOf(max(lo)), is the later of their
  // first strips.
  keepRoom(stripsOf_, 0, n);
  stripsOf_.resize(n);
  for (BodyId id{}; id < n; ++id)
    stripsOf_[id] = {static_cast<std::uint32_t>(stripOf(bounds_[id].lo[t])),
                     static_cast<std::uint32_t>(stripOf(bounds_[id].hi[t]))};
  auto wide = [&](BodyId id) {
    return stripsOf_[id].second - stripsOf_[id].first >= settings.maxStripsPerBody;
  };
  auto overlap = [&](const Bounds& a, const Bounds& b, int axis) {
    return a.lo[axis] <= b.hi[axis] && b.lo[axis] <= a.hi[axis];
  };

  // Deal the boxes into the strips, in sweep order: count, then starts, then fill. With room kept
  // as for the contacts (keepRoom), so that the step does not allocate.
  keepRoom(stripStart_, 0, most + 1);
  keepRoom(wideBodies_, 0, n);
  stripStart_.assign(strips + 1, 0);
  wideBodies_.clear();
  std::size_t entries = 0;
  for (const Interval& it : sweep_) {
    if (wide(it.body)) {
      wideBodies_.push_back(it.body);
      continue;
    }
    const auto [first, last] = stripsOf_[it.body];
    for (std::size_t k = first; k <= last; ++k) ++stripStart_[k + 1];
    entries += last - first + 1;
  }
  for (std::size_t k = 0; k < strips; ++k) stripStart_[k + 1] += stripStart_[k];
  keepRoom(stripBodies_, 0, settings.maxStripsPerBody * n);  // what the bodies that are not wide can fill
  keepRoom(stripEntries_, 0, settings.maxStripsPerBody * n);
  stripBodies_.resize(entries);
  stripEntries_.resize(entries);
  for (const Interval& it : sweep_) {
    if (wide(it.body)) continue;
    const auto [first, last] = stripsOf_[it.body];
    const Bounds& b = bounds_[it.body];
    const StripEntry entry{{b.lo[s], b.hi[s]}, {b.lo[t], b.hi[t]}, {b.lo[u], b.hi[u]}, it.body, first};
    for (std::size_t k = first; k <= last; ++k) {
      stripEntries_[stripStart_[k]] = entry;
      stripBodies_[stripStart_[k]++] = it.body;
    }
  }
  // The fill moved each start to the next strip's: move them back.
  for (std::size_t k = strips; k > 0; --k) stripStart_[k] = stripStart_[k - 1];
  stripStart_[0] = 0;

  auto meetInto = [&](std::vector<Pair>& out, std::size_t k, BodyId a, BodyId b) {
    const Bounds &ba = bounds_[a], &bb = bounds_[b];
    if (!overlap(ba, bb, t) || !overlap(ba, bb, u)) return;
    if (std::max(stripsOf_[a].first, stripsOf_[b].first) != k) return;  // kept in another strip
    if (collides(bodies, a, b)) out.emplace_back(std::min(a, b), std::max(a, b));
  };
  auto meet = [&](std::size_t k, BodyId a, BodyId b) { meetInto(unsortedPairs_, k, a, b); };
  if (asleep.empty()) {
    // Over the strips' own copies of the bounds, in sweep order: the nearest entries are the next
    // ones in memory, not bodies scattered through bounds_.
    auto sweepStrips = [&](std::size_t first, std::size_t last, std::vector<Pair>& out) {
      const StripEntry* e = stripEntries_.data();
      for (std::size_t k = first; k < last; ++k) {
        const std::size_t end = stripStart_[k + 1];
        for (std::size_t i = stripStart_[k]; i < end; ++i) {
          const StripEntry& a = e[i];
          for (std::size_t j = i + 1; j < end && e[j].s[0] <= a.s[1]; ++j) {
            const StripEntry& b = e[j];
            if (!(a.t[0] <= b.t[1] && b.t[0] <= a.t[1] && a.u[0] <= b.u[1] && b.u[0] <= a.u[1])) continue;
            if (std::max(a.firstStrip, b.firstStrip) != k) continue;  // kept in another strip
            if (collides(bodies, a.body, b.body))
              out.emplace_back(std::min(a.body, b.body), std::max(a.body, b.body));
          }
        }
      }
    };
    sweepInPieces(strips, entries, workers, sweepStrips);
  } else {
    // Only the pairs with an awake body: each awake body sweeps forward as above, and back over
    // the sleeping bodies before it while one of them can still reach it (the furthest reach of
    // the sleeping bodies up to each entry, kept per strip), so a sleeping pile costs the awake
    // bodies' neighbours alone.
    keepRoom(sleepingReach_, 0, settings.maxStripsPerBody * n);
    sleepingReach_.resize(entries);
    for (std::size_t k = 0; k < strips; ++k) {
      Real reach = -kInfinity;
      for (std::size_t i = stripStart_[k]; i < stripStart_[k + 1]; ++i) {
        const BodyId b = stripBodies_[i];
        if (asleep[b] != 0) reach = std::max(reach, bounds_[b].hi[s]);
        sleepingReach_[i] = reach;
      }
    }
    for (std::size_t k = 0; k < strips; ++k) {
      const std::size_t begin = stripStart_[k], end = stripStart_[k + 1];
      for (std::size_t i = begin; i < end; ++i) {
        const BodyId a = stripBodies_[i];
        if (asleep[a] != 0) continue;
        const Bounds& ba = bounds_[a];
        for (std::size_t j = i + 1; j < end && bounds_[stripBodies_[j]].lo[s] <= ba.hi[s]; ++j)
          meet(k, a, stripBodies_[j]);
        for (std::size_t j = i; j > begin && sleepingReach_[j - 1] >= ba.lo[s]; --j) {
          const BodyId b = stripBodies_[j - 1];
          if (asleep[b] != 0 && bounds_[b].hi[s] >= ba.lo[s]) meet(k, a, b);
        }
      }
    }
  }
  for (const BodyId w : wideBodies_) {
    for (BodyId b{}; b < n; ++b) {
      if (b == w || (b < w && wide(b))) continue;  // two wide boxes: once, from the lower id
      if (!asleep.empty() && asleep[w] != 0 && asleep[b] != 0) continue;
      const Bounds &bw = bounds_[w], &bb = bounds_[b];
      if (overlap(bw, bb, s) && overlap(bw, bb, t) && overlap(bw, bb, u) && collides(bodies, w, b)) {
        unsortedPairs_.emplace_back(std::min(w, b), std::max(w, b));
      }
    }
  }
}

// Strip entries one thread sweeps at a time.
constexpr std::size_t kEntriesPerPiece = 256;

// sweep(first, last, out) over the strips: on the step's threads in runs of strips,
// kSweepPiecesPerThread a thread, cut where the strips' entries are shared evenly (an entry's
// candidates are as many as the bodies near it, so runs of equal entries are not equal work: a thread
// done first takes another), each into pairs of its own, then appended. The
// strips share nothing, and sortPairsByBody puts the pairs (each found once) into one order
// whatever the order they come in, so the pairs are the same on any number of threads.
template <class Sweep>
void BroadPhase::sweepInPieces(std::size_t strips, std::size_t entries, const Workers* workers,
                               Sweep&& sweep) {
  const std::size_t pieces =
      workers == nullptr ? 1 : std::min({stripPairs_.size() + 1, strips, entries / kEntriesPerPiece});
  if (pieces <= 1) {
    sweep(0, strips, unsortedPairs_);
    return;
  }
  // Where piece p starts: the first strip whose entries start at or after its even share.
  auto start = [&](std::size_t p) -> std::size_t {
    if (p == pieces) return strips;
    return static_cast<std::size_t>(
        std::lower_bound(stripStart_.begin(), stripStart_.begin() + static_cast<std::ptrdiff_t>(strips),
                         entries * p / pieces) -
        stripStart_.begin());
  };
  auto range = [&](std::size_t first, std::size_t last) {
    for (std::size_t p = first; p < last; ++p) {
      std::vector<Pair>& out = p == 0 ? unsortedPairs_ : stripPairs_[p - 1];
      if (p > 0) out.clear();
      sweep(start(p), start(p + 1), out);
    }
  };
  workers->forEach(pieces, 1, range);
  for (std::size_t p = 1; p < pieces; ++p)
    unsortedPairs_.insert(unsortedPairs_.end(), stripPairs_[p - 1].begin(), stripPairs_[p - 1].end());
}

// Into body order, not sweep order: the contacts are solved in this order, which then depends on
// the state alone, not on the sweep axis the world's history chose (a saved and reloaded world
// steps as the original). By counting on the lower id, then by insertion on the higher within each
// body's few: linear in the pairs, where a sort of the whole list was N log N in them.
void BroadPhase::sortPairsByBody() {
  const std::size_t n = sweep_.size();
  pairStart_.assign(n + 1, 0);
  for (const auto& [a, b] : unsortedPairs_) ++pairStart_[a + 1];
  for (std::size_t k = 0; k < n; ++k) pairStart_[k + 1] += pairStart_[k];
  pairs_.resize(unsortedPairs_.size());
  for (const auto& pair : unsortedPairs_) pairs_[pairStart_[pair.first]++] = pair;
  // Each start has moved to the next body's: body k's pairs end at pairStart_[k].
  std::uint32_t begin = 0;
  for (std::size_t k = 0; k < n; ++k) {
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
