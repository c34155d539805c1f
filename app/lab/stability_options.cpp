#include "stability_options.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "scenes/scene.h"
#include "text.h"

namespace lab::stability {

void describeOptions(CommandLine& line, StabilityOptions& o) {
  line.about(
      "Runs every scene of <data>/assets/scenes/stability under every method x model x iterations\n"
      "x substeps, and in each peer engine, and judges each run by the scene's <expect kind=\"pass\">.");
  line.option(
      option::kOut, o.out,
      "stability.md, .csv, .gp and the heat maps stability-pass.png/.svg and stability-error.png/.svg "
      "(default: the report on stdout alone)");
  line.option(option::kMethods, o.methods, "(default: all four)");
  line.option(option::kIterations, o.iterations, "(default 1,3,10)");
  line.option(option::kSubsteps, o.substeps, "(default 1,4,16)");
  line.models(o.models, false,
              "(ragdolls take their kind's: corners seed, tetra lean; default: each file's own)");
  line.custom(
      option::kScene, true,
      [&o](const std::string& text) {
        const std::optional<std::vector<std::string>> names = splitList(text);
        if (!names) return "an empty name in '" + text + "'";
        for (const std::string& name : *names) addOnce(o.scenes, name);  // a scene listed twice runs once
        return std::string();
      },
      "");
  line.option(option::kSleep, o.sleep, "(ours and the peers'; default off, whatever the scene says)");
  line.flag(option::kNoPeers, o.peers, false, "");
  line.option(option::kJobs, o.jobs, "(default 1; the peers run one at a time)");
  line.flag(option::kWholeRuns, o.wholeRuns, true,
            "(default: a run of ours stops once a criterion is past its limit for good)");
  line.existingFolder(option::kData, o.dataDir, "");
}

bool naturalLess(const std::string& a, const std::string& b) {
  return ::strverscmp(a.c_str(), b.c_str()) < 0;  // glibc's version order: digit runs by value
}

std::vector<std::filesystem::path> sceneFiles(const StabilityOptions& o) {
  const std::filesystem::path folder = scenes::sceneDirectory(dataDir(o.dataDir)) / "stability";
  std::vector<std::filesystem::path> files;
  if (!o.scenes.empty()) {
    for (const std::string& name : o.scenes) {
      const std::filesystem::path file = scenes::resolveScene(name, folder);
      std::error_code ec;
      const std::filesystem::file_status status = std::filesystem::status(file, ec);
      // Nothing there is "no scene"; a path that cannot be looked at says the system's reason.
      if (ec && status.type() != std::filesystem::file_type::not_found)
        throw std::runtime_error("--scene: " + file.string() + ": cannot open: " + ec.message());
      if (std::filesystem::is_directory(status))
        throw std::runtime_error("--scene: " + file.string() + ": is a folder, not a scene file");
      if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
        throw std::runtime_error("--scene: " + file.string() + ": is not a regular file");
      if (!std::filesystem::is_regular_file(status)) {
        throw std::runtime_error("--scene: no scene '" + name + "' (looked for " + file.string() + ")");
      }
      files.push_back(file);
    }
    return files;
  }
  if (!std::filesystem::is_directory(folder))
    throw std::runtime_error("no stability suite at " + folder.string());
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.is_regular_file() && entry.path().extension() == ".xml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end(),
            [](const auto& a, const auto& b) { return naturalLess(a.stem().string(), b.stem().string()); });
  if (files.empty()) throw std::runtime_error("no scene files in " + folder.string());
  return files;
}

}  // namespace lab::stability
