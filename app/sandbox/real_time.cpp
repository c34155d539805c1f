#include "real_time.h"

namespace sandbox {

void RealTimeMeter::add(double simulated, double wall, bool running) {
  if (!running) {
    count_ = 0;  // a pause starts the measure again
    return;
  }
  simulated_[next_] = simulated;
  wall_[next_] = wall;
  next_ = (next_ + 1) % kFrames;
  if (count_ < kFrames) ++count_;
}

std::optional<double> RealTimeMeter::factor() const {
  double simulated = 0.0, wall = 0.0;
  // Newest first, until a second of wall time is summed.
  for (std::size_t k = 1; k <= count_ && wall < kWindow; ++k) {
    const std::size_t i = (next_ + kFrames - k) % kFrames;
    simulated += simulated_[i];
    wall += wall_[i];
  }
  if (!(wall > 0.0)) return std::nullopt;
  return simulated / wall;
}

bool RealTimeMeter::fallingBehind(double timeScale) const {
  const std::optional<double> f = factor();
  return f && *f < 0.95 * timeScale;
}

}  // namespace sandbox
