// lab compare SCENE: the sweep preset that puts our four relaxation methods and the peer
// engines side by side on one scene (sweep_plan.h): each stepped at the same dt for the same
// steps, measured against the same accuracy target at the same checkpoints, and shown as one
// table or JSON lines (docs/lab.md, "lab compare and the peers").
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "accuracy.h"
#include "bodies.h"
#include "commands.h"
#include "json.h"
#include "lab.h"
#include "options.h"
#include "peer.h"
#include "run.h"
#include "run_metrics.h"
#include "scenes/scene.h"
#include "sweep_plan.h"
#include "text.h"

namespace lab {
namespace {

// The scene's overrides as `lab run` takes them (--methods, --threads and --dump aside); ours only
// where the help says so.
struct CompareOptions {
  RunOptions run;
  int repeats = 1;                ///< timed runs of each of ours
  std::optional<bool> peerSleep;  ///< --peer-sleep: the peers' alone, when it differs from --sleep
};

void describeCompare(CommandLine& line, CompareOptions& o) {
  line.about(
      "Runs SCENE with each of our four methods at its own iterations and substeps (xpbd alone for\n"
      "rigid bodies with no stick, which every method steps alike), then in each peer engine built in\n"
      "(Bullet, ODE, MuJoCo), and prints one table: ms per step, accuracy error, penetration\n"
      "and joint gap (by our code on every engine's poses) and what each peer could not express.");
  line.scene(o.run.scene);
  line.option(option::kSteps, o.run.steps,
              "in every run (default 600; a scene's analytic checkpoints may ask for more)");
  line.option(option::kDt, o.run.dt, "(default: the scene's)");
  line.option(option::kModels, o.run.model,
              "(rigid: ragdolls too), for ours and for the scene the peers are given");
  line.option(option::kIterations, o.run.iterations, "for ours (default: the scene's)");
  line.option(option::kSubsteps, o.run.substeps, "for ours (default: the scene's)");
  line.option(option::kRepeat, o.repeats, "(of ours; default 1)");
  line.option(
      option::kSleep, o.run.sleep,
      "(ours and the peers'; default off: every engine steps every body, so costs compare awake with awake)");
  line.option(option::kPeerSleep, o.peerSleep, "(default: as --sleep)");
  line.option(option::kJointProjection, o.run.jointProjection, "for ours (default: the scene's)");
  line.flag(option::kJson, o.run.json, true, "one object per row, one per line, instead of the table");
  line.existingFolder(option::kData, o.run.dataDir, "");
}

using Row = SweepRow;

// The plan: our four methods at the scene's iterations and substeps, or those asked, then the
// peers, on the scene as loaded with --models and --sleep.
Plan comparePlan(const CompareOptions& o, const scenes::SceneSource& source, double dt) {
  PlanRequest request;
  const std::string label = o.run.model ? std::string(phys::toString(*o.run.model)) : std::string();
  request.models.push_back(
      ModelChoice{label, imposedAtLoad(o.run.model, o.run.sleep, o.run.jointProjection)});
  request.methods = {phys::SolverMethod::GaussSeidel, phys::SolverMethod::Jacobi, phys::SolverMethod::Xpbd,
                     phys::SolverMethod::Shake};
  if (o.run.iterations) request.iterations = {*o.run.iterations};
  if (o.run.substeps) request.substeps = {*o.run.substeps};
  request.dts = {dt};
  request.repeats = o.repeats;
  request.peerSleep = o.peerSleep.value_or(o.run.sleep);
  request.horizon = o.run.steps * dt;  // --steps counts steps of the dt asked, not of the scene's
  return makePlan(source, request);
}

// `file` relative to `data` when it lies inside it, else as given.
std::filesystem::path shownPath(const std::filesystem::path& file, const std::filesystem::path& data) {
  std::error_code ec;
  const std::filesystem::path canonicalFile = std::filesystem::weakly_canonical(file, ec);
  const std::filesystem::path canonicalData = std::filesystem::weakly_canonical(data, ec);
  if (ec) return file;
  std::filesystem::path relative = canonicalFile.lexically_relative(canonicalData);  // not const: moved out
  if (relative.empty() || *relative.begin() == "..") return file;
  return relative;
}

// Table cells may not hold a '|' or a line break.
std::string cell(std::string text) {
  std::replace(text.begin(), text.end(), '|', '/');
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

std::string engineOf(const Row& r) {
  return r.peer ? r.method : "ours";
}

// A figure of a run that blew up says nothing (its bodies are frozen or not finite): read as
// infinite, it shows "blew up" in the table and null in the JSON, as the error does.
double figureOf(const Row& r, double value) {
  return r.blewUp() ? kInf : value;
}

void printTable(std::ostream& out, const std::vector<Row>& rows, double fastest) {
  out << "| engine | method | settings | ms/step | vs our fastest | error, first checkpoint (m) | "
         "error, all (m) | penetration (m) | joint gap (m) |";
  // Then the figures of every step, ours alone (run_metrics.h).
  for (const RunMetric& m : kRunMetrics)
    out << " " << m.nameAndUnit() << (m.over == OverRun::Rms ? ", RMS over the run |" : ", every step |");
  out << " unsupported / notes |\n|---|---|---|---:|---:|---:|---:|---:|---:|";
  for (std::size_t i = 0; i < kRunMetricCount; ++i) out << "---:|";
  out << "---|\n";
  for (const Row& r : rows) {
    out << "| " << engineOf(r) << " | " << (r.peer ? "" : r.method) << " | " << cell(r.figures.settings)
        << " | ";
    if (r.ran) {
      const Figures& f = r.figures;
      // Below a nanometre a depth is round-off (ours rest at 1e-20 m or so), shown as 0.
      const double depth = std::abs(f.posePenetration) < 1e-9 ? 0.0 : f.posePenetration;
      out << formatNumber(r.msPerStep, 4) << " | " << formatFigure(r.msPerStep / fastest, "x", 3) << " | "
          << formatNumber(f.errorFirst, 3) << " | " << formatNumber(f.error, 3) << " | "
          << formatNumber(figureOf(r, depth), 3) << " | " << formatNumber(figureOf(r, f.poseJointGap), 3);
      for (const double v : f.maxima.worst) out << " | " << (r.peer ? "-" : formatNumber(figureOf(r, v), 3));
    } else {
      out << "not run | | | | | ";
      for (std::size_t i = 0; i < kRunMetricCount; ++i) out << " | ";
    }
    out << " | " << cell(r.note) << " |\n";
  }
}

void printJson(std::ostream& out, const std::vector<Row>& rows, double fastest, const std::string& scene,
               const AccuracyTarget& target) {
  for (const Row& r : rows) {
    const Figures& f = r.figures;
    Json j;
    j["scene"] = scene;
    j["engine"] = engineOf(r);
    j["method"] = r.peer ? "" : r.method;
    j["settings"] = r.figures.settings;
    j["steps"] = r.steps;
    j["dt"] = r.dt;
    j["repeats"] = r.repeats;
    j["ran"] = r.ran;
    j["ms_per_step"] = r.ran ? r.msPerStep : std::nan("");
    j["ratio"] = r.ran ? r.msPerStep / fastest : std::nan("");
    j["accuracy"] = target.kind;
    j["error_first"] = f.errorFirst;
    j["error"] = f.error;
    j["max_penetration"] = figureOf(r, f.posePenetration);
    j["max_joint_gap"] = figureOf(r, f.poseJointGap);
    for (std::size_t i = 0; i < kRunMetricCount; ++i) {
      j[std::string(kRunMetrics[i].column) + "_every_step"] =
          r.peer ? std::nan("") : figureOf(r, f.maxima[i]);
    }
    j["notes"] = r.note;
    out << jsonLine(j);
  }
}

// "2 boxes, 1 capsule, 3 loose particles, 9 links, 0 joints"
std::string contents(const phys::World& world) {
  const auto capsules = static_cast<std::size_t>(
      std::count_if(world.bodies().begin(), world.bodies().end(),
                    [](const phys::Body& b) { return b.shape == phys::Shape::Capsule; }));
  return count(world.bodies().size() - capsules, "box", "boxes") + ", " +
         (capsules > 0 ? count(capsules, "capsule", "capsules") + ", " : std::string()) +
         count(looseParticles(world).size(), "loose particle", "loose particles") + ", " +
         count(world.links().size() + world.rigidLinks().size(), "link", "links") + ", " +
         count(world.rigidJoints().size(), "joint", "joints");
}

// Every run, then the table or the JSON.
int runCompare(const CompareOptions& options, std::ostream& out, std::ostream& err) {
  const std::filesystem::path file = sceneFile(options.run.scene, options.run.dataDir);
  const scenes::SceneSource source = scenes::readSceneSource(file);  // ours and the peers' alike
  const scenes::Scene scene = scenes::loadSceneSource(
      source, imposedAtLoad(options.run.model, options.run.sleep, options.run.jointProjection));
  const double dt = options.run.dt.value_or(scene.world.solverSettings().dt);
  const Plan plan = comparePlan(options, source, dt);
  PlanResult result = runPlan(plan, err, "compare");
  const AccuracyTarget& target = firstTarget(plan, result.targets, dt);
  const std::vector<Row>& rows = result.rows;

  double fastest = kInf;
  for (const Row& r : rows) {
    if (!r.peer && r.msPerStep > 0.0) fastest = std::min(fastest, r.msPerStep);
  }
  if (options.run.json) {
    printJson(out, rows, fastest, scene.name, target);
    return kExitOk;
  }
  // A project scene is named from the data folder (assets/scenes/x.xml), so the table that
  // docs/results.md quotes says the same on every machine.
  const std::filesystem::path shown = shownPath(file, dataDir(options.run.dataDir));
  const int steps = rows.front().steps;
  out << "scene     " << scene.name << " (" << shown.string() << "): " << contents(scene.world) << "\n";
  out << "run       " << steps << " steps of " << dt << " s (" << steps * dt
      << " s) in each engine, one after another in this process; ms/step: the steps' time over their "
         "number, ours the median of "
      << count(static_cast<std::size_t>(plan.repeats), "timed run", "timed runs")
      << " after a measured one\n";
  out << "accuracy  " << target.description << "; error = the largest distance (m) of a body from it\n";
  if (peerEngines().empty())
    out << "peers     none built in (LAB_PEERS off, or no Bullet, ODE or MuJoCo found at build time)\n";
  out << "\n";
  printTable(out, rows, fastest);
  return kExitOk;
}

}  // namespace

constinit const CommandMain compareMain = commandMainOf<CompareOptions, describeCompare, runCompare>;

}  // namespace lab
