#pragma once
// The exact answer as a ghost (docs/sandbox.md, "Draw"): a scene with analytic answers (its
// <expect kind="position"> elements) is run a second time, from the file's start, at the lab's
// reference settings (lab::referenceSettings: 128 substeps of a method that converges), and drawn
// beside the simulated one at the same time. Its crosses are the closed-form positions at a few
// times; the ghost is where the answer is in between, so one sees the simulated body drift from
// it as it goes. Both are of the scene's bodies, so they are drawn only beside a world that holds
// them: not once key 0 has cleared them, back when a rewind, Reload or a recording brings them.
// Both are the answer under the file's settings, so they are drawn only while the world has them
// too: not once gravity, damping or any other setting the answer depends on is changed, back when
// it is changed back or Reload restores it (settingsChanged()). Save As makes the saved file the
// current one (fileSaved()): the world is then compared with what that file says, and a file saved
// with other settings than the answer's has no answer (Save As leaves its <expect>s out, and
// closed-form positions cannot be recomputed for other settings), which the panel says.
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "physics/world.h"
#include "scenes/scene.h"
#include "trails.h"  // kMaxStepsPerFrame

namespace sandbox {

/// The most particles and rigid bodies together a ghost steps: the analytic scenes have a few; a
/// scene of thousands at 128 substeps would cost the frame.
inline constexpr std::size_t kMaxGhostParticlesAndBodies = 200;
/// A copy of the ghost is kept every this many simulated seconds, so that going back in time (B,
/// the timeline) steps it from the copy before, not from the start. unit: s
inline constexpr double kGhostSnapshotEvery = 1.0;
/// How near (relative) a setting must be to the file's to count as the file's again: a float
/// slider gives 9.81 back as 9.8100004 (4e-8 off), and ten presses of Y and ten of H give
/// 9.809999999999999.
inline constexpr double kSameSetting = 1e-6;
/// Copies kept at most; past it every other one goes (a long run keeps fewer, further apart).
inline constexpr std::size_t kMaxGhostSnapshots = 256;
/// The most steps beside() takes a frame into time the ghost has not been to. At 128 substeps a
/// step of an analytic scene costs 0.15 to 0.3 ms, so a frame spends at most about 10 ms on it;
/// four times the run's own most a frame, so a running world is always kept up with, and a backlog
/// (exact answers turned on after a minute off) is caught up at four times the run's fastest.
inline constexpr int kGhostStepsPerFrame = 4 * kMaxStepsPerFrame;

class ExactGhost {
 public:
  /// What is drawn beside a world: the ghost at its time (null when there is none) and the crosses.
  struct Drawn {
    const phys::World* ghost = nullptr;
    std::span<const std::pair<double, glm::vec3>> answers;
  };

  /// Starts over from `scene` as it is now (just opened: at its start). No ghost when it has no
  /// position answers or is too big.
  void reset(const scenes::Scene& scene);
  /// Save As wrote `saved`, and its file is now the current one: settings are compared with that
  /// file's from here. Saved with other settings than the answer's, the answer is not that file's,
  /// and stays hidden (hiddenBecause says so) until a file is opened or saved again.
  void fileSaved(const phys::World& saved);
  void clear();
  bool active() const { return start_.has_value(); }
  /// What to draw beside `shown`, the world on screen: the ghost at its time, stepped at its dt
  /// (at(), at most kGhostStepsPerFrame steps into time it has not been to), and the crosses;
  /// nothing when hiddenBecause(shown) gives a reason (the ghost is stepped to its time all the
  /// same, so that it comes back without a minute's steps at once), or while it is catching up.
  Drawn beside(const phys::World& shown);
  /// Why beside(shown) draws nothing though the scene has answers, for the panel: "the scene's
  /// bodies are gone", "saved with gravity changed, and the answer (projectile.xml's) cannot be
  /// recomputed for the saved settings", "gravity changed", "gravity and damping changed"; "" when
  /// it draws them, or when the scene has none.
  std::string hiddenBecause(const phys::World& shown) const;
  /// The settings of `shown` that the exact answer depends on and that differ from the current
  /// file's (the one opened, or the one Save As wrote last), named as the panels name them
  /// ("gravity", "damping", "restitution", ...), in the panels' order; empty when there are none.
  /// It depends on every world setting in effect (not the gravity point in uniform mode), and on
  /// every solver setting the ghost does not set itself (it has its own method, substeps and
  /// iterations, and follows dt) or that changes nothing (threads). A number counts as the file's
  /// within a relative 1e-6 (kSameSetting).
  std::vector<std::string> settingsChanged(const phys::World& shown) const;
  /// Whether `shown` holds the bodies of the scene last reset from, as its file made them: its
  /// particles (by name, inverse mass and body) and bodies (by name) first, in order; bodies thrown
  /// in since come after them. A cleared world (key 0), and one rebuilt from it, does not.
  bool holds(const phys::World& shown) const;
  /// The ghost at simulated time `time` (unit: s), stepped at `dt` (the main run's) from where it
  /// was, or from the last copy before `time` when that is nearer (time went back, or on past copies
  /// kept before); null when there is none. It takes at most `newSteps` steps beyond the furthest
  /// time it has been to, and is then short of `time`.
  const phys::World* at(double time, double dt, long newSteps = std::numeric_limits<long>::max());
  /// The steps at() has taken since reset: what the ghost has cost, over every jump of the clock.
  long stepsTaken() const { return stepsTaken_; }
  /// The scene's answers, time (unit: s) and place (unit: m): its crosses.
  const std::vector<std::pair<double, glm::vec3>>& answers() const { return answers_; }

 private:
  /// What holds() compares: the scene's particles and bodies as reset() found them.
  struct Particle {
    std::string name;
    phys::Real inverseMass = 0.0;
    phys::BodyId body = phys::kNoBody;
  };
  std::vector<Particle> particles_;
  std::vector<std::string> bodies_;
  std::vector<std::pair<double, glm::vec3>> answers_;
  std::string answerFile_;                   // the name of the file the answers are from
  phys::WorldSettings answerWorldSettings_;  // that file's, that the answers are for
  phys::SolverSettings answerSolverSettings_;
  phys::WorldSettings fileWorldSettings_;  // the current file's: the answer's until a Save As
  phys::SolverSettings fileSolverSettings_;
  std::vector<std::string> savedChanged_;  // the current file's settings that are not the answer's
  std::optional<phys::World> start_;
  std::optional<phys::World> now_;
  std::vector<phys::World> snapshots_;  // by time
  double reached_ = 0.0;                // the furthest time the ghost has been to (unit: s)
  long stepsTaken_ = 0;
};

}  // namespace sandbox
