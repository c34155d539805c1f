#pragma once
// The links laid out by joined group for the relaxation passes (docs/performance.md, "Links by
// ragdoll"): the links of a ragdoll join only its own parts, whose particles are consecutive, and
// no link joins two ragdolls. So ragdolls built alike (the same parts, the same joints: every
// ragdoll of one model) are relaxed kLinkLanes at a time, one per SIMD lane, each lane doing its
// ragdoll's links in creation order: the same result, bit for bit, as the plain loop over
// World::links(). The same holds for any group of links whose particles no other link touches.
#include <cstdint>
#include <span>
#include <vector>

#include "physics/constraints.h"

namespace phys {

/// Groups relaxed together, one per lane.
inline constexpr int kLinkLanes = 8;
/// The most particles a group's range may span to be put in lanes (a capsule ragdoll has 44 or 88).
inline constexpr int kMaxLinkGroupParticles = 96;

/// A link of a group, by the positions of its particles in the group's range.
struct LocalLink {
  std::uint8_t a[4]{}, b[4]{};
  std::uint8_t countA = 0, countB = 0;
  bool pin = false;
};

/// kLinkLanes groups of one shape: their particles are the ranges from firstParticle.
struct LinkLanes {
  ParticleId firstParticle[kLinkLanes]{};
  /// Where each lane's link indices (into World::links()) start in LinkLayout::laneLinks().
  std::uint32_t links[kLinkLanes]{};
  std::uint16_t particleCount = 0;
  std::uint16_t linkCount = 0;
  std::uint32_t firstLocal = 0;  ///< the shape's links in LinkLayout::localLinks()
  /// Per link in LinkLayout::laneValues(): kLinkValues rows of kLinkLanes values, one per lane:
  /// the 4 weights of a, the 4 of b, the min and the max length.
  std::uint32_t firstValue = 0;
};

inline constexpr int kLinkValues = 10;

class LinkLayout {
 public:
  /// Groups of links joined through their particles, each over a range of particles that no
  /// other group's link touches; groups alike go into lanes, kLinkLanes at a time. Every other
  /// link stays in others(), in creation order. Allocates: called when links are added.
  void build(std::span<const Link> links, std::size_t particleCount);

  std::span<const LinkLanes> lanes() const { return lanes_; }
  std::span<const LocalLink> localLinks() const { return localLinks_; }
  std::span<const Real> laneValues() const { return laneValues_; }
  /// Each lane group's lanes' link indices, lane by lane (LinkLanes::links).
  std::span<const std::uint32_t> laneLinks() const { return laneLinks_; }
  /// The links in no lane group, in creation order.
  std::span<const std::uint32_t> others() const { return others_; }
  /// Per lane group, 1 when every particle of its lanes has inverse mass 0 in this step (asleep,
  /// pinned or frozen), so that the passes skip it: they would move none of them. Empty unless
  /// markStill was called since the last clearStill.
  std::span<const std::uint8_t> still() const { return still_; }
  void markStill(std::span<const Real> inverseMass);
  void clearStill() { still_.clear(); }

 private:
  std::vector<LinkLanes> lanes_;
  std::vector<LocalLink> localLinks_;
  std::vector<Real> laneValues_;
  std::vector<std::uint32_t> laneLinks_;
  std::vector<std::uint32_t> others_;
  std::vector<std::uint8_t> still_;
};

}  // namespace phys
