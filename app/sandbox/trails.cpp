#include "trails.h"

namespace sandbox {

void Trails::clear() {
  paths_.clear();
  lastStep_ = -1;
}

void Trails::record(const phys::World& world, std::optional<phys::BodyId> followed) {
  const long step = world.stepCount();
  if (step == lastStep_ && followed == followed_) return;
  if (step < lastStep_ || followed != followed_) clear();
  lastStep_ = step;
  followed_ = followed;
  std::vector<glm::vec3> points;
  const auto owners = world.particleBodies();
  for (std::size_t i = 0; i < owners.size() && points.size() < kMaxTrails; ++i) {
    if (owners[i] == phys::kNoBody) points.emplace_back(world.particles().position[i]);
  }
  if (followed && *followed < world.bodies().size()) points.emplace_back(world.bodyPose(*followed).center);
  if (points.size() != paths_.size()) paths_.assign(points.size(), {});  // particles came or went
  for (std::size_t k = 0; k < points.size(); ++k) {
    paths_[k].push_back(points[k]);
    if (paths_[k].size() > kTrailPoints) paths_[k].pop_front();
  }
}

void Trails::draw(engine::DebugLines& lines, const glm::vec3& color) const {
  for (const std::deque<glm::vec3>& path : paths_) {
    for (std::size_t k = 1; k < path.size(); ++k) {
      const float age = static_cast<float>(k) / static_cast<float>(path.size());  // 1 is the newest
      lines.addLine(path[k - 1], path[k], color * (0.35f + 0.65f * age));
    }
  }
}

}  // namespace sandbox
