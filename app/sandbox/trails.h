#pragma once
// The recent paths of chosen points (Draw > trails): every loose particle, up to kMaxTrails of
// them, and the centre of the body the camera follows. One point per step shown, the last
// kTrailPoints of them: an orbit's circle, a pendulum's arc, a projectile's parabola.
#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "engine/debug_lines.h"
#include "physics/world.h"

namespace sandbox {

inline constexpr std::size_t kMaxTrails = 64;
inline constexpr std::size_t kTrailPoints = 600;  ///< 10 s at the default step

class Trails {
 public:
  void clear();
  /// Adds where the points are, once per step of the world (a step count already seen adds
  /// nothing; a smaller one, a world reloaded or rewound, starts the paths over).
  void record(const phys::World& world, std::optional<phys::BodyId> followed);
  /// Each path as lines, older parts fainter.
  void draw(engine::DebugLines& lines, const glm::vec3& color) const;
  std::size_t pathCount() const { return paths_.size(); }
  std::size_t pointCount(std::size_t path) const { return paths_[path].size(); }

 private:
  long lastStep_ = -1;
  std::optional<phys::BodyId> followed_;
  std::vector<std::deque<glm::vec3>> paths_;  // the loose particles' in order, then the followed body's
};

}  // namespace sandbox
