#include "run_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace lab {

double maxAngularSpeed(const phys::World& world) {
  double fastest = 0.0;
  for (phys::BodyId id{}; id < world.bodies().size(); ++id) {
    const double speed = glm::length(world.bodyVelocity(id).second);
    if (!std::isfinite(speed)) return speed;
    fastest = std::max(fastest, speed);
  }
  return fastest;
}

void RunMaxima::observe(const phys::World& world) {
  const phys::Metrics metrics = world.metrics();
  for (std::size_t i = 0; i < kRunMetricCount; ++i) {
    const double v = kRunMetrics[i].read(world, metrics);
    worst[i] = std::isfinite(v) ? std::max(worst[i], v) : std::numeric_limits<double>::infinity();
  }
}

}  // namespace lab
