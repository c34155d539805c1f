#pragma once
// The figures read after every step of a run, each kept at its worst over the run, or as the root
// mean square over the run's steps where that says more (how well a pose is tracked). This table is
// the one place a figure is defined: `lab run --json` and its summary, sweep's results.csv,
// tune's targets and compare's table all list it, so a figure added here appears in each
// (docs/lab.md, "Figures of a run").
#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "physics/world.h"
#include "root_mean_square.h"

namespace lab {

/// How a figure read after every step becomes the run's.
enum class OverRun {
  Worst,  ///< the largest after any step
  Rms,    ///< the root mean square over the steps
};

/// One figure of the table.
struct RunMetric {
  const char* name;    ///< tune's METRIC and compare's heading: "joint-error"
  const char* column;  ///< sweep's CSV column; run's JSON key with "_over_run" after it
  const char* unit;    ///< "m", "rad/s"; "" for a ratio
  const char* help;    ///< what it is, in a few words
  /// The figure after a step; `metrics` is world.metrics(), read once for all of them.
  double (*read)(const phys::World& world, const phys::Metrics& metrics);
  OverRun over = OverRun::Worst;
  /// What the world lacks to make the figure anything but 0 whatever its settings ("no joint"),
  /// or null when it has it: a bound on such a figure is met by every setting (tune refuses it).
  const char* (*lacks)(const phys::World& world) = nullptr;

  /// "joint-error (m)", or the name alone for a ratio: the figure's heading.
  std::string nameAndUnit() const { return *unit == '\0' ? name : std::string(name) + " (" + unit + ")"; }
  /// " m" to put after the figure's value; "" for a ratio.
  std::string unitAfter() const { return *unit == '\0' ? "" : std::string(" ") + unit; }
};

/// The fastest spin of any body, rad/s: each body's angular velocity over the last substep
/// (World::bodyVelocity; a particle body's from its particles' motion).
double maxAngularSpeed(const phys::World& world);

/// How far the characters' parts are from their targets after a step, unit: degrees: the root mean
/// square over every character's parts of phys::trackingError's angle; 0 without characters.
double trackingErrorDegrees(const phys::World& world);

/// What a world lacks to touch anything: the ground and something on it, or two bodies; null when it
/// has them.
const char* lacksContact(const phys::World& world);

inline constexpr std::array kRunMetrics{
    RunMetric{"stick-error", "max_stick_error", "", "largest stick violation / rest length (0.01 = 1%)",
              [](const phys::World&, const phys::Metrics& m) { return double(m.maxConstraintError); },
              OverRun::Worst, [](const phys::World& w) { return w.sticks().empty() ? "no stick" : nullptr; }},
    RunMetric{"joint-error", "max_joint_error", "m", "largest joint gap",
              [](const phys::World&, const phys::Metrics& m) { return double(m.maxJointError); },
              OverRun::Worst,
              [](const phys::World& w) { return w.jointCount() == 0 ? "no joint" : nullptr; }},
    RunMetric{"penetration", "max_penetration", "m", "deepest penetration",
              [](const phys::World&, const phys::Metrics& m) { return double(m.maxPenetration); },
              OverRun::Worst, lacksContact},
    RunMetric{"angular-speed", "max_angular_speed", "rad/s", "fastest spin of a body",
              [](const phys::World& w, const phys::Metrics&) { return maxAngularSpeed(w); }, OverRun::Worst,
              [](const phys::World& w) { return w.bodies().empty() ? "no body" : nullptr; }},
    RunMetric{"tracking-error", "rms_tracking_error", "deg",
              "characters' parts from their clip's pose, RMS over the run",
              [](const phys::World& w, const phys::Metrics&) { return trackingErrorDegrees(w); },
              OverRun::Rms,
              [](const phys::World& w) { return w.characters().empty() ? "no character" : nullptr; }},
};
inline constexpr std::size_t kRunMetricCount = kRunMetrics.size();

/// Where a metric sits in kRunMetrics; kRunMetricCount for none.
constexpr std::size_t runMetricIndex(std::string_view name) {
  for (std::size_t i = 0; i < kRunMetricCount; ++i) {
    if (name == kRunMetrics[i].name) return i;
  }
  return kRunMetricCount;
}
/// The figures some code reads by name (a peer's penetration, sweep's stdout table).
inline constexpr std::size_t kStickErrorMetric = runMetricIndex("stick-error");
inline constexpr std::size_t kPenetrationMetric = runMetricIndex("penetration");
static_assert(kStickErrorMetric < kRunMetricCount && kPenetrationMetric < kRunMetricCount);

/// Keeps the largest of a figure's samples in `worst`, and infinity for good once one is not
/// finite: a run that blew up is not rescued by a later small value.
void keepLargest(double& worst, double sample);

/// Each figure of kRunMetrics over the run so far: the largest, or the root mean square for an
/// OverRun::Rms figure, and infinity for good once a figure was not finite (a run that blew up is
/// not rescued by a later small value).
struct RunMaxima {
  std::array<double, kRunMetricCount> worst{};
  std::array<RootMeanSquare, kRunMetricCount> rms{};  ///< of the OverRun::Rms figures

  /// Reads every figure of the world as it is now.
  void observe(const phys::World& world);
  /// Takes one step's figures, in the order of kRunMetrics.
  void observe(const std::array<double, kRunMetricCount>& figures);
  double operator[](std::size_t i) const { return worst[i]; }
};

}  // namespace lab
