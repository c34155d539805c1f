// lab compare SCENE: our four relaxation methods and the peer engines on one scene, in one
// process, one after another, each stepped at the same dt for the same steps, timed step by
// step, and measured against the same accuracy target at the same checkpoints (docs/lab.md,
// "lab compare and the peers").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "accuracy.h"
#include "commands.h"
#include "json.h"
#include "lab.h"
#include "options.h"
#include "peer.h"
#include "peers/peer_scene.h"
#include "peers/pose_measures.h"
#include "report.h"
#include "run.h"
#include "run_metrics.h"
#include "runner.h"
#include "scenes/scene.h"
#include "text.h"

namespace lab {
namespace {

struct CompareOptions {
  std::string scene;
  int steps = kDefaultSteps;
  std::optional<double> dt;
  std::optional<phys::BodyModel> model;     ///< imposed at load on ours and on what the peers are given
  std::optional<int> iterations, substeps;  ///< ours; the scene's own when unset
  std::filesystem::path dataDir;
  bool json = false;
  bool sleep = false;             ///< --sleep: whether ours put islands at rest to sleep, and the peers too
  std::optional<bool> peerSleep;  ///< --peer-sleep: the peers' alone, when it differs from --sleep
};

void describeCompare(CommandLine& line, CompareOptions& o) {
  line.scene(o.scene);
  line.count(option::kSteps, kMaxSteps, o.steps,
             "in every run (default 600; a scene's analytic checkpoints may ask for more)");
  line.dt(o.dt, "(default: the scene's)");
  line.model(o.model, "(rigid: ragdolls too), for ours and for the scene the peers are given");
  line.count(option::kIterations, phys::kMaxIterations, o.iterations, "for ours (default: the scene's)");
  line.count(option::kSubsteps, phys::kMaxSubsteps, o.substeps, "for ours (default: the scene's)");
  line.onOff(
      option::kSleep, o.sleep,
      "(ours and the peers'; default off: every engine steps every body, so costs compare awake with awake)");
  line.onOff(option::kPeerSleep, o.peerSleep, "(default: as --sleep)");
  line.flag(option::kJson, o.json, true, "one object per row, one per line, instead of the table");
  line.folder(option::kData, o.dataDir, "");
}

// One row of the table.
struct Row {
  std::string engine;    // "ours", or a peer's name
  std::string method;    // our method's name; empty for a peer
  std::string settings;  // what ran, one line
  bool ran = false;
  double msPerStep = 0.0;
  double error = std::numeric_limits<double>::quiet_NaN();       // over every checkpoint
  double errorFirst = std::numeric_limits<double>::quiet_NaN();  // at the first alone
  // Measured the same way for every engine, by our code on its bodies' poses at each checkpoint
  // (peers/pose_measures.h), the largest: so speed is compared at equal joint error.
  double penetration = std::numeric_limits<double>::quiet_NaN();  // below the ground or into a body
  double jointGap = std::numeric_limits<double>::quiet_NaN();     // the widest joint
  // Ours alone, after every step (run_metrics.h): a peer's state is read at the checkpoints only.
  RunMaxima maxima;
  std::string notes;
};

// The largest penetration and joint gap over the checkpoints' poses, into the row.
void measurePoses(const peers::Description& scene, const std::vector<std::vector<phys::Vec3>>& positions,
                  const std::vector<std::vector<phys::Quat>>& orientations, Row& row) {
  row.penetration = row.jointGap = 0.0;
  for (std::size_t k = 0; k < positions.size() && k < orientations.size(); ++k) {
    row.penetration = std::max(row.penetration, peers::posePenetration(scene, positions[k], orientations[k]));
    row.jointGap = std::max(row.jointGap, peers::jointGap(scene, positions[k], orientations[k]));
  }
}

// The error at the first checkpoint alone: in a chaotic scene (a pile) later checkpoints
// measure mostly which way things happened to fall, the first still how well each one steps.
double firstError(const AccuracyTarget& target, const std::vector<std::vector<phys::Vec3>>& positions) {
  if (target.expected.empty() || positions.empty()) return std::numeric_limits<double>::quiet_NaN();
  AccuracyTarget first;
  first.kind = target.kind;
  first.checkpoints.push_back(target.checkpoints.front());
  first.expected.push_back(target.expected.front());
  return accuracyError(first, {positions.front()});
}

// How our world steps: Verlet for its particles, XPBD's poses for its rigid bodies, or both.
std::string ourSettings(const phys::World& world) {
  const phys::SolverSettings& s = world.solverSettings();
  const bool particles = world.particles().size() > 0, rigid = world.rigidBodies().size() > 0;
  std::ostringstream o;
  o << (particles && rigid ? "Verlet and rigid bodies, "
        : rigid            ? "rigid bodies, "
                           : "Verlet, ")
    << ixsWords(s.iterations, s.substeps);
  if (s.bodyDamping > 0.0) o << ", body damping " << s.bodyDamping;
  if (s.sleep.enabled) o << ", sleeping";
  return o.str();
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

Row runOurs(const std::filesystem::path& file, phys::SolverMethod method, const CompareOptions& options,
            int steps, const AccuracyTarget& target) {
  scenes::Scene scene = scenes::loadSceneFile(file, imposedAtLoad(options.model, options.sleep));
  RunOptions overrides;
  overrides.method = method;
  overrides.dt = options.dt;
  overrides.iterations = options.iterations;
  overrides.substeps = options.substeps;
  applyOverrides(scene.world, overrides);

  Row row;
  row.engine = "ours";
  row.method = std::string(phys::toString(method));
  row.settings = ourSettings(scene.world);
  RunSpec spec;
  spec.steps = steps;
  spec.checkpoints = target.checkpoints;
  spec.orientations = true;
  spec.stepTimes = true;
  spec.maxima = true;
  RunRecord run = runSteps(scene.world, spec);
  const std::vector<std::vector<phys::Vec3>>& positions = run.positions;
  row.maxima = run.maxima;
  row.ran = true;
  row.msPerStep = median(std::move(run.stepMs));
  row.error = accuracyError(target, positions);
  row.errorFirst = firstError(target, positions);
  measurePoses(peers::describe(scene), positions, run.orientations, row);
  if (!scene.world.freezes().empty()) {
    // As in the sweep (docs/lab.md, "Accuracy"): a frozen body's position says nothing of the
    // solver, so the run has no error to report.
    row.error = row.errorFirst = std::numeric_limits<double>::infinity();
    row.notes = std::to_string(scene.world.freezes().size()) + " frozen by the guard";
  }
  return row;
}

std::string fixed(double v, const char* format) {
  if (!std::isfinite(v)) return v > 0 ? "inf" : "n/a";
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

// Table cells may not hold a '|' or a line break.
std::string cell(std::string text) {
  std::replace(text.begin(), text.end(), '|', '/');
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

void printTable(std::ostream& out, const std::vector<Row>& rows, double fastest) {
  out << "| engine | method | settings | ms/step (median) | vs our fastest | error, first checkpoint (m) | "
         "error, all (m) | penetration (m) | joint gap (m) |";
  // Then the figures of every step, ours alone (run_metrics.h).
  for (const RunMetric& m : kRunMetrics)
    out << " " << m.name << (*m.unit == '\0' ? "" : " (") << m.unit << (*m.unit == '\0' ? "" : ")")
        << ", every step |";
  out << " unsupported / notes |\n|---|---|---|---:|---:|---:|---:|---:|---:|";
  for (std::size_t i = 0; i < kRunMetricCount; ++i) out << "---:|";
  out << "---|\n";
  for (const Row& r : rows) {
    out << "| " << r.engine << " | " << (r.method.empty() ? "" : r.method) << " | " << cell(r.settings)
        << " | ";
    if (r.ran) {
      // Below a nanometre a depth is round-off (ours rest at 1e-20 m or so), shown as 0.
      const double depth = std::abs(r.penetration) < 1e-9 ? 0.0 : r.penetration;
      out << fixed(r.msPerStep, "%.4g") << " | " << fixed(r.msPerStep / fastest, "%.3gx") << " | "
          << fixed(r.errorFirst, "%.3g") << " | " << fixed(r.error, "%.3g") << " | " << fixed(depth, "%.3g")
          << " | " << fixed(r.jointGap, "%.3g");
      for (const double v : r.maxima.worst) out << " | " << (r.engine == "ours" ? fixed(v, "%.3g") : "-");
    } else {
      out << "not run | | | | | ";
      for (std::size_t i = 0; i < kRunMetricCount; ++i) out << " | ";
    }
    out << " | " << cell(r.notes) << " |\n";
  }
}

void printJson(std::ostream& out, const std::vector<Row>& rows, double fastest, const std::string& scene,
               int steps, double dt, const AccuracyTarget& target) {
  for (const Row& r : rows) {
    Json j;
    j["scene"] = scene;
    j["engine"] = r.engine;
    j["method"] = r.method;
    j["settings"] = r.settings;
    j["steps"] = steps;
    j["dt"] = dt;
    j["ran"] = r.ran;
    j["ms_per_step"] = r.ran ? r.msPerStep : std::nan("");
    j["ratio"] = r.ran ? r.msPerStep / fastest : std::nan("");
    j["accuracy"] = target.kind;
    j["error_first"] = r.errorFirst;
    j["error"] = r.error;
    j["max_penetration"] = r.penetration;
    j["max_joint_gap"] = r.jointGap;
    for (std::size_t i = 0; i < kRunMetricCount; ++i) {
      j[std::string(kRunMetrics[i].column) + "_every_step"] = r.engine == "ours" ? r.maxima[i] : std::nan("");
    }
    j["notes"] = r.notes;
    out << jsonLine(j);
  }
}

// Every run, then the table or the JSON.
int runCompare(const CompareOptions& options, std::ostream& out) {
  const std::filesystem::path file = sceneFile(options.scene, options.dataDir);
  const scenes::Scene scene = scenes::loadSceneFile(file, imposedAtLoad(options.model, options.sleep));
  const double dt = options.dt.value_or(scene.world.solverSettings().dt);
  const AccuracyTarget target = accuracyTarget(scene, {}, dt, options.steps);
  // An analytic target may check a time past the steps asked for; every run goes that far.
  const int steps = stepsFor(target, options.steps);

  // Rigid bodies and no stick step alike under the four methods (xpbdWhateverTheMethod): one row,
  // under the method that names how they are solved.
  std::vector<phys::SolverMethod> methods{phys::SolverMethod::GaussSeidel, phys::SolverMethod::Jacobi,
                                          phys::SolverMethod::Xpbd, phys::SolverMethod::Shake};
  if (xpbdWhateverTheMethod(scene.world)) methods = {phys::SolverMethod::Xpbd};
  std::vector<Row> rows;
  rows.reserve(methods.size() + peerEngines().size());
  for (phys::SolverMethod method : methods) rows.push_back(runOurs(file, method, options, steps, target));
  const peers::Description description = peers::describe(scene);
  for (const std::string& engine : peerEngines()) {
    // Each peer reads the scene as loaded, unstepped (the first load is kept for them).
    const PeerResult p =
        runPeer(engine, scene, dt, steps, target.checkpoints, options.peerSleep.value_or(options.sleep));
    Row row;
    row.engine = p.engine;
    row.settings = p.settings;
    row.ran = p.ran;
    row.msPerStep = p.medianMsPerStep;
    if (p.ran) {
      row.error = accuracyError(target, p.positions);
      row.errorFirst = firstError(target, p.positions);
      measurePoses(description, p.positions, p.orientations, row);
    }
    row.notes = p.unsupported;
    rows.push_back(row);
  }

  double fastest = std::numeric_limits<double>::infinity();
  for (const Row& r : rows) {
    if (r.engine == "ours" && r.msPerStep > 0.0) fastest = std::min(fastest, r.msPerStep);
  }

  if (options.json) {
    printJson(out, rows, fastest, scene.name, steps, dt, target);
    return kExitOk;
  }
  const phys::World& world = scene.world;
  std::size_t loose = world.particles().size(), capsules = 0;
  for (const phys::Body& b : world.bodies()) {
    loose -= static_cast<std::size_t>(b.particleCount);
    capsules += b.shape == phys::Shape::Capsule ? 1 : 0;
  }
  auto count = [](std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
  };
  // A project scene is named from the data folder (assets/scenes/x.xml), so the table that
  // docs/results.md quotes says the same on every machine.
  const std::filesystem::path shown = shownPath(file, dataDir(options.dataDir));
  out << "scene     " << scene.name << " (" << shown.string()
      << "): " << count(world.bodies().size() - capsules, "box", "boxes") << ", "
      << (capsules > 0 ? count(capsules, "capsule", "capsules") + ", " : std::string())
      << count(loose, "loose particle", "loose particles") << ", "
      << count(world.links().size() + world.rigidLinks().size(), "link", "links") << ", "
      << count(world.rigidJoints().size(), "joint", "joints") << "\n";
  out << "run       " << steps << " steps of " << dt << " s (" << steps * dt
      << " s) in each engine, one after another in this process; ms/step is the median of the steps timed "
         "one by one\n";
  out << "accuracy  " << target.description << "; error = the largest distance (m) of a body from it\n";
  if (peerEngines().empty())
    out << "peers     none built in (LAB_PEERS off, or no Bullet, ODE or MuJoCo found at build time)\n";
  out << "\n";
  printTable(out, rows, fastest);
  return kExitOk;
}

}  // namespace

int compareMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CompareOptions options;
  CommandLine line(
      "compare",
      "Runs SCENE with each of our four methods at its own iterations and substeps (xpbd alone for\n"
      "rigid bodies with no stick, which every method steps alike), then in each peer engine built in\n"
      "(Bullet, ODE, MuJoCo), and prints one table: median ms per step, accuracy error, penetration\n"
      "and joint gap (by our code on every engine's poses) and what each peer could not express.");
  describeCompare(line, options);
  return commandMain(line, args, out, err, [&] { return runCompare(options, out); });
}

}  // namespace lab
