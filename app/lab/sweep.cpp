// lab sweep: every combination of the listed settings run on one scene, each timed and measured
// against the scene's accuracy target (accuracy.h), written as a CSV and drawn as error against
// cost with the Pareto front. docs/lab.md, "lab sweep", documents the options and the files.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "accuracy.h"
#include "charts.h"
#include "command_line.h"
#include "commands.h"
#include "csv.h"
#include "lab.h"
#include "output_files.h"
#include "sweep_core.h"
#include "sweep_plan.h"
#include "text.h"

namespace lab {
namespace {

/// The chart of error against cost: its script, and its pictures NAME.png and NAME.svg.
constexpr const char* kSweepScript = "sweep.gp";
constexpr const char* kSweepChart = "error-vs-cost";

/// Errors below this are round-off: a Verlet projectile, exact in exact arithmetic, collects
/// 1e-11 m over a thousand substeps. They are drawn and compared as this, so the front does not
/// chase noise. unit: m
constexpr double kErrorFloor = 1e-9;
/// Errors within this share of each other are one error on the front: what parts them is round-off
/// (pendulum-exact's SHAKE at 1 to 8 iterations x 8 substeps differ by 1.3e-13 m in 2.1e-5, at up to
/// three times the cost), not accuracy bought.
constexpr double kSameError = 1e-6;

// Whether error a is below error b by more than round-off.
bool lessError(double a, double b) {
  return a < b * (1.0 - kSameError);
}

struct SweepOptions {
  std::string scene;
  /// Empty lists take the scene's own; `models` is read once the scene is (modelChoices).
  PlanRequest request;
  std::vector<std::string> models;
  std::filesystem::path dataDir;
  std::filesystem::path out;
  /// What the chart and the front measure: kRunMetricCount for the distance from the accuracy
  /// target, else that figure of kRunMetrics.
  std::size_t measure = kRunMetricCount;
};

// --error's value: "position", or a figure of the run table by name.
std::string readMeasure(const std::string& text, std::size_t& measure) {
  if (text == "position") {
    measure = kRunMetricCount;
    return {};
  }
  measure = runMetricIndex(text);
  if (measure < kRunMetricCount) return {};
  std::string names = "position";
  for (const RunMetric& m : kRunMetrics) names += std::string(", ") + m.name;
  return "unknown figure '" + text + "' (one of " + names + ")";
}

void describeSweep(CommandLine& line, SweepOptions& o) {
  line.about(
      "Runs every combination of the listed settings on SCENE (LIST: comma-separated values),\n"
      "times each and measures its error against the scene's accuracy target.");
  const std::string scenes = "(default: the scene's)";
  line.scene(o.scene);
  line.option(option::kMethods, o.request.methods, scenes);
  line.option(option::kIterations, o.request.iterations, scenes);
  line.option(option::kSubsteps, o.request.substeps, scenes);
  line.option(option::kDt, o.request.dts, scenes);
  line.models(o.models, true, "(ragdolls: seed, lean or rigid)");
  line.option(option::kRepeat, o.request.repeats, "(default 3)");
  line.option(option::kSteps, o.request.steps,
              "at the scene's dt (default: 1 s of them); other dts run as long");
  line.custom(
      option::kError, false, [&o](const std::string& text) { return readMeasure(text, o.measure); }, "");
  line.flag(option::kNoPeers, o.request.peers, false, "");
  line.existingFolder(option::kData, o.dataDir, "");
  line.option(option::kOut, o.out, "results.csv, pareto.csv, sweep.gp and the chart (required)");
  line.require(option::kOut, "sweep needs --out DIR (where the CSV and the chart go)");
}

using Row = SweepRow;

// ---- the front ------------------------------------------------------------------------------

// The cost the chart and the front use: ms per step when every row has one dt, else wall ms
// per simulated second, since a step of a larger dt does more.
bool oneDt(const std::vector<Row>& rows) {
  return std::all_of(rows.begin(), rows.end(), [&](const Row& r) { return r.dt == rows.front().dt; });
}

double cost(const Row& r, bool perStep) {
  return perStep ? r.msPerStep : r.msPerSimSecond();
}
// The error the chart and the front measure (SweepOptions::measure); NaN for a peer under a figure
// of ours: the one it has, its penetration, is its deepest body at the end alone, where ours is
// the deepest of every contact after every step, and would put it on the front by a kinder measure.
double shownError(const Row& r, std::size_t measure) {
  if (measure < kRunMetricCount) return r.peer ? kNaN : std::max(r.figures.maxima[measure], kErrorFloor);
  return std::max(r.figures.error, kErrorFloor);
}
// Whether a row has its place on the chart: it did not blow up and has the figure.
bool charted(const Row& r, std::size_t measure) {
  return !r.blewUp() && std::isfinite(shownError(r, measure));
}

// Marks the rows no other row beats on both cost and error (a blown-up run is never on it).
void markPareto(std::vector<Row>& rows, std::size_t measure) {
  const bool perStep = oneDt(rows);
  for (Row& r : rows) {
    if (!charted(r, measure)) continue;
    r.pareto = std::none_of(rows.begin(), rows.end(), [&](const Row& q) {
      if (!charted(q, measure)) return false;
      const double qe = shownError(q, measure), re = shownError(r, measure);
      const bool noWorse = cost(q, perStep) <= cost(r, perStep) && !lessError(re, qe);
      const bool better = cost(q, perStep) < cost(r, perStep) || lessError(qe, re);
      return noWorse && better;
    });
  }
}

std::vector<Row> frontByCost(const std::vector<Row>& rows) {
  std::vector<Row> front;
  std::copy_if(rows.begin(), rows.end(), std::back_inserter(front), [](const Row& r) { return r.pareto; });
  const bool perStep = oneDt(rows);
  std::stable_sort(front.begin(), front.end(),
                   [&](const Row& a, const Row& b) { return cost(a, perStep) < cost(b, perStep); });
  return front;
}

// ---- files ----------------------------------------------------------------------------------

std::string csvRow(const std::string& scene, const Row& r) {
  auto opt = [](const std::optional<int>& v) { return v ? std::to_string(*v) : std::string(); };
  auto number = [](double v) { return csvNumber(v, 10); };
  // A blown-up run's errors are no figure: blank, as any figure that is not finite, and
  // `blew_up` says why.
  const bool blewUp = r.blewUp();  // a peer that did not run has no row
  std::vector<std::string> fields;
  fields.insert(fields.end(),
                {csvField(scene), csvField(r.method), csvField(r.model), opt(r.iterations), opt(r.substeps),
                 number(r.dt), std::to_string(r.steps), std::to_string(r.repeats), number(r.msPerStep),
                 number(r.msPerSimSecond()), number(blewUp ? kNaN : r.figures.error), number(r.uncertainty)});
  for (const double v : r.figures.maxima.worst) fields.push_back(number(v));
  fields.insert(fields.end(),
                {number(blewUp ? kNaN : r.figures.errorFirst), number(r.figures.posePenetration),
                 number(r.figures.poseJointGap), r.peer ? std::string() : number(r.figures.energyDrift),
                 r.peer ? std::string() : std::to_string(r.figures.frozen), blewUp ? "1" : "0",
                 r.pareto ? "1" : "0", csvField(r.note)});
  return csvLine(fields);
}

// The header, then a row for each run.
std::string csvText(const std::string& scene, const std::vector<Row>& rows) {
  std::string text =
      "scene,method,model,iterations,substeps,dt,steps,repeats,ms_per_step,ms_per_sim_second,"
      "error,ref_uncertainty,";
  for (const RunMetric& m : kRunMetrics) text += std::string(m.column) + ",";
  text += "error_first,pose_penetration,pose_joint_gap,energy_drift,frozen,blew_up,pareto,note\n";
  for (const Row& r : rows) text += csvRow(scene, r);
  return text;
}

// "3x1": iterations x substeps; nothing for a peer, whose method column names it.
std::string pointLabel(const Row& r) {
  return r.peer ? std::string() : ixs(*r.iterations, *r.substeps);
}

// " tetra dt 0.01": what tells a row from the others of its method, the model (ours) and the dt,
// each where the sweep has several.
std::string modelAndDt(const Row& r, const Plan& plan) {
  const std::string model = plan.models.size() > 1 && !r.peer ? " " + r.model : "";
  return plan.dts.size() > 1 ? model + " dt " + formatNumber(r.dt, 4) : model;
}

// "shake 1x8" (with its model and dt when the sweep has several), or the peer's name.
std::string rowName(const Row& r, const Plan& plan) {
  return (r.peer ? r.method : r.method + " " + pointLabel(r)) + modelAndDt(r, plan);
}

// The simulated time the runs covered, "1" or, when dts cover it differently (a whole step of a
// dt longer than the horizon, rounding), "0.03333 to 1": the horizon, or later for an analytic
// answer after it.
std::string simulatedSeconds(const std::vector<Row>& rows) {
  double shortest = kInf, longest = 0.0;
  for (const Row& r : rows) {
    shortest = std::min(shortest, r.steps * r.dt);
    longest = std::max(longest, r.steps * r.dt);
  }
  if (rows.empty()) shortest = 0.0;
  const std::string most = formatNumber(longest, 4);
  const std::string least = formatNumber(shortest, 4);
  return least == most ? most : least + " to " + most;
}

// The chart's up axis: the distance from the target, or the figure measured.
std::string errorLabel(const AccuracyTarget& firstTarget, std::size_t measure) {
  if (measure < kRunMetricCount) {
    const RunMetric& m = kRunMetrics[measure];
    return m.nameAndUnit() + ": " + m.help;
  }
  return "error (m): largest distance from the " + firstTarget.kind +
         (firstTarget.kind == "analytic" ? " answer" : " run");
}

// A reference's own uncertainty as a line on the chart, `which` naming its model and dt among
// several; none for an analytic answer, a figure of the run table, or a reference that blew up
// (gnuplot read "inf" as a variable).
std::optional<ChartGuide> uncertaintyGuide(const AccuracyTarget& target, std::size_t measure,
                                           const std::string& which) {
  const double u = maxUncertainty(target);
  if (measure < kRunMetricCount || target.kind != "reference" || !std::isfinite(u) || u <= kErrorFloor)
    return std::nullopt;
  return ChartGuide{u, "reference's own uncertainty" + which};
}

// `guides`: each target's uncertainty (uncertaintyGuide).
Chart errorChart(const Plan& plan, const std::vector<Row>& rows, const AccuracyTarget& firstTarget,
                 std::size_t measure, std::vector<ChartGuide> guides) {
  const bool perStep = oneDt(rows);
  Chart c = logChart(
      plan.sceneName + ": " + (measure < kRunMetricCount ? kRunMetrics[measure].name : "error") +
          " against cost (" + simulatedSeconds(rows) + " s simulated; labels: iterations x substeps)",
      perStep ? "ms per step (median wall time of the stepping loop)" : "wall ms per simulated second",
      errorLabel(firstTarget, measure), true, kSweepChart);
  // One series per method or engine (and per model and dt when there are several).
  std::vector<std::string> order;
  auto seriesName = [&](const Row& r) {
    return (r.peer ? r.method + " (peer)" : r.method) + modelAndDt(r, plan);
  };
  for (const Row& r : rows) addOnce(order, seriesName(r));
  // The front first, so the points are drawn over its line.
  ChartSeries front{.title = "Pareto front", .line = true, .labels = true};
  for (const Row& r : frontByCost(rows))
    front.points.push_back({cost(r, perStep), shownError(r, measure), pointLabel(r)});
  c.series.push_back(front);
  for (const std::string& name : order) {
    ChartSeries s{.title = name};
    for (const Row& r : rows) {
      if (seriesName(r) == name && charted(r, measure))
        s.points.push_back({cost(r, perStep), shownError(r, measure), pointLabel(r)});
    }
    c.series.push_back(s);
  }
  c.guides = std::move(guides);
  return c;
}

// ---- the report on stdout ---------------------------------------------------------------------

// One column of the table: its width, and whether its text is set right in it.
struct Column {
  std::size_t width;
  bool right;
};
// method, model, iterations, substeps, a gap, dt, steps, ms/step, error, stick error, penetration,
// energy drift, frozen: the header and the rows through the same widths.
constexpr Column kColumns[] = {{14, false}, {12, false}, {5, true},  {5, true},  {2, false},
                               {10, false}, {6, true},   {10, true}, {11, true}, {10, true},
                               {10, true},  {10, true},  {7, true}};
constexpr std::size_t kErrorColumn = 8;

// The error column's heading: the distance from the target, or the figure --error measures, named
// (a column headed "error (m)" over a tracking error in degrees said the wrong figure).
std::string errorHeading(std::size_t measure) {
  return measure < kRunMetricCount ? kRunMetrics[measure].name : "error (m)";
}

// A line of the table, a cell for each of kColumns. Each figure is set apart from the one before
// by at least a space: a figure wider than its column pushes what follows right only as far as it
// must, and the line is back in its columns where later figures leave room ("1.00001e-05101666"
// was a dt run into a step count).
using TableCells = std::array<std::string, std::size(kColumns)>;

// The two spaces between the setting and the dt: a column with nothing in it.
constexpr const char* kGap = "";

// `measure` widens the error column to its heading's width and a space.
std::string tableLine(const TableCells& cells, std::size_t measure, bool pareto = false) {
  std::string line;
  std::size_t end = 0;  // where the last column ends when nothing overflowed
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::string& text = cells[i];
    const std::size_t width =
        i == kErrorColumn ? std::max(kColumns[i].width, errorHeading(measure).size() + 1) : kColumns[i].width;
    const std::size_t columnEnd = end + width;
    const std::size_t start = !kColumns[i].right        ? end
                              : columnEnd > text.size() ? columnEnd - text.size()
                                                        : 0;
    const bool touching = !line.empty() && line.back() != ' ';
    line.append(start > line.size() ? start - line.size() : touching ? 1 : 0, ' ');
    line += text;
    end = columnEnd;
  }
  return line + (pareto ? "  *" : "") + "\n";
}

std::string tableLine(const Row& r, std::size_t measure) {
  auto opt = [](const std::optional<int>& v) { return v ? std::to_string(*v) : std::string("-"); };
  auto ours = [&](double v) { return r.peer ? std::string("-") : formatNumber(v, 3); };
  const std::string error = measure < kRunMetricCount ? ours(r.figures.maxima[measure])
                                                      : formatNumber(r.blewUp() ? kInf : r.figures.error, 3);
  return tableLine(
      {r.method, r.model.empty() ? "-" : r.model, opt(r.iterations), opt(r.substeps), kGap,
       formatNumber(r.dt, 6), std::to_string(r.steps), formatNumber(r.msPerStep, 4), error,
       ours(r.figures.maxima[kStickErrorMetric]), formatNumber(r.figures.maxima[kPenetrationMetric], 3),
       ours(r.figures.energyDrift), r.peer ? "-" : std::to_string(r.figures.frozen)},
      measure, r.pareto);
}

void printReport(std::ostream& out, const Plan& plan, const std::vector<Row>& rows, std::size_t measure,
                 const std::vector<std::string>& accuracy, const std::vector<std::string>& notes) {
  out << "sweep       " << plan.sceneName << " (" << plan.scene.file.string() << ")\n";
  out << "runs        " << count(plan.settings.size(), "setting", "settings") << " x "
      << count(static_cast<std::size_t>(plan.repeats), "timed run", "timed runs") << " and 1 measured, each "
      << simulatedSeconds(rows) << " s simulated\n";
  for (const std::string& a : accuracy) out << "accuracy    " << a << "\n";
  for (const std::string& n : notes) out << "peers       " << n << "\n";
  if (measure < kRunMetricCount)
    out << "error       " << kRunMetrics[measure].nameAndUnit() << ": " << kRunMetrics[measure].help << "\n";
  out << tableLine({"method", "model", "iter", "sub", kGap, "dt (s)", "steps", "ms/step",
                    errorHeading(measure), "stick err", "penet (m)", "drift (J)", "frozen"},
                   measure);
  for (const Row& r : rows) out << tableLine(r, measure);
}

// ---- the command ----------------------------------------------------------------------------

// The CSVs and the chart, into `files`: "" when the chart was drawn, else why not.
std::string writeOutputs(OutputFolder& files, const Plan& plan, const std::vector<Row>& rows,
                         const AccuracyTarget& firstTarget, std::size_t measure,
                         std::vector<ChartGuide> guides) {
  files.write("results.csv", csvText(plan.sceneName, rows));
  files.write("pareto.csv", csvText(plan.sceneName, frontByCost(rows)));
  const Chart chart = errorChart(plan, rows, firstTarget, measure, std::move(guides));
  std::string problem =  // not const, so that the return moves it
      files.draw(kSweepScript, chart,
                 "no run has a finite error, so there is no chart to draw");  // a 0 is drawn at kErrorFloor
  files.commit();
  return problem;
}

// A line for each dt whose runs cover more than the horizon asked: one whole step of a dt longer
// than it, or a later analytic answer. Said before running, since a small dt then runs long.
std::vector<std::string> longerRuns(const Plan& plan) {
  const scenes::Scene scene = scenes::loadSceneSource(plan.scene, plan.models.front().options);
  std::vector<std::string> lines;
  for (const double dt : plan.dts) {
    const long long asked = std::llround(plan.horizon / dt);
    const int steps = stepsToCover(scene, dt, plan.stepsAt(dt));
    if (steps <= asked) continue;
    lines.push_back("dt " + formatNumber(dt) + " runs " +
                    count(static_cast<std::size_t>(steps), "step", "steps") + " to cover " +
                    formatNumber(steps * dt, 4) + " s (the horizon asked: " + formatNumber(plan.horizon, 4) +
                    " s)");
  }
  return lines;
}

int runSweep(const Plan& plan, std::size_t measure, const std::filesystem::path& outDir, std::ostream& out,
             std::ostream& err) {
  for (const std::string& line : longerRuns(plan)) out << "longer      " << line << "\n";
  out.flush();
  PlanResult result = runPlan(plan, err, "sweep");
  TargetCache& targets = result.targets;
  // A peer that could not run has no row in the files: a line says why.
  std::vector<Row> rows;
  std::vector<std::string> notes;
  for (Row& r : result.rows) {
    if (r.ran)
      rows.push_back(std::move(r));
    else
      notes.push_back(r.method + " not run: " + r.note);
  }
  markPareto(rows, measure);

  // Each distinct target once, named by its model and dt when there are several; each reference's
  // uncertainty a line of the chart (only the first target's was drawn).
  std::vector<std::string> accuracy;
  std::vector<ChartGuide> guides;
  for (const ModelChoice& m : plan.models) {
    for (double dt : plan.dts) {
      const Setting key{m, phys::SolverMethod::GaussSeidel, 1, 1, dt};
      const AccuracyTarget& target = targets.get(plan.scene, key, plan.stepsAt(dt));
      std::string which;
      if (plan.models.size() > 1 || plan.dts.size() > 1) {
        // Built piecewise: "(" + std::string trips GCC 12's false -Wrestrict (bug 105329).
        which = "(";
        if (!m.label.empty()) which += m.label + ", ";
        which += "dt " + formatNumber(dt) + ")";
      }
      accuracy.push_back(which.empty() ? target.description : which + " " + target.description);
      if (auto guide = uncertaintyGuide(target, measure, which.empty() ? which : " " + which))
        guides.push_back(*guide);
    }
  }
  printReport(out, plan, rows, measure, accuracy, notes);
  OutputFolder files(outDir);
  const std::string chartProblem = writeOutputs(
      files, plan, rows, firstTarget(plan, targets, plan.dts.front()), measure, std::move(guides));
  const auto front = frontByCost(rows);
  out << "pareto      " << count(front.size(), "setting", "settings") << " (marked *):";
  for (std::size_t i = 0; i < front.size(); ++i) out << (i == 0 ? " " : ", ") << rowName(front[i], plan);
  out << "\n" << files.wroteLine();
  if (!chartProblem.empty()) err << "lab: sweep: " << chartProblem << "\n";
  return files.failed() ? kExitFailure : kExitOk;
}

int sweepCommand(const SweepOptions& o, std::ostream& out, std::ostream& err) {
  const scenes::SceneSource scene = scenes::readSceneSource(sceneFile(o.scene, o.dataDir));
  PlanRequest request = o.request;
  // Throws UsageError for a --models that does not fit the scene (and makePlan for too many runs).
  request.models = modelChoices(o.models, sceneModels(scene));
  const Plan plan = makePlan(scene, request);
  // A chart of a figure that is 0 at every setting (a tracking error without a character) says nothing.
  if (o.measure < kRunMetricCount) {
    const RunMetric& m = kRunMetrics[o.measure];
    requireMeasurable(m.lacks, scene, plan.models,
                      "--error " + std::string(m.name) + ": scene " + plan.sceneName, "swept",
                      "it is 0 at every setting");
  }
  refuseOutputsOverScenes(o.out, sweepFiles(), {sceneFile(o.scene, o.dataDir)});
  prepareOutputFiles(o.out, sweepFiles());  // a sweep takes minutes: say a bad --out now
  return runSweep(plan, o.measure, o.out, out, err);
}

}  // namespace

std::vector<std::string> sweepFiles() {
  return {"results.csv", "pareto.csv", kSweepScript, std::string(kSweepChart) + ".png",
          std::string(kSweepChart) + ".svg"};
}

constinit const CommandMain sweepMain = commandMainOf<SweepOptions, describeSweep, sweepCommand>;

}  // namespace lab
