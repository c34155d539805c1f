#pragma once
// Steps taken on another thread, so that no setting can freeze the window (docs/sandbox.md,
// "Time budget"): copies of the session's runs step there while the window draws the runs as
// they were, and replace them when done. A command cancels them first: the copies are dropped
// within a substep and the command acts on what the window shows.
#include <atomic>
#include <chrono>
#include <optional>
#include <thread>
#include <vector>

#include "recording.h"
#include "run.h"

namespace sandbox {

/// What the background steps did.
struct StepsTaken {
  int steps = 0;                    ///< steps of the main run
  bool cut = false;                 ///< the wall-time budget ended them before all the steps asked for
  std::vector<StepRecord> records;  ///< the main run's steps, for the recording (recording.h)
};

class BackgroundSteps {
 public:
  BackgroundSteps() = default;
  ~BackgroundSteps() { cancel(); }
  BackgroundSteps(const BackgroundSteps&) = delete;
  BackgroundSteps& operator=(const BackgroundSteps&) = delete;

  /// Steps `runs` (copies, which it owns from now on) up to `steps` times on another thread (as
  /// stepRuns does), no more once `budget` of wall time has gone by (a step begun is finished).
  /// Cancels any steps still running first.
  void start(std::vector<Run> runs, int steps, std::chrono::duration<double> budget);
  /// Started, and neither collected nor cancelled.
  bool running() const { return thread_.joinable(); }
  /// Once the steps are done: the stepped runs and what they did; the job is over. Nothing while
  /// they run or when none were started.
  std::optional<std::pair<std::vector<Run>, StepsTaken>> collect();
  /// Stops the steps before their next substep and drops the copies; waits for the thread.
  void cancel();

 private:
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> done_{false};
  std::vector<Run> runs_;  // the thread's alone until done_
  StepsTaken taken_;
};

}  // namespace sandbox
