#include "physics/link_layout.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <numeric>

#include "still_groups.h"

namespace phys {

void LinkLayout::markStill(std::span<const Real> inverseMass) {
  detail::markStillGroups(std::span<const LinkLanes>(lanes_), inverseMass, still_);
}

namespace {

ParticleId findRoot(std::vector<ParticleId>& parent, ParticleId i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// A group of links joined through their particles.
struct Group {
  ParticleId lo{}, hi{};             // the range its particles span
  std::vector<std::uint32_t> links;  // in creation order
};

}  // namespace

void LinkLayout::build(std::span<const Link> links, std::size_t particleCount) {
  lanes_.clear();
  localLinks_.clear();
  laneValues_.clear();
  laneLinks_.clear();
  others_.clear();

  std::vector<ParticleId> parent(particleCount);
  std::iota(parent.begin(), parent.end(), ParticleId{0});
  std::vector<std::uint8_t> inLink(particleCount, 0);
  for (const Link& link : links) {
    const ParticleId first = findRoot(parent, link.a.particle[0]);
    for (const Embedding* e : {&link.a, &link.b}) {
      for (int i = 0; i < e->count; ++i) {
        inLink[e->particle[i]] = 1;
        parent[findRoot(parent, e->particle[i])] = findRoot(parent, first);
      }
    }
  }

  // The groups in the order of their first link, so the layout is the same run after run.
  std::vector<Group> groups;
  std::map<ParticleId, std::size_t> groupOf;  // root -> index in groups
  for (std::uint32_t k = 0; k < links.size(); ++k) {
    const ParticleId root = findRoot(parent, links[k].a.particle[0]);
    auto [at, isNew] = groupOf.try_emplace(root, groups.size());
    if (isNew) groups.push_back({links[k].a.particle[0], links[k].a.particle[0], {}});
    Group& group = groups[at->second];
    group.links.push_back(k);
    for (const Embedding* e : {&links[k].a, &links[k].b}) {
      for (int i = 0; i < e->count; ++i) {
        group.lo = std::min(group.lo, e->particle[i]);
        group.hi = std::max(group.hi, e->particle[i]);
      }
    }
  }

  // Keyed by the group's shape: its span, then each link's local particles and kind.
  using ShapeKey = std::vector<std::uint16_t>;
  std::map<ShapeKey, std::vector<const Group*>> waiting;
  std::map<ShapeKey, std::uint32_t> shapeStart;  // the shape's first LocalLink
  ShapeKey shape;
  for (const Group& group : groups) {
    bool own = group.hi - group.lo < kMaxLinkGroupParticles && group.links.size() <= UINT16_MAX;
    for (ParticleId i = group.lo; own && i <= group.hi; ++i) {
      // A particle of another group inside the range: a store of the range would overwrite it.
      own = !inLink[i] || findRoot(parent, i) == findRoot(parent, group.lo);
    }
    if (!own) {
      others_.insert(others_.end(), group.links.begin(), group.links.end());
      continue;
    }
    shape.assign(1, static_cast<std::uint16_t>(group.hi - group.lo + 1));
    for (const std::uint32_t k : group.links) {
      for (const Embedding* e : {&links[k].a, &links[k].b}) {
        shape.push_back(static_cast<std::uint16_t>(e->count));
        for (int i = 0; i < e->count; ++i)
          shape.push_back(static_cast<std::uint16_t>(e->particle[i] - group.lo));
      }
      shape.push_back(links[k].isPin() ? 1 : 0);
    }
    std::vector<const Group*>& alike = waiting[shape];
    alike.push_back(&group);
    if (alike.size() < kLinkLanes) continue;

    auto [start, isNew] = shapeStart.try_emplace(shape, static_cast<std::uint32_t>(localLinks_.size()));
    if (isNew) {
      for (const std::uint32_t k : group.links) {
        LocalLink local;
        local.countA = static_cast<std::uint8_t>(links[k].a.count);
        local.countB = static_cast<std::uint8_t>(links[k].b.count);
        for (int i = 0; i < local.countA; ++i)
          local.a[i] = static_cast<std::uint8_t>(links[k].a.particle[i] - group.lo);
        for (int i = 0; i < local.countB; ++i)
          local.b[i] = static_cast<std::uint8_t>(links[k].b.particle[i] - group.lo);
        local.pin = links[k].isPin();
        localLinks_.push_back(local);
      }
    }
    LinkLanes lanes;
    lanes.particleCount = static_cast<std::uint16_t>(group.hi - group.lo + 1);
    lanes.linkCount = static_cast<std::uint16_t>(group.links.size());
    lanes.firstLocal = start->second;
    lanes.firstValue = static_cast<std::uint32_t>(laneValues_.size());
    for (int l = 0; l < kLinkLanes; ++l) {
      lanes.firstParticle[l] = alike[l]->lo;
      lanes.links[l] = static_cast<std::uint32_t>(laneLinks_.size());
      laneLinks_.insert(laneLinks_.end(), alike[l]->links.begin(), alike[l]->links.end());
    }
    for (std::size_t j = 0; j < group.links.size(); ++j) {
      for (int row = 0; row < kLinkValues; ++row) {
        for (int l = 0; l < kLinkLanes; ++l) {
          const Link& link = links[alike[l]->links[j]];
          const Real value = row < 4    ? (row < link.a.count ? link.a.weight[row] : 0.0)
                             : row < 8  ? (row - 4 < link.b.count ? link.b.weight[row - 4] : 0.0)
                             : row == 8 ? link.minLength
                                        : link.maxLength;
          laneValues_.push_back(value);
        }
      }
    }
    lanes_.push_back(lanes);
    alike.clear();
  }
  for (const auto& [key, alike] : waiting) {
    for (const Group* group : alike) others_.insert(others_.end(), group->links.begin(), group->links.end());
  }
  std::sort(others_.begin(), others_.end());
  still_.clear();
  still_.reserve(lanes_.size());
}

}  // namespace phys
