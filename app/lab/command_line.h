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
#include <stdexcept>
#include <string>
#include <vector>

#include "numbers.h"  // kMaxSteps
#include "physics/body.h"
#include "physics/settings.h"

namespace CLI {
class App;
}

namespace lab {

/// One option, everything about it but where its value goes and the command's default.
struct OptionSpec {
  const char* names;  ///< "--steps", or "--methods,--method": the first is the one errors name
  const char* value;  ///< what one value is called in the help ("N", "DIR"); "" for a flag
  /// What it does; "{range}" in it stands for the range below, written from the numbers ("1 to
  /// 1000", "above 0 and at most 3600"), so the help never disagrees with what is refused.
  const char* help;
  double most = 0.0;  ///< a count's or a time's largest value (counts start at 1)
  /// What a missing value should have been ("--dt needs a time step in seconds"); when null, what
  /// the option's type reads ("a whole number", "a folder", "a value (on or off)"...).
  const char* needs = nullptr;
  double least = 0.0;  ///< a time's smallest value, itself allowed unless `aboveLeast`
  bool aboveLeast = false;
};

/// The table: every option any command takes. --iterations, --substeps, --dt and --threads take
/// the physics' ranges (physics/settings.h).
namespace option {
inline constexpr OptionSpec kSteps{"--steps", "N", "steps to run, {range}", kMaxSteps};
inline constexpr OptionSpec kDt{
    "--dt", "S", "seconds per step, {range}", phys::kMaxDt, "a time step in seconds", phys::kMinDt};
inline constexpr OptionSpec kMethods{"--methods,--method", "M", "gauss-seidel, jacobi, xpbd or shake"};
inline constexpr OptionSpec kIterations{"--iterations", "K", "relaxation passes per substep, {range}",
                                        phys::kMaxIterations};
inline constexpr OptionSpec kSubsteps{"--substeps", "S", "integrations per step, {range}",
                                      phys::kMaxSubsteps};
inline constexpr OptionSpec kModels{"--models,--model", "M",
                                    "corners, tetra or rigid, imposed at load on every box and capsule"};
inline constexpr OptionSpec kSleep{"--sleep", "on|off", "whether islands at rest sleep"};
inline constexpr OptionSpec kJointProjection{
    "--joint-projection", "on|off", "whether rigid joints are closed exactly after each substep's passes"};
inline constexpr OptionSpec kPeerSleep{"--peer-sleep", "on|off",
                                       "whether the peers' bodies at rest sleep (Bullet's deactivation)"};
inline constexpr OptionSpec kThreads{"--threads", "N", "threads the step may use, {range}",
                                     phys::kMaxThreads};
// 64 runs at a time is more than any machine this lab runs on has cores for.
inline constexpr OptionSpec kJobs{"--jobs", "N",
                                  "runs of our engine at a time, {range}; above 1 each run's timing is of a "
                                  "core shared with the others",
                                  64};
inline constexpr OptionSpec kRepeat{"--repeat", "R", "timed runs of each setting, {range}; the median counts",
                                    1000};
inline constexpr OptionSpec kJson{"--json", "", "print JSON:"};
inline constexpr OptionSpec kDump{"--dump", "FILE", "write each named body's final pose to FILE as CSV"};
inline constexpr OptionSpec kData{"--data", "DIR", "folder holding assets/ (default: the source tree)"};
inline constexpr OptionSpec kOut{"--out", "DIR", "the folder for"};
inline constexpr OptionSpec kError{
    "--error", "FIGURE",
    "what the chart and the Pareto front measure: position (the distance from the "
    "accuracy target; the default) or a figure of the run table (tracking-error, "
    "joint-error, ...)",
    0.0, "a figure's name"};
inline constexpr OptionSpec kNoPeers{"--no-peers", "", "leave out the peer engines (Bullet, ODE, MuJoCo)"};
inline constexpr OptionSpec kWholeRuns{
    "--whole-runs", "",
    "step every run to its end, failing ones too, for how far each failing run "
    "goes over its whole window"};
inline constexpr OptionSpec kScene{
    "--scene", "NAME...",
    "only these scenes: names in the suite's folder, or scene files (repeatable; "
    "comma-separated lists too)",
    0.0, "a scene name"};
inline constexpr OptionSpec kTarget{"--target", "METRIC=VALUE",
                                    "an upper bound the setting must meet (repeatable)", 0.0, "METRIC=VALUE"};
// 4096 ragdolls, or a pyramid's base: 8.4 million boxes, is beyond any run.
inline constexpr OptionSpec kSizes{"--sizes", "LIST",
                                   "sizes, comma-separated, {range}: ragdolls, or a pyramid's base row", 4096,
                                   "a list of sizes"};
inline constexpr OptionSpec kSaveScenes{"--save-scenes", "DIR",
                                        "also write each size's scene as DIR/KIND-N.xml, for lab run"};
// An hour of a free body is already a long run.
inline constexpr OptionSpec kTime{.names = "--time",
                                  .value = "S",
                                  .help = "horizon of a free-body scene, s, {range}",
                                  .most = 3600.0,
                                  .needs = "a number of seconds",
                                  .aboveLeast = true};
inline constexpr OptionSpec kQuick{
    "--quick", "", "tiny sweeps and one stability scene: checks the pipeline, not the physics"};
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

/// Runs `fileWork` (calls of fileio), saying a fileio::FileError it throws as CommandFailure
/// "OPTION: <why>": how every file the lab writes or checks for an option reports a failure.
void asOptionFailure(const char* option, const std::function<void()>& fileWork);

/// Creates the folder an option names, or throws CommandFailure "OPTION: <why>". Commands that
/// run for minutes call it first, so a folder they cannot write to is said at once.
void prepareOutputFolder(const std::filesystem::path& folder, const char* option = "--out");

/// Throws CommandFailure "OPTION: FILE: <why>" for a file that writeAtomically would refuse before
/// writing (fileio::checkWritable). Commands that write a file at the end of a long run call it first.
void checkOutputFile(const std::filesystem::path& file, const char* option = "--out");

/// Creates the folder (prepareOutputFolder) and holds each FOLDER/NAME of `names` to checkOutputFile.
/// A command calls it before its runs with every file it will write there (output_files.h), so a
/// folder or a device in place of one is said before the work, not after it.
void prepareOutputFiles(const std::filesystem::path& folder, const std::vector<std::string>& names,
                        const char* option = "--out");

/// Throws CommandFailure "OPTION: FOLDER/NAME: is the scene FILE being run; ..." when one of the
/// files a command will write (FOLDER/NAME of `names`) is, by any name, one of the scene files it
/// reads: the output would write over its own input (`lab run --dump` is refused by it too).
void refuseOutputsOverScenes(const std::filesystem::path& folder, const std::vector<std::string>& names,
                             const std::vector<std::filesystem::path>& scenes, const char* option = "--out");

/// Throws CommandFailure "OPTION: FOLDER: <the system's reason>" unless `folder` is an existing
/// folder ("No such file or directory", "Not a directory"). A command that runs others and
/// writes what they print calls it first, so a wrong folder is said before anything runs.
void requireFolder(const std::filesystem::path& folder, const char* option);

/// One command's command line: which options of the table it takes, where their values go, its
/// help. The targets passed in must outlive parse().
class CommandLine {
 public:
  explicit CommandLine(std::string command);
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  /// What the command does, printed under the usage line.
  void about(std::string text) { about_ = std::move(text); }

  // ---- positionals -------------------------------------------------------------------------
  /// The one SCENE, required: a scene file, or a name in <data>/assets/scenes.
  void scene(std::string& into);
  /// Optional positionals called `name`: one, or any number when `many`. `read` takes each
  /// word and returns the error ("unknown KIND 'x'"), or "".
  void positional(const std::string& name, const std::string& help, bool many,
                  std::function<std::string(const std::string&)> read);

  // ---- options, each from the table; `note` goes after the table's help ---------------------
  /// An option read as its target's type: int (a count from 1 to spec.most), double (seconds, in
  /// the spec's range), phys::SolverMethod, phys::BodyModel, bool (on or off) or a path (a file or
  /// folder). A std::optional target is set when the option is given; a std::vector takes
  /// comma-separated lists (LIST): the command's defaults go at the first value given, a second
  /// option adds to the first, and a value given twice counts once.
  template <typename T>
  void option(const OptionSpec& spec, T& into, const std::string& note);
  /// Names of body models; with `ragdollModels`, the ragdoll models (seed, lean) too.
  void models(std::vector<std::string>& into, bool ragdollModels, const std::string& note);
  /// A flag: sets `into` to `value` when given.
  void flag(const OptionSpec& spec, bool& into, bool value, const std::string& note);
  /// Any option whose values the command reads itself: `read` returns the error (without the
  /// option's name), or "". `many`: every word up to the next option is a value.
  void custom(const OptionSpec& spec, bool many, std::function<std::string(const std::string&)> read,
              const std::string& note);
  /// The option must be given; else the error is `why`.
  void require(const OptionSpec& spec, std::string why);
  /// A folder that must exist when given (--data): read as option() reads a path, and held to
  /// requireFolder by requireGivenFolders before the command runs, so a wrong one is said up
  /// front with the system's reason rather than when a run first reads from it.
  void existingFolder(const OptionSpec& spec, std::filesystem::path& into, const std::string& note);
  /// Throws CommandFailure (requireFolder) for the first existingFolder given that is not a folder.
  void requireGivenFolders() const;

  /// Parses the arguments after the command's name; returns the error (one line naming the
  /// argument), or "" when they are good.
  std::string parse(const std::vector<std::string>& args);
  /// `lab CMD --help`.
  std::string help() const;
  const std::string& command() const { return command_; }

 private:
  struct Entry;
  /// `help`: the table's, its range written out, with the command's note.
  void add(const OptionSpec& spec, std::string label, std::string needs, const std::string& help, bool many,
           std::function<std::string(const std::string&)> read);

  /// The words CLI11 gave the positional (none without one).
  std::vector<std::string> positionalWords() const;

  std::string command_;
  std::string about_;
  std::unique_ptr<CLI::App> app_;
  std::vector<Entry> entries_;      // in the order the help lists them
  std::vector<std::string> flags_;  // every spelling of every flag
  std::string positionalName_;
  std::vector<std::pair<std::string, std::string>> required_;                  // option, why
  std::vector<std::pair<std::string, const std::filesystem::path*>> folders_;  // option, its target
};

/// The frame every command runs in: its help on --help (exit 0); a command-line error as
/// "lab: ERROR" and the help (exit 2); else `body`, whose exceptions become one line and exit 1
/// (a scene's LoadError as "file:line: ...", settings the world refused, anything else) or,
/// for a UsageError, the same as a parse error.
int commandMain(CommandLine& line, const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
                const std::function<int()>& body);
/// A command's main (commands.h) made of its options struct, the function that describes them to
/// the command line, `kDescribe(line, options)`, and the one that runs the command, `kRun(options,
/// out, err)`, in the frame above.
template <typename Options, auto kDescribe, auto kRun>
int commandMainOf(CommandLine& line, const std::vector<std::string>& args, std::ostream& out,
                  std::ostream& err) {
  Options options;
  kDescribe(line, options);
  return commandMain(line, args, out, err, [&] { return kRun(options, out, err); });
}

/// The folder holding assets/: `given`, or the source tree set at build time when it is empty.
std::filesystem::path dataDir(const std::filesystem::path& given);
/// A SCENE argument as a file: itself, or NAME.xml in <data>/assets/scenes.
std::filesystem::path sceneFile(const std::string& scene, const std::filesystem::path& dataGiven);

}  // namespace lab
