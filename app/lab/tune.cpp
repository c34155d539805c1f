// lab tune: the cheapest settings of a scene that meet every target asked for. It searches the
// models the scene can take, the four methods, and substeps and iterations over a ladder of
// counts, measuring figures untimed and timing only the settings that qualify. docs/lab.md,
// "lab tune", documents the search and the output.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "accuracy.h"
#include "command_line.h"
#include "commands.h"
#include "lab.h"
#include "numbers.h"
#include "run_metrics.h"
#include "sweep_core.h"
#include "text.h"

namespace lab {
namespace {

/// The counts searched for iterations and for substeps: roughly geometric, so a search over
/// both stays short, and fine enough (steps of 1.33 to 1.5 above 2) that the winner is near the
/// true cheapest.
constexpr int kLadder[] = {1, 2, 3, 4, 6, 8, 12, 16, 24, 32};

// The ladder as the help and the output write it: "1,2,3,4,6,8,12,16,24,32".
std::string ladderText() {
  return joinNumbers({std::begin(kLadder), std::end(kLadder)}, ",");
}

/// A substep count whose 1-iteration run already costs this much more than the cheapest
/// qualifying setting so far ends the search of its method: more substeps only cost more. The
/// margin absorbs the rough timings' noise (one run each).
constexpr double kPruneFactor = 1.5;
/// Qualifying settings within this factor of the cheapest (rough timing) are timed properly.
constexpr double kFinalistFactor = 1.5;

/// The seed's settings (docs/physics.md, "Defaults"): what tune compares its winner with.
constexpr phys::SolverMethod kSeedMethod = phys::SolverMethod::GaussSeidel;
constexpr int kSeedIterations = 3;
constexpr int kSeedSubsteps = 1;

/// What a --target bounds: a figure of the run, or one of tune's own two, the accuracy error and
/// the energy drift, each a row of the run table's kind (run_metrics.h: name, unit, help, what a
/// world lacks for it); and its bound once a --target gives one.
struct Target {
  RunMetric metric;                   ///< tune's own two are read by figure(), not by `read`
  std::size_t run = kRunMetricCount;  ///< its place in kRunMetrics; kRunMetricCount for tune's own
  double bound = 0.0;

  std::string name() const { return metric.name; }
};

constexpr const char* kError = "error";
constexpr const char* kDrift = "drift";

// A world whose particles and bodies are all pinned: its error and drift are 0 whatever the settings.
const char* lacksMotion(const phys::World& world) {
  const auto moves = [](phys::Real inverseMass) { return inverseMass > 0.0; };
  const auto& particles = world.particles().inverseMass;
  const auto& bodies = world.rigidBodies().inverseMass;
  return std::any_of(particles.begin(), particles.end(), moves) ||
                 std::any_of(bodies.begin(), bodies.end(), moves)
             ? nullptr
             : "nothing that moves";
}

// Every figure a --target may bound, in the order the help and the output list them.
std::vector<Target> boundable() {
  std::vector<Target> all{
      {{kError, "", "m", "largest distance from the accuracy target (analytic or reference)", nullptr,
        OverRun::Worst, lacksMotion}}};
  for (std::size_t i = 0; i < kRunMetricCount; ++i) all.push_back({kRunMetrics[i], i});
  all.push_back({{kDrift, "", "J", "|energy after the last step - energy before the first|", nullptr,
                  OverRun::Worst, lacksMotion}});
  return all;
}

// "error, stick-error, ... or drift": every name a --target takes.
std::string metricNames() {
  std::vector<std::string> names;
  for (const Target& t : boundable()) names.push_back(t.name());
  const std::string last = names.back();
  names.pop_back();
  return join(names, ", ") + " or " + last;
}

double figure(const Figures& f, const Target& t) {
  if (t.name() == kError) return f.error;
  if (t.name() == kDrift) return std::abs(f.energyDrift);
  return f.maxima[t.run];
}

struct TuneOptions {
  std::string scene;
  std::vector<Target> targets;
  std::optional<int> steps;
  int repeats = 3;
  std::filesystem::path dataDir;
};

std::string readTarget(const std::string& text, TuneOptions& o) {
  const std::size_t eq = text.find('=');
  const std::string name = text.substr(0, eq);
  const std::vector<Target> all = boundable();
  const auto known = std::find_if(all.begin(), all.end(), [&](const Target& t) { return t.name() == name; });
  if (known == all.end()) return "unknown metric '" + name + "' in '" + text + "' (" + metricNames() + ")";
  const std::optional<double> v = eq == std::string::npos ? std::nullopt : parseNumber(text.substr(eq + 1));
  if (!v || *v <= 0.0) return "'" + text + "' needs METRIC=VALUE with a finite VALUE > 0";
  for (const Target& given : o.targets) {
    if (given.name() == name) return name + " is given twice";
  }
  o.targets.push_back(*known);
  o.targets.back().bound = *v;
  return {};
}

// What `lab tune --help` says: the metrics a --target may bound, from the run table.
std::string tuneAbout() {
  std::string metrics;
  for (const Target& t : boundable()) {
    std::string line = "  " + t.name();
    line.resize(17, ' ');
    // A figure of the run is at its worst after any step; tune's own two are of the whole run.
    metrics += line + (*t.metric.unit == '\0' ? "" : t.metric.unit + std::string(", ")) + t.metric.help +
               (t.run < kRunMetricCount ? " after any step" : "") + "\n";
  }
  const std::string counts = "substeps and iterations over " + ladderText() + ", at the\nscene's dt.";
  return "The cheapest setting whose run meets every --target METRIC=VALUE, an upper bound on:\n" + metrics +
         "Searched: the box and ragdoll models the scene has and the rigid model, the four methods\n"
         "(xpbd alone for rigid), and " +
         counts + " A setting whose run froze anything never qualifies.";
}

void describeTune(CommandLine& line, TuneOptions& o) {
  line.about(tuneAbout());
  line.scene(o.scene);
  line.custom(
      option::kTarget, false, [&o](const std::string& text) { return readTarget(text, o); }, "");
  line.require(option::kTarget, "tune needs at least one --target METRIC=VALUE");
  line.option(option::kSteps, o.steps, "at the scene's dt (default: 1 s of them)");
  line.option(option::kRepeat, o.repeats, "(of each finalist; default 3)");
  line.existingFolder(option::kData, o.dataDir, "");
}

// ---- the search -------------------------------------------------------------------------------

struct Candidate {
  Setting setting;
  Figures figures;
  double msPerStep = kInf;  // the proper (median) timing; inf until timed
};

class Search {
 public:
  Search(scenes::SceneSource scene, int steps, std::vector<Target> targets)
      : scene_(std::move(scene)), steps_(steps), targets_(std::move(targets)) {}

  bool needsError() const {
    return std::any_of(targets_.begin(), targets_.end(), [](const Target& t) { return t.name() == kError; });
  }

  /// The target of the setting's model: the accuracy target when error is asked for, else
  /// none (a reference costs two fine runs, wasted when no error is asked for).
  const AccuracyTarget& target(const Setting& s) {
    static const AccuracyTarget kNone{};
    return needsError() ? targets_cache_.get(scene_, s, steps_) : kNone;
  }

  int stepsOf(const Setting& s) { return stepsFor(target(s), steps_); }

  /// The setting's figures, measured once.
  const Figures& evaluate(const Setting& s) {
    const std::string key = s.describe();  // one dt per search
    auto it = measured_.find(key);
    if (it == measured_.end()) {
      it = measured_.emplace(key, measureFigures(scene_, s, stepsOf(s), target(s))).first;
      noteClosest(s, it->second);
    }
    return it->second;
  }

  bool meets(const Figures& f) const {
    if (f.frozen > 0) return false;
    return std::all_of(targets_.begin(), targets_.end(),
                       [&](const Target& t) { return figure(f, t) <= t.bound; });
  }

  /// How far the figures are from meeting the targets: the largest figure / bound (<= 1 meets).
  double excess(const Figures& f) const {
    if (f.frozen > 0) return kInf;
    double worst = 0.0;
    for (const Target& t : targets_) worst = std::max(worst, figure(f, t) / t.bound);
    return std::isnan(worst) ? kInf : worst;
  }

  /// For each substep count, the fewest iterations that meet the targets (bisection over the
  /// ladder, which assumes more passes never hurt), stopping once more substeps cannot pay.
  void searchMethod(const ModelChoice& model, phys::SolverMethod method, double dt) {
    // The most iterations still worth trying, as a ladder index.
    int upper = static_cast<int>(std::size(kLadder)) - 1;
    for (int substeps : kLadder) {
      const Setting one{model, method, 1, substeps, dt};
      const Figures& f1 = evaluate(one);
      if (meets(f1)) {
        record(one, f1);
        break;  // more substeps at 1 iteration, or more iterations, only cost more
      }
      if (f1.roughMsPerStep > kPruneFactor * cheapestRough_) break;
      if (upper < 1) continue;  // only 1 iteration could still be cheaper; try more substeps
      const Setting top{model, method, kLadder[upper], substeps, dt};
      if (!meets(evaluate(top))) continue;
      int lo = 0;      // fails
      int hi = upper;  // meets
      while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        const Setting s{model, method, kLadder[mid], substeps, dt};
        (meets(evaluate(s)) ? hi : lo) = mid;
      }
      const Setting found{model, method, kLadder[hi], substeps, dt};
      record(found, evaluate(found));
      upper = hi - 1;  // with more substeps, as many passes would cost more than this
    }
  }

  /// Times the qualifying settings near the cheapest properly; the winner is the fastest.
  std::optional<Candidate> winner(int repeats) {
    std::optional<Candidate> best;
    for (Candidate& c : qualifying_) {
      if (c.figures.roughMsPerStep > kFinalistFactor * cheapestRough_) continue;
      c.msPerStep = timeSetting(scene_, c.setting, stepsOf(c.setting), repeats);
      if (!best || c.msPerStep < best->msPerStep) best = c;
    }
    return best;
  }

  /// A fixed setting, measured and timed (the seed's defaults, the scene's own).
  Candidate measureAndTime(const Setting& s, int repeats) {
    Candidate c{s, evaluate(s)};
    if (meets(c.figures)) record(s, c.figures);
    c.msPerStep = timeSetting(scene_, s, stepsOf(s), repeats);
    return c;
  }

  const std::optional<Candidate>& closest() const { return closest_; }
  std::size_t evaluations() const { return measured_.size(); }
  const std::vector<Target>& targets() const { return targets_; }

 private:
  void record(const Setting& s, const Figures& f) {
    const bool known = std::any_of(qualifying_.begin(), qualifying_.end(),
                                   [&](const Candidate& c) { return c.setting.describe() == s.describe(); });
    if (!known) qualifying_.push_back(Candidate{s, f});
    cheapestRough_ = std::min(cheapestRough_, f.roughMsPerStep);
  }

  void noteClosest(const Setting& s, const Figures& f) {
    if (!closest_ || excess(f) < excess(closest_->figures)) closest_ = Candidate{s, f};
  }

  scenes::SceneSource scene_;  // the file as read once: every setting is built from it
  int steps_;
  std::vector<Target> targets_;
  TargetCache targets_cache_;
  std::map<std::string, Figures> measured_;
  std::vector<Candidate> qualifying_;
  double cheapestRough_ = kInf;
  std::optional<Candidate> closest_;
};

// ---- the report -------------------------------------------------------------------------------

std::string figuresText(const Figures& f, bool withError) {
  std::string s;
  for (const Target& t : boundable()) {
    if (t.name() != kError || withError)
      s += t.name() + " " + formatFigure(figure(f, t), t.metric.unitAfter(), 3) + ", ";
  }
  return s + "frozen " + std::to_string(f.frozen);
}

// "meets the targets", or which it misses and by how much.
std::string verdict(const Search& search, const Figures& f) {
  std::string misses;
  if (f.frozen > 0) misses = "it froze " + std::to_string(f.frozen) + " particles";
  for (const Target& t : search.targets()) {
    const double v = figure(f, t);
    if (v <= t.bound) continue;
    misses += (misses.empty() ? "" : ", ") + t.name() + " " + formatFigure(v, t.metric.unitAfter(), 3) +
              " > " + formatLimit(t.bound) + t.metric.unitAfter();
  }
  return misses.empty() ? "meets the targets" : "misses: " + misses;
}

std::string targetsText(const std::vector<Target>& targets) {
  std::string s;
  for (const Target& t : targets) {
    s += (s.empty() ? "" : ", ") + t.name() + " <= " + formatLimit(t.bound) + t.metric.unitAfter();
  }
  return s;
}

void printCompared(std::ostream& out, const char* label, const Candidate& c, const Candidate* winner,
                   const Search& search, bool withError) {
  out << label << c.setting.describe() << ": " << formatNumber(c.msPerStep, 4) << " ms/step";
  if (winner != nullptr && winner->msPerStep > 0.0) {
    out << " (" << formatNumber(c.msPerStep / winner->msPerStep, 3) << "x the winner's)";
  }
  out << "\n            " << figuresText(c.figures, withError) << "; " << verdict(search, c.figures) << "\n";
}

// ---- the command --------------------------------------------------------------------------------

int runTune(const TuneOptions& o, std::ostream& out, std::ostream& err) {
  const std::filesystem::path file = sceneFile(o.scene, o.dataDir);
  const scenes::SceneSource source = scenes::readSceneSource(file);
  const scenes::Scene scene = scenes::loadSceneSource(source);
  const phys::SolverSettings own = scene.world.solverSettings();
  const SceneModels models = sceneModels(source);
  const int steps = o.steps ? *o.steps : defaultSteps(own.dt);
  Search search(source, steps, o.targets);

  // The seed's defaults: its method and counts with its models, the first of the choices (corners
  // boxes, seed ragdolls; the file's own when it has neither).
  const std::vector<ModelChoice> choices = allModelChoices(models);
  // A target whose figure is 0 in every model the search tries, whatever the settings (a tracking
  // error without a character), would be met by every setting at once, and the cheapest would win
  // for nothing: refused before any run.
  for (const Target& t : o.targets)
    requireMeasurable(t.metric.lacks, source, choices, "--target " + t.name() + ": scene " + scene.name,
                      "searched", "every setting would meet it");
  const Setting defaults{choices.front(), kSeedMethod, kSeedIterations, kSeedSubsteps, own.dt};
  const Setting sceneOwn{models.asFile, own.method, own.iterations, own.substeps, own.dt};

  // An analytic answer later than the horizon lengthens every run to reach it.
  out << "tune        " << scene.name << " (" << file.string() << "), "
      << count(static_cast<std::size_t>(search.stepsOf(sceneOwn)), "step", "steps") << " at dt "
      << formatNumber(own.dt) << " s\n";
  out << "targets     " << targetsText(o.targets) << "\n";
  if (search.needsError()) out << "accuracy    " << search.target(sceneOwn).description << "\n";
  out.flush();

  // The scene's and the seed's settings first: when they qualify, they bound the search early.
  const Candidate ownResult = search.measureAndTime(sceneOwn, o.repeats);
  const Candidate seedResult = search.measureAndTime(defaults, o.repeats);
  std::vector<phys::SolverMethod> methods{own.method};
  for (phys::SolverMethod m : {phys::SolverMethod::GaussSeidel, phys::SolverMethod::Jacobi,
                               phys::SolverMethod::Xpbd, phys::SolverMethod::Shake})
    addOnce(methods, m);
  for (const ModelChoice& model : choices) {
    // A rigid body is solved by XPBD whatever the method: the other three would repeat it.
    if (model.label == phys::toString(phys::BodyModel::Rigid)) {
      search.searchMethod(model, phys::SolverMethod::Xpbd, own.dt);
      continue;
    }
    for (phys::SolverMethod method : methods) search.searchMethod(model, method, own.dt);
  }
  const std::optional<Candidate> win = search.winner(o.repeats);

  std::string modelNames;
  for (const ModelChoice& m : choices) modelNames += (modelNames.empty() ? "" : ", ") + m.label;
  out << "searched    " << search.evaluations()
      << " settings: " << (modelNames.empty() ? std::string() : "models " + modelNames + "; ")
      << "4 methods (rigid: xpbd); substeps and iterations from " << ladderText() << "\n";
  const bool withError = search.needsError();
  if (withError && search.target(sceneOwn).kind == "reference") {
    const double u = maxUncertainty(search.target(sceneOwn));
    if (std::isfinite(u)) {
      out << "note        the reference itself is uncertain to " << formatNumber(u, 2)
          << " m here; error targets below that cannot be told apart\n";
    } else {
      out << "note        the reference itself blew up here: no error target can be judged against it\n";
    }
  }
  if (win) {
    out << "winner      " << win->setting.describe() << ": " << formatNumber(win->msPerStep, 4)
        << " ms/step\n";
    out << "            " << figuresText(win->figures, withError) << "\n";
  } else {
    out << "winner      none: no setting meets the targets\n";
    if (search.closest()) {
      Candidate c = *search.closest();
      c.msPerStep = timeSetting(source, c.setting, search.stepsOf(c.setting), o.repeats);
      printCompared(out, "closest     ", c, nullptr, search, withError);
    }
  }
  const Candidate* winner = win ? &*win : nullptr;
  printCompared(out, "defaults    ", seedResult, winner, search, withError);
  printCompared(out, "scene       ", ownResult, winner, search, withError);
  if (win) return kExitOk;
  err << "lab: tune: no setting meets the targets (the closest found is on stdout)\n";
  return kExitFailure;
}

}  // namespace

constinit const CommandMain tuneMain = commandMainOf<TuneOptions, describeTune, runTune>;

}  // namespace lab
