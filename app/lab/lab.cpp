#include "lab.h"

#include <filesystem>
#include <ostream>
#include <sstream>
#include <string>
#include <system_error>

#include "commands.h"
#include "fileio/files.h"
#include "report.h"
#include "run.h"
#include "scenes/scene.h"

namespace lab {
namespace {

// Refuses, as CommandFailure "--dump: ...", what makes a dump unwritable that can be told before
// the run: the scene itself there (by any name), its folder missing (requireFolder), or anything
// writeAtomically would refuse before writing (checkOutputFile: a folder or a device in its place,
// a folder it cannot create a file in). Only a full disk is found out after.
void checkDump(const std::filesystem::path& file, const std::filesystem::path& scene) {
  refuseOutputsOverScenes(file.parent_path(), {file.filename().string()}, {scene}, "--dump");
  requireFolder(file.parent_path().empty() ? "." : file.parent_path(), "--dump");
  checkOutputFile(file, "--dump");
}

// Load, override, step, report, dump.
int runCommand(const RunOptions& options, std::ostream& out, std::ostream& err) {
  if (options.dump) checkDump(*options.dump, sceneFile(options.scene, options.dataDir));
  scenes::Scene scene =
      scenes::loadSceneFile(sceneFile(options.scene, options.dataDir),
                            imposedAtLoad(options.model, options.sleep, options.jointProjection));
  const RunResult result = runScene(scene, options, &err);
  out << (options.json ? jsonText(result) : summaryText(result));
  out.flush();
  // The report goes out first, so a long run's figures survive a dump that cannot be written.
  if (options.dump) {
    asOptionFailure("--dump",
                    [&] { fileio::writeAtomically(*options.dump, dumpCsv(scene.world, scene.bodies)); });
    if (!options.json) {
      out << "dump         " << scene.bodies.size() << " named bodies to " << options.dump->string() << "\n";
    }
  }
  return kExitOk;
}

struct CommandEntry {
  const char* name;
  const char* arguments;  // what `lab help` shows after the name
  const char* summary;
  // The address of the command's main, defined (constinit) in the command's own file: its value
  // is not a constant here, its address is.
  const CommandMain* main;
};

constexpr CommandEntry kCommands[] = {
    {"run", "SCENE", "steps a scene and reports its figures", &runMain},
    {"sweep", "SCENE --out DIR", "speed against accuracy over settings", &sweepMain},
    {"stability", "", "where each method fails", &stabilityMain},
    {"tune", "SCENE --target M=V", "the cheapest settings that meet targets", &tuneMain},
    {"compare", "SCENE", "our methods beside Bullet, ODE and MuJoCo", &compareMain},
    {"scale", "[KIND]", "cost per body against the scene's size", &scaleMain},
    {"converge", "[SCENE...]", "error against substep size: each method's order", &convergeMain},
    {"report", "", "docs/results.md and its charts", &reportMain},
};

std::string commandNames() {
  std::string names;
  for (const CommandEntry& c : kCommands) names += std::string(c.name) + ", ";
  return names.substr(0, names.size() - 2) + " or help";
}

}  // namespace

std::string usage() {
  std::string text = "usage: lab COMMAND [options]   (lab COMMAND --help lists a command's options)\n";
  for (const CommandEntry& c : kCommands) {
    const std::string head = std::string("  ") + c.name + " " + c.arguments;
    text += printed("%-29s %s\n", head.c_str(), c.summary);
  }
  return text + "  help                        this text\n";
}

int labMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  if (args.empty()) {
    err << "lab: no command (" << commandNames() << ")\n" << usage();
    return kExitUsage;
  }
  const std::string& name = args[0];
  if (name == "help" || name == "--help" || name == "-h") {
    out << usage();
    return kExitOk;
  }
  for (const CommandEntry& c : kCommands) {
    if (name != c.name) continue;
    CommandLine line(c.name);
    return (*c.main)(line, {args.begin() + 1, args.end()}, out, err);
  }
  err << "lab: unknown command '" << name << "' (" << commandNames() << ")\n" << usage();
  return kExitUsage;
}

constinit const CommandMain runMain = commandMainOf<RunOptions, describeRun, runCommand>;

CommandOutput runCaptured(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int code = labMain(args, out, err);
  return {code, out.str(), err.str()};
}

CommandOutput runCaptured(const std::string& command, std::vector<std::string> args) {
  args.insert(args.begin(), command);
  return runCaptured(args);
}

}  // namespace lab
