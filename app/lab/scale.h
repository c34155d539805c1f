#pragma once
// lab scale (docs/lab.md, "lab scale"): one scene generated at growing sizes, and what a step
// costs at each. scaleMain (commands.h) is the command; the pieces are here for the tests.
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "options.h"
#include "physics/settings.h"

namespace lab {

/// What the generator makes.
enum class ScaleKind {
  CapsuleRagdolls,  ///< n of Bullet's capsule ragdolls (11 capsules each) on a grid, tipped to fall
  BoxRagdolls,      ///< n of the seed's ragdolls (10 boxes each), the same way
  Pyramid,          ///< a pyramid of boxes whose base row is n: n (n + 1) / 2 boxes
};

std::string_view toString(ScaleKind kind);  ///< "capsule-ragdolls", "box-ragdolls", "pyramid"

/// The scene file of the kind at size n, with the solver settings its kind is run at elsewhere.
std::string scaleSceneXml(ScaleKind kind, int n);

/// One size's measurements.
struct ScaleRow {
  std::string scene;            ///< the kind's name
  int n = 0;                    ///< ragdolls, or the pyramid's base
  std::size_t bodies = 0;       ///< boxes and capsules
  phys::SolverSettings solver;  ///< what it ran at, after the overrides (its threads too)
  double msPerStep = 0.0;       ///< unit: ms; median of the steps' Profile::total
  double usPerBodyStep = 0.0;   ///< unit: microseconds; msPerStep per body
  double maxJointGap = 0.0;     ///< unit: m; the largest Metrics::maxJointError after any step
  bool blewUp = false;          ///< the guard froze something
};

/// Generates and runs each size for options.steps steps under options' overrides, once at each
/// number of `threads` in turn (none given: at options.threads, or the scene's); progress lines
/// for long runs go to `progress`. Throws std::invalid_argument when the overrides are refused.
std::vector<ScaleRow> runScale(ScaleKind kind, const std::vector<int>& sizes, const RunOptions& options,
                               const std::vector<int>& threads = {}, std::ostream* progress = nullptr);

/// A JSON array, one object a run: scene, n, threads, bodies, ms_per_step, us_per_body_step,
/// max_joint_gap.
std::string scaleJson(const std::vector<ScaleRow>& rows);
/// The same as CSV, with a header.
std::string scaleCsv(const std::vector<ScaleRow>& rows);
/// The table `lab scale` prints.
std::string scaleTable(const std::vector<ScaleRow>& rows);

}  // namespace lab
