#pragma once
// One scene of the stability suite run under one solver setting, or in one peer engine, and
// judged against the scene's criteria.
#include <filesystem>
#include <string>
#include <vector>

#include "physics/settings.h"
#include "scenes/scene.h"
#include "stability_criteria.h"
#include "stability_judge.h"
#include "sweep_core.h"

namespace lab::stability {

/// A suite run's setting (sweep's): METHOD, ITERATIONS x SUBSTEPS, with MODEL imposed at load on
/// the scene's boxes and the ragdolls of its kind (corners and seed, tetra and lean, rigid; "": the
/// file's own) and sleeping on or off whatever the file says. Its dt is the scene's (runSetting).
Setting suiteSetting(phys::SolverMethod method, int iterations, int substeps, const std::string& model = "",
                     bool sleep = false);

/// A scene of the suite, read once: every run builds its world afresh from that one text, so a
/// file saved over during the suite changes no run.
struct SuiteScene {
  std::string name;  ///< the file's stem ("stack-10")
  scenes::SceneSource source;
  std::string description;  ///< the scene's own one line
  std::vector<Criterion> criteria;
  int steps = 0;          ///< runSteps(criteria)
  double dt = 0.0;        ///< unit: s; the scene's
  std::size_t boxes = 0;  ///< bodies (boxes, capsules, ragdoll parts): none, and a model imposes nothing
};

/// Loads a scene file and parses its criteria; throws scenes::LoadError.
SuiteScene loadSuiteScene(const std::filesystem::path& file);

/// What one run (a scene under a setting, or in a peer) came to.
struct Outcome {
  std::vector<Verdict> verdicts;  ///< one per criterion
  bool judged = false;            ///< at least one criterion could be judged
  bool passed = false;            ///< every judged criterion passed
  std::size_t worst = 0;          ///< the judged criterion with the largest ratio
  double wallMs = 0.0;            ///< unit: ms; the stepping alone (World::step or the peer's)
  double msPerStep = 0.0;         ///< unit: ms
  /// The step after which a run that had failed for good stopped (RunLength::UntilFailed); 0 for
  /// a run that went to its end or blew up. Whether a stopped run would have blown up is not known.
  int stoppedAt = 0;
  /// the guard's first freeze, what a peer could not do, or that the setting's model found nothing
  /// to apply to
  std::string note;
};

/// How far a run of ours steps: to its scene's last step, or only until it has failed for good (a
/// criterion past its limit that no later step can bring back, WorldJudge::failedForGood), which
/// saves the steps of a run whose verdict is already a failure. Such a run's figures are those of
/// the steps it ran: its worst criterion's value then, past its limit but no more than the whole run
/// would read.
enum class RunLength { Whole, UntilFailed };

/// Runs the scene under the setting for its steps; stops at the first freeze (a blow-up), and
/// with RunLength::UntilFailed once the run has failed for good (its note says where).
/// Throws scenes::LoadError for a model the file refuses, std::invalid_argument if the world
/// refuses the setting.
Outcome runSetting(const SuiteScene& scene, const Setting& setting, RunLength length = RunLength::Whole);

/// Runs the scene in a peer engine (peer.h) and judges what its positions can answer.
Outcome runPeerEngine(const SuiteScene& scene, const std::string& engine, bool sleep = false);

/// "gauss-seidel 3x4" (iterations x substeps), "xpbd 1x4 rigid" with a model.
std::string settingLabel(const Setting& setting);
/// The block of settings a setting belongs to in the reports: its method, and its model if any.
std::string settingGroup(const Setting& setting);

}  // namespace lab::stability
