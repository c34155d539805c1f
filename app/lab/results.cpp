// lab report: runs the sweeps of the seed's scenes, the stability suite and the comparison with
// the peers, each through its own command (so the report shows exactly what a user would get
// from them), and writes docs/results.md around their files. The words about which method wins
// where are computed from the figures, so regenerating the report cannot leave them stale.
#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <ostream>
#include <sstream>
#include <type_traits>

#include "command_line.h"
#include "commands.h"
#include "converge.h"
#include "csv.h"
#include "fileio/files.h"
#include "gnuplot.h"
#include "lab.h"
#include "output_files.h"
#include "report.h"
#include "scenes/scene.h"
#include "text.h"

namespace lab {
namespace {

namespace fs = std::filesystem;

// The four methods, as --methods takes them: the seed's scenes and the particle ragdoll are swept over all.
constexpr const char* kEveryMethod = "gauss-seidel,jacobi,xpbd,shake";

struct ReportOptions {
  fs::path out;
  fs::path data;
  bool quick = false;
};

// "xpbd 2x4" or "bullet": how a row is named in the report's sentences.
std::string settingName(const CsvRow& r) {
  const std::string iterations = fieldText(r, "iterations"), substeps = fieldText(r, "substeps");
  if (iterations.empty()) return fieldText(r, "method");  // a peer engine
  std::string name = fieldText(r, "method") + " " + iterations + "x" + substeps;
  if (!fieldText(r, "model").empty()) name += " (model " + fieldText(r, "model") + ")";
  return name;
}

// A length as people read it: millimetres up to a metre, metres beyond.
std::string millimetres(double metres) {
  if (!std::isfinite(metres)) return "blew up";
  if (metres >= 1.0) return formatNumber(metres, 3) + " m";
  return formatNumber(metres * 1000.0, 3) + " mm";
}

// Ratios to two decimals, so 1.04 does not read as "1 times".
std::string ratio(double value) {
  return printed("%.2f", value);
}

// The commands write reports that start at "#"; inside results.md they sit under a "##".
std::string demoteHeadings(const std::string& markdown) {
  std::istringstream in(markdown);
  std::string line, out;
  bool fenced = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) fenced = !fenced;
    if (!fenced && !line.empty() && line[0] == '#') line = "##" + line;
    out += line + "\n";
  }
  return out;
}

// ---- running the commands ---------------------------------------------------------------------

// A command's table as a code block, without its last line ("wrote ..."), which names the files
// by their paths on this machine.
std::string tableBlock(std::string printed) {
  if (const std::size_t wrote = printed.rfind("wrote "); wrote != std::string::npos) printed.erase(wrote);
  return "```\n" + printed + "```\n";
}

// results.md as it is written, and whether any of the commands it ran failed.
struct Report {
  const ReportOptions& o;
  std::ostream& progress;
  std::ostringstream md;
  bool failed = false;

  // `common`, then the quick report's own arguments or the full report's.
  std::vector<std::string> quickOrFull(std::vector<std::string> common, const std::vector<std::string>& quick,
                                       const std::vector<std::string>& full = {}) const {
    const std::vector<std::string>& own = o.quick ? quick : full;
    common.insert(common.end(), own.begin(), own.end());
    return common;
  }

  // Runs `lab COMMAND ARGS`, saying which first (the full report takes minutes), and writes what
  // `shown` makes of its output; if it failed, its message stands where its figures would be.
  void section(const std::string& command, const std::vector<std::string>& args,
               const std::function<std::string(const std::string&)>& shown = demoteHeadings) {
    progress << "lab report: lab " << command << ' ' << join(args, " ") << std::endl;  // every one has args
    const CommandOutput r = runCaptured(command, args);
    failed |= r.code != 0;
    if (r.code == 0) {
      md << shown(r.out);
      sayWarnings(r.err);
    } else
      md << "The command failed (exit " << r.code << "):\n\n```\n" << r.err << "```\n";
    md << "\n";
  }

  // What a command that succeeded said on stderr as "lab: ..." (a chart with nothing to draw, say),
  // which was dropped; but gnuplot missing, which the report says once.
  void sayWarnings(const std::string& err) const {
    std::istringstream lines(err);
    for (std::string line; std::getline(lines, line);) {
      if (line.starts_with("lab: ") && line.find(kGnuplotMissing) == std::string::npos)
        progress << line << "\n";
    }
  }

  // The link to a chart, results/PATH, when the command before drew it: without gnuplot, or with
  // nothing to draw, it is not there (a command removes a chart it did not draw), and a link
  // would show a broken picture.
  std::string picture(const std::string& alt, const std::string& path) const {
    return fs::exists(o.out / "results" / path) ? "![" + alt + "](results/" + path + ")\n\n" : std::string();
  }

  // A sweep into results/FOLDER: its chart (`chart` its alt text), what `words` make of its
  // figures, and a link to all its runs.
  void sweep(const std::string& folder, const std::string& chart,
             std::string (*words)(const std::vector<CsvRow>&), const std::vector<std::string>& args) {
    section("sweep", args, [&](const std::string&) {
      return picture(chart, folder + "/error-vs-cost.png") +
             words(readCsv(o.out / "results" / folder / "results.csv").rows) +
             "\nAll runs: [results.csv](results/" + folder + "/results.csv).\n";
    });
  }
};

// ---- the sweeps -------------------------------------------------------------------------------

struct SweepScene {
  const char* name;
  const char* why;  // one line for the report
};

// The seed's three scenes, the chain its mass ratio makes hard, and a scene with an exact answer.
constexpr SweepScene kSweepScenes[] = {
    {"ragdoll", "the seed's scene 1: one ragdoll dropped from 2 m (reference run; chaotic after it lands)"},
    {"pyramid", "the seed's scene 2: a pyramid of boxes that vary in size (reference run)"},
    {"box-of-boxes", "the seed's scene 3: three 3x3 layers of boxes (reference run)"},
    {"chain", "a 20-link chain with a 100:1 end mass (reference run)"},
    {"pendulum-exact", "a 2 m pendulum released at 90 degrees, against its exact motion (analytic)"},
};

// The row of least `cost` for each key (`keyOf` a row) among the rows `keep` accepts, the first
// on a tie; every key of the rows is there, null where `keep` accepts none of its rows, so a
// table can say which never qualified.
template <typename KeyOf, typename Keep>
auto cheapestBy(const std::vector<CsvRow>& rows, KeyOf keyOf, const char* cost, Keep keep) {
  std::map<std::invoke_result_t<KeyOf, const CsvRow&>, const CsvRow*> cheapest;
  for (const CsvRow& r : rows) {
    const CsvRow*& c = cheapest[keyOf(r)];
    if (keep(r) && (c == nullptr || fieldNumber(r, cost) < fieldNumber(*c, cost))) c = &r;
  }
  return cheapest;
}

// The keys the report's tables group rows by.
constexpr auto methodOf = [](const CsvRow& r) { return fieldText(r, "method"); };
constexpr auto dtOf = [](const CsvRow& r) { return fieldNumber(r, "dt"); };

// "Pareto front, cheapest first: a; b.": a sweep's rows marked as on its front, cheapest per
// simulated second first, each as `describe` puts it.
template <typename Describe>
std::string frontSentence(const std::vector<CsvRow>& rows, Describe describe) {
  std::vector<const CsvRow*> front;
  for (const CsvRow& r : rows) {
    if (fieldText(r, "pareto") == "1") front.push_back(&r);
  }
  std::sort(front.begin(), front.end(), [](const CsvRow* a, const CsvRow* b) {
    return fieldNumber(*a, "ms_per_sim_second") < fieldNumber(*b, "ms_per_sim_second");
  });
  std::string text = "Pareto front, cheapest first:";
  for (std::size_t i = 0; i < front.size(); ++i) text += (i == 0 ? " " : "; ") + describe(*front[i]);
  return text + ".";
}

// What the figures say about a sweep, in sentences: the front from cheap to accurate, and for
// each method its cheapest setting that comes within reach of the most accurate run.
std::string sweepWords(const std::vector<CsvRow>& rows) {
  double best = kInf, uncertainty = 0.0;
  for (const CsvRow& r : rows) {
    best = std::min(best, fieldNumber(r, "error"));
    const double u = fieldNumber(r, "ref_uncertainty");
    if (std::isfinite(u)) uncertainty = std::max(uncertainty, u);
  }
  std::ostringstream md;
  md << frontSentence(rows, [](const CsvRow& r) {
    return settingName(r) + " (" + formatNumber(fieldNumber(r, "ms_per_step"), 3) + " ms/step, " +
           millimetres(fieldNumber(r, "error")) + ")";
  }) << "\n\n";
  // "Within reach": ten times the best error, or the reference's own uncertainty if larger
  // (errors below it cannot be told apart), and never below 1 mm.
  const double reach = std::max({10.0 * best, uncertainty, 1e-3});
  md << "Cheapest setting of each method within " << millimetres(reach) << " of the target:\n\n";
  md << "| method | setting | ms/step | error |\n|---|---|---|---|\n";
  const auto cheapest = cheapestBy(rows, methodOf, "ms_per_sim_second",
                                   [&](const CsvRow& r) { return fieldNumber(r, "error") <= reach; });
  std::vector<std::pair<double, const CsvRow*>> ordered;
  std::string never;
  for (const auto& [method, row] : cheapest) {
    if (row == nullptr)
      never += (never.empty() ? " " : ", ") + method;
    else
      ordered.emplace_back(fieldNumber(*row, "ms_per_sim_second"), row);
  }
  std::sort(ordered.begin(), ordered.end());
  for (const auto& [cost, row] : ordered) {
    md << "| " << fieldText(*row, "method") << " | " << settingName(*row) << " | "
       << formatNumber(fieldNumber(*row, "ms_per_step"), 3) << " | "
       << millimetres(fieldNumber(*row, "error")) << " |\n";
  }
  if (!never.empty()) md << "\nNever within reach at the settings swept:" << never << ".\n";
  if (!ordered.empty()) {
    md << "\n**Winner here: " << settingName(*ordered.front().second) << "**";
    if (ordered.size() > 1) {
      md << "; the next method's cheapest, " << settingName(*ordered[1].second) << ", costs "
         << ratio(ordered[1].first / ordered.front().first) << " times as much";
    }
    md << ".\n";
  }
  return md.str();
}

// ---- pose tracking ---------------------------------------------------------------------------

// The issue's bar for the run cycle: its parts within 5 degrees RMS of the clip at 1/60 s.
constexpr double kTrackingBar = 5.0;  // unit: degrees

// Whether a tracking row is within the bar; a run that blew up (inf or NaN) is not.
bool withinBar(const CsvRow& r) {
  const double e = fieldNumber(r, "rms_tracking_error");
  return std::isfinite(e) && e <= kTrackingBar;
}

// A row's tracking error as the report prints it: "11.4 deg".
std::string degrees(const CsvRow& r) {
  return formatNumber(fieldNumber(r, "rms_tracking_error"), 3) + " deg";
}

// "setting | ms/step | error" of a cheapest-within-the-bar row, or "none | - | -".
std::string cheapestCells(const CsvRow* r) {
  if (r == nullptr) return "none | - | -";
  return settingName(*r) + " | " + formatNumber(fieldNumber(*r, "ms_per_step"), 3) + " | " + degrees(*r);
}

// The tracking scenes, one a ragdoll shape, each swept into results/<folder>.
// A rigid ragdoll is solved by XPBD whatever the method, so only particle ones sweep the four.
struct TrackingScene {
  const char* scene;
  const char* folder;
  const char* what;
  bool everyMethod;
};
constexpr TrackingScene kTrackingScenes[] = {
    {"run-cycle", "tracking", "The box ragdoll (`run-cycle.xml`)", false},
    {"run-cycle-capsule", "tracking-capsule",
     "The capsule ragdoll (`run-cycle-capsule.xml`, on its own run cycle)", false},
    {"run-cycle-lean", "tracking-lean",
     "The lean particle box ragdoll (`run-cycle-lean.xml`: the box ragdoll's shapes, each box four particles "
     "and six sticks, driven through its particle joints), under each of the four methods",
     true},
};

// Where a sweep ran more than one method: each one's cheapest setting within the bar at the issue's
// dt of 1/60 s, so that the methods can be read against each other at one step size.
std::string trackingByMethod(const std::vector<CsvRow>& rows) {
  constexpr double kDt = 1.0 / 60.0;  // unit: s
  std::vector<CsvRow> atDt;
  std::copy_if(rows.begin(), rows.end(), std::back_inserter(atDt),
               [](const CsvRow& r) { return std::abs(dtOf(r) - kDt) <= 1e-9; });
  const auto cheapest = cheapestBy(atDt, methodOf, "ms_per_step", withinBar);
  if (cheapest.size() < 2) return {};
  std::ostringstream md;
  md << "\nAt dt 1/60, each method's cheapest setting within the bar:\n\n"
     << "| method | cheapest within the bar | ms/step | tracking error |\n|---|---|---:|---:|\n";
  for (const auto& [method, r] : cheapest) md << "| " << method << " | " << cheapestCells(r) << " |\n";
  return md.str();
}

// The front of the tracking sweep and, at each dt, the cheapest setting within the bar.
std::string trackingWords(const std::vector<CsvRow>& rows) {
  std::ostringstream md;
  md << frontSentence(rows, [](const CsvRow& r) {
    return settingName(r) + " at dt 1/" + formatNumber(1.0 / dtOf(r), 3) + " (" +
           formatNumber(fieldNumber(r, "ms_per_sim_second"), 3) + " ms per simulated s, " + degrees(r) + ")";
  }) << "\n\n";
  md << "Cheapest setting at each dt within " << formatNumber(kTrackingBar, 3)
     << " degrees RMS, and the best any setting at that dt reached:\n\n"
     << "| dt | cheapest within the bar | ms/step | tracking error | best setting | its error |\n"
     << "|---|---|---:|---:|---|---:|\n";
  const auto best = cheapestBy(rows, dtOf, "rms_tracking_error", [](const CsvRow& r) {
    return std::isfinite(fieldNumber(r, "rms_tracking_error"));
  });
  for (const auto& [dt, cheapest] : cheapestBy(rows, dtOf, "ms_per_step", withinBar)) {
    const CsvRow* b = best.at(dt);
    md << "| 1/" << formatNumber(1.0 / dt, 3) << " | " << cheapestCells(cheapest) << " | "
       << (b != nullptr ? settingName(*b) + " | " + degrees(*b) : std::string("- | -")) << " |\n";
  }
  md << trackingByMethod(rows);
  return md.str();
}

// ---- the report -------------------------------------------------------------------------------

std::string today() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d", std::gmtime(&now));
  return text;
}

std::string machine() {
  std::ifstream cpu("/proc/cpuinfo");
  std::string line, model;
  int cores = 0;
  while (std::getline(cpu, line)) {
    if (line.rfind("model name", 0) == 0 && model.empty()) model = line.substr(line.find(':') + 2);
    if (line.rfind("processor", 0) == 0) ++cores;
  }
  return (model.empty() ? std::string("unknown CPU") : model) + ", " + std::to_string(cores) + " cores";
}

void describeReport(CommandLine& line, ReportOptions& o) {
  line.about(
      "Runs the lab's commands and writes docs/results.md and its charts from what they print.\n"
      "Takes several minutes in full; `make charts` runs it.");
  line.option(option::kOut, o.out,
              "results.md and its results/ folder (default: <data>/docs; required with --quick)");
  line.flag(option::kQuick, o.quick, true, "");
  line.option(option::kData, o.data, "");
}

// The scenes of the report's `lab converge`: one checks the pipeline.
std::vector<std::string> convergeScenes(const ReportOptions& o) {
  return o.quick ? std::vector<std::string>{"circular-orbit"} : kConvergeScenes;
}

// Every file the report and the commands it runs will write, checked before the first of them runs:
// a folder in place of the last command's CSV is said before the sweeps, not after them.
void prepareEveryOutput(const ReportOptions& o, const fs::path& results) {
  prepareOutputFolder(results);
  checkOutputFile(o.out / "results.md");
  for (const SweepScene& s : kSweepScenes) prepareOutputFiles(results / s.name, sweepFiles());
  for (const TrackingScene& t : kTrackingScenes) prepareOutputFiles(results / t.folder, sweepFiles());
  for (const char* folder : {"stability", "stability-rigid"})
    prepareOutputFiles(results / folder, stabilityFiles());
  prepareOutputFiles(results / "scale", scaleFiles());
  prepareOutputFiles(results / "converge",
                     convergeFiles(convergeSceneNames(convergeScenes(o), scenes::sceneDirectory(o.data))));
}

int writeReport(ReportOptions o, std::ostream& out, std::ostream& err) {
  o.data = dataDir(o.data);
  // Every part would fail on it, and the default --out lies inside it: said before either.
  requireFolder(o.data, "--data");
  // The default --out holds the checked-in results: a quick report's tiny figures there would
  // replace them, so a quick report goes where it is told.
  if (o.quick && o.out.empty())
    throw UsageError("--quick needs --out DIR: its tiny figures would replace the checked-in " +
                     (o.data / "docs" / "results.md").string());
  if (o.out.empty()) o.out = o.data / "docs";
  const fs::path results = o.out / "results";
  prepareEveryOutput(o, results);  // before the runs, which take minutes
  const std::string data = o.data.string();
  Report report{o, err};
  std::ostringstream& md = report.md;
  md << "# Results\n\nMeasured on " << today() << " on " << machine() << ", in one run of `"
     << (o.quick ? "lab report --quick" : "make charts")
     << "` (`lab report`, docs/lab.md), so every figure below comes from the same machine, build and load. "
        "Regenerate with `make charts`. Times are wall-clock ms per step as each command defines them "
        "(docs/lab.md); errors are in millimetres against each scene's analytic answers or its converged "
        "reference run (docs/lab.md, \"Accuracy\"). A peer's error also holds the difference between its "
        "contact model and ours, which no setting of either removes.\n\n";
  if (o.quick)
    md << "**This is a --quick report: tiny sweeps that check the pipeline, not figures to quote.**\n\n";
  // Said once here, not by every command it runs (and dropped from their stderr).
  if (findGnuplot().empty()) {
    err << "lab report: " << kGnuplotMissing
        << ": no chart is drawn, "
           "results.md links none, and the stability suite, which needs its heat maps, fails\n";
    md << "**gnuplot was not installed: no chart was drawn.** Each command's data and gnuplot script are "
          "written; run gnuplot on a script in its folder to draw its chart.\n\n";
  }

  md << "## Speed against accuracy\n\n"
     << "Each chart plots error against cost for every method x iterations x substeps combination "
        "(and each peer engine at the scene's dt); the line joins the Pareto front, the runs nothing beats "
        "on both.\n\n";
  for (const SweepScene& s : kSweepScenes) {
    md << "### " << s.name << "\n\n" << s.why << ".\n\n";
    report.sweep(s.name, "error against cost, " + std::string(s.name), sweepWords,
                 report.quickOrFull({s.name, "--out", (results / s.name).string(), "--data", data},
                                    {"--methods", "gauss-seidel,xpbd", "--iterations", "1,2", "--substeps",
                                     "1", "--repeat", "1", "--steps", "10"},
                                    {"--methods", kEveryMethod, "--iterations", "1,2,4,8", "--substeps",
                                     "1,2,4,8", "--repeat", "3"}));
  }

  md << "## Pose tracking\n\n"
     << "One ragdoll on the run cycle (strength 0.9, its root part carried by the hand of god), the RMS over "
        "the run's steps and over its parts of the angle between each part and its target (`lab sweep "
        "run-cycle --error tracking-error`), against cost per simulated second, at dt 1/30, 1/60 and 1/120 "
        "s, for the box ragdoll and the capsule ragdoll, both rigid, and for the lean particle box ragdoll. "
        "A rigid body is solved by XPBD whatever the method, so the four methods are one for the rigid "
        "ragdolls; the lean ragdoll's boxes are particles held by sticks and its drives are its particle "
        "joints' (docs/physics.md, \"Joint drives\"), which each method projects its own way, so it is swept "
        "under all four. The runner starts in the clip's first pose (`pose=\"clip\"`), so the figure is the "
        "tracking and not the turn into the clip.\n\n";
  for (const TrackingScene& t : kTrackingScenes) {
    md << "### " << t.scene << "\n\n" << t.what << ".\n\n";
    std::vector<std::string> args{t.scene,      "--error", "tracking-error",
                                  "--no-peers", "--out",   (results / t.folder).string(),
                                  "--data",     data};
    if (t.everyMethod) args.insert(args.end(), {"--methods", kEveryMethod});
    report.sweep(
        t.folder, "tracking error against cost, " + std::string(t.scene), trackingWords,
        report.quickOrFull(args, {"--iterations", "1,2", "--substeps", "1", "--repeat", "1", "--steps", "10"},
                           {"--iterations", "1,2,4,8", "--substeps", "1,2,4,8", "--dt",
                            "0.0333333333333333,0.0166666666666667,0.00833333333333333", "--steps", "600"}));
    report.section("run", report.quickOrFull({t.scene, "--json", "--data", data}, {"--steps", "10"}),
                   [&](const std::string& json) { return drivesTable(t.scene, json); });
  }

  md << "## Where methods fail\n\n";
  // Every run to its end: the error map shades how far each failing run went, which a run
  // stopped once it failed for good would not say.
  report.section(
      "stability",
      report.quickOrFull(
          {"--out", (results / "stability").string(), "--data", data, "--whole-runs"},
          {"--scene", "face-face", "--methods", "gauss-seidel,xpbd", "--iterations", "1", "--substeps", "1"}),
      [&](const std::string& printed) {
        return report.picture("pass or fail per scene and setting", "stability/stability-pass.png") +
               report.picture("error figure per scene and setting", "stability/stability-error.png") +
               demoteHeadings(printed);
      });
  // The same suite with every box and ragdoll rigid, the model as the map's axis: a rigid body
  // is solved by XPBD whatever the method, so one block of settings.
  md << "### The rigid model on the same suite\n\n"
     << "Every box and ragdoll of each scene made rigid (`lab stability --models rigid --methods xpbd "
        "--no-peers`): the chains have no body and run as they are. Set beside the table above, it shows "
        "which model holds each scene at the fewest passes.\n\n";
  report.section("stability",
                 report.quickOrFull({"--out", (results / "stability-rigid").string(), "--data", data,
                                     "--models", "rigid", "--methods", "xpbd", "--no-peers"},
                                    {"--scene", "face-face", "--iterations", "1", "--substeps", "1"}),
                 [&](const std::string& printed) {
                   return report.picture("pass or fail per scene and setting, rigid",
                                         "stability-rigid/stability-pass.png") +
                          demoteHeadings(printed);
                 });

  md << "## Beside Bullet, ODE and MuJoCo\n\n";
  // The scenes set beside the peers, each with what the full report adds to its arguments.
  const std::pair<const char*, std::vector<std::string>> compared[] = {
      {"pyramid", {}}, {"ragdoll", {}}, {"bullet-ragdolls", {"--steps", "120"}}};
  for (const auto& [scene, full] : compared) {
    md << "### " << scene << "\n\n";
    report.section("compare", report.quickOrFull({scene, "--data", data}, {"--steps", "5"}, full));
    if (o.quick) break;  // one scene checks the pipeline
  }
  if (!o.quick) {
    md << "### bullet-ragdolls, rigid ragdolls with their joints projected\n\n"
       << "The same pile with every ragdoll rigid at 1 iteration x 2 substeps, its joints closed by a direct "
          "solve after each substep's passes (docs/physics.md, \"Joint projection\"): the joint gap against "
          "the peers' at a fraction of Bullet's step.\n\n";
    report.section("compare", {"bullet-ragdolls", "--data", data, "--models", "rigid", "--iterations", "1",
                               "--substeps", "2", "--joint-projection", "on", "--steps", "120"});
  }

  md << "## Cost against size\n\n"
     << "Capsule ragdolls on a grid, 2 m apart, tipped to fall onto each other, at each size for 1 s at "
        "Bullet's pile's settings, on one thread and on two (`lab scale`, docs/lab.md): a step whose cost is "
        "linear in the number of bodies draws a flat line.\n\n";
  report.section("scale",
                 report.quickOrFull({"--out", (results / "scale").string()},
                                    {"--sizes", "1,2", "--steps", "5"}, {"--threads", "1,2"}),
                 [&](const std::string& printed) {
                   return report.picture("microseconds per body-step against bodies", "scale/scale.png") +
                          tableBlock(printed);
                 });

  md << "## Error against substep size\n\n"
     << "Each method and model on the scenes with exact answers, at the scene's dt of 1/60 s and 4 "
        "iterations, the substep h halving from dt to dt / 64 (`lab converge`, docs/lab.md): a method of "
        "order p draws a line of slope p. docs/physics.md, \"Order of accuracy\", says why projection along "
        "the stick's current direction is first order and SHAKE second.\n\n";
  report.section(
      "converge",
      report.quickOrFull({"--out", (results / "converge").string(), "--data", data},
                         {"circular-orbit", "--substeps", "1,2"}),
      [&](const std::string& printed) {
        // Each chart by the name converge gave it, from the scene's own name and unique in the
        // folder: a link made of the name given here missed a scene whose <scene name> differs.
        const std::vector<std::string> names =
            convergeSceneNames(convergeScenes(o), scenes::sceneDirectory(o.data));
        const std::vector<std::string> files = convergeChartNames(names);
        std::string charts;
        for (std::size_t k = 0; k < names.size(); ++k)
          charts += report.picture("error against h, " + names[k], "converge/" + files[k] + ".png");
        return charts + tableBlock(printed) + "\nAll runs: [converge.csv](results/converge/converge.csv).\n";
      });

  fileio::writeAtomically(o.out / "results.md", md.str());
  out << "wrote " << (o.out / "results.md").string() << " and " << results.string() << "/\n";
  return report.failed ? kExitFailure : kExitOk;
}

}  // namespace

constinit const CommandMain reportMain = commandMainOf<ReportOptions, describeReport, writeReport>;

}  // namespace lab
