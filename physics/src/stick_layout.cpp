#include "physics/stick_layout.h"

#include <algorithm>
#include <map>

#include "still_groups.h"

namespace phys {

void StickLayout::markStill(std::span<const Real> inverseMass) {
  detail::markStillGroups(std::span<const StickLanes>(lanes_), inverseMass, still_);
}

StickLayout StickLayout::inOrder(std::size_t stickCount) {
  StickLayout layout;
  if (stickCount > 0) layout.runs_.push_back({0, static_cast<std::uint32_t>(stickCount)});
  return layout;
}

void StickLayout::addToRuns(std::uint32_t stick) {
  if (!runs_.empty() && runs_.back().end == stick) {
    ++runs_.back().end;
  } else {
    runs_.push_back({stick, stick + 1});
  }
}

void StickLayout::build(std::span<const Stick> sticks, std::span<const Body> boxes, std::size_t particleCount,
                        std::span<const std::uint8_t> heldElsewhere) {
  constexpr std::int32_t kNone = -1;
  std::vector<std::int32_t> particleOwner(particleCount, kNone), stickOwner(sticks.size(), kNone);
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    const Body& box = boxes[b];
    for (int i = 0; i < box.particleCount; ++i)
      particleOwner[box.firstParticle + i] = static_cast<std::int32_t>(b);
    for (int k = 0; k < box.stickCount; ++k) stickOwner[box.firstStick + k] = static_cast<std::int32_t>(b);
  }
  // A body stays a block when every stick at its particles is its own, and its own join only its
  // particles (true of every body addBody makes; checked, so that the layout never relies on it).
  std::vector<std::uint8_t> isolated(boxes.size(), 1);
  for (std::size_t k = 0; k < sticks.size(); ++k) {
    const std::int32_t owner = stickOwner[k];
    for (const ParticleId end : {sticks[k].a, sticks[k].b}) {
      const std::int32_t body = particleOwner[end];
      if (owner != body) {
        if (body != kNone) isolated[static_cast<std::size_t>(body)] = 0;
        if (owner != kNone) isolated[static_cast<std::size_t>(owner)] = 0;
      }
    }
  }
  blocks_.clear();
  runs_.clear();
  runBodies_.clear();
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    const Body& box = boxes[b];
    if (box.model == BodyModel::Rigid) continue;  // no particles, no sticks
    if (isolated[b] && box.particleCount <= kMaxBlockParticles) {
      blocks_.push_back({box.firstParticle, box.firstStick, static_cast<std::uint16_t>(box.particleCount),
                         static_cast<std::uint16_t>(box.stickCount)});
    } else {
      for (int k = 0; k < box.stickCount; ++k) stickOwner[box.firstStick + k] = kNone;
      runBodies_.push_back(static_cast<std::uint32_t>(b));
    }
  }
  for (std::size_t k = 0; k < sticks.size(); ++k) {
    if (stickOwner[k] == kNone) addToRuns(static_cast<std::uint32_t>(k));
  }
  std::vector<std::uint8_t> loose(particleCount, 0);
  for (std::size_t i = 0; i < particleCount; ++i)
    loose[i] = particleOwner[i] == kNone && (heldElsewhere.empty() || heldElsewhere[i] == 0) ? 1 : 0;
  findChains(sticks, loose);
  groupIntoLanes(sticks);
  still_.clear();
  still_.reserve(lanes_.size());
}

// Takes the chains out of the runs (chains()): a chain starts at a stick with an end in no other
// stick and follows, stick by stick in creation order, the particle it shares with the next, as
// long as that particle is in exactly these two sticks, until it reaches the path's other end. So
// no stick outside the chain touches it, and it cannot close on itself.
void StickLayout::findChains(std::span<const Stick> sticks, std::span<const std::uint8_t> loose) {
  chains_.clear();
  std::vector<std::uint8_t> degree(loose.size(), 0);  // sticks at each particle, counted to 3
  for (const Stick& s : sticks) {
    for (const ParticleId end : {s.a, s.b})
      degree[end] = static_cast<std::uint8_t>(std::min(degree[end] + 1, 3));
  }
  auto usable = [&](const Stick& s) {
    return s.a != s.b && loose[s.a] != 0 && loose[s.b] != 0 && degree[s.a] <= 2 && degree[s.b] <= 2;
  };
  // The end of the whole chain that starts at stick k, within [k, limit); k when none does.
  auto chainFrom = [&](std::uint32_t k, std::uint32_t limit) {
    const Stick& first = sticks[k];
    if (!usable(first)) return k;
    ParticleId forward{};
    if (degree[first.a] == 1) {
      forward = first.b;
    } else if (degree[first.b] == 1) {
      forward = first.a;
    } else {
      return k;
    }
    std::uint32_t j = k + 1;
    for (; degree[forward] == 2; ++j) {
      if (j == limit || !usable(sticks[j])) return k;
      if (sticks[j].a == forward) {
        forward = sticks[j].b;
      } else if (sticks[j].b == forward) {
        forward = sticks[j].a;
      } else {
        return k;
      }
    }
    return j;
  };
  std::vector<StickRun> left;  // the runs without their chains
  auto keep = [&](std::uint32_t begin, std::uint32_t end) {
    if (begin < end) left.push_back({begin, end});
  };
  for (const StickRun& run : runs_) {
    std::uint32_t kept = run.begin;  // the first stick not yet placed
    for (std::uint32_t k = run.begin; k < run.end;) {
      const std::uint32_t end = chainFrom(k, run.end);
      if (end - k >= kMinChainSticks) {
        keep(kept, k);
        chains_.push_back({k, end});
        k = kept = end;
      } else {
        ++k;
      }
    }
    keep(kept, run.end);
  }
  runs_ = std::move(left);
  ahead_.assign(chains_.size(), 0);
}

// Blocks of one shape (particle count and local sticks), kStickLanes at a time, in body order;
// what is left of each shape stays a block.
void StickLayout::groupIntoLanes(std::span<const Stick> sticks) {
  lanes_.clear();
  localSticks_.clear();
  laneValues_.clear();
  // Keyed by the shape: particle count, then each stick's two local particles. 16-bit elements,
  // not bytes: GCC 12 warns wrongly about the memcmp that byte vectors compare with.
  using ShapeKey = std::vector<std::uint16_t>;
  std::map<ShapeKey, std::vector<StickBlock>> waiting;
  std::map<ShapeKey, std::uint32_t> shapeStart;  // the shape's first LocalStick
  ShapeKey shape;
  for (const StickBlock& block : blocks_) {
    shape.assign(1, block.particleCount);
    for (std::uint32_t k = block.firstStick; k < block.firstStick + block.stickCount; ++k) {
      shape.push_back(static_cast<std::uint16_t>(sticks[k].a - block.firstParticle));
      shape.push_back(static_cast<std::uint16_t>(sticks[k].b - block.firstParticle));
    }
    std::vector<StickBlock>& group = waiting[shape];
    group.push_back(block);
    if (group.size() < kStickLanes) continue;

    auto [start, isNew] = shapeStart.try_emplace(shape, static_cast<std::uint32_t>(localSticks_.size()));
    if (isNew) {
      for (std::size_t j = 1; j < shape.size(); j += 2) {
        localSticks_.push_back(
            {static_cast<std::uint8_t>(shape[j]), static_cast<std::uint8_t>(shape[j + 1])});
      }
    }
    StickLanes lanes;
    lanes.particleCount = block.particleCount;
    lanes.stickCount = block.stickCount;
    lanes.firstLocal = start->second;
    lanes.firstValue = static_cast<std::uint32_t>(laneValues_.size());
    for (int l = 0; l < kStickLanes; ++l) {
      lanes.firstParticle[l] = group[l].firstParticle;
      lanes.firstStick[l] = group[l].firstStick;
    }
    for (std::uint32_t k = 0; k < block.stickCount; ++k) {
      for (int l = 0; l < kStickLanes; ++l) laneValues_.push_back(sticks[group[l].firstStick + k].minLength);
      for (int l = 0; l < kStickLanes; ++l) laneValues_.push_back(sticks[group[l].firstStick + k].maxLength);
      for (int l = 0; l < kStickLanes; ++l) laneValues_.push_back(sticks[group[l].firstStick + k].compliance);
    }
    lanes_.push_back(lanes);
    group.clear();
  }
  blocks_.clear();
  for (const auto& [key, group] : waiting) blocks_.insert(blocks_.end(), group.begin(), group.end());
}

}  // namespace phys
