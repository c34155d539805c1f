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
  RootMeanSquare overParts;
  for (std::size_t k = 0; k < world.characters().size(); ++k)
    overParts.add(phys::trackingError(world, k), double(world.characters()[k].bones.size()));
  return overParts.value() * 180.0 / std::numbers::pi;
}

const char* lacksContact(const phys::World& world) {
  const bool something = !world.particles().inverseMass.empty() || world.rigidBodies().size() > 0;
  if ((world.worldSettings().ground && something) || world.bodies().size() >= 2) return nullptr;
  return world.worldSettings().ground ? "nothing to touch the ground" : "no ground and fewer than two bodies";
}

void keepLargest(double& worst, double sample) {
  worst = std::isfinite(sample) && std::isfinite(worst) ? std::max(worst, sample) : kInf;
}

void RunMaxima::observe(const phys::World& world) {
  const phys::Metrics metrics = world.metrics();
  std::array<double, kRunMetricCount> figures{};
  for (std::size_t i = 0; i < kRunMetricCount; ++i) figures[i] = kRunMetrics[i].read(world, metrics);
  observe(figures);
}

void RunMaxima::observe(const std::array<double, kRunMetricCount>& figures) {
  for (std::size_t i = 0; i < kRunMetricCount; ++i) {
    const double v = figures[i];
    if (!std::isfinite(v) || std::isinf(worst[i])) {
      worst[i] = kInf;
    } else if (kRunMetrics[i].over == OverRun::Rms) {
      rms[i].add(v);
      worst[i] = rms[i].value();
    } else {
      worst[i] = std::max(worst[i], v);
    }
  }
}

}  // namespace lab
