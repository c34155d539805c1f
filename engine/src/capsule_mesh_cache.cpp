#include "engine/capsule_mesh_cache.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "engine/error.h"
#include "engine/mesh_data.h"

namespace engine {

const GpuMesh& CapsuleMeshCache::get(float radius, float halfSegment, Detail detail) {
  if (!(std::abs(radius) <= kLargest && std::abs(halfSegment) <= kLargest)) {
    throw Error("capsule mesh: radius " + std::to_string(radius) + ", half segment " +
                std::to_string(halfSegment) + ": not a size that can be drawn");
  }
  const Key key{std::llround(radius / kResolution), std::llround(halfSegment / kResolution), detail};
  if (auto found = meshes_.find(key); found != meshes_.end()) {
    found->second.lastUse = round_;
    return found->second.mesh;
  }
  // Built from the key's size, so every capsule that shares the mesh gets the same one
  // (makeCapsuleMesh refuses a radius that rounds to 0 or a negative half segment).
  GpuMesh mesh(makeCapsuleMesh(static_cast<float>(std::get<0>(key)) * kResolution,
                               static_cast<float>(std::get<1>(key)) * kResolution, detail.segments,
                               detail.rings));
  return meshes_.emplace(key, Entry{std::move(mesh), round_}).first->second.mesh;
}

void CapsuleMeshCache::trim() {
  if (meshes_.size() > capacity_) {
    std::vector<std::pair<std::uint64_t, Key>> idle;  // (last use, key), oldest first once sorted
    for (const auto& [key, entry] : meshes_) {
      if (entry.lastUse != round_) idle.emplace_back(entry.lastUse, key);
    }
    std::sort(idle.begin(), idle.end());
    for (std::size_t i = 0; i < idle.size() && meshes_.size() > capacity_; ++i) meshes_.erase(idle[i].second);
  }
  ++round_;
}

}  // namespace engine
