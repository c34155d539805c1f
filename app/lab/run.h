#pragma once
// Stepping a loaded scene under the lab's overrides, and what the run measured.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "options.h"
#include "physics/world.h"
#include "run_metrics.h"
#include "scenes/scene.h"
#include "text.h"

namespace lab {

/// What one part of a character needed to follow its clip over a run: its joint's drive (the
/// torque from its parent), or for the root its body drive, the hand of god (a force and a torque).
struct DriveFigures {
  std::string character;    ///< its ragdoll's name
  std::string bone;         ///< the clip's name for the part
  bool root = false;        ///< the root: driven against the world, not by a joint
  double rmsTorque = 0.0;   ///< unit: N m; root mean square over the run's steps
  double peakTorque = 0.0;  ///< unit: N m; the largest after any step
  double rmsForce = 0.0;    ///< unit: N; the root's alone
  double peakForce = 0.0;   ///< unit: N
};

/// Everything `lab run` reports, gathered once so the summary, the JSON and the tests agree.
struct RunResult {
  std::string scene;            ///< the scene's name
  std::filesystem::path file;   ///< where it was loaded from
  phys::SolverSettings solver;  ///< after the overrides
  int steps = 0;                ///< World::step() calls made
  double simulatedTime = 0.0;   ///< unit: s; World::time() at the end
  std::size_t particles = 0;    ///< world.particles().size()
  std::size_t constraints = 0;  ///< sticks and links: world.sticks().size() + world.links().size()
  std::size_t joints = 0;       ///< links (joints) alone
  std::size_t bodies = 0;       ///< world.bodies().size()
  bool xpbdAlone = false;       ///< xpbdWhateverTheMethod(world): the method changes nothing
  double energyInitial = 0.0;   ///< unit: J; before the first step
  phys::Metrics final;          ///< after the last step
  RunMaxima worst;              ///< each figure of run_metrics.h at its worst after any step
  double wallMs = 0.0;          ///< unit: ms; the calls to World::step(), steady_clock
  double msPerStep = 0.0;       ///< unit: ms; wallMs / steps
  double medianStepMs = 0.0;    ///< unit: ms; median of the steps' Profile::total
  phys::Profile stageSums;      ///< unit: ms; each stage summed over the run
  std::vector<phys::FreezeReport> freezes;  ///< the guard's reports, oldest first
  std::uint64_t hash = 0;                   ///< World::stateHash() at the end
  std::size_t islands = 0;                  ///< Islands::islandCount() at the end
  std::size_t largestIsland = 0;            ///< bodies in the island with the most, at the end
  std::size_t awakeBodies = 0;              ///< at the end
  std::size_t sleepingBodies = 0;           ///< at the end
  std::vector<DriveFigures> drives;         ///< every character's parts, root first, in order
};

/// Whether `world` is stepped by XPBD whatever the method: it has rigid bodies and no stick. The
/// four methods are ways of relaxing sticks; links, contacts and rigid bodies are solved the same
/// way under each (rigid bodies by XPBD's corrections), so such a world steps alike under all four.
bool xpbdWhateverTheMethod(const phys::World& world);

/// What `lab run` and `lab compare` impose at load. `--model M`: M on every box, capsule, stack,
/// pyramid and grid box; ragdolls keep their own models (seed, lean), except that rigid makes
/// their parts rigid too; nothing for no model. `--sleep`: sleeping off unless `sleep`, whatever
/// the file says.
scenes::LoadOptions imposedAtLoad(std::optional<phys::BodyModel> model, bool sleep = false,
                                  std::optional<bool> jointProjection = {});

/// Puts the options' overrides into the world's solver settings; rethrows the
/// std::invalid_argument of World::setSolverSettings when the world refuses them.
void applyOverrides(phys::World& world, const RunOptions& options);

/// When a run says how far it has got, on the progress stream: after `after` seconds, then every
/// `every` seconds. unit: s
struct ProgressTiming {
  double after = 2.0;
  double every = 5.0;
};

/// Applies the overrides, then steps the scene's world options.steps times and measures it.
/// Throws std::invalid_argument (from applyOverrides) before any step when they are refused.
/// With a progress stream, a run that takes longer than timing.after prints a line there every
/// timing.every: the step it is at, seconds a step, and the time left.
/// The figures of run_metrics.h are read after every step, outside the steps' clocks.
RunResult runScene(scenes::Scene& scene, const RunOptions& options, std::ostream* progress = nullptr,
                   const ProgressTiming& timing = {});

}  // namespace lab
