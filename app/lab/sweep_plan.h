#pragma once
// What `lab sweep` and `lab compare` run: a plan of settings (every combination of models, dts,
// methods, iterations and substeps) and the peers at each dt, each run once measured and timed
// `repeats` times, into one row type. Sweep writes the rows as a CSV and a chart, compare as a
// table or JSON lines: compare is the sweep over our four methods at one setting, with the peers.
#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "accuracy.h"
#include "sweep_core.h"

namespace lab {

/// One row: one of our settings, or one peer engine at one dt.
struct SweepRow {
  std::string method;             ///< our method's name, or the peer's
  std::string model;              ///< the model's label
  std::optional<int> iterations;  ///< none for a peer
  std::optional<int> substeps;
  double dt = 0.0;
  int steps = 0;
  int repeats = 0;
  bool peer = false;
  bool ran = true;  ///< false for a peer that could not express the scene; `note` says why
  /// unit: ms; the stepping loop's wall time over its steps: ours the median of `repeats` runs,
  /// a peer's of its one run
  double msPerStep = 0.0;
  Figures figures;
  double uncertainty = 0.0;  ///< unit: m; the target's own (maxUncertainty)
  std::string note;
  bool pareto = false;  ///< set by the sweep

  double msPerSimSecond() const { return msPerStep / dt; }
  bool blewUp() const { return figures.frozen > 0 || !std::isfinite(figures.error); }
};

/// What a plan covers, once the scene's own values filled what was not asked.
struct Plan {
  scenes::SceneSource scene;  ///< the file as read once: every setting and peer is built from it
  std::string sceneName;
  double horizon = 0.0;  ///< unit: s of simulated time
  std::vector<ModelChoice> models;
  std::vector<Setting> settings;  ///< every combination, in run order
  std::vector<double> dts;
  int repeats = 3;
  bool peers = true;
  bool peerSleep = false;  ///< whether the peers may put resting bodies to sleep (runPeer)
  /// Called after each setting has run, with its place in `settings` (tests: a file saved over
  /// mid-sweep); none by default.
  std::function<void(std::size_t)> afterSetting;

  int stepsAt(double dt) const;
};

/// What to plan. Empty lists take the scene's own value; `models` empty, the file's own.
struct PlanRequest {
  std::vector<ModelChoice> models;
  std::vector<phys::SolverMethod> methods;
  std::vector<int> iterations;
  std::vector<int> substeps;
  std::vector<double> dts;
  std::optional<int> steps;       ///< at the scene's dt; default kDefaultHorizon of them
  std::optional<double> horizon;  ///< unit: s of simulated time; instead of `steps`
  int repeats = 3;
  bool peers = true;
  bool peerSleep = false;
};

/// A sweep of more runs than this is surely a typo in a list.
inline constexpr std::size_t kMaxCombinations = 10000;

/// Builds the plan: every model x dt x method x iterations x substeps, except that a model that
/// leaves rigid bodies and no stick (xpbdWhateverTheMethod) runs once, as xpbd. Throws
/// UsageError for more than kMaxCombinations runs or more than kMaxSteps steps at some dt,
/// scenes::LoadError like the loader.
Plan makePlan(const scenes::SceneSource& scene, const PlanRequest& request);

/// What running a plan gives.
struct PlanResult {
  std::vector<SweepRow> rows;  ///< the settings in plan order, then each dt's peers (ran or not)
  TargetCache targets;         ///< every target computed, for the reports
};

/// Runs every setting (measured, then timed `repeats` times), then the peers at each dt on the
/// scene as loaded with the first model, against that model's target. A peer that throws gets a
/// row that did not run, saying why: one engine failing costs no one else their results. A
/// progress bar called `name` ("sweep") goes to `err` meanwhile.
PlanResult runPlan(const Plan& plan, std::ostream& err, const std::string& name);

/// The target of the plan's first model at `dt` (the peers' and the chart's).
const AccuracyTarget& firstTarget(const Plan& plan, TargetCache& targets, double dt);

}  // namespace lab
