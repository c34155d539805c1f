#include "trails.h"

namespace sandbox {

void Trails::clear() {
  paths_.clear();
  steps_.clear();
}

void Trails::dropBack() {
  for (std::deque<glm::vec3>& path : paths_) path.pop_back();
  steps_.pop_back();
}

void Trails::record(const phys::World& world, std::optional<phys::BodyId> followed) {
  const long step = world.stepCount();
  if (followed != followed_) clear();
  if (!steps_.empty() && steps_.back() == step) return;
  followed_ = followed;
  // Rewound: the points after the step shown are a future the world has not reached (yet); the
  // ones before it are the path it took to get there, the same whether stepped or rebuilt.
  while (!steps_.empty() && steps_.back() >= step) dropBack();
  std::vector<glm::vec3> points;
  const auto owners = world.particleBodies();
  for (std::size_t i = 0; i < owners.size() && points.size() < kMaxTrails; ++i) {
    if (owners[i] == phys::kNoBody) points.emplace_back(world.particles().position[i]);
  }
  if (followed && *followed < world.bodies().size()) points.emplace_back(world.bodyPose(*followed).center);
  if (points.size() != paths_.size()) {  // particles came or went
    paths_.assign(points.size(), {});
    steps_.clear();
  }
  steps_.push_back(step);
  for (std::size_t k = 0; k < points.size(); ++k) paths_[k].push_back(points[k]);
  if (steps_.size() > kTrailPoints) {
    for (std::deque<glm::vec3>& path : paths_) path.pop_front();
    steps_.pop_front();
  }
}

void Trails::draw(engine::DebugLines& lines, const glm::vec3& color) const {
  for (std::size_t path = 0; path < paths_.size(); ++path) {
    forEachLine(path, [&](const glm::vec3& a, const glm::vec3& b, float age) {  // age 1 is the newest
      lines.addLine(a, b, color * (0.35f + 0.65f * age));
    });
  }
}

}  // namespace sandbox
