#pragma once
// The one step loop of the lab: every command that steps a scene (run, sweep, tune, compare,
// stability, scale, converge, the accuracy references) and every peer engine runs through
// runSteps, asking for what it needs: the bodies' poses at checkpoints, the figures of
// run_metrics.h after every step, the physics' own profile, or a look after every step that may
// stop the run. Only the steps are timed; what is read between them is not.
#include <atomic>
#include <exception>
#include <functional>
#include <vector>

#include "physics/world.h"
#include "run_metrics.h"

namespace lab {

/// What to record while stepping.
struct RunSpec {
  int steps = 0;
  /// Steps (counted from 1, ascending) after which the bodies' centres are kept (bodies.h order).
  std::vector<int> checkpoints;
  bool orientations = false;  ///< the bodies' orientations at the checkpoints too
  bool maxima = false;        ///< every figure of kRunMetrics after every step (our world only)
  bool profile = false;       ///< each step's Profile::total, and every stage summed (our world only)
  /// After each step (its number from 1), once the above are recorded: false stops the run there.
  std::function<bool(int step)> afterStep;
};

/// What a run recorded.
struct RunRecord {
  int stepsRun = 0;
  double energyBefore = 0.0;                          ///< unit: J; before the first step (our world only)
  double energyAfter = 0.0;                           ///< unit: J; after the last (our world only)
  double steppingMs = 0.0;                            ///< unit: ms; inside the steps alone
  RunMaxima maxima;                                   ///< with RunSpec::maxima
  std::vector<std::vector<phys::Vec3>> positions;     ///< per checkpoint, the bodies' centres
  std::vector<std::vector<phys::Quat>> orientations;  ///< per checkpoint, with RunSpec::orientations
  std::vector<double> profileTotals;                  ///< with RunSpec::profile, unit: ms
  phys::Profile stageSums;                            ///< with RunSpec::profile, unit: ms
};

/// What the runner steps: our world, or a peer engine (peers/peers.cpp).
class Stepper {
 public:
  virtual ~Stepper() = default;
  virtual void step() = 0;
  /// After each step, before anything is read, outside the clock (the step's number from 1).
  virtual void afterStep(int /*step*/) {}
  virtual std::vector<phys::Vec3> positions() const = 0;
  virtual std::vector<phys::Quat> orientations() const = 0;
  /// Our world, for what only it has (energy, the figures, the profile); nullptr for a peer.
  virtual const phys::World* world() const { return nullptr; }
};

/// What runSteps throws, after the step under way, once the flag of a StopOnFlag on its thread is set.
struct RunStopped : std::exception {
  const char* what() const noexcept override { return "the run was stopped"; }
};

/// While one lives, every runSteps on its thread checks `flag` after each step and throws
/// RunStopped once it is set: how the sandbox's Lab sweep, on a thread of its own, stops within a
/// step, where a setting of a big scene (Bullet's pile: its reference at 128 substeps first) took
/// about 20 s.
class StopOnFlag {
 public:
  explicit StopOnFlag(const std::atomic<bool>& flag);
  ~StopOnFlag();
  StopOnFlag(const StopOnFlag&) = delete;
  StopOnFlag& operator=(const StopOnFlag&) = delete;

 private:
  const std::atomic<bool>* outer_;  ///< the one it hides, back in place when it dies
};

/// Steps as the spec says. Reserves what it records before the first step; a peer's exception
/// goes through.
RunRecord runSteps(Stepper& stepper, const RunSpec& spec);
/// The same on our world.
RunRecord runSteps(phys::World& world, const RunSpec& spec);

}  // namespace lab
