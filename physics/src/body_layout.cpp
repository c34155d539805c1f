#include "physics/body_layout.h"

#include <algorithm>
#include <map>

#include "physics/stick_layout.h"
#include "still_groups.h"

namespace phys {

void BodyLayout::markStill(std::span<const Real> inverseMass) {
  detail::markStillGroups(std::span<const BodyLanes>(lanes_), inverseMass, still_);
}

void BodyLayout::build(std::span<const Body> boxes) {
  lanes_.clear();
  others_.clear();
  std::map<int, std::vector<BodyId>> waiting;  // by particle count
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    const Body& box = boxes[b];
    if (box.model == BodyModel::Rigid) continue;  // no particles to damp
    std::vector<BodyId>& alike = waiting[box.particleCount];
    if (box.particleCount > kMaxBlockParticles) {
      others_.push_back(static_cast<BodyId>(b));
      continue;
    }
    alike.push_back(static_cast<BodyId>(b));
    if (alike.size() < kBodyLanes) continue;
    BodyLanes lanes;
    lanes.particleCount = static_cast<std::uint16_t>(box.particleCount);
    for (int l = 0; l < kBodyLanes; ++l) lanes.firstParticle[l] = boxes[alike[l]].firstParticle;
    lanes_.push_back(lanes);
    alike.clear();
  }
  for (const auto& [count, alike] : waiting) others_.insert(others_.end(), alike.begin(), alike.end());
  std::sort(others_.begin(), others_.end());
  still_.clear();
  still_.reserve(lanes_.size());
}

}  // namespace phys
