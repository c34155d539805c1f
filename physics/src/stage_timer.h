#pragma once
// The timer every stage of World::step times itself with (step.cpp, sweep.cpp).
#include <chrono>

#include "physics/metrics.h"

namespace phys::detail {

// Adds the time from its construction to its destruction to one stage of a profile. A clock read
// costs about 20 ns, a tenth of a microsecond per timer: a stage with nothing to do returns before
// it starts one, so a world of two particles does not pay for the stages of a pile.
class StageTimer {
 public:
  using Clock = std::chrono::steady_clock;
  StageTimer(Profile& profile, Stage stage) : slot_(profile[stage]), start_(Clock::now()) {}
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  ~StageTimer() { slot_ += std::chrono::duration<double, std::milli>(Clock::now() - start_).count(); }

 private:
  double& slot_;
  Clock::time_point start_;
};

}  // namespace phys::detail
