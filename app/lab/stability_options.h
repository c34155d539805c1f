#pragma once
// The command line of `lab stability` (docs/lab.md, "lab stability"), and which scene files it
// names.
#include <filesystem>
#include <string>
#include <vector>

#include "command_line.h"
#include "physics/settings.h"

namespace lab::stability {

/// What `lab stability` was asked to do.
struct StabilityOptions {
  std::filesystem::path out;  ///< empty: the report on stdout only
  std::vector<phys::SolverMethod> methods{phys::SolverMethod::GaussSeidel, phys::SolverMethod::Jacobi,
                                          phys::SolverMethod::Xpbd, phys::SolverMethod::Shake};
  std::vector<int> iterations{1, 3, 10};
  std::vector<int> substeps{1, 4, 16};
  /// corners, tetra or rigid imposed on every box and ragdoll (Setting::model); empty: the files'
  std::vector<std::string> models;
  std::vector<std::string> scenes;  ///< as given to --scene; empty: the whole suite
  bool peers = true;
  int jobs = 1;        ///< our runs at a time (--jobs); the peers run one at a time whatever it says
  bool sleep = false;  ///< --sleep on: islands at rest sleep, ours and the peers' (Bullet's deactivation)
  /// --whole-runs: every run of ours to its end; else a run stops once it has failed for good
  /// (stability_run.h, RunLength)
  bool wholeRuns = false;
  std::filesystem::path dataDir;  ///< holds assets/; empty: the build's default
};

/// `lab stability`'s options, into `options`.
void describeOptions(CommandLine& line, StabilityOptions& options);

/// "stack-10" < "stack-20" < "stack-100": runs of digits compare as numbers, so the suite's
/// files sort by size. glibc's strverscmp, which reads a run with leading zeros as a fraction
/// ("a-01" before "a-1"; no name of the suite has one).
bool naturalLess(const std::string& a, const std::string& b);

/// The scene files to run: each --scene name (a file, or NAME.xml in the suite's folder
/// <data>/assets/scenes/stability), else every .xml of that folder in natural order. Throws
/// std::runtime_error naming what is missing.
std::vector<std::filesystem::path> sceneFiles(const StabilityOptions& options);

}  // namespace lab::stability
