#include "sweep_plan.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

#include "command_line.h"
#include "peer.h"
#include "peers/peer_scene.h"
#include "progress.h"
#include "run.h"
#include "text.h"

namespace lab {
namespace {

// The progress bar's units for a plan: a measured and `repeats` timed runs per setting, a target
// per model and dt, a run per peer and dt.
std::size_t planWork(const Plan& plan) {
  const std::size_t engines = plan.peers ? peerEngines().size() : 0;
  return plan.settings.size() * static_cast<std::size_t>(plan.repeats + 1) +
         plan.models.size() * plan.dts.size() + engines * plan.dts.size();
}

SweepRow runSetting(const Plan& plan, const Setting& s, TargetCache& targets, Progress& progress) {
  const bool fresh = !targets.has(s, plan.stepsAt(s.dt));
  const AccuracyTarget& target = targets.get(plan.scene, s, plan.stepsAt(s.dt));
  if (fresh) progress.advance();
  SweepRow r;
  r.method = std::string(phys::toString(s.method));
  r.model = s.model.label;
  r.iterations = s.iterations;
  r.substeps = s.substeps;
  r.dt = s.dt;
  r.steps = stepsFor(target, plan.stepsAt(s.dt));
  r.repeats = plan.repeats;
  r.uncertainty = maxUncertainty(target);
  r.figures = measureFigures(plan.scene, s, r.steps, target);
  progress.advance();
  r.msPerStep = timeSetting(plan.scene, s, r.steps, plan.repeats);
  progress.advance(static_cast<std::size_t>(plan.repeats));
  if (r.figures.frozen > 0)
    r.note = "blew up: the guard froze " +
             count(static_cast<std::size_t>(r.figures.frozen), "particle", "particles");
  return r;
}

void runPeers(const Plan& plan, double dt, TargetCache& targets, std::vector<SweepRow>& rows,
              Progress& progress) {
  const AccuracyTarget& target = firstTarget(plan, targets, dt);
  const int steps = stepsFor(target, plan.stepsAt(dt));
  const scenes::Scene scene = scenes::loadSceneSource(plan.scene, plan.models.front().options);
  const peers::Description description = peers::describe(scene);
  for (const std::string& engine : peerEngines()) {
    PeerResult p;
    try {
      p = runPeer(engine, scene, dt, steps, target.checkpoints, plan.peerSleep);
    } catch (const std::exception& e) {
      p.unsupported = std::string("failed: ") + e.what();
    }
    progress.advance();
    SweepRow r;
    r.peer = true;
    r.ran = p.ran;
    r.method = engine;
    r.model = plan.models.front().label;
    r.figures.settings = p.settings;
    r.dt = dt;
    r.steps = steps;
    r.repeats = 1;
    r.note = p.unsupported;
    r.uncertainty = maxUncertainty(target);
    r.figures.maxima.worst.fill(kNaN);  // a peer has none of our figures but the penetration
    if (p.ran) {
      r.msPerStep = p.meanMsPerStep;
      r.figures.error = accuracyError(target, p.positions);
      r.figures.errorFirst = firstCheckpointError(target, p.positions);
      r.figures.maxima.worst[kPenetrationMetric] = p.maxPenetration;
      poseFigures(description, p.positions, p.orientations, r.figures.posePenetration,
                  r.figures.poseJointGap);
      // Before what the peer left out, which may be why.
      if (r.blewUp())
        r.note = "blew up: a body's position is not finite" + (r.note.empty() ? "" : "; " + r.note);
    } else {
      r.figures.error = r.figures.errorFirst = kNaN;
      r.figures.posePenetration = r.figures.poseJointGap = kNaN;
    }
    rows.push_back(std::move(r));
  }
}

}  // namespace

int Plan::stepsAt(double dt) const {
  return std::max(1, static_cast<int>(std::lround(horizon / dt)));
}

Plan makePlan(const scenes::SceneSource& source, const PlanRequest& request) {
  Plan plan;
  const scenes::Scene scene = scenes::loadSceneSource(source);
  const phys::SolverSettings own = scene.world.solverSettings();
  plan.scene = source;
  plan.sceneName = scene.name;
  plan.horizon =
      request.horizon ? *request.horizon : (request.steps ? *request.steps : defaultSteps(own.dt)) * own.dt;
  plan.repeats = request.repeats;
  plan.peers = request.peers;
  plan.peerSleep = request.peerSleep;
  plan.models = request.models;
  if (plan.models.empty()) plan.models.push_back(sceneModels(source).asFile);
  const std::vector<phys::SolverMethod> methods =
      request.methods.empty() ? std::vector{own.method} : request.methods;
  const std::vector<int> iterations =
      request.iterations.empty() ? std::vector{own.iterations} : request.iterations;
  const std::vector<int> substeps = request.substeps.empty() ? std::vector{own.substeps} : request.substeps;
  plan.dts = request.dts.empty() ? std::vector{own.dt} : request.dts;
  for (const double dt : plan.dts) {
    // The horizon is set at one dt and run at every other: a tiny dt may ask too many steps.
    if (std::llround(plan.horizon / dt) > kMaxSteps) {
      throw UsageError("at dt " + formatNumber(dt) + " the " + formatNumber(plan.horizon) +
                       " s asked take more than " + std::to_string(kMaxSteps) +
                       " steps (shorten --steps or raise --dt)");
    }
  }
  // A model that leaves the scene rigid bodies and no stick steps alike under every method
  // (xpbdWhateverTheMethod): it runs once, as xpbd, which is how its rigid bodies are solved,
  // instead of as equal rows under names that did nothing.
  std::vector<std::vector<phys::SolverMethod>> methodsOf;
  std::size_t count = 0;
  for (const ModelChoice& model : plan.models) {
    const bool xpbdAlone = xpbdWhateverTheMethod(scenes::loadSceneSource(source, model.options).world);
    methodsOf.push_back(xpbdAlone ? std::vector{phys::SolverMethod::Xpbd} : methods);
    count += plan.dts.size() * methodsOf.back().size() * iterations.size() * substeps.size();
  }
  if (count > kMaxCombinations) {
    throw UsageError(std::to_string(count) + " combinations; at most " + std::to_string(kMaxCombinations) +
                     " (shorten a list)");
  }
  for (std::size_t m = 0; m < plan.models.size(); ++m) {
    const ModelChoice& model = plan.models[m];
    for (double dt : plan.dts) {
      for (phys::SolverMethod method : methodsOf[m]) {
        for (int it : iterations) {
          for (int sub : substeps) plan.settings.push_back(Setting{model, method, it, sub, dt});
        }
      }
    }
  }
  return plan;
}

PlanResult runPlan(const Plan& plan, std::ostream& err, const std::string& name) {
  Progress progress(err, name, planWork(plan));
  PlanResult result;
  for (std::size_t i = 0; i < plan.settings.size(); ++i) {
    result.rows.push_back(runSetting(plan, plan.settings[i], result.targets, progress));
    if (plan.afterSetting) plan.afterSetting(i);
  }
  if (plan.peers) {
    for (double dt : plan.dts) runPeers(plan, dt, result.targets, result.rows, progress);
  }
  progress.finish();
  return result;
}

const AccuracyTarget& firstTarget(const Plan& plan, TargetCache& targets, double dt) {
  const Setting first{plan.models.front(), phys::SolverMethod::GaussSeidel, 1, 1, dt};
  return targets.get(plan.scene, first, plan.stepsAt(dt));
}

}  // namespace lab
