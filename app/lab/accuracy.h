#pragma once
// How accurate a run is (docs/lab.md, "Accuracy"): the bodies' positions (bodies.h) at a few
// checkpoint steps, compared with what they should be. A scene with analytic answers says so
// in its file (<expect kind="position" body="NAME" at="T" pos="x y z"/>: the named body is at
// pos at time T); any other scene is compared with a converged reference run of itself: the
// same file, model and dt, stepped with far more substeps (accuracy.cpp says how many and why).
// Our runs and the peers' are measured by the same functions.
#include <string>
#include <vector>

#include "physics/settings.h"
#include "scenes/scene.h"

namespace lab {

/// What a run is compared with.
struct AccuracyTarget {
  std::string kind;              ///< "analytic" or "reference"
  std::string description;       ///< one line: what is compared, for reports
  std::vector<int> checkpoints;  ///< steps (1-based counts of World::step calls), ascending
  /// Per checkpoint, per body (bodies.h order): where it should be; NaN where nothing is said.
  std::vector<std::vector<phys::Vec3>> expected;
  /// Per checkpoint, unit m: how far the target itself may be off. 0 for analytic answers;
  /// for a reference, the largest distance between it and the same run with half its
  /// substeps (errors below this cannot be told apart; a chaotic scene shows it growing).
  std::vector<double> uncertainty;
};

/// The reference run's settings (accuracy.cpp says why these): `shake` (`xpbd` when the scene
/// has compliance, which only xpbd honours), kReferenceSubsteps substeps of
/// kReferenceIterations passes, at the run's dt. Its uncertainty comes from the same run with
/// kReferenceSubsteps / 2.
inline constexpr int kReferenceSubsteps = 128;
inline constexpr int kReferenceIterations = 4;
/// The settings of a reference run of `world` at `dt`: its own solver settings (body damping,
/// restitution, compliance and the rest stay) with the method, substeps and iterations above.
phys::SolverSettings referenceSettings(const phys::World& world, double dt);
/// A reference is compared at this many checkpoints, evenly spread over the run, the last step
/// among them.
inline constexpr int kReferenceCheckpoints = 4;
/// kReferenceCheckpoints steps spread evenly over 1..steps, the last among them, ascending and
/// distinct (fewer when steps is smaller).
std::vector<int> spreadCheckpoints(int steps);

/// Steps a run needs to reach every checkpoint of the target: `steps`, or more for an analytic
/// answer later than that.
int stepsFor(const AccuracyTarget& target, int steps);

/// The steps a run of `scene` at `dt` takes, as stepsFor(accuracyTarget(scene, dt, steps), steps)
/// says, without running a reference: `steps`, or more to reach a later analytic answer. Throws
/// as accuracyTarget does for a malformed answer.
int stepsToCover(const scenes::Scene& scene, double dt, int steps);

/// The largest of the target's uncertainties (0 when it has none). unit: m
double maxUncertainty(const AccuracyTarget& target);

/// The target for `scene` (freshly loaded, with the run's model) stepped `steps` times at `dt`:
/// its analytic answers if it has any (then the checkpoints are their times, and `steps` is only
/// a minimum), else a reference run. Throws scenes::LoadError naming file, line and attribute for
/// a malformed <expect kind="position">.
AccuracyTarget accuracyTarget(const scenes::Scene& scene, double dt, int steps);

/// One of a scene's analytic answers: where a body should be, when.
struct PositionAnswer {
  double time = 0.0;    ///< unit: s
  phys::Vec3 pos{0.0};  ///< unit: m
};
/// The scene's <expect kind="position"> answers at its own dt, each checked as accuracyTarget
/// checks them (the sandbox draws them, and refuses a scene whose answers are wrong); throws
/// scenes::LoadError naming the file, line and attribute of one that is.
std::vector<PositionAnswer> positionAnswers(const scenes::Scene& scene);

/// The run's error: the largest distance (m) between a body's position at a checkpoint and the
/// target's, over every body and checkpoint the target says something of. `positions` holds,
/// per checkpoint, bodyPositions() at that step. Infinity when a position is not finite or the
/// body counts differ.
double accuracyError(const AccuracyTarget& target, const std::vector<std::vector<phys::Vec3>>& positions);

}  // namespace lab
