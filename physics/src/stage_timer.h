#pragma once
// The timers every stage of World::step times itself with (step.cpp, sweep.cpp).
#include <chrono>

#include "physics/metrics.h"

namespace phys::detail {

// Adds the time from its construction to its destruction to one stage of a profile. A clock read
// costs about 20 ns, a tenth of a microsecond per timer: a stage with nothing to do returns before
// it starts one, so a world of two particles does not pay for the stages of a pile. Given no
// profile (World::setStageTiming(false)) it reads no clock.
class StageTimer {
 public:
  using Clock = std::chrono::steady_clock;
  StageTimer(Profile* profile, Stage stage)
      : slot_(profile != nullptr ? &(*profile)[stage] : nullptr),
        start_(slot_ != nullptr ? Clock::now() : Clock::time_point{}) {}
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  ~StageTimer() {
    if (slot_ != nullptr) *slot_ += std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  }

 private:
  double* slot_;
  Clock::time_point start_;
};

// Times stages that follow one another, one clock read between two of them where a StageTimer each
// takes two. The passes of World::relax run three to six stages each, 160 passes a step at
// 10 x 16, and their timers' clock reads were 2% of the stability suite. Each lap() files the time
// since the last lap (or the construction, or skip()) under the stage just run; a stage with
// nothing to do takes no lap, so the little between two stages goes to the next one. Given no
// profile it reads no clock.
class StageLaps {
 public:
  using Clock = std::chrono::steady_clock;
  explicit StageLaps(Profile* profile)
      : profile_(profile), last_(profile != nullptr ? Clock::now() : Clock::time_point{}) {}
  StageLaps(const StageLaps&) = delete;
  StageLaps& operator=(const StageLaps&) = delete;

  void lap(Stage stage) {
    if (profile_ == nullptr) return;
    const Clock::time_point now = Clock::now();
    (*profile_)[stage] += std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
  }
  /// Starts the next lap now, filing what ran since the last under no stage (work timed otherwise).
  void skip() {
    if (profile_ != nullptr) last_ = Clock::now();
  }

 private:
  Profile* profile_;
  Clock::time_point last_;
};

}  // namespace phys::detail
