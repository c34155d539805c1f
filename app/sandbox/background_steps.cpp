#include "background_steps.h"

#include <utility>

namespace sandbox {

void BackgroundSteps::start(std::vector<Run> runs, int steps, std::chrono::duration<double> budget) {
  cancel();
  runs_ = std::move(runs);
  taken_ = {};
  stop_.store(false);
  done_.store(false);
  thread_ = std::thread([this, steps, budget] {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    for (int n = 0; n < steps; ++n) {
      if (n > 0 && Clock::now() - start >= budget) {
        taken_.cut = true;
        break;
      }
      if (!stepRuns(runs_, &stop_)) break;  // cancelled: the copies are dropped
      ++taken_.steps;
      taken_.records.push_back(recordOf(runs_.front().scene->world));
    }
    done_.store(true, std::memory_order_release);
  });
}

std::optional<std::pair<std::vector<Run>, StepsTaken>> BackgroundSteps::collect() {
  if (!thread_.joinable() || !done_.load(std::memory_order_acquire)) return std::nullopt;
  thread_.join();
  std::pair<std::vector<Run>, StepsTaken> result(std::move(runs_), taken_);
  runs_.clear();
  return result;
}

void BackgroundSteps::cancel() {
  if (!thread_.joinable()) return;
  stop_.store(true, std::memory_order_relaxed);
  thread_.join();
  runs_.clear();
}

}  // namespace sandbox
