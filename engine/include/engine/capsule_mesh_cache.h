#pragma once
// Capsule meshes on the GPU, one per size and detail. A capsule scaled from a unit one would
// have squashed caps, so each (radius, half segment) gets a mesh of its own, built the first
// time it is asked for. Drawing goes in rounds (a frame, or one run's part of it) ended by
// trim(), which frees the meshes not asked for in that round, least recently used first, while
// more than `capacity` are kept: so opening scene after scene does not pile them up, and a
// world with more sizes than that still keeps all of its own.
#include <compare>
#include <cstddef>
#include <cstdint>
#include <map>
#include <tuple>

#include "engine/gpu_mesh.h"

namespace engine {

class CapsuleMeshCache {
 public:
  /// Sizes are told apart to this much (unit: m): closer ones share a mesh.
  static constexpr float kResolution = 1e-5f;
  /// The largest radius or half segment get() takes (unit: m).
  static constexpr float kLargest = 1e6f;
  /// How finely a capsule is cut: columns around the axis, rows of each cap from pole to equator.
  struct Detail {
    int segments;
    int rings;
    auto operator<=>(const Detail&) const = default;
  };
  static constexpr Detail kFine{24, 6};    ///< lit faces: smooth at any size on screen
  static constexpr Detail kCoarse{12, 3};  ///< edges (wireframe): few enough to tell apart

  /// Keeps at most `capacity` meshes, or more while more are asked for in one round.
  explicit CapsuleMeshCache(std::size_t capacity = 64) : capacity_(capacity) {}

  /// The mesh of a capsule along y about the origin (makeCapsuleMesh), uploaded on first use;
  /// needs a current GL context. Valid until the next trim(). Throws engine::Error on a size or
  /// detail makeCapsuleMesh refuses.
  const GpuMesh& get(float radius, float halfSegment, Detail detail = kFine);
  /// Ends a round of drawing: frees the least recently used meshes beyond the capacity, never
  /// one drawn since the previous trim().
  void trim();
  /// Frees every mesh (needs the GL context the meshes were made in).
  void clear() { meshes_.clear(); }

  std::size_t size() const { return meshes_.size(); }
  std::size_t capacity() const { return capacity_; }

 private:
  struct Entry {
    GpuMesh mesh;
    std::uint64_t lastUse = 0;
  };
  using Key = std::tuple<std::int64_t, std::int64_t, Detail>;  // radius and half segment in kResolution

  std::size_t capacity_;
  std::uint64_t round_ = 1;  // increases with each trim()
  std::map<Key, Entry> meshes_;
};

}  // namespace engine
