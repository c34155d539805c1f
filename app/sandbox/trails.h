#pragma once
// The recent paths of chosen points (Draw > trails): every loose particle, up to kMaxTrails of
// them, and the centre of the body the camera follows. One point per frame, at the step shown (a
// step a frame at the default pace), the last kTrailPoints of them: an orbit's circle, a pendulum's
// arc, a projectile's parabola. A trail is the path the body took: where the world jumped (the
// timeline scrubbed forward, >|) the two points are not joined, and going back in time keeps the
// path up to the step shown.
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
/// The most steps the world advances by in a frame, running or playing the recording: the loop
/// owes no more (beyond, the world slows down instead of spiralling). Points of a trail further
/// apart than this were not reached by stepping from one to the other, and are not joined.
inline constexpr int kMaxStepsPerFrame = 8;

class Trails {
 public:
  void clear();
  /// Adds where the points are, once per step of the world (a step count already seen adds
  /// nothing). A smaller step count, the world rewound, drops the points after it: the path up
  /// to the step shown stays. A step more than kMaxStepsPerFrame on from the last point starts a
  /// new piece of the path, not joined to it. A world reloaded, cleared or opened from a
  /// recording is another path: the caller clears the trails.
  void record(const phys::World& world, std::optional<phys::BodyId> followed);
  /// Each path as lines, older parts fainter.
  void draw(engine::DebugLines& lines, const glm::vec3& color) const;
  std::size_t pathCount() const { return paths_.size(); }
  std::size_t pointCount(std::size_t path) const { return paths_[path].size(); }
  /// Calls line(a, b, age) for each line `draw` draws of path `path`, oldest first: two
  /// consecutive points joined, `age` from 0 (the oldest point) to 1 (the newest).
  template <typename Line>
  void forEachLine(std::size_t path, Line&& line) const {
    const std::deque<glm::vec3>& p = paths_[path];
    for (std::size_t k = 1; k < p.size(); ++k) {
      // A line only where the world stepped from one point to the next: across a jump (the
      // timeline, >|) it would cut straight through where the body went.
      if (steps_[k] - steps_[k - 1] <= kMaxStepsPerFrame)
        line(p[k - 1], p[k], static_cast<float>(k) / static_cast<float>(p.size()));
    }
  }

 private:
  void dropBack();

  std::optional<phys::BodyId> followed_;
  std::vector<std::deque<glm::vec3>> paths_;  // the loose particles' in order, then the followed body's
  std::deque<long> steps_;                    // each point's step, the same for every path
};

}  // namespace sandbox
