#include "options.h"

#include <algorithm>
#include <string_view>
#include <utility>

#include "numbers.h"

namespace lab {
namespace {

// Everything after "run". Returns the error, or "" when the options are good.
std::string parseRun(const std::vector<std::string>& args, std::size_t first, RunOptions& o) {
  for (std::size_t i = first; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&] { return optionValue(args, i); };
    auto missing = [&](const char* what) { return a + " needs " + what; };
    if (std::optional<std::string> solverError = parseSolverOption(args, i, o)) {
      if (!solverError->empty()) return *solverError;
    } else if (a == "--dt") {
      const std::string* v = value();
      if (v == nullptr) return missing("a time step in seconds");
      o.dt = parseDt(*v);
      if (!o.dt) return a + ": '" + *v + "' is not a number of seconds from 1e-06 to 1";
    } else if (a == "--model") {
      if (std::string e = parseModelOption(args, i, o.model); !e.empty()) return e;
    } else if (a == "--sleep") {
      if (std::string e = parseOnOffOption(a, value(), o.sleep); !e.empty()) return e;
    } else if (a == "--threads") {
      int n = 0;
      if (std::string e = parseCountOption(a, value(), phys::kMaxThreads, n); !e.empty()) return e;
      o.threads = n;
    } else if (a == "--json") {
      o.json = true;
    } else if (a == "--dump") {
      const std::string* v = value();
      if (v == nullptr) return missing("a file name");
      if (v->empty()) return a + ": the file name is empty";
      o.dump = *v;
    } else if (a == "--data") {
      const std::string* v = value();
      if (v == nullptr) return missing("a folder");
      o.dataDir = *v;
    } else if (std::string e = sceneArgument("run", a, o.scene); !e.empty()) {
      return e;
    }
  }
  if (o.scene.empty()) return missingScene("run");
  return {};
}

}  // namespace

std::optional<std::string> parseSolverOption(const std::vector<std::string>& args, std::size_t& i,
                                             RunOptions& o) {
  const std::string& a = args[i];
  if (a == "--steps" || a == "--iterations" || a == "--substeps") {
    const int high = a == "--steps"        ? kMaxSteps
                     : a == "--iterations" ? phys::kMaxIterations
                                           : phys::kMaxSubsteps;
    int n = 0;
    if (std::string e = parseCountOption(a, optionValue(args, i), high, n); !e.empty()) return e;
    if (a == "--steps")
      o.steps = n;
    else if (a == "--iterations")
      o.iterations = n;
    else
      o.substeps = n;
    return std::string();
  }
  if (a == "--method") {
    const std::string* v = optionValue(args, i);
    if (v == nullptr) return a + " needs a method (gauss-seidel, jacobi, xpbd or shake)";
    o.method = phys::parseSolverMethod(*v);
    if (!o.method) return a + ": unknown method '" + *v + "' (gauss-seidel, jacobi, xpbd or shake)";
    return std::string();
  }
  return std::nullopt;
}

std::string usage() {
  return "usage: lab run SCENE [--steps N] [--dt S] [--method M] [--iterations K] [--substeps S]\n"
         "                     [--model M] [--sleep on|off] [--threads N] [--json] [--dump FILE]\n"
         "                     [--data DIR]\n"
         "       lab sweep SCENE ... --out DIR     speed against accuracy over settings\n"
         "       lab stability [--out DIR]         where each method fails\n"
         "       lab tune SCENE --target M=V ...   the cheapest settings that meet targets\n"
         "       lab compare SCENE                 our methods beside Bullet, ODE and MuJoCo\n"
         "       lab scale [KIND] ...              cost per body against the scene's size\n"
         "       lab converge [SCENE...]           error against substep size: each method's order\n"
         "       lab report [--out DIR]            docs/results.md and its charts\n"
         "       lab help                          (each command takes --help)\n"
         "  SCENE           a scene file, or a name in <data>/assets/scenes (NAME.xml)\n"
         "  --steps N       steps to run, 1 to 10000000 (default 600)\n"
         "  --dt S          seconds per step, 1e-06 to 1 (default: the scene's)\n"
         "  --method M      gauss-seidel, jacobi, xpbd or shake (default: the scene's)\n"
         "  --iterations K  relaxation passes per substep, 1 to 1000 (default: the scene's)\n"
         "  --substeps S    integrations per step, 1 to 1000 (default: the scene's)\n"
         "  --model M       corners, tetra or rigid: imposed on every box and capsule of the scene\n"
         "                  (rigid on ragdolls too; a rigid body is solved by XPBD whatever --method)\n"
         "  --sleep on|off  whether islands at rest sleep (default off, whatever the scene says)\n"
         "  --threads N     threads the step may use, 1 to 64 (default: the scene's, else 1)\n"
         "  --json          print one JSON object instead of the summary\n"
         "  --dump FILE     write each named body's final pose to FILE as CSV\n"
         "  --data DIR      folder holding assets/ (default: the source tree)\n"
         "  --help          show this text\n";
}

ParsedCommand parseCommandLine(const std::vector<std::string>& args) {
  ParsedCommand out;
  // The commands with options of their own parse them (and their --help) themselves.
  static constexpr std::pair<std::string_view, Command> kOwnParsers[] = {
      {"sweep", Command::Sweep},     {"stability", Command::Stability}, {"tune", Command::Tune},
      {"compare", Command::Compare}, {"scale", Command::Scale},         {"converge", Command::Converge},
      {"report", Command::Report}};
  for (const auto& [name, command] : kOwnParsers) {
    if (!args.empty() && args[0] == name) {
      out.command = command;
      out.rest.assign(args.begin() + 1, args.end());
      return out;
    }
  }
  if (asksForHelp(args)) return out;
  if (args.empty()) {
    out.error = "no command (run, sweep, stability, tune, compare, scale, converge, report or help)";
  } else if (args[0] == "help") {
    out.command = Command::Help;
  } else if (args[0] == "run") {
    out.command = Command::Run;
    out.error = parseRun(args, 1, out.run);
  } else {
    out.error = "unknown command '" + args[0] +
                "' (run, sweep, stability, tune, compare, scale, converge, report or help)";
  }
  return out;
}

std::filesystem::path dataDir(const RunOptions& options) {
  return options.dataDir.empty() ? std::filesystem::path(LAB_DATA_DIR) : options.dataDir;
}

bool asksForHelp(const std::vector<std::string>& args) {
  return std::any_of(args.begin(), args.end(),
                     [](const std::string& a) { return a == "--help" || a == "-h"; });
}

const std::string* optionValue(const std::vector<std::string>& args, std::size_t& i) {
  if (i + 1 >= args.size() || args[i + 1].starts_with("--")) return nullptr;
  return &args[++i];
}

std::string notWholeNumber(const std::string& option, const std::string& text, int high) {
  return option + ": '" + text + "' is not a whole number from 1 to " + std::to_string(high);
}

std::string parseCountOption(const std::string& option, const std::string* value, int high, int& into) {
  if (value == nullptr) return option + " needs a whole number";
  const std::optional<int> n = parseWholeNumber(*value, 1, high);
  if (!n) return notWholeNumber(option, *value, high);
  into = *n;
  return {};
}

std::string parseOnOffOption(const std::string& option, const std::string* value, bool& into) {
  if (value == nullptr) return option + " needs a value (on or off)";
  if (*value != "on" && *value != "off") return option + ": '" + *value + "' is not on or off";
  into = *value == "on";
  return {};
}

std::string parseModelOption(const std::vector<std::string>& args, std::size_t& i,
                             std::optional<phys::BodyModel>& model) {
  const std::string& option = args[i];
  const std::string* v = optionValue(args, i);
  if (v == nullptr) return option + " needs a body model (corners, tetra or rigid)";
  model = phys::parseBodyModel(*v);
  if (!model) return option + ": unknown model '" + *v + "' (corners, tetra or rigid)";
  return {};
}

std::optional<double> parseDt(const std::string& text) {
  const std::optional<double> v = parseNumber(text);
  if (!v || !(*v >= phys::kMinDt && *v <= phys::kMaxDt)) return std::nullopt;
  return v;
}

std::string sceneArgument(const std::string& command, const std::string& arg, std::string& scene) {
  if (arg.size() > 1 && arg[0] == '-') return "unknown option '" + arg + "'";
  if (!scene.empty()) return command + " takes one SCENE; got '" + scene + "' and '" + arg + "'";
  scene = arg;
  return {};
}

std::string missingScene(const std::string& command) {
  return command + " needs a SCENE (a scene file, or a name in <data>/assets/scenes)";
}

}  // namespace lab
