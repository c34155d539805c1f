#pragma once
// The pass criteria of the stability suite: <expect kind="pass" metric="..." .../> in a scene
// file (docs/scene-format.md, docs/lab.md "lab stability"). Each criterion measures one figure
// over a window of simulated time and compares it with a limit; a scene passes when all of its
// criteria do. Parsing is strict, like the loader's: a bad attribute is a scenes::LoadError
// naming the file, the <expect>'s line and the attribute (expect_reader.h).
#include <cstddef>
#include <string>
#include <vector>

#include "physics/metrics.h"
#include "physics/types.h"
#include "scenes/scene.h"

namespace lab::stability {

/// What a criterion measures. Every one of them also fails when the guard froze anything
/// (the run blew up or left the world), whatever the figure says.
enum class Metric { Drift, Penetration, StickError, JointGap, Speed, StaysBehind, Flips };

/// All that the parser, the judge and the reports know of a metric: one row of kMetrics.
struct MetricInfo {
  Metric metric;
  const char* name;  ///< as a scene file writes it
  const char* unit;  ///< for reports; "" for ratios and counts
  /// Our world's figure, World::metrics(), the worst in the window; null for those measured
  /// from the bodies' poses (drift, stays-behind, flips).
  phys::Real phys::Metrics::*figure;
  bool needsOrientations;  ///< a peer's positions alone cannot answer it
};

inline constexpr MetricInfo kMetrics[] = {
    // The farthest a body (or every body) gets from where it was at the window's start.
    {Metric::Drift, "drift", "m", nullptr, false},
    {Metric::Penetration, "penetration", "m", &phys::Metrics::maxPenetration, true},
    {Metric::StickError, "stick-error", "", &phys::Metrics::maxConstraintError, false},
    {Metric::JointGap, "joint-gap", "m", &phys::Metrics::maxJointError, true},
    {Metric::Speed, "speed", "m/s", &phys::Metrics::maxSpeed, false},
    // A body's coordinate must stay below max (or above min): tunnelling.
    {Metric::StaysBehind, "stays-behind", "m", nullptr, false},
    // A box's middle axis turns over from min to max times (Dzhanibekov).
    {Metric::Flips, "flips", "", nullptr, true},
};

/// The metric's row of kMetrics.
const MetricInfo& metricInfo(Metric metric);

/// One parsed <expect kind="pass">.
struct Criterion {
  Metric metric = Metric::Drift;
  std::string body;                 ///< as written: a body's name, "*" (drift), or "" (none taken)
  std::vector<std::size_t> bodies;  ///< in bodyPositions() order, boxes first (all for "*")
  int fromStep = 0;                 ///< the window, in World::step() counts: from this state...
  int toStep = 0;                   ///< ...to this one, both included (0 is the loaded state)
  double from = 0.0, to = 0.0;      ///< unit: s; the window as written
  double limit = 0.0;               ///< max; flips: min (0 if none); stays-behind: the plane
  double upper = 0.0;               ///< flips: max (infinity if none)
  bool atLeast = false;             ///< true: the figure must be >= limit (flips, stays-behind min)
  int axis = 0;                     ///< stays-behind: 0, 1, 2 for x, y, z
  double start = 0.0;               ///< stays-behind: the body's coordinate when loaded (m)

  /// One line for reports: "drift of stack[9] <= 0.05 m over 2-10 s".
  std::string describe() const;
};

/// Every kind="pass" criterion of a loaded (not yet stepped) scene, in file order. <expect>s of
/// kind "position" belong to the accuracy runs (accuracy.h) and are skipped. Throws
/// scenes::LoadError on a malformed one, and when the scene has none.
std::vector<Criterion> parseCriteria(const scenes::Scene& scene);

/// Steps a run of the scene takes: the latest window end over its criteria.
int runSteps(const std::vector<Criterion>& criteria);

/// How far a measured figure is from its limit, as one number where <= 1 passes and > 1 fails:
/// value / max for the "at most" metrics, the larger of min / value and value / max for flips, and
/// for stays-behind the share of the way from the body's start to the plane. Infinity when the run
/// blew up, or when a flips body never flipped under a min; finite for any other finite figure.
double errorRatio(const Criterion& criterion, double value);

}  // namespace lab::stability
