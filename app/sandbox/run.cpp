#include "run.h"

#include <algorithm>
#include <chrono>

namespace sandbox {
namespace {

using Clock = std::chrono::steady_clock;

bool timedStep(Run& run, const std::atomic<bool>* stop) {
  const auto start = Clock::now();
  if (stop == nullptr)
    run.scene->world.step();
  else if (!run.scene->world.step(*stop))
    return false;
  run.stepMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  run.recentMs[static_cast<std::size_t>(run.timed % Run::kTimedSteps)] = run.stepMs;
  ++run.timed;
  return true;
}

}  // namespace

double Run::medianMs() const {
  const int n = std::min(timed, kTimedSteps);
  if (n == 0) return 0.0;
  std::array<double, kTimedSteps> sorted = recentMs;
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.begin() + n);
  return sorted[static_cast<std::size_t>(n / 2)];
}

double Run::behind(double now) const {
  const phys::World& world = scene->world;
  return world.time() + 0.5 * world.solverSettings().dt <= now ? now - world.time() : 0.0;
}

Run Run::copy() const {
  Run c;
  c.scene = std::make_unique<scenes::Scene>(*scene);
  c.label = label;
  c.color = color;
  c.stepMs = stepMs;
  c.recentMs = recentMs;
  c.timed = timed;
  return c;
}

bool stepRuns(std::vector<Run>& runs, const std::atomic<bool>* stop) {
  if (!timedStep(runs.front(), stop)) return false;
  const double now = runs.front().scene->world.time();
  for (std::size_t i = 1; i < runs.size(); ++i) {
    Run& run = runs[i];
    for (int n = 0; n < kMaxCatchUpSteps && run.behind(now) > 0.0; ++n) {
      if (!timedStep(run, stop)) return false;
    }
  }
  return true;
}

}  // namespace sandbox
