#include "stability_run.h"
#include "text.h"

#include <optional>

#include "peer.h"
#include "physics/ragdoll.h"
#include "runner.h"
#include "scenes/scene.h"
#include "sweep_core.h"

namespace lab::stability {
namespace {

// Fills judged, passed and worst from the verdicts.
void summarize(Outcome& o) {
  o.judged = false;
  o.passed = true;
  for (std::size_t i = 0; i < o.verdicts.size(); ++i) {
    const Verdict& v = o.verdicts[i];
    if (!v.judged) continue;
    if (!o.judged || !(v.ratio <= o.verdicts[o.worst].ratio)) o.worst = i;
    o.judged = true;
    o.passed = o.passed && v.passed;
  }
  o.passed = o.passed && o.judged;
}

}  // namespace

SuiteScene loadSuiteScene(const std::filesystem::path& file) {
  SuiteScene s;
  s.source = scenes::readSceneSource(file);
  const scenes::Scene scene = scenes::loadSceneSource(s.source);
  s.name = file.stem().string();
  s.description = scene.description;
  s.criteria = parseCriteria(scene);
  s.steps = runSteps(s.criteria);
  s.dt = scene.world.solverSettings().dt;
  s.boxes = scene.world.bodies().size();
  return s;
}

Setting suiteSetting(phys::SolverMethod method, int iterations, int substeps, const std::string& model,
                     bool sleep) {
  // A box model and the ragdolls' of the same kind: corners and seed, tetra and lean, rigid.
  scenes::LoadOptions load{.sleep = sleep};
  if (const std::optional<phys::BodyModel> box = phys::parseBodyModel(model)) {
    load.boxModel = *box;
    load.ragdollModel = phys::ragdollModelOf(*box);
  }
  return {.model = {model, load}, .method = method, .iterations = iterations, .substeps = substeps};
}

std::string settingLabel(const Setting& setting) {
  return lab::settingLabel(setting.method, setting.iterations, setting.substeps) +
         (setting.model.label.empty() ? "" : " " + setting.model.label);
}

std::string settingGroup(const Setting& setting) {
  return std::string(phys::toString(setting.method)) +
         (setting.model.label.empty() ? "" : " " + setting.model.label);
}

Outcome runSetting(const SuiteScene& s, const Setting& setting, RunLength length) {
  Setting atSceneDt = setting;  // the world keeps its own dt as it is
  atSceneDt.dt = s.dt;
  scenes::Scene scene = loadSetting(s.source, atSceneDt);
  phys::World& world = scene.world;
  world.setStageTiming(false);  // the suite times whole steps and reads no stage of them
  WorldJudge judge(s.criteria, world);
  Outcome o;
  std::optional<std::size_t> failed;  // the criterion that stopped the run (RunLength::UntilFailed)
  // Only the steps are timed (runSteps), not the judge's figures; the run stops at a freeze, and
  // when asked once a criterion has failed for good. Named lab::runSteps: this namespace's
  // runSteps (stability_criteria.h) hides it from a braced spec.
  const RunRecord run = lab::runSteps(world, {.steps = s.steps, .afterStep = [&](int step) {
                                                judge.observe(world, step);
                                                if (length == RunLength::UntilFailed && step < s.steps)
                                                  failed = judge.failedForGood();
                                                return world.freezes().empty() && !failed;
                                              }});
  const int steps = run.stepsRun;
  const bool blewUp = !world.freezes().empty();
  if (blewUp) {
    const phys::FreezeReport& f = world.freezes().front();
    o.note = "froze " + f.name + " at " + formatNumber(f.time) + " s: " + f.reason;
  } else if (!setting.model.label.empty() && s.boxes == 0) {
    o.note = "no body for the model: the scene's own run";
  } else if (setting.model.options.sleep == true) {
    const phys::Islands& islands = world.islands();
    o.note = std::string(failed ? "asleep at the stop: " : "asleep at the end: ") +
             std::to_string(islands.sleepingBodies()) + " of " + std::to_string(world.bodies().size()) +
             " bodies";
  }
  if (failed && !blewUp) {  // first: where the run's figures end (a blow-up in the same step says so)
    o.stoppedAt = steps;
    o.note = "stopped at step " + std::to_string(steps) + " of " + std::to_string(s.steps) + " (" +
             formatNumber(steps * s.dt) + " s), failed for good: " + s.criteria[*failed].describe() +
             (o.note.empty() ? "" : "; " + o.note);
  }
  o.verdicts = judge.verdicts(blewUp);
  o.wallMs = run.steppingMs;
  o.msPerStep = steps > 0 ? o.wallMs / steps : 0.0;
  summarize(o);
  return o;
}

Outcome runPeerEngine(const SuiteScene& s, const std::string& engine, bool sleep) {
  const scenes::Scene scene = scenes::loadSceneSource(s.source);
  std::vector<int> checkpoints;
  for (int k = 1; k <= s.steps; ++k) checkpoints.push_back(k);
  const PeerResult r = runPeer(engine, scene, s.dt, s.steps, checkpoints, sleep);
  Outcome o;
  o.note = r.unsupported;
  // The mean, as ours: the steps' summed time over their number, landing spikes and all.
  o.msPerStep = r.meanMsPerStep;
  o.wallMs = r.meanMsPerStep * s.steps;
  if (!r.ran || r.dropped) {
    // A run whose engine dropped contacts for want of room (MuJoCo 2.2.2's fixed buffers) says
    // nothing of its solver's stability: not judged, as a scene it cannot build.
    if (o.note.empty()) o.note = "not run";
    if (r.dropped) o.note = "too large: " + o.note;
    o.verdicts.assign(s.criteria.size(), Verdict{.judged = false, .why = o.note});
  } else {
    o.verdicts = judgePeer(s.criteria, scene, s.dt, r.positions, r.orientations);
  }
  summarize(o);
  if (!o.judged && r.ran && !r.dropped) {
    // Say why from the criteria themselves: "stick-error: rigid bodies; ...".
    for (const Verdict& v : o.verdicts) o.note += (o.note.empty() ? "" : "; ") + v.why;
  }
  return o;
}

}  // namespace lab::stability
