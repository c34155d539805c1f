#include "sweep_core.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <utility>

#include "command_line.h"  // UsageError
#include "peers/pose_measures.h"
#include "run.h"
#include "runner.h"
#include "text.h"

namespace lab {
namespace {

// What tells the models of a world apart: its particles and its rigid bodies. Particles alone did
// not: a rigid box (none) beside a corners box (8) counts as two tetra boxes (4 each).
struct ModelCounts {
  std::size_t particles = 0;
  std::size_t rigidBodies = 0;
  bool operator==(const ModelCounts&) const = default;
};

ModelCounts countsWhenLoadedWith(const scenes::SceneSource& source, const scenes::LoadOptions& options) {
  const scenes::Scene scene = scenes::loadSceneSource(source, options);
  return {scene.world.particles().size(), scene.world.rigidBodies().size()};
}

// The same for a model the file may refuse: none then.
std::optional<ModelCounts> countsIfLoads(const scenes::SceneSource& source,
                                         const scenes::LoadOptions& options) {
  try {
    return countsWhenLoadedWith(source, options);
  } catch (const scenes::LoadError&) {
    return std::nullopt;
  }
}

// The first model whose world has `counts`: the one every body of its kind already has.
template <class Model>
std::optional<Model> modelWithCount(const ModelCounts& counts,
                                    std::initializer_list<std::pair<Model, ModelCounts>> countsUnder) {
  for (const auto& [model, under] : countsUnder) {
    if (under == counts) return model;
  }
  return std::nullopt;
}

// 'text' in quotes. Appended piecewise: "'" + std::string(...) trips GCC 12's false -Wrestrict
// warning (GCC bug 105329).
std::string inQuotes(std::string_view text) {
  std::string out(1, '\'');
  out.append(text);
  out.push_back('\'');
  return out;
}

// The model named by a --model value, or nullopt with `error` set: an unknown name, or one of a
// kind the scene does not have ("lean" for a scene without ragdolls).
std::optional<ModelChoice> modelChoice(std::string_view name, const SceneModels& models, std::string& error) {
  // Rigid is a model of both kinds: imposed on the boxes and the ragdolls the scene has.
  if (name == phys::toString(phys::BodyModel::Rigid)) {
    if (!models.boxes && !models.ragdolls) {
      error = inQuotes(name) + " is a box and ragdoll model and the scene has neither";
      return std::nullopt;
    }
    ModelChoice c{std::string(name), {}};
    if (models.boxes) c.options.boxModel = phys::BodyModel::Rigid;
    if (models.ragdolls) c.options.ragdollModel = phys::RagdollModel::Rigid;
    return c;
  }
  if (const auto box = phys::parseBodyModel(name)) {
    if (!models.boxes) {
      error = inQuotes(name) + " is a box model and the scene has no boxes";
      return std::nullopt;
    }
    return ModelChoice{std::string(name), {.boxModel = *box}};
  }
  if (const auto ragdoll = phys::parseRagdollModel(name)) {
    if (!models.ragdolls) {
      error = inQuotes(name) + " is a ragdoll model and the scene has no ragdolls";
      return std::nullopt;
    }
    return ModelChoice{std::string(name), {.ragdollModel = *ragdoll}};
  }
  error = "unknown model " + inQuotes(name) + " (corners, tetra, seed, lean or rigid)";
  return std::nullopt;
}

// How a world steps, one line: "Verlet, 3 iterations x 1 substep" (or "rigid bodies", or "Verlet
// and rigid bodies"), with body damping and sleeping when on.
std::string settingsWords(const phys::World& world) {
  const phys::SolverSettings& s = world.solverSettings();
  const bool particles = world.particles().size() > 0, rigid = world.rigidBodies().size() > 0;
  std::ostringstream o;
  o << (particles && rigid ? "Verlet and rigid bodies, "
        : rigid            ? "rigid bodies, "
                           : "Verlet, ")
    << ixsWords(s.iterations, s.substeps);
  if (s.bodyDamping > 0.0) o << ", body damping " << s.bodyDamping;
  if (s.sleep.enabled) o << ", sleeping";
  if (s.jointProjection.enabled && !world.rigidJoints().empty()) o << ", joints projected";
  return o.str();
}

// A target depends on the model, the dt and the steps alone.
std::string cacheKey(const Setting& setting, int steps) {
  return setting.model.label + "|" + formatNumber(setting.dt, 17) + "|" + std::to_string(steps);
}

}  // namespace

SceneModels sceneModels(const scenes::SceneSource& source) {
  const ModelCounts asWritten = countsWhenLoadedWith(source, {});
  const ModelCounts corners = countsWhenLoadedWith(source, {.boxModel = phys::BodyModel::Corners});
  const ModelCounts tetra = countsWhenLoadedWith(source, {.boxModel = phys::BodyModel::Tetra});
  // The file as written loads (or has thrown above); a ragdoll model it refuses is not one to offer.
  const std::optional<ModelCounts> seed = countsIfLoads(source, {.ragdollModel = phys::RagdollModel::Seed});
  const std::optional<ModelCounts> lean = countsIfLoads(source, {.ragdollModel = phys::RagdollModel::Lean});
  // All of a kind is rigid when making it rigid changes no count.
  const ModelCounts rigidBoxes = countsWhenLoadedWith(source, {.boxModel = phys::BodyModel::Rigid});
  const ModelCounts rigidRagdolls = countsWhenLoadedWith(source, {.ragdollModel = phys::RagdollModel::Rigid});

  SceneModels m;
  m.boxes = corners != tetra;
  m.ragdolls = seed && lean && *seed != *lean;
  // No boxes or ragdolls: there is no model to name (empty label).
  if (!m.boxes && !m.ragdolls) return m;
  // A model kind is uniform in the file when imposing one of its models changes nothing.
  // The box option leaves ragdolls alone and the ragdoll option boxes, so each count
  // compares one kind alone.
  ModelChoice c;
  std::vector<std::string> parts;
  if (m.boxes) {
    c.options.boxModel = modelWithCount<phys::BodyModel>(asWritten, {{phys::BodyModel::Corners, corners},
                                                                     {phys::BodyModel::Tetra, tetra},
                                                                     {phys::BodyModel::Rigid, rigidBoxes}});
    if (c.options.boxModel) parts.emplace_back(phys::toString(*c.options.boxModel));
  }
  if (m.ragdolls) {
    c.options.ragdollModel =
        modelWithCount<phys::RagdollModel>(asWritten, {{phys::RagdollModel::Seed, *seed},
                                                       {phys::RagdollModel::Lean, *lean},
                                                       {phys::RagdollModel::Rigid, rigidRagdolls}});
    if (c.options.ragdollModel) parts.emplace_back(phys::toString(*c.options.ragdollModel));
  }
  if (parts.size() != static_cast<std::size_t>(m.boxes) + static_cast<std::size_t>(m.ragdolls)) {
    m.asFile = ModelChoice{"scene", {}};  // models mixed within a kind: keep the file's as they are
    return m;
  }
  c.label = join(parts, "+");
  m.asFile = c;
  return m;
}

std::vector<ModelChoice> modelChoices(const std::vector<std::string>& names, const SceneModels& models) {
  std::vector<ModelChoice> out;
  for (const std::string& name : names) {
    std::string error;
    const std::optional<ModelChoice> c = modelChoice(name, models, error);
    if (!c) throw UsageError("--models: " + error);
    out.push_back(*c);
  }
  return out;
}

std::vector<ModelChoice> allModelChoices(const SceneModels& models) {
  std::vector<ModelChoice> boxes{ModelChoice{"", {}}};
  if (models.boxes) {
    boxes = {ModelChoice{"corners", {.boxModel = phys::BodyModel::Corners}},
             ModelChoice{"tetra", {.boxModel = phys::BodyModel::Tetra}}};
  }
  if (!models.boxes && !models.ragdolls) return {models.asFile};
  std::vector<ModelChoice> out;
  for (const ModelChoice& b : boxes) {
    if (!models.ragdolls) {
      out.push_back(b);
      continue;
    }
    for (const phys::RagdollModel r : {phys::RagdollModel::Seed, phys::RagdollModel::Lean}) {
      ModelChoice c = b;
      c.options.ragdollModel = r;
      c.label = (b.label.empty() ? "" : b.label + "+") + std::string(phys::toString(r));
      out.push_back(c);
    }
  }
  // Last, the rigid model of both kinds at once: the particle models' combinations first keep
  // their order (and the first, corners+seed, the seed's own).
  std::string unused;
  out.push_back(*modelChoice(phys::toString(phys::BodyModel::Rigid), models, unused));
  return out;
}

std::string Setting::describe() const {
  return std::string(phys::toString(method)) + ", " + ixsWords(iterations, substeps, ", ") +
         (model.label.empty() ? "" : ", model " + model.label);
}

scenes::Scene loadSetting(const scenes::SceneSource& source, const Setting& setting) {
  scenes::Scene scene = scenes::loadSceneSource(source, setting.model.options);
  // As `lab run` puts its overrides in: all at once, so the world judges the combination.
  applyOverrides(scene.world, RunOptions{.dt = setting.dt,
                                         .method = setting.method,
                                         .iterations = setting.iterations,
                                         .substeps = setting.substeps});
  return scene;
}

double firstCheckpointError(const AccuracyTarget& target,
                            const std::vector<std::vector<phys::Vec3>>& positions) {
  if (target.expected.empty() || positions.empty()) return kNaN;
  AccuracyTarget first;
  first.kind = target.kind;
  first.checkpoints.push_back(target.checkpoints.front());
  first.expected.push_back(target.expected.front());
  return accuracyError(first, {positions.front()});
}

void poseFigures(const peers::Description& scene, const std::vector<std::vector<phys::Vec3>>& positions,
                 const std::vector<std::vector<phys::Quat>>& orientations, double& penetration,
                 double& jointGap) {
  penetration = jointGap = 0.0;
  for (std::size_t k = 0; k < positions.size() && k < orientations.size(); ++k) {
    penetration = std::max(penetration, peers::posePenetration(scene, positions[k], orientations[k]));
    jointGap = std::max(jointGap, peers::jointGap(scene, positions[k], orientations[k]));
  }
}

Figures measureFigures(const scenes::SceneSource& source, const Setting& setting, int steps,
                       const AccuracyTarget& target) {
  scenes::Scene scene = loadSetting(source, setting);
  const peers::Description loaded = peers::asOurs(peers::describe(scene));
  const RunRecord run = runSteps(
      scene.world, {.steps = steps, .checkpoints = target.checkpoints, .orientations = true, .maxima = true});
  Figures f;
  f.maxima = run.maxima;
  // An energy that overflowed leaves no drift (a start of inf J gives -inf): NaN, which the CSV
  // leaves empty and the tables and tune print n/a, as they do inf - inf.
  const double drift = run.energyAfter - run.energyBefore;
  f.energyDrift = std::isfinite(drift) ? drift : kNaN;
  f.frozen = scene.world.metrics().frozen;
  // A frozen body's position says nothing of the solver (docs/lab.md, "Accuracy").
  f.error = f.frozen > 0 ? kInf : accuracyError(target, run.positions);
  f.errorFirst = f.frozen > 0 ? kInf : firstCheckpointError(target, run.positions);
  f.roughMsPerStep = steps > 0 ? run.steppingMs / steps : 0.0;
  poseFigures(loaded, run.positions, run.orientations, f.posePenetration, f.poseJointGap);
  f.settings = settingsWords(scene.world);
  return f;
}

double timeSetting(const scenes::SceneSource& source, const Setting& setting, int steps, int repeats) {
  std::vector<double> msPerStep;
  for (int r = 0; r < repeats; ++r) {
    scenes::Scene scene = loadSetting(source, setting);  // each repeat from a fresh load
    msPerStep.push_back(runSteps(scene.world, {.steps = steps}).steppingMs / steps);  // a bare loop
  }
  return median(std::move(msPerStep));
}

const AccuracyTarget& TargetCache::get(const scenes::SceneSource& source, const Setting& setting, int steps) {
  const std::string key = cacheKey(setting, steps);
  auto it = targets_.find(key);
  if (it == targets_.end()) {
    const scenes::Scene scene = scenes::loadSceneSource(source, setting.model.options);
    it = targets_.emplace(key, accuracyTarget(scene, setting.dt, steps)).first;
  }
  return it->second;
}

bool TargetCache::has(const Setting& setting, int steps) const {
  return targets_.count(cacheKey(setting, steps)) != 0;
}

int defaultSteps(double dt) {
  return std::max(1, static_cast<int>(std::lround(kDefaultHorizon / dt)));
}

void requireMeasurable(const char* (*lacks)(const phys::World& world), const scenes::SceneSource& scene,
                       const std::vector<ModelChoice>& choices, const std::string& figure, const char* tried,
                       const char* consequence) {
  if (lacks == nullptr || choices.empty()) return;
  const char* lacking = "";  // by every model so far: none yet
  for (std::size_t k = 0; k < choices.size() && lacking != nullptr; ++k)
    lacking = lacks(scenes::loadSceneSource(scene, choices[k].options).world);
  if (lacking == nullptr) return;
  throw UsageError(figure + " has " + lacking +
                   (choices.size() > 1 ? std::string(" in any model ") + tried : "") + ", so " + consequence);
}

}  // namespace lab
