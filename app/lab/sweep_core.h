#pragma once
// What `lab sweep` and `lab tune` share: a point of the settings space (models, method,
// passes, substeps, dt), the untimed pass that measures its figures, the timed runs that
// measure its cost, which box and ragdoll models a scene can take, and the small parsers of
// their command lines. docs/lab.md, "lab sweep" and "lab tune", describe the figures.
#include <map>
#include <string>
#include <vector>

#include "accuracy.h"
#include "peers/peer_scene.h"
#include "physics/settings.h"
#include "run_metrics.h"
#include "scenes/scene.h"

namespace lab {

/// Which bodies of a scene a --model value changes, imposed at load (scenes::LoadOptions).
struct ModelChoice {
  /// "corners", "tetra", "seed", "lean", "tetra+lean"; "scene" for the file's own mixed models;
  /// empty for a scene with neither boxes nor ragdolls.
  std::string label;
  scenes::LoadOptions options;  ///< what is imposed; nothing for "scene"
};

/// The model kinds a scene has, found by loading it under each model and counting particles
/// (a box's model changes its particle count, 8 or 4; a ragdoll's, 80 or 40).
struct SceneModels {
  bool boxes = false;     ///< box models (corners, tetra) change something
  bool ragdolls = false;  ///< ragdoll models (seed, lean) change something
  /// The file's own models, named when every box (ragdoll) has the same one: then imposing
  /// it gives the same world, so "corners" stands for the file's corners boxes.
  ModelChoice asFile;
};

/// Throws scenes::LoadError like the loader.
SceneModels sceneModels(const scenes::SceneSource& scene);

/// The models a --models list names, in its order; throws UsageError "--models: <why>" at the
/// first that does not fit the scene: an unknown name, or a model of a kind the scene does not
/// have ("lean" for a scene without ragdolls).
std::vector<ModelChoice> modelChoices(const std::vector<std::string>& names, const SceneModels& models);

/// Every model choice that applies: the box models times the ragdoll models the scene has
/// ("corners", "tetra+lean", ...), then "rigid" (both kinds rigid); just the file's own when it has
/// neither kind.
std::vector<ModelChoice> allModelChoices(const SceneModels& models);

/// Refuses a figure the scene cannot make other than 0 in any of `choices`, whatever the settings
/// (`lacks` is a RunMetric's): a bound on, or a chart of, such a figure says nothing. Throws
/// UsageError "FIGURE has LACK, so CONSEQUENCE", with " in any model TRIED" after LACK when there
/// are several choices ("--error tracking-error: scene pendulum has no character, so it is 0 at
/// every setting"): sweep's --error and tune's --target say it alike. Loads the scene under each
/// choice; throws scenes::LoadError.
void requireMeasurable(const char* (*lacks)(const phys::World& world), const scenes::SceneSource& scene,
                       const std::vector<ModelChoice>& choices, const std::string& figure, const char* tried,
                       const char* consequence);

/// One point of the settings space.
struct Setting {
  ModelChoice model;
  phys::SolverMethod method = phys::SolverMethod::GaussSeidel;
  int iterations = 3;
  int substeps = 1;
  double dt = 1.0 / 60.0;  ///< unit: s

  /// "xpbd, 2 iterations, 4 substeps, model tetra" (no model part when the label is empty)
  std::string describe() const;
};

/// What one untimed pass over a setting measured.
struct Figures {
  double error = 0.0;  ///< unit: m; accuracyError against the target; inf if it blew up
  RunMaxima maxima;    ///< each figure of run_metrics.h at its worst after any step
  /// unit: J; energy after the last step minus before the first; NaN where that is not finite
  double energyDrift = 0.0;
  int frozen = 0;  ///< particles the guard froze by the end
  /// unit: ms; this pass's own steps timed one by one and averaged: rough (one run, the
  /// metrics read between the steps disturb the caches), for the tune's pruning only.
  double roughMsPerStep = 0.0;
  /// unit: m; the error at the first checkpoint alone: in a chaotic scene (a pile) later
  /// checkpoints measure mostly which way things happened to fall, the first still how well a
  /// setting steps. Infinity when `error` is.
  double errorFirst = 0.0;
  /// unit: m; the largest penetration and joint gap over the checkpoints, measured from the
  /// bodies' poses by the code that measures every peer's (peers/pose_measures.h), so ours and
  /// theirs compare at equal joint error.
  double posePenetration = 0.0;
  double poseJointGap = 0.0;
  /// What stepped the world, one line ("Verlet, 3 iterations x 1 substep"); a peer's its own.
  std::string settings;
};

/// The error at the first of the target's checkpoints alone (`positions` per checkpoint, as for
/// accuracyError); NaN when the target has no checkpoint.
double firstCheckpointError(const AccuracyTarget& target,
                            const std::vector<std::vector<phys::Vec3>>& positions);

/// The largest penetration and joint gap of the described bodies at the recorded poses
/// (peers::posePenetration, peers::jointGap), into `penetration` and `jointGap`. `scene` is
/// described as loaded: a body the guard froze later is still judged by its joints.
void poseFigures(const peers::Description& scene, const std::vector<std::vector<phys::Vec3>>& positions,
                 const std::vector<std::vector<phys::Quat>>& orientations, double& penetration,
                 double& jointGap);

// Every point of a command is built from the scene file as read once (scenes::SceneSource), so a
// file saved over during a long sweep changes none of them.

/// Loads the scene with the setting's models and puts its solver settings in. Throws
/// scenes::LoadError, or std::invalid_argument when the world refuses the settings.
scenes::Scene loadSetting(const scenes::SceneSource& scene, const Setting& setting);

/// Runs the setting `steps` times (the target's checkpoints must be among them) with the
/// world's metrics read after every step, and compares it with the target. A run in which the
/// guard froze anything has error infinity: a frozen body's position says nothing.
Figures measureFigures(const scenes::SceneSource& scene, const Setting& setting, int steps,
                       const AccuracyTarget& target);

/// Median over `repeats` fresh loads of the wall time of the bare stepping loop / steps.
/// unit: ms
double timeSetting(const scenes::SceneSource& scene, const Setting& setting, int steps, int repeats);

/// Targets computed once per (model, dt, steps) and reused: a reference costs two fine runs.
class TargetCache {
 public:
  /// The target for the setting's model and dt over `steps` steps.
  const AccuracyTarget& get(const scenes::SceneSource& scene, const Setting& setting, int steps);
  /// Whether get() would compute (for progress counts).
  bool has(const Setting& setting, int steps) const;

 private:
  std::map<std::string, AccuracyTarget> targets_;
};

/// Default horizon of sweep and tune, unit: s of simulated time. Short, because a tumbling
/// body's run and its reference part ways soon after the first hard contact (accuracy.cpp):
/// the reference of the ragdoll scene is uncertain to 3 cm after 1 s, to 22 cm after 2 s.
inline constexpr double kDefaultHorizon = 1.0;
/// Steps covering the default horizon at dt.
int defaultSteps(double dt);

}  // namespace lab
