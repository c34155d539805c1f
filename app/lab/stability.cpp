// lab stability: the suite of scenes where solvers are known to fail (assets/scenes/stability/),
// each run under every setting asked for and in every peer engine, judged against the pass
// criteria in its file (docs/lab.md, "lab stability").
#include <chrono>
#include <exception>
#include <filesystem>
#include <ostream>
#include <utility>

#include "charts.h"
#include "commands.h"
#include "gnuplot.h"
#include "lab.h"
#include "options.h"
#include "peer.h"
#include "progress.h"
#include "report.h"
#include "stability_options.h"
#include "stability_report.h"
#include "text.h"

namespace lab {
namespace {

using stability::Setting;
using stability::StabilityOptions;
using stability::SuiteResult;
using stability::SuiteScene;

std::vector<Setting> settingsOf(const StabilityOptions& o) {
  std::vector<Setting> out;
  const std::vector<std::string> models = o.models.empty() ? std::vector<std::string>{""} : o.models;
  for (phys::SolverMethod m : o.methods) {
    for (const std::string& model : models) {
      for (int it : o.iterations) {
        for (int sub : o.substeps) out.push_back({m, it, sub, model, o.sleep});
      }
    }
  }
  return out;
}

SuiteResult runSuite(const StabilityOptions& o, const std::vector<SuiteScene>& scenes, std::ostream& err) {
  SuiteResult r;
  r.scenes = scenes;
  r.settings = settingsOf(o);
  // settingsOf lists each method's (and model's) settings together: a block each.
  for (const Setting& s : r.settings) addOnce(r.methods, stability::settingGroup(s));
  if (o.peers) r.peers = peerEngines();
  r.peerNote = !o.peers ? "--no-peers" : "the lab was built without peer engines (LAB_PEERS)";
  const auto start = std::chrono::steady_clock::now();
  Progress progress(err, "stability", scenes.size() * (r.settings.size() + r.peers.size()));
  std::size_t done = 0;
  for (const SuiteScene& s : scenes) {
    std::vector<stability::Outcome> row;
    const bool first = done == 0;
    for (const Setting& setting : r.settings) {
      progress.show(done++, s.name + " " + stability::settingLabel(setting), row.empty() && !first);
      row.push_back(stability::runSetting(s, setting));
    }
    for (const std::string& peer : r.peers) {
      progress.show(done++, s.name + " " + peer, false);
      row.push_back(stability::runPeerEngine(s, peer, o.sleep));
    }
    r.outcomes.push_back(std::move(row));
  }
  progress.show(done, "done", true);
  progress.finish();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// The files of --out, written as one set; without gnuplot they are written without the heat maps.
int writeOutputs(const SuiteResult& r, const std::string& md, const std::filesystem::path& dir,
                 std::ostream& err) {
  OutputFolder files(dir);
  files.write("stability.md", md);
  files.write("stability.csv", stability::csvReport(r));
  files.write("stability-pass.dat", stability::passMatrix(r));
  files.write("stability-error.dat", stability::errorMatrix(r));
  files.write("stability.gp", stability::gnuplotScript(r));
  // Unlike the other commands' charts, heat maps left undrawn for want of gnuplot fail the suite.
  const std::string problem = files.render("stability.gp", {"stability-pass.png", "stability-pass.svg",
                                                            "stability-error.png", "stability-error.svg"});
  files.commit();
  if (!problem.empty()) {
    err << "lab: stability: the heat maps were not drawn: " << problem << "\n";
    return kExitFailure;
  }
  return kExitOk;
}

int stabilityCommand(const StabilityOptions& o, std::ostream& out, std::ostream& err) {
  if (!o.out.empty()) prepareOutputFolder(o.out);  // the suite takes minutes: say a bad --out now
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
  return o.out.empty() ? kExitOk : writeOutputs(result, md, o.out, err);
}

}  // namespace

constinit const CommandMain stabilityMain =
    commandMainOf<StabilityOptions, stability::describeOptions, stabilityCommand>;

}  // namespace lab
