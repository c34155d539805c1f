#include "run_metrics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "physics/character.h"
#include "text.h"

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

double trackingErrorDegrees(const phys::World& world) {
  double sum = 0.0, parts = 0.0;
  for (std::size_t k = 0; k < world.characters().size(); ++k) {
    const double e = phys::trackingError(world, k), n = double(world.characters()[k].bones.size());
    sum += e * e * n;
    parts += n;
  }
  return parts > 0.0 ? std::sqrt(sum / parts) * 180.0 / std::numbers::pi : 0.0;
}

void RunMaxima::observe(const phys::World& world) {
  const phys::Metrics metrics = world.metrics();
  ++steps;
  for (std::size_t i = 0; i < kRunMetricCount; ++i) {
    const double v = kRunMetrics[i].read(world, metrics);
    if (!std::isfinite(v) || std::isinf(worst[i])) {
      worst[i] = kInf;
    } else if (kRunMetrics[i].over == OverRun::Rms) {
      sumOfSquares[i] += v * v;
      worst[i] = std::sqrt(sumOfSquares[i] / double(steps));
    } else {
      worst[i] = std::max(worst[i], v);
    }
  }
}

}  // namespace lab
