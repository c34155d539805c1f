#pragma once
// Bodies grouped for the passes that work body by body (body damping): bodies of one particle
// count, kBodyLanes at a time, one per SIMD lane; the rest one by one. Bodies share no particle,
// so the order they are visited in changes nothing.
#include <cstdint>
#include <span>
#include <vector>

#include "physics/body.h"

namespace phys {

inline constexpr int kBodyLanes = 8;

/// kBodyLanes bodies of particleCount particles each.
struct BodyLanes {
  ParticleId firstParticle[kBodyLanes]{};
  std::uint16_t particleCount = 0;
};

class BodyLayout {
 public:
  /// Allocates: called when bodies are added.
  void build(std::span<const Body> boxes);
  std::span<const BodyLanes> lanes() const { return lanes_; }
  /// The bodies in no lane group, by index in World::bodies(), in order.
  std::span<const BodyId> others() const { return others_; }
  /// Per lane group, 1 when every particle of its lanes has inverse mass 0 in this step (asleep,
  /// pinned or frozen), so that the passes skip it: they would move none of them. Empty unless
  /// markStill was called since the last clearStill.
  std::span<const std::uint8_t> still() const { return still_; }
  void markStill(std::span<const Real> inverseMass);
  void clearStill() { still_.clear(); }

 private:
  std::vector<BodyLanes> lanes_;
  std::vector<BodyId> others_;
  std::vector<std::uint8_t> still_;
};

}  // namespace phys
