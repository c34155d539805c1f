#pragma once
// One simulation of the session: the main scene is run 0; the method overlay adds more, the same
// world under other solver settings.
#include <array>
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scenes/scene.h"

namespace sandbox {

/// One simulation: the main scene is run 0; the overlay adds more.
struct Run {
  static constexpr int kTimedSteps = 61;  ///< steps the median step time is taken over (~1 s)

  std::unique_ptr<scenes::Scene> scene;
  std::string label;  ///< the overlay settings as given; empty for the main scene alone
  glm::vec3 color{1.0f};
  double stepMs = 0.0;                         ///< unit: ms; wall time of the last step
  std::array<double, kTimedSteps> recentMs{};  ///< the last steps' times, a ring
  int timed = 0;                               ///< steps timed so far

  /// Median wall time of the last kTimedSteps steps (one step's time is too noisy to compare
  /// runs by). unit: ms; 0 before the first step
  double medianMs() const;
  /// How far its simulated time is behind `now`, the main run's (unit: s): 0 less than half its
  /// own step behind, more when kMaxCatchUpSteps a frame could not keep up (its picture is of an earlier
  /// moment).
  double behind(double now) const;
  /// A run with a copy of the scene, steps and timings included.
  Run copy() const;
};

/// Most steps a run takes in one step of the main run: a run far behind (dt a thousandth of the
/// main run's) catches up over several frames rather than stalling one.
inline constexpr int kMaxCatchUpSteps = 1000;

/// One step of the main run, and as many of every other run as it takes to reach the main run's
/// simulated time (a run with half the dt takes two, up to kMaxCatchUpSteps), timing each. False when `stop`
/// (if given) came true before a substep: the runs are then part of the way through and fit only to be
/// dropped (phys::World::step).
bool stepRuns(std::vector<Run>& runs, const std::atomic<bool>* stop = nullptr);

}  // namespace sandbox
