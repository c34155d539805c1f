#pragma once
// The lab's command line (docs/lab.md):
//   lab run SCENE [--steps N] [--dt S] [--method M] [--iterations K] [--substeps S]
//                 [--model M] [--sleep on|off] [--threads N] [--json] [--dump FILE] [--data DIR]
//   lab help | lab --help
// Parsing never touches the file system, so every bad argument is caught (exit 2) before a
// scene is loaded or a step is run.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "physics/body.h"
#include "physics/settings.h"

namespace lab {

/// Limits of the numeric options, shared by the parser, the usage text and the tests.
inline constexpr int kMaxSteps = 10000000;
// --iterations, --substeps and --dt take the physics' own ranges (phys::kMaxIterations,
// phys::kMaxSubsteps, phys::kMinDt, phys::kMaxDt in physics/settings.h).
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
  std::optional<int> threads;                 ///< --threads N: SolverSettings::threads (default: the scene's)
  bool json = false;                          ///< one JSON object instead of the summary
  std::optional<std::filesystem::path> dump;  ///< CSV of the named bodies' final poses
  std::filesystem::path dataDir;              ///< holds assets/; empty: the build's default
};

/// The command the arguments name.
enum class Command { Help, Run, Sweep, Stability, Tune, Compare, Scale, Converge, Report };

/// The parser's answer: a command and its options, or an error.
struct ParsedCommand {
  Command command = Command::Help;  ///< meaningless when error is set
  RunOptions run;                   ///< filled for Command::Run
  /// The arguments after the command's name, for the commands that parse their own
  /// (commands.h): sweep, stability, tune, compare, scale, converge, report.
  std::vector<std::string> rest;
  std::string error;  ///< empty on success; otherwise one line naming the bad argument
};

/// Parses the arguments after the program name.
ParsedCommand parseCommandLine(const std::vector<std::string>& args);
/// The usage text printed by help and after a command-line error.
std::string usage();
/// The folder holding assets/: options.dataDir, or the source tree set at build time.
std::filesystem::path dataDir(const RunOptions& options);

// ---- pieces of the parsers: run's here, and sweep's, tune's and stability's (commands.h) -----
// Shared so that every command reads a value, a count and a SCENE alike and words the same
// mistake the same way.

/// "--help" or "-h" anywhere: help wins wherever it is, so "lab run x --help" shows the usage
/// instead of running.
bool asksForHelp(const std::vector<std::string>& args);

/// The value of the option at args[i], stepping i onto it; nullptr when there is none. A
/// following "--word" is taken as a forgotten value, not as a file called "--json".
const std::string* optionValue(const std::vector<std::string>& args, std::size_t& i);

/// "OPTION: 'TEXT' is not a whole number from 1 to HIGH".
std::string notWholeNumber(const std::string& option, const std::string& text, int high);

/// A count option's value (--steps N, --repeat N) from 1 to high into `into`. Returns the
/// error, "OPTION needs a whole number" when `value` is nullptr or notWholeNumber's, or "".
std::string parseCountOption(const std::string& option, const std::string* value, int high, int& into);

/// An on/off option's value (--sleep on|off) into `into`. Returns the error, "OPTION needs a value
/// (on or off)" when `value` is nullptr or "OPTION: 'TEXT' is not on or off", or "".
std::string parseOnOffOption(const std::string& option, const std::string* value, bool& into);

/// The options every command that steps a scene shares: --steps, --iterations, --substeps and
/// --method at args[i], into `o` (stepping i onto the value). nullopt when args[i] is none of
/// them; else the error, or "" when the value was good.
std::optional<std::string> parseSolverOption(const std::vector<std::string>& args, std::size_t& i,
                                             RunOptions& o);
/// --model M at args[i] (stepping i onto the value): corners, tetra or rigid into `model`.
/// Returns the error, or "".
std::string parseModelOption(const std::vector<std::string>& args, std::size_t& i,
                             std::optional<phys::BodyModel>& model);
/// A time step from phys::kMinDt to phys::kMaxDt seconds, nothing else.
std::optional<double> parseDt(const std::string& text);

/// The one SCENE of `lab COMMAND SCENE [options]`: stores `arg` in `scene` and returns "", or
/// returns the error (an unknown option, or a second SCENE).
std::string sceneArgument(const std::string& command, const std::string& arg, std::string& scene);
/// "COMMAND needs a SCENE (...)", for a command line without one.
std::string missingScene(const std::string& command);

}  // namespace lab
