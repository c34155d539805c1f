// lab converge: error against the substep size, for every method and model, on scenes with an
// exact answer (docs/lab.md, "lab converge"). A method of order p has an error that falls as h^p
// once h is small, a straight line of slope p on a log-log chart; the fitted slope is the
// measured order.
#include "converge.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <ostream>
#include <set>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "accuracy.h"
#include "bodies.h"
#include "commands.h"
#include "csv.h"
#include "fileio/printable.h"
#include "free_body.h"
#include "lab.h"
#include "numbers.h"
#include "options.h"
#include "output_files.h"
#include "physics/rigid_bodies.h"
#include "runner.h"
#include "sweep_core.h"
#include "text.h"

namespace lab {
namespace {

constexpr const char* kParticleModel = "particle";

void describeConverge(CommandLine& line, ConvergeOptions& o) {
  line.about(
      "Error against the substep size h for every method and model, on scenes with an exact\n"
      "answer; the slope of the log-log line is the method's measured order.");
  line.positional(
      "SCENE",
      "scenes with an exact answer: analytic positions (<expect kind=\"position\">) or free bodies in zero "
      "gravity, checked against Euler's equations (default: projectile, pendulum-exact, circular-orbit, "
      "tumbling-box)",
      true, [&o](const std::string& name) {
        addOnce(o.scenes, name);  // a scene named twice runs once, as a list option's repeats are dropped
        return std::string();
      });
  line.option(option::kMethods, o.methods,
              "(default: all four); rigid bodies are solved by XPBD whatever the method, so they run once");
  line.models(o.models, false,
              "(default: every model a scene's boxes take; a scene of particles alone has none and runs as "
              "'particle')");
  line.option(option::kSubsteps, o.substeps, "(default 1,2,4,8,16,32,64): h = dt / each");
  line.option(option::kIterations, o.iterations, "(default 4)");
  line.option(option::kTime, o.time, "(default 4); analytic scenes use their answers' times");
  line.option(option::kOut, o.out, "converge.csv and, per scene, converge-SCENE.gp, .png, .svg");
  line.existingFolder(option::kData, o.dataDir, "");
}

// ---- what a scene is compared with ------------------------------------------------------------

bool hasAnalyticAnswers(const scenes::Scene& scene) {
  return std::any_of(scene.expectations.begin(), scene.expectations.end(), [](const scenes::Expectation& e) {
    const std::string* kind = e.find("kind");
    return kind != nullptr && *kind == "position";
  });
}

// Why the world is not free bodies that Euler's equations answer for, or "" when it is.
std::string notFreeBodies(const phys::World& world) {
  const phys::WorldSettings& w = world.worldSettings();
  if (world.bodies().empty()) return "it has no boxes or capsules";
  if (w.gravityMode != phys::GravityMode::Uniform || w.gravity != phys::Vec3(0.0)) return "it has gravity";
  if (w.damping != 0.0 || world.solverSettings().bodyDamping != 0.0) return "it has damping";
  if (world.jointCount() > 0) return "it has joints";
  for (const phys::BodyId b : world.particleBodies()) {
    if (b == phys::kNoBody) return "it has particles that belong to no body";
  }
  std::size_t ownSticks = 0;
  for (const phys::Body& b : world.bodies()) ownSticks += static_cast<std::size_t>(b.stickCount);
  if (world.sticks().size() != ownSticks) return "it has sticks between bodies";
  return {};
}

// The free bodies' exact poses at the checkpoints, from the file loaded with every body rigid
// (whose pose, velocities and principal moments are the file's, exactly as given). A body of a
// particle model turns as its particles' point masses make it: for both models (8 corners, or 4
// alternate ones, of equal mass) the moments are proportional to a solid box's, so with
// `boxInertia` a capsule is given its box's moments, not the solid capsule's of the rigid model.
struct FreeBodies {
  std::vector<std::vector<FreeBodyPose>> poses;  // per body, per checkpoint
  std::vector<phys::Vec3> halfExtents;           // per body
  double uncertainty = 0.0;
};

FreeBodies freeBodyReference(const scenes::SceneSource& source, const std::vector<double>& times,
                             bool boxInertia) {
  const scenes::Scene scene = scenes::loadSceneSource(source, {.boxModel = phys::BodyModel::Rigid});
  const phys::World& world = scene.world;
  const double h = world.solverSettings().dt / world.solverSettings().substeps;
  FreeBodies out;
  for (std::size_t i = 0; i < world.bodies().size(); ++i) {
    const phys::BodyId id(static_cast<std::uint32_t>(i));
    const phys::Body& body = world.bodies()[i];
    FreeBodyStart start;
    const phys::BodyPose pose = world.bodyPose(id);
    start.centre = pose.center;
    start.orientation = pose.orientation;
    const auto [velocity, kept] = world.bodyVelocity(id);
    start.velocity = velocity;  // zero gravity: the same at every time
    // The kept spin was shifted with the rigid body's own moments: undone with the same.
    const phys::BodyMass own = world.bodyMass(id);
    const std::optional<phys::Vec3> spin = spinAtStart(kept, pose.orientation, own.inertia, h);
    // Beyond a radian a substep the physics keeps a spin unshifted, and the shift has no inverse.
    if (!spin || !(h * glm::length(*spin) <= 1.0)) {
      const double turn = h * glm::length(kept);  // inf for a spin of 1e300 on each axis
      throw std::invalid_argument(
          scene.name + ": body '" + body.name + "' spins too fast for its substep (h |w| = " +
          (std::isfinite(turn) ? formatNumber(turn, 3) : std::string("more than 1e308")) +
          " rad; the free-body reference needs at most 1 rad a substep at the scene's " + formatNumber(h, 4) +
          " s)");
    }
    start.angularVelocity = *spin;
    start.inertia = boxInertia ? phys::solidBoxInertia(body.halfExtents, own.mass) : own.inertia;
    const double uncertainty = freeBodyUncertainty(start, times, body.halfExtents);
    if (!std::isfinite(uncertainty)) {
      throw std::invalid_argument(scene.name + ": body '" + body.name +
                                  "': the free-body reference is not finite (its own uncertainty: " +
                                  formatNumber(uncertainty, 3) + ")");
    }
    out.poses.push_back(freeBodyPoses(start, times, kFreeBodyStep));
    out.halfExtents.push_back(body.halfExtents);
    out.uncertainty = std::max(out.uncertainty, uncertainty);
  }
  return out;
}

// The model choices of the file that the options ask for; "particle" for a scene without boxes.
// A scene of particles alone has no model to choose: a --models list is then said to be left aside,
// not dropped in silence.
std::vector<ModelChoice> chosenModels(const scenes::SceneSource& source, const std::string& sceneName,
                                      const ConvergeOptions& o, std::ostream* progress) {
  const SceneModels models = sceneModels(source);
  if (!models.boxes && !models.ragdolls) {
    if (!o.models.empty() && progress != nullptr)
      *progress << "converge    " << sceneName
                << " has no boxes or ragdolls: --models does not apply to it\n";
    return {ModelChoice{kParticleModel, {}}};
  }
  return o.models.empty() ? allModelChoices(models) : modelChoices(o.models, models);
}

}  // namespace

namespace {

// Throws, as runConverge would after its first runs, for a scene converge cannot measure: one with
// no exact answer, or a free-body scene whose --time is no whole number of steps in range.
void checkMeasurable(const scenes::Scene& own, const ConvergeOptions& o) {
  if (hasAnalyticAnswers(own)) return;
  const double dt = own.world.solverSettings().dt;
  const double time = o.time.value_or(kConvergeTime);
  if (const std::string why = notFreeBodies(own.world); !why.empty()) {
    throw std::invalid_argument(own.name + " has no exact answer: no <expect kind=\"position\">, and " + why +
                                " (a free-body reference needs boxes alone in zero gravity)");
  }
  if (std::llround(time / dt) > kMaxSteps) {
    throw UsageError("--time: at the scene's dt " + formatNumber(dt) + " s the " + formatNumber(time) +
                     " s asked take more than " + std::to_string(kMaxSteps) + " steps");
  }
  // Less than half a step rounds to none: refused, not run as one step the user did not ask for.
  if (std::lround(time / dt) < 1) {
    throw UsageError("--time: '" + formatNumber(time) + "' s is shorter than one step of the scene's dt " +
                     formatNumber(dt) + " s");
  }
}

}  // namespace

std::vector<ConvergeRow> runConverge(const std::filesystem::path& file, const ConvergeOptions& o,
                                     ConvergeTarget& target, std::ostream* progress) {
  // Read once: every run and reference is built from this text, whatever happens to the file.
  const scenes::SceneSource source = scenes::readSceneSource(file);
  return runConverge(source, scenes::loadSceneSource(source), o, target, progress);
}

std::vector<ConvergeRow> runConverge(const scenes::SceneSource& source, const scenes::Scene& own,
                                     const ConvergeOptions& o, ConvergeTarget& target,
                                     std::ostream* progress) {
  const double dt = own.world.solverSettings().dt;
  const bool analytic = hasAnalyticAnswers(own);
  // The options first: a model the scene has nothing for is said before what its bodies lack.
  const std::vector<ModelChoice> models = chosenModels(source, own.name, o, progress);
  std::vector<int> checkpoints;
  FreeBodies freeRigid, freeParticle;  // the references for the rigid model and the particle ones
  AccuracyTarget t;  // analytic: the answers, the same whatever the model (bodies.h's order)
  checkMeasurable(own, o);
  if (analytic) {
    if (o.time && progress != nullptr)
      *progress << "converge    " << own.name
                << " has exact answers at their own times: --time does not apply to it\n";
    t = accuracyTarget(own, dt, 1);
    checkpoints = t.checkpoints;
    target.kind = "analytic";
    target.description = t.description;
  } else {
    const int steps = static_cast<int>(std::lround(o.time.value_or(kConvergeTime) / dt));
    checkpoints = spreadCheckpoints(steps);
    std::vector<double> times;
    times.reserve(checkpoints.size());
    for (const int step : checkpoints) times.push_back(step * dt);
    freeRigid = freeBodyReference(source, times, false);
    freeParticle = freeBodyReference(source, times, true);
    const double uncertainty = std::max(freeRigid.uncertainty, freeParticle.uncertainty);
    target.kind = "free body";
    target.description = "free body: Euler's equations by RK4 at " + formatNumber(kFreeBodyStep, 3) +
                         " s, every corner, at t = " + formatNumber(times.front(), 4) + " to " +
                         formatNumber(times.back(), 4) + " s; the reference's own uncertainty " +
                         formatNumber(uncertainty, 2) + " m";
  }

  std::vector<ConvergeRow> rows;
  for (const ModelChoice& model : models) {
    const bool rigid = model.options.boxModel == phys::BodyModel::Rigid;
    const FreeBodies& free = rigid ? freeRigid : freeParticle;
    for (const phys::SolverMethod method : o.methods) {
      // A rigid body is solved by XPBD whatever the method: one line, named for what it is.
      if (rigid && method != o.methods.front()) continue;
      const phys::SolverMethod used = rigid ? phys::SolverMethod::Xpbd : method;
      for (const int substeps : o.substeps) {
        const Setting setting{
            .model = model, .method = used, .iterations = o.iterations, .substeps = substeps, .dt = dt};
        scenes::Scene scene = loadSetting(source, setting);
        phys::World& world = scene.world;
        double error = 0.0;
        RunSpec spec;
        spec.steps = checkpoints.empty() ? 0 : checkpoints.back();
        if (analytic) spec.checkpoints = checkpoints;
        std::size_t next = 0;  // the next checkpoint of a free body
        spec.afterStep = [&](int step) {
          if (analytic) return true;
          if (world.metrics().contacts > 0) {
            throw std::invalid_argument(own.name + ": a body touched something at t = " +
                                        formatNumber(world.time(), 4) + " s under " + setting.describe() +
                                        "; the free-body reference is of bodies that touch nothing");
          }
          if (step != checkpoints[next]) return true;
          for (std::size_t b = 0; b < free.poses.size(); ++b) {
            const phys::BodyPose pose = world.bodyPose(phys::BodyId(static_cast<std::uint32_t>(b)));
            const double d =
                cornerDistance({pose.center, pose.orientation}, free.poses[b][next], free.halfExtents[b]);
            error = std::isfinite(d) ? std::max(error, d) : kInf;
          }
          ++next;
          return true;
        };
        const std::vector<std::vector<phys::Vec3>> positions = runSteps(world, spec).positions;
        if (analytic) error = accuracyError(t, positions);
        if (world.metrics().frozen > 0) error = kInf;  // a frozen body's position says nothing
        rows.push_back({.scene = own.name,
                        .method = std::string(phys::toString(used)),
                        .model = model.label.empty() ? kParticleModel : model.label,
                        .substeps = substeps,
                        .h = dt / substeps,
                        .error = error});
      }
    }
  }
  if (progress != nullptr) *progress << "converge    " << own.name << ": " << rows.size() << " runs\n";
  return rows;
}

std::optional<double> fittedOrder(const std::vector<ConvergeRow>& line) {
  std::vector<const ConvergeRow*> usable;
  for (const ConvergeRow& r : line) {
    if (std::isfinite(r.error) && r.error > kConvergeFloor && r.h > 0.0) usable.push_back(&r);
  }
  std::sort(usable.begin(), usable.end(),
            [](const ConvergeRow* a, const ConvergeRow* b) { return a->h < b->h; });
  if (usable.size() > static_cast<std::size_t>(kOrderPoints)) usable.resize(kOrderPoints);
  if (usable.size() < 2) return std::nullopt;
  double mx = 0.0, my = 0.0;
  for (const ConvergeRow* r : usable) {
    mx += std::log(r->h);
    my += std::log(r->error);
  }
  mx /= static_cast<double>(usable.size());
  my /= static_cast<double>(usable.size());
  double sxy = 0.0, sxx = 0.0;
  for (const ConvergeRow* r : usable) {
    sxy += (std::log(r->h) - mx) * (std::log(r->error) - my);
    sxx += (std::log(r->h) - mx) * (std::log(r->h) - mx);
  }
  if (!(sxx > 0.0)) return std::nullopt;  // every usable point at the same h
  return sxy / sxx;
}

std::vector<std::vector<ConvergeRow>> convergeLines(const std::vector<ConvergeRow>& rows) {
  std::vector<std::vector<ConvergeRow>> lines;
  for (const ConvergeRow& r : rows) {
    auto same = [&](const std::vector<ConvergeRow>& l) {
      return l.front().scene == r.scene && l.front().method == r.method && l.front().model == r.model;
    };
    auto it = std::find_if(lines.begin(), lines.end(), same);
    if (it == lines.end())
      lines.push_back({r});
    else
      it->push_back(r);
  }
  return lines;
}

std::string convergeCsv(const std::vector<ConvergeRow>& rows) {
  std::string s = "scene,method,model,substeps,h,error,blew_up\n";
  for (const ConvergeRow& r : rows) {
    // A blow-up's error, infinity, is written blank, as every figure that is not finite.
    s += csvLine({csvField(r.scene), csvField(r.method), csvField(r.model), std::to_string(r.substeps),
                  csvNumber(r.h, 10), csvNumber(r.error, 6), std::isfinite(r.error) ? "0" : "1"});
  }
  return s;
}

namespace {

std::string orderText(const std::vector<ConvergeRow>& line) {
  const std::optional<double> order = fittedOrder(line);
  // An error that grows as h shrinks is round-off or a method that does not converge, not an order.
  if (order) return *order < 0.0 ? "grows" : formatNumber(*order, 3);
  const bool allSmall = std::all_of(line.begin(), line.end(), [](const ConvergeRow& r) {
    return std::isfinite(r.error) && r.error <= kConvergeFloor;
  });
  return allSmall ? "exact" : "-";
}

}  // namespace

std::string convergeTable(const std::vector<ConvergeRow>& rows, const ConvergeTarget& target) {
  if (rows.empty()) return {};
  std::string s = "converge    " + rows.front().scene + ", against its " + target.description + "\n";
  s += "            error (m): the largest distance from the exact answer; order: the slope of log error\n";
  s += "            against log h over the finest " + std::to_string(kOrderPoints) + " points above " +
       formatNumber(kConvergeFloor, 2) + " m (exact: every error below it)\n";
  const std::vector<std::vector<ConvergeRow>> lines = convergeLines(rows);
  s += printed("%-13s %-9s %6s", "method", "model", "order");
  for (const ConvergeRow& r : lines.front())
    s += printed(" %9s", ("S=" + std::to_string(r.substeps)).c_str());
  s += "\n";
  for (const std::vector<ConvergeRow>& line : lines) {
    s += printed("%-13s %-9s %6s", line.front().method.c_str(), line.front().model.c_str(),
                 orderText(line).c_str());
    for (const ConvergeRow& r : line)
      s += std::isfinite(r.error) ? printed(" %9.2e", r.error) : printed(" %9s", kBlewUp);
    s += "\n";
  }
  return s;
}

Chart convergeChart(const std::vector<ConvergeRow>& rows) {
  const std::string scene = rows.empty() ? std::string() : rows.front().scene;
  Chart chart = logChart("Error against substep size: " + scene, "substep h (s)", "error (m)", true,
                         "converge-" + scene);
  chart.guides.push_back({kConvergeFloor, "floor: left out of the fit"});
  for (const std::vector<ConvergeRow>& line : convergeLines(rows)) {
    ChartSeries series{.title = line.front().method + " " + line.front().model + ": order " + orderText(line),
                       .line = true,
                       .markers = true};
    for (const ConvergeRow& r : line) series.points.push_back({r.h, r.error, ""});
    chart.series.push_back(series);
  }
  return chart;
}

namespace {

// Every scene's runs and table, then the files of --out.
int runConvergeCommand(ConvergeOptions o, std::ostream& out, std::ostream& err) {
  if (o.scenes.empty()) o.scenes = kConvergeScenes;
  const std::filesystem::path sceneDir = scenes::sceneDirectory(dataDir(o.dataDir));
  // Each scene read and loaded once: its name (which names its chart), the check, and the runs
  // all come from that read (it was read three times, and could change between them).
  std::vector<std::filesystem::path> sceneFiles;
  std::vector<scenes::SceneSource> sources;
  std::vector<scenes::Scene> owns;
  std::vector<std::string> names;
  for (const std::string& scene : o.scenes) {
    sceneFiles.push_back(scenes::resolveScene(scene, sceneDir));
    sources.push_back(scenes::readSceneSource(sceneFiles.back()));
    owns.push_back(scenes::loadSceneSource(sources.back()));
    names.push_back(owns.back().name);
  }
  // The charts are named after the scenes, so that every file is checked before the runs.
  const std::vector<std::string> chartNames = convergeChartNames(names);
  if (o.out) {
    refuseOutputsOverScenes(*o.out, convergeFiles(names), sceneFiles);
    prepareOutputFiles(*o.out, convergeFiles(names));
  }
  std::vector<ConvergeRow> all;
  std::vector<Chart> charts;
  std::string current;
  try {
    // Every scene checked before the first run: one that cannot be measured was found only after
    // the scenes before it had run (minutes), and nothing was written.
    for (std::size_t k = 0; k < owns.size(); ++k) {
      current = o.scenes[k];
      chosenModels(sources[k], owns[k].name, o, nullptr);  // as runConverge: the options first
      checkMeasurable(owns[k], o);
    }
    for (std::size_t k = 0; k < owns.size(); ++k) {
      current = o.scenes[k];
      ConvergeTarget target;
      const std::vector<ConvergeRow> rows = runConverge(sources[k], owns[k], o, target, &err);
      out << convergeTable(rows, target) << "\n";
      out.flush();
      all.insert(all.end(), rows.begin(), rows.end());
      charts.push_back(convergeChart(rows));
    }
  } catch (const scenes::LoadError&) {
    throw;  // commandMain says it: "file:line: ..."
  } catch (const UsageError&) {
    throw;  // an option the scene cannot take: commandMain says it with the usage, exit 2
  } catch (const std::invalid_argument& e) {
    throw CommandFailure(std::string("converge: ") + e.what());  // it names its scene
  } catch (const std::exception& e) {
    throw CommandFailure("converge: " + current + ": " + e.what());
  }
  if (!o.out) return kExitOk;
  for (std::size_t k = 0; k < charts.size(); ++k) charts[k].output = chartNames.at(k);
  OutputFolder files(*o.out);
  files.write("converge.csv", convergeCsv(all));
  std::string problems;
  for (const Chart& chart : charts) {
    const std::string problem = files.draw(chart.output + ".gp", chart,
                                           "no run has a finite error above 0 (the axes are logarithmic)");
    if (!problem.empty()) problems += "lab: converge: the chart " + chart.output + ": " + problem + "\n";
  }
  files.commit();
  out << files.wroteLine();
  err << problems;
  return files.failed() ? kExitFailure : kExitOk;
}

}  // namespace

// A chart's files are named after its scene's name, which two files can share and which can hold
// a '/': each chart gets a name of its own within the folder (the second of two overwrote the first).
std::vector<std::string> convergeChartNames(const std::vector<std::string>& sceneNames) {
  std::set<std::string> taken;
  std::vector<std::string> names;
  names.reserve(sceneNames.size());
  for (const std::string& scene : sceneNames) {
    std::string base = "converge-" + scene;
    // A '/' would name a folder, a control character (a line break in a scene's name) has no
    // place in a file name.
    for (char& c : base) {
      if (c == '/' || fileio::isControl(static_cast<unsigned char>(c))) c = '-';
    }
    std::string name = base;
    for (int k = 2; !taken.insert(name).second; ++k) name = base + "-" + std::to_string(k);
    names.push_back(name);
  }
  return names;
}

std::vector<std::string> convergeFiles(const std::vector<std::string>& sceneNames) {
  std::vector<std::string> files{"converge.csv"};
  files.reserve(1 + 3 * sceneNames.size());
  for (const std::string& chart : convergeChartNames(sceneNames)) {
    for (const char* extension : {".gp", ".png", ".svg"}) files.push_back(chart + extension);
  }
  return files;
}

std::vector<std::string> convergeSceneNames(const std::vector<std::string>& scenes,
                                            const std::filesystem::path& sceneDir) {
  std::vector<std::string> names;
  names.reserve(scenes.size());
  for (const std::string& scene : scenes)
    names.push_back(scenes::loadSceneFile(scenes::resolveScene(scene, sceneDir)).name);
  return names;
}

constinit const CommandMain convergeMain =
    commandMainOf<ConvergeOptions, describeConverge, runConvergeCommand>;

}  // namespace lab
