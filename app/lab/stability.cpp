// lab stability: the suite of scenes where solvers are known to fail (assets/scenes/stability/),
// each run under every setting asked for and in every peer engine, judged against the pass
// criteria in its file (docs/lab.md, "lab stability").
#include <chrono>
#include <filesystem>
#include <mutex>
#include <ostream>

#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include "charts.h"
#include "commands.h"
#include "lab.h"
#include "output_files.h"
#include "peer.h"
#include "progress.h"
#include "stability_options.h"
#include "stability_report.h"
#include "text.h"

namespace lab {
namespace {

/// The heat maps' script and the pictures it draws.
constexpr const char* kHeatMapScript = "stability.gp";
const std::vector<std::string> kHeatMaps{"stability-pass.png", "stability-pass.svg", "stability-error.png",
                                         "stability-error.svg"};

using stability::StabilityOptions;
using stability::SuiteResult;
using stability::SuiteScene;

std::vector<Setting> settingsOf(const StabilityOptions& o) {
  std::vector<Setting> out;
  const std::vector<std::string> models = o.models.empty() ? std::vector<std::string>{""} : o.models;
  for (phys::SolverMethod m : o.methods) {
    for (const std::string& model : models) {
      for (int it : o.iterations) {
        for (int sub : o.substeps) out.push_back(stability::suiteSetting(m, it, sub, model, o.sleep));
      }
    }
  }
  return out;
}

SuiteResult runSuite(const StabilityOptions& o, const std::vector<SuiteScene>& scenes, std::ostream& err) {
  SuiteResult r;
  r.scenes = scenes;
  r.settings = settingsOf(o);
  r.jobs = o.jobs;
  r.wholeRuns = o.wholeRuns;
  // settingsOf lists each method's (and model's) settings together: a block each.
  for (const Setting& s : r.settings) addOnce(r.methods, stability::settingGroup(s));
  if (o.peers) r.peers = peerEngines();
  r.peerNote = !o.peers ? "--no-peers" : "the lab was built without peer engines (LAB_PEERS)";
  const auto start = std::chrono::steady_clock::now();
  const std::size_t ours = r.settings.size(), perScene = ours + r.peers.size();
  r.outcomes.assign(scenes.size(), std::vector<stability::Outcome>(perScene));
  Progress progress(err, "stability", scenes.size() * perScene);
  std::mutex drawing;  // the bar and its counts, shared by the runs' threads
  std::size_t done = 0;
  std::vector<std::size_t> left(scenes.size(), perScene);
  // A run of scene `s` starting, or finished ("... done"): it counts, and a scene with no run left
  // gets a line of its own in a log ("stack-10 done").
  auto show = [&](std::size_t s, const std::string& label, bool finished) {
    const std::lock_guard lock(drawing);
    done += finished ? 1 : 0;
    const bool sceneDone = finished && --left[s] == 0;
    progress.show(done, scenes[s].name + (sceneDone ? "" : " " + label) + (finished ? " done" : ""),
                  sceneDone);
  };
  const auto length = o.wholeRuns ? stability::RunLength::Whole : stability::RunLength::UntilFailed;
  // Each run of ours has a world of its own, so they run --jobs at a time; each outcome goes to
  // its slot, so every output keeps the order of --jobs 1.
  tbb::task_arena(o.jobs).execute([&] {
    tbb::parallel_for(
        std::size_t{0}, scenes.size() * ours,
        [&](std::size_t i) {
          const std::size_t s = i / ours;
          const Setting& setting = r.settings[i % ours];
          show(s, stability::settingLabel(setting), false);
          r.outcomes[s][i % ours] = stability::runSetting(scenes[s], setting, length);
          show(s, stability::settingLabel(setting), true);
        },
        tbb::simple_partitioner());
  });
  // The peers one at a time, after ours: ODE and MuJoCo keep global state.
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    for (std::size_t k = 0; k < r.peers.size(); ++k) {
      show(s, r.peers[k], false);
      r.outcomes[s][ours + k] = stability::runPeerEngine(scenes[s], r.peers[k], o.sleep);
      show(s, r.peers[k], true);
    }
  }
  progress.show(done, "done", true);
  progress.finish();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// The files of --out, written as one set; without gnuplot they are written without the heat maps.
void writeOutputs(const SuiteResult& r, const std::string& md, const std::filesystem::path& dir) {
  OutputFolder files(dir);
  files.write("stability.md", md);
  files.write("stability.csv", stability::csvReport(r));
  files.write("stability-pass.dat", stability::passMatrix(r));
  files.write("stability-error.dat", stability::errorMatrix(r));
  files.write(kHeatMapScript, stability::gnuplotScript(r));
  // Unlike the other commands' charts, heat maps left undrawn for want of gnuplot fail the suite.
  const std::string problem = files.render(kHeatMapScript, kHeatMaps);
  files.commit();
  if (!problem.empty()) throw CommandFailure("stability: the heat maps were not drawn: " + problem);
}

int stabilityCommand(const StabilityOptions& o, std::ostream& out, std::ostream& err) {
  if (!o.out.empty()) {
    refuseOutputsOverScenes(o.out, stabilityFiles(), stability::sceneFiles(o));
    prepareOutputFiles(o.out, stabilityFiles());  // the suite takes minutes: say a bad --out now
  }
  std::vector<SuiteScene> scenes;
  for (const std::filesystem::path& file : stability::sceneFiles(o))
    scenes.push_back(stability::loadSuiteScene(file));
  SuiteResult result;
  try {
    result = runSuite(o, scenes, err);
  } catch (...) {
    err << "\n";  // ends the progress line, so the message has a line of its own
    throw;
  }
  const std::string md = stability::markdownReport(result);
  out << md << std::flush;
  if (!o.out.empty()) writeOutputs(result, md, o.out);
  return kExitOk;
}

}  // namespace

std::vector<std::string> stabilityFiles() {
  std::vector<std::string> files{"stability.md", "stability.csv", "stability-pass.dat", "stability-error.dat",
                                 kHeatMapScript};
  files.insert(files.end(), kHeatMaps.begin(), kHeatMaps.end());
  return files;
}

constinit const CommandMain stabilityMain =
    commandMainOf<StabilityOptions, stability::describeOptions, stabilityCommand>;

}  // namespace lab
