#pragma once
// The lab's command line (docs/lab.md): the commands, and what `lab run` takes.
//   lab run SCENE [--steps N] [--dt S] [--methods M] [--iterations K] [--substeps S]
//                 [--models M] [--sleep on|off] [--threads N] [--json] [--dump FILE] [--data DIR]
//   lab COMMAND --help, lab help
#include <filesystem>
#include <optional>
#include <string>

#include "command_line.h"
#include "physics/body.h"
#include "physics/settings.h"

namespace lab {

inline constexpr int kDefaultSteps = 600;  ///< 10 s at the default dt of 1/60 s

/// What `lab run` was asked to do. Unset overrides keep the scene's own solver settings.
struct RunOptions {
  std::string scene;                         ///< a file, or a name in <data>/assets/scenes
  int steps = kDefaultSteps;                 ///< World::step() calls
  std::optional<double> dt;                  ///< unit: s
  std::optional<phys::SolverMethod> method;  ///< relaxation method
  std::optional<int> iterations;             ///< relaxation passes per substep
  std::optional<int> substeps;               ///< integrations per step
  /// Imposed on every box, capsule, stack, pyramid and grid box of the scene (not on ragdolls).
  std::optional<phys::BodyModel> model;
  /// --sleep on: islands at rest sleep (SolverSettings::sleep). Off, the lab's default, steps every
  /// body whatever the scene says, so that costs and errors compare like with like.
  bool sleep = false;
  std::optional<bool> jointProjection;        ///< --joint-projection: SolverSettings::jointProjection
  std::optional<int> threads;                 ///< --threads N: SolverSettings::threads (default: the scene's)
  bool json = false;                          ///< one JSON object instead of the summary
  std::optional<std::filesystem::path> dump;  ///< CSV of the named bodies' final poses
  std::filesystem::path dataDir;              ///< holds assets/; empty: the build's default
};

/// `lab run`'s options, into `o`.
void describeRun(CommandLine& line, RunOptions& o);

/// `lab help`: every command and what it does.
std::string usage();

}  // namespace lab
