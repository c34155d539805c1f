#pragma once
// The Lab panel's sweep (docs/sandbox.md, "Lab"): the open scene's file under each method x
// iterations x substeps of a small grid, measured by the lab's own functions (lab::measureFigures
// against lab::accuracyTarget, lab::timeSetting), the same figures `lab sweep` writes, on a
// thread of its own so the window goes on; cancelled within a step (lab::StopOnFlag).
#include <atomic>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "physics/settings.h"

namespace sandbox {

/// One setting's figures.
struct LabPoint {
  phys::SolverMethod method = phys::SolverMethod::GaussSeidel;
  int iterations = 1;
  int substeps = 1;
  double msPerStep = 0.0;  ///< unit: ms; median of the timed runs
  double error = 0.0;      ///< unit: m; against the scene's exact answer or a converged reference
  bool blewUp = false;     ///< the guard froze something: no error to speak of
};

/// The grid: the four methods, 1, 2 and 4 iterations, 1, 2, 4 and 8 substeps.
inline constexpr int kLabIterations[] = {1, 2, 4};
inline constexpr int kLabSubsteps[] = {1, 2, 4, 8};

class LabSweep {
 public:
  LabSweep() = default;
  ~LabSweep() { stop(); }
  LabSweep(const LabSweep&) = delete;
  LabSweep& operator=(const LabSweep&) = delete;

  /// Starts sweeping `file` (at its own dt, over lab sweep's default horizon); drops what an
  /// earlier sweep found.
  void start(const std::filesystem::path& file);
  /// Asks it to stop after the step it is on, dropping the setting it was measuring; returns at
  /// once, so the window goes on.
  void cancel();
  bool cancelling() const { return stop_.load() && running(); }
  bool running() const { return running_.load(); }
  /// Settings done and in all.
  int done() const { return done_.load(); }
  int total() const { return total_.load(); }
  std::vector<LabPoint> points() const;
  /// "" or why the sweep stopped (a file that no longer loads).
  std::string error() const;
  const std::filesystem::path& file() const { return file_; }

 private:
  void run();
  /// Cancels and waits for the thread.
  void stop();

  std::filesystem::path file_;
  std::thread thread_;
  std::atomic<bool> stop_{false}, running_{false};
  std::atomic<int> done_{0}, total_{0};
  mutable std::mutex mutex_;  // guards points_ and error_
  std::vector<LabPoint> points_;
  std::string error_;
};

/// The points no other point beats in both cost and error (the blown-up ones left out), by cost.
std::vector<LabPoint> paretoFront(const std::vector<LabPoint>& points);

}  // namespace sandbox
