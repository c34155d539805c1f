#pragma once
// The pass criteria of the stability suite: <expect kind="pass" metric="..." .../> in a scene
// file (docs/scene-format.md, docs/lab.md "lab stability"). Each criterion measures one figure
// over a window of simulated time and compares it with a limit; a scene passes when all of its
// criteria do. Parsing is strict, like the loader's: a bad attribute is a scenes::LoadError
// naming the file, the <expect>'s line and the attribute.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "physics/types.h"
#include "scenes/scene.h"

namespace lab::stability {

/// What a criterion measures. Every one of them also fails when the guard froze anything
/// (the run blew up or left the world), whatever the figure says.
enum class Metric {
  Drift,        ///< m: farthest a body (or every body) gets from where it was at the window's start
  Penetration,  ///< m: World::metrics().maxPenetration, the worst in the window
  StickError,   ///< unitless: World::metrics().maxConstraintError, the worst in the window
  JointGap,     ///< m: World::metrics().maxJointError, the worst in the window
  Speed,        ///< m/s: World::metrics().maxSpeed, the worst in the window
  StaysBehind,  ///< m: a body's coordinate must stay below max (or above min): tunnelling
  Flips,        ///< count: a box's middle axis turns over from min to max times (Dzhanibekov)
};

/// The name a scene file uses for the metric ("drift", "stick-error", ...).
std::string metricName(Metric metric);

/// One parsed <expect kind="pass">.
struct Criterion {
  Metric metric = Metric::Drift;
  std::string body;                 ///< as written: a body's name, "*" (drift), or "" (none taken)
  std::vector<std::size_t> bodies;  ///< the body's index in bodyPositions() order (all for "*")
  std::int64_t boxId = -1;          ///< flips: the box (World::bodies() index)
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
  /// The figure's unit for reports ("m", "m/s", "" for ratios and counts).
  std::string unit() const;
};

/// Every kind="pass" criterion of a loaded (not yet stepped) scene, in file order. <expect>s of
/// kind "position" belong to the accuracy runs (accuracy.h) and are skipped. Throws
/// scenes::LoadError on a malformed one, and when the scene has none.
std::vector<Criterion> parseCriteria(const scenes::Scene& scene);

/// Steps a run of the scene takes: the latest window end over its criteria.
int runSteps(const std::vector<Criterion>& criteria);

/// How far a measured figure is from its limit, as one number where <= 1 passes and > 1 fails
/// (infinity when the run blew up): value / max for the "at most" metrics, the larger of
/// min / value and value / max for flips, and for stays-behind the share of the way from the body's start to
/// the plane.
double errorRatio(const Criterion& criterion, double value);

}  // namespace lab::stability
