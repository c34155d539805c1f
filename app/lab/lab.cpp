#include "lab.h"

#include <exception>
#include <filesystem>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "commands.h"
#include "fileio/files.h"
#include "report.h"
#include "run.h"
#include "scenes/scene.h"

namespace lab {

int labMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const ParsedCommand parsed = parseCommandLine(args);
  if (!parsed.error.empty()) {
    err << "lab: " << parsed.error << "\n" << usage();
    return kExitUsage;
  }
  switch (parsed.command) {
    case Command::Help:
      out << usage();
      return kExitOk;
    case Command::Run:
      return runCommand(parsed.run, out, err);
    case Command::Sweep:
      return sweepMain(parsed.rest, out, err);
    case Command::Stability:
      return stabilityMain(parsed.rest, out, err);
    case Command::Tune:
      return tuneMain(parsed.rest, out, err);
    case Command::Compare:
      return compareMain(parsed.rest, out, err);
    case Command::Scale:
      return scaleMain(parsed.rest, out, err);
    case Command::Converge:
      return convergeMain(parsed.rest, out, err);
    case Command::Report:
      return reportMain(parsed.rest, out, err);
  }
  return kExitUsage;
}

CommandOutput runCaptured(CommandMain main, const std::vector<std::string>& args) {
  std::ostringstream out;
  std::ostringstream err;
  CommandOutput r;
  r.code = main(args, out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

int runCommand(const RunOptions& options, std::ostream& out, std::ostream& err) {
  // Optional only so the load can sit inside the try; the Scene is moved in, never copied.
  std::optional<scenes::Scene> scene;
  std::filesystem::path file = options.scene;
  try {
    file = scenes::resolveScene(options.scene, scenes::sceneDirectory(dataDir(options)));
    scene.emplace(scenes::loadSceneFile(file, imposedAtLoad(options.model, options.sleep)));
  } catch (const scenes::LoadError& e) {
    err << e.what() << "\n";  // already "file:line: ...", the form editors jump to
    return kExitFailure;
  } catch (const std::exception& e) {
    // The loader promises LoadError only, but resolving a path can throw filesystem_error;
    // either way a message and exit 1, not a crash.
    err << "lab: " << file.string() << ": " << e.what() << "\n";
    return kExitFailure;
  }

  RunResult result;
  try {
    result = runScene(*scene, options, &err);
  } catch (const std::invalid_argument& e) {
    // A combination the world refuses (options.cpp already checked each value's range).
    err << "lab: the overrides were refused: " << e.what() << "\n";
    return kExitFailure;
  }

  out << (options.json ? jsonText(result) : summaryText(result));
  out.flush();
  // The report goes out first, so a long run's figures survive a dump that cannot be written.
  if (options.dump) {
    try {
      fileio::writeAtomically(*options.dump, dumpCsv(scene->world, scene->bodies));
    } catch (const std::exception& e) {
      err << "lab: --dump: " << e.what() << "\n";
      return kExitFailure;
    }
    if (!options.json) {
      out << "dump         " << scene->bodies.size() << " named bodies to " << options.dump->string() << "\n";
    }
  }
  return kExitOk;
}

}  // namespace lab
