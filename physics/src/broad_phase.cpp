// The broad phase (Stage::BroadPhase): the pairs of bodies whose bounds, grown by how far each
// can go in a step, overlap, found once per step from a dynamic tree of bounds enlarged further.
#include "physics/broad_phase.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "room.h"

namespace phys {
namespace {

using detail::keepRoom;
using detail::kRoomPerBody;

std::uint64_t pairKey(BodyId a, BodyId b) {
  const BodyId lo = std::min(a, b), hi = std::max(a, b);
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

}  // namespace

void BroadPhase::addBody() {
  leaf_.push_back(AabbTree::kNone);
  isMoved_.push_back(0);
  bounds_.emplace_back();
  travel_.push_back(0.0);
  motion_.emplace_back();
  pairFrames_.emplace_back();
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
  const std::size_t n = leaf_.size();
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

// Once per step, for all its substeps: each body's bounds are its AABB grown by how far it can go
// in the step at its speed of the first substep (its fastest particle's speed times dt, and
// gravity's g dt^2, twice what free fall adds). A body that goes further within the step (an
// impact, a joint, a drag gave it speed) makes the next substep find them again (needsUpdate).
// Found every substep, the pairs of Bullet's 136-ragdoll pile (each ragdoll's bounds overlap ~200
// others' along any one axis) cost a fifth of the step.
void BroadPhase::update(const Particles& particles, std::span<const Body> bodies, std::span<const Obb> frames,
                        const BroadPhaseStep& step) {
  measureBounds(particles, bodies, frames, step);
  moveEscapedBodies(step.settings.margin);
  updateCandidates(bodies);
  pairs_.clear();
  for (const Pair& pair : candidates_) {
    if (overlaps(bounds_[pair.first], bounds_[pair.second])) pairs_.push_back(pair);
  }
  for (BodyId id{}; id < bodies.size(); ++id) pairFrames_[id] = frames[id];
  stale_ = false;
}

void BroadPhase::measureBounds(const Particles& particles, std::span<const Body> bodies,
                               std::span<const Obb> frames, const BroadPhaseStep& step) {
  const Real margin = step.featureEpsilon;
  const Real dt = step.dt, h = step.h;
  const Real g = step.gravity;
  for (BodyId id{}; id < bodies.size(); ++id) {
    const Body& box = bodies[id];
    Real fastest = 0.0;  // squared displacement over the last substep
    Vec3 mean(0.0);
    for (int j = 0; j < box.particleCount; ++j) {
      const Vec3 d = particles.position[box.firstParticle + j] - particles.previous[box.firstParticle + j];
      fastest = std::max(fastest, glm::dot(d, d));
      mean += d;
    }
    mean /= static_cast<Real>(box.particleCount);
    Real turning = 0.0;  // squared, the most a particle's displacement differs from the mean
    for (int j = 0; j < box.particleCount; ++j) {
      const Vec3 d =
          particles.position[box.firstParticle + j] - particles.previous[box.firstParticle + j] - mean;
      turning = std::max(turning, glm::dot(d, d));
    }
    const Real travel = std::sqrt(fastest) / h * dt + g * dt * dt;
    motion_[id] = {mean / h * dt, std::sqrt(turning) / h * dt};
    const Obb& f = frames[id];
    Vec3 reach(margin + travel);
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) reach[k] += std::abs(f.axes[j][k]) * f.halfExtents[j];
    }
    bounds_[id] = {f.center - reach, f.center + reach};
    travel_[id] = travel;
  }
}

// A body whose bounds of this step still lie within its enlarged bounds in the tree stays where it
// is; one that left them gets new ones, its bounds grown by the margin all round, and is put back
// into the tree. Stale pairs (bodies added, filters changed) put every body back.
void BroadPhase::moveEscapedBodies(Real margin) {
  const std::size_t n = bounds_.size();
  // Ahead of a moving body by 4 steps of its motion, as Box2D's tree enlarges by its displacement:
  // a falling body then moves in the tree every few steps, not every step.
  constexpr Real kStepsAhead = 4.0;
  auto enlarged = [&](BodyId id) {
    const Vec3 ahead = kStepsAhead * motion_[id].shift;
    return Aabb{bounds_[id].lo - Vec3(margin) + glm::min(ahead, Vec3(0.0)),
                bounds_[id].hi + Vec3(margin) + glm::max(ahead, Vec3(0.0))};
  };
  moved_.clear();
  if (stale_ || tree_.leafCount() != n) {
    if (moved_.capacity() < n) moved_.reserve(n);
    tree_.clear();
    tree_.reserve(n);
    for (BodyId id{}; id < n; ++id) {
      leaf_[id] = tree_.insert(enlarged(id), id);
      moved_.push_back(id);
    }
  } else {
    // Bounds enlarged ahead of a fall stay that large once the body has landed, and meet many
    // more neighbours than the body's own: put back when 4 margins too loose, summed over axes.
    constexpr Real kLooseMargins = 4.0;
    for (BodyId id{}; id < n; ++id) {
      const Aabb& fat = tree_.box(leaf_[id]);
      if (contains(fat, bounds_[id])) {
        const Aabb want = enlarged(id);
        const Vec3 loose = (fat.hi - fat.lo) - (want.hi - want.lo);
        if (loose.x + loose.y + loose.z <= kLooseMargins * margin) continue;
      }
      tree_.move(leaf_[id], enlarged(id));
      moved_.push_back(id);
    }
  }
}

// The candidates are every pair whose enlarged bounds overlap. Between two bodies that did not
// move the answer is the one of the last update; each moved body asks the tree for its own. A
// pair of two moved bodies is found by both: kept from the lower id's query.
void BroadPhase::updateCandidates(std::span<const Body> bodies) {
  const std::size_t n = bodies.size();
  if (moved_.empty()) return;
  std::fill(isMoved_.begin(), isMoved_.end(), 0);
  for (const BodyId id : moved_) isMoved_[id] = 1;
  unsortedPairs_.clear();
  for (const Pair& pair : candidates_) {
    if (!isMoved_[pair.first] && !isMoved_[pair.second]) unsortedPairs_.push_back(pair);
  }
  for (const BodyId m : moved_) {
    tree_.query(tree_.box(leaf_[m]), [&](BodyId other) {
      if (other == m || (isMoved_[other] && other < m)) return;
      if (collides(bodies, m, other)) unsortedPairs_.emplace_back(std::min(m, other), std::max(m, other));
    });
  }
  sortByBody(unsortedPairs_, candidates_);
  const std::size_t room = kRoomPerBody * n;
  keepRoom(candidates_, candidates_.size(), room);
  keepRoom(unsortedPairs_, candidates_.size(), room);
  keepRoom(pairs_, candidates_.size(), room);
}

// A body's corners moved at most |dc| + sum_k |da_k| h_k since the pairs were found.
bool BroadPhase::needsUpdate(std::span<const Obb> frames) const {
  if (stale_) return true;
  for (BodyId id{}; id < frames.size(); ++id) {
    const Obb& now = frames[id];
    const Obb& then = pairFrames_[id];
    Real moved = glm::length(now.center - then.center);
    for (int k = 0; k < 3; ++k) moved += glm::length(now.axes[k] - then.axes[k]) * now.halfExtents[k];
    if (moved > travel_[id]) return true;
  }
  return false;
}

// Into body order, not the order the tree gives them: the contacts are solved in this order, which
// then depends on the state alone, not on the tree's shape that the world's history made (a saved
// and reloaded world steps as the original). By counting on the lower id, then by insertion on the
// higher within each body's few: linear in the pairs, where a sort of the whole list was N log N.
void BroadPhase::sortByBody(std::vector<Pair>& from, std::vector<Pair>& to) {
  const std::size_t n = leaf_.size();
  pairStart_.assign(n + 1, 0);
  for (const auto& [a, b] : from) ++pairStart_[a + 1];
  for (std::size_t k = 0; k < n; ++k) pairStart_[k + 1] += pairStart_[k];
  to.resize(from.size());
  for (const auto& pair : from) to[pairStart_[pair.first]++] = pair;
  // Each start has moved to the next body's: body k's pairs end at pairStart_[k].
  std::uint32_t begin = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t end = pairStart_[k];
    for (std::uint32_t i = begin + 1; i < end; ++i) {
      const auto moving = to[i];
      std::uint32_t j = i;
      while (j > begin && to[j - 1].second > moving.second) {
        to[j] = to[j - 1];
        --j;
      }
      to[j] = moving;
    }
    begin = end;
  }
}

}  // namespace phys
