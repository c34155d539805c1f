#pragma once
// The lab's command lines. Every option of every command is defined once, in `option` below
// (its name, its value, its range, its help); a command says which ones it takes and where each
// value goes, CLI11 splits the arguments, and the values are read and refused here in one
// wording. `lab CMD --help` is generated from the same definitions, and every command's main
// runs in the one frame, commandMain. Parsing never touches the file system, so every bad
// argument is refused (exit 2) before a scene is loaded or a step is run. docs/lab.md lists the
// options.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/body.h"
#include "physics/settings.h"

namespace CLI {
class App;
}

namespace lab {

// The ranges of the lab's own counts; --iterations, --substeps, --dt and --threads take the
// physics' (physics/settings.h).
inline constexpr int kMaxSteps = 10000000;
inline constexpr int kMaxRepeats = 1000;

/// One option, everything about it but where its value goes and the command's default.
struct OptionSpec {
  const char* names;  ///< "--steps", or "--methods,--method": the first is the one errors name
  const char* value;  ///< what one value is called in the help ("N", "DIR"); "" for a flag
  const char* needs;  ///< what a missing value should have been: "--steps needs a whole number"
  const char* help;   ///< what it does, with its range
};

/// The table: every option any command takes.
namespace option {
inline constexpr OptionSpec kSteps{"--steps", "N", "a whole number", "steps to run, 1 to 10000000"};
inline constexpr OptionSpec kDt{"--dt", "S", "a time step in seconds", "seconds per step, 1e-06 to 1"};
inline constexpr OptionSpec kMethods{"--methods,--method", "M",
                                     "a method (gauss-seidel, jacobi, xpbd or shake)",
                                     "gauss-seidel, jacobi, xpbd or shake"};
inline constexpr OptionSpec kIterations{"--iterations", "K", "a whole number",
                                        "relaxation passes per substep, 1 to 1000"};
inline constexpr OptionSpec kSubsteps{"--substeps", "S", "a whole number",
                                      "integrations per step, 1 to 1000"};
inline constexpr OptionSpec kModels{"--models,--model", "M", "a body model (corners, tetra or rigid)",
                                    "corners, tetra or rigid, imposed at load on every box and capsule"};
inline constexpr OptionSpec kSleep{"--sleep", "on|off", "a value (on or off)",
                                   "whether islands at rest sleep"};
inline constexpr OptionSpec kJointProjection{
    "--joint-projection", "on|off", "a value (on or off)",
    "whether rigid joints are closed exactly after each substep's passes"};
inline constexpr OptionSpec kPeerSleep{"--peer-sleep", "on|off", "a value (on or off)",
                                       "whether the peers' bodies at rest sleep (Bullet's deactivation)"};
inline constexpr OptionSpec kThreads{"--threads", "N", "a whole number", "threads the step may use, 1 to 64"};
inline constexpr OptionSpec kRepeat{"--repeat", "R", "a whole number",
                                    "timed runs of each setting, 1 to 1000; the median counts"};
inline constexpr OptionSpec kJson{"--json", "", "", "print JSON:"};
inline constexpr OptionSpec kDump{"--dump", "FILE", "a file name",
                                  "write each named body's final pose to FILE as CSV"};
inline constexpr OptionSpec kData{"--data", "DIR", "a folder",
                                  "folder holding assets/ (default: the source tree)"};
inline constexpr OptionSpec kOut{"--out", "DIR", "a folder", "the folder for"};
inline constexpr OptionSpec kError{"--error", "FIGURE", "a figure's name",
                                   "what the chart and the Pareto front measure: position (the distance "
                                   "from the accuracy target; the default) or a figure of the run table "
                                   "(tracking-error, joint-error, ...)"};
inline constexpr OptionSpec kNoPeers{"--no-peers", "", "",
                                     "leave out the peer engines (Bullet, ODE, MuJoCo)"};
inline constexpr OptionSpec kScene{"--scene", "NAME...", "a scene name",
                                   "only these scenes: names in the suite's folder, or scene files "
                                   "(repeatable; comma-separated lists too)"};
inline constexpr OptionSpec kTarget{"--target", "METRIC=VALUE", "METRIC=VALUE",
                                    "an upper bound the setting must meet (repeatable)"};
inline constexpr OptionSpec kSizes{"--sizes", "LIST", "a list of sizes",
                                   "sizes, comma-separated, 1 to 4096: ragdolls, or a pyramid's base row"};
inline constexpr OptionSpec kSaveScenes{"--save-scenes", "DIR", "a folder",
                                        "also write each size's scene as DIR/KIND-N.xml, for lab run"};
inline constexpr OptionSpec kTime{"--time", "S", "a number of seconds",
                                  "horizon of a free-body scene, s, above 0 and at most 3600"};
inline constexpr OptionSpec kQuick{
    "--quick", "", "", "tiny sweeps and one stability scene: checks the pipeline, not the physics"};
}  // namespace option

/// A mistake on the command line found after parsing (a --model the scene has no body for):
/// commandMain words it like a parse error, exit 2 with the help.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A failure that is already worded (exit 1): commandMain prints "lab: " and the message alone.
class CommandFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Creates the folder an option names, or throws CommandFailure "OPTION: <why>". Commands that
/// run for minutes call it first, so a folder they cannot write to is said at once.
void prepareOutputFolder(const std::filesystem::path& folder, const char* option = "--out");

/// One command's command line: which options of the table it takes, where their values go, its
/// help. The targets passed in must outlive parse().
class CommandLine {
 public:
  /// `about`: what the command does, printed under the usage line.
  CommandLine(std::string command, std::string about);
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  // ---- positionals -------------------------------------------------------------------------
  /// The one SCENE, required: a scene file, or a name in <data>/assets/scenes.
  void scene(std::string& into);
  /// Optional positionals called `name`: one, or any number when `many`. `read` takes each
  /// word and returns the error ("unknown KIND 'x'"), or "".
  void positional(const std::string& name, const std::string& help, bool many,
                  std::function<std::string(const std::string&)> read);

  // ---- options, each from the table; `note` goes after the table's help ---------------------
  void count(const OptionSpec& spec, int high, int& into, const std::string& note);
  void count(const OptionSpec& spec, int high, std::optional<int>& into, const std::string& note);
  /// A comma-separated list of counts; a value listed twice counts once.
  void counts(const OptionSpec& spec, int high, std::vector<int>& into, const std::string& note);
  void dt(std::optional<double>& into, const std::string& note);
  void dts(std::vector<double>& into, const std::string& note);
  void method(std::optional<phys::SolverMethod>& into, const std::string& note);
  void methods(std::vector<phys::SolverMethod>& into, const std::string& note);
  void model(std::optional<phys::BodyModel>& into, const std::string& note);
  /// Names of body models; with `ragdollModels`, the ragdoll models (seed, lean) too.
  void models(std::vector<std::string>& into, bool ragdollModels, const std::string& note);
  void onOff(const OptionSpec& spec, bool& into, const std::string& note);
  void onOff(const OptionSpec& spec, std::optional<bool>& into, const std::string& note);
  /// A flag: sets `into` to `value` when given.
  void flag(const OptionSpec& spec, bool& into, bool value, const std::string& note);
  void folder(const OptionSpec& spec, std::filesystem::path& into, const std::string& note);
  void folder(const OptionSpec& spec, std::optional<std::filesystem::path>& into, const std::string& note);
  void file(const OptionSpec& spec, std::optional<std::filesystem::path>& into, const std::string& note);
  /// A number from above `low` to `high`, with its unit in the message.
  void seconds(const OptionSpec& spec, double low, double high, double& into, const std::string& note);
  /// Any option whose values the command reads itself: `read` returns the error (without the
  /// option's name), or "". `many`: every word up to the next option is a value.
  void custom(const OptionSpec& spec, bool many, std::function<std::string(const std::string&)> read,
              const std::string& note);
  /// The option must be given; else the error is `why`.
  void require(const OptionSpec& spec, std::string why);

  /// Parses the arguments after the command's name; returns the error (one line naming the
  /// argument), or "" when they are good.
  std::string parse(const std::vector<std::string>& args);
  /// `lab CMD --help`.
  std::string help() const;
  const std::string& command() const { return command_; }

 private:
  struct Entry;
  void add(const OptionSpec& spec, std::string label, const std::string& note, bool many,
           std::function<std::string(const std::string&)> read);

  /// The words CLI11 gave the positional (none without one).
  std::vector<std::string> positionalWords() const;

  std::string command_;
  std::string about_;
  std::unique_ptr<CLI::App> app_;
  std::vector<Entry> entries_;  // in the order the help lists them
  std::string positionalName_;
  std::vector<std::pair<std::string, std::string>> required_;  // option, why
};

/// "--help" or "-h" anywhere: help wins wherever it is, so "lab run x --help" shows the help
/// instead of running.
bool asksForHelp(const std::vector<std::string>& args);

/// The frame every command runs in: its help on --help (exit 0); a command-line error as
/// "lab: ERROR" and the help (exit 2); else `body`, whose exceptions become one line and exit 1
/// (a scene's LoadError as "file:line: ...", settings the world refused, anything else) or,
/// for a UsageError, the same as a parse error.
int commandMain(CommandLine& line, const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
                const std::function<int()>& body);

/// The folder holding assets/: `given`, or the source tree set at build time when it is empty.
std::filesystem::path dataDir(const std::filesystem::path& given);
/// A SCENE argument as a file: itself, or NAME.xml in <data>/assets/scenes.
std::filesystem::path sceneFile(const std::string& scene, const std::filesystem::path& dataGiven);

}  // namespace lab
