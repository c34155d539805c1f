#include "lab_sweep.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "accuracy.h"  // the lab's (lab_core)
#include "runner.h"    // the lab's
#include "scenes/scene.h"
#include "sweep_core.h"  // the lab's

namespace sandbox {
namespace {

// Timed runs per setting: the median of three, as a short `lab sweep --repeats 3`.
constexpr int kRepeats = 3;

}  // namespace

void LabSweep::start(const std::filesystem::path& file) {
  stop();
  file_ = file;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    points_.clear();
    error_.clear();
  }
  stop_.store(false);
  done_.store(0);
  total_.store(0);
  running_.store(true);
  thread_ = std::thread([this] { run(); });
}

void LabSweep::cancel() {
  stop_.store(true);  // it stops after the step it is on; running() says when
}

void LabSweep::stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  running_.store(false);
}

std::vector<LabPoint> LabSweep::points() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return points_;
}

std::string LabSweep::error() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

void LabSweep::run() {
  const lab::StopOnFlag stopWithin(stop_);  // every run below stops after the step it is on
  try {
    // Read once, so that every point measures the same scene even if Save As overwrites the file
    // while the sweep runs.
    const scenes::SceneSource source = scenes::readSceneSource(file_);
    const double dt = scenes::loadSceneSource(source).world.solverSettings().dt;
    const lab::SceneModels models = lab::sceneModels(source);
    std::vector<lab::Setting> settings;
    for (phys::SolverMethod m : {phys::SolverMethod::GaussSeidel, phys::SolverMethod::Jacobi,
                                 phys::SolverMethod::Xpbd, phys::SolverMethod::Shake}) {
      for (int it : kLabIterations) {
        for (int sub : kLabSubsteps) settings.push_back(lab::Setting{models.asFile, m, it, sub, dt});
      }
    }
    total_.store(static_cast<int>(settings.size()));
    lab::TargetCache targets;
    for (const lab::Setting& s : settings) {
      if (stop_.load()) break;
      const lab::AccuracyTarget& target = targets.get(source, s, lab::defaultSteps(dt));
      const int steps = lab::stepsFor(target, lab::defaultSteps(dt));
      const lab::Figures f = lab::measureFigures(source, s, steps, target);
      if (stop_.load()) break;
      LabPoint p{s.method,   s.iterations,
                 s.substeps, lab::timeSetting(source, s, steps, kRepeats),
                 f.error,    f.frozen > 0 || !std::isfinite(f.error)};
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        points_.push_back(p);
      }
      done_.fetch_add(1);
    }
  } catch (const lab::RunStopped&) {
    // cancelled or closing: the setting under way is dropped, and that is no error
  } catch (const std::exception& e) {
    const std::lock_guard<std::mutex> lock(mutex_);
    error_ = e.what();
  }
  running_.store(false);
}

std::vector<LabPoint> paretoFront(const std::vector<LabPoint>& points) {
  std::vector<LabPoint> sorted;
  for (const LabPoint& p : points) {
    if (!p.blewUp) sorted.push_back(p);
  }
  std::sort(sorted.begin(), sorted.end(), [](const LabPoint& a, const LabPoint& b) {
    return a.msPerStep != b.msPerStep ? a.msPerStep < b.msPerStep : a.error < b.error;
  });
  std::vector<LabPoint> front;
  for (const LabPoint& p : sorted) {
    if (front.empty() || p.error < front.back().error) front.push_back(p);
  }
  return front;
}

}  // namespace sandbox
