#include "physics/contact_bins.h"

#include <algorithm>
#include <numeric>

#include "room.h"

namespace phys {

std::uint32_t ContactBins::root(std::uint32_t body) {
  while (parent_[body] != body) {
    parent_[body] = parent_[parent_[body]];  // halving the path keeps the trees flat
    body = parent_[body];
  }
  return body;
}

void ContactBins::append(std::vector<Range>& ranges, std::uint32_t begin, std::uint32_t count) {
  if (!ranges.empty() && ranges.back().end == begin) {
    ranges.back().end += count;
    return;
  }
  ranges.push_back({begin, begin + count});
}

void ContactBins::indexGround(std::span<const GroundContact> ground) {
  owners_.clear();
  for (std::uint32_t k = 0; k < ground.size(); ++k) {
    const GroundContact& g = ground[k];
    // A body's points are consecutive; a loose particle has one.
    if (g.body != kNoBody && !owners_.empty() && owners_.back().body == g.body && owners_.back().end == k)
      ++owners_.back().end;
    else
      owners_.push_back({g.body, k, k + 1});
  }
  indexedGround_ = ground.size();
}

bool ContactBins::deal(std::span<const Manifold> manifolds, std::span<const GroundContact> ground,
                       std::size_t bodies) {
  parent_.resize(bodies);
  work_.assign(bodies, 0);
  bin_.resize(bodies);
  std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
  for (const Manifold& m : manifolds) {
    const std::uint32_t a = root(m.a), b = root(m.b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }
  for (const Manifold& m : manifolds) work_[root(m.a)] += m.contactCount;
  if (ground.size() != indexedGround_) indexGround(ground);
  for (const Owner& o : owners_) {
    if (o.body != kNoBody) work_[root(o.body)] += o.end - o.begin;
  }
  // The groups in the order of their first bodies to the first bin until it holds half the work,
  // then to the second, so that each bin's bodies lie mostly together in the particle arrays: bins
  // taking the groups in turn wrote to the same cache lines from two cores at once, and were
  // slower than one thread. A loose particle's point (its own owner) goes to the bin with less.
  std::uint32_t total = 0;
  for (std::uint32_t body = 0; body < bodies; ++body) total += work_[body];
  std::uint32_t binWork[2] = {0, 0};
  for (std::uint32_t body = 0; body < bodies; ++body) {
    const std::uint32_t r = root(body);
    if (r == body) {
      bin_[body] = 2 * binWork[0] < total ? 0 : 1;
      binWork[bin_[body]] += work_[body];
    } else {
      bin_[body] = bin_[r];  // r < body: its bin is set
    }
  }
  for (std::vector<Range>& ranges : groundRanges_) {
    detail::keepRoom(ranges, ranges.size(), ground.size());
    ranges.clear();
  }
  for (const Owner& o : owners_) {
    int bin = 0;
    if (o.body != kNoBody) {
      bin = bin_[o.body];
    } else {
      bin = binWork[1] < binWork[0] ? 1 : 0;
      ++binWork[bin];
    }
    append(groundRanges_[bin], o.begin, o.end - o.begin);
  }
  total = binWork[0] + binWork[1];
  dealt_ = total > 0 && static_cast<Real>(std::max(binWork[0], binWork[1])) <= kMostBinShare * total;
  rangeContacts(manifolds);
  return dealt_;
}

void ContactBins::rangeContacts(std::span<const Manifold> manifolds) {
  // Each manifold adds at most one range: room for them all, kept as the narrow phase keeps its
  // own (room.h), so that a count of manifolds creeping up does not allocate in every step.
  const std::size_t room = detail::kRoomPerBody * bin_.size();
  for (std::vector<Range>& ranges : contactRanges_) {
    detail::keepRoom(ranges, manifolds.size(), room);
    ranges.clear();
  }
  if (!dealt_) return;
  for (const Manifold& m : manifolds) {
    if (m.rigid || m.contactCount == 0) continue;  // a rigid pair's points are in another list
    append(contactRanges_[bin_[m.a]], m.firstContact, m.contactCount);
  }
}

}  // namespace phys
