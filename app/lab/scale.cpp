// lab scale: the cost of a step against the size of the scene (docs/lab.md, "lab scale"). A scene
// generator makes the same scene at each size, at the same density, so that a step whose cost is
// linear in the number of bodies shows as a flat line of microseconds per body-step.
#include "scale.h"
#include "json.h"
#include "text.h"

#include <cmath>
#include <ostream>
#include <stdexcept>

#include "charts.h"
#include "command_line.h"
#include "commands.h"
#include "csv.h"
#include "lab.h"
#include "options.h"
#include "output_files.h"
#include "run.h"
#include "scenes/scene.h"
#include "sweep_core.h"

namespace lab {
namespace {

constexpr int kDefaultScaleSteps = 60;

// What each kind generates, in ScaleKind's order: its name, the <world>, <solver> and <ground> it
// is run at elsewhere, and each ragdoll's attributes (none for the pyramid).
struct ScaleKindSpec {
  const char* name;
  const char* settings;
  const char* ragdoll;
};
constexpr ScaleKindSpec kScaleKinds[] = {
    // Bullet's pile's settings (bullet-ragdolls.xml) at scale 1.
    {"capsule-ragdolls",
     "  <world gravity=\"0 -10 0\" damping=\"0.05\"/>\n"
     "  <solver method=\"gauss-seidel\" iterations=\"2\" substeps=\"4\" body-damping=\"1\"/>\n"
     "  <ground friction=\"0.25\"/>\n",
     "shape=\"capsule\" model=\"lean\" mass=\"11\" friction=\"0.25\" joint-damping=\"2\""},
    // The 16 ragdolls' settings (ragdolls.xml).
    {"box-ragdolls",
     "  <world gravity=\"0 -9.81 0\" damping=\"0.2\"/>\n"
     "  <solver method=\"gauss-seidel\" iterations=\"2\" substeps=\"4\" body-damping=\"1\"/>\n"
     "  <ground friction=\"0.6\"/>\n",
     "shape=\"box\""},
    // 10 passes x 4 substeps: where the stability suite's pyramids stand.
    {"pyramid",
     "  <world gravity=\"0 -9.81 0\"/>\n"
     "  <solver method=\"gauss-seidel\" iterations=\"10\" substeps=\"4\"/>\n"
     "  <ground friction=\"0.6\"/>\n",
     nullptr},
};

static_assert(std::string_view(kScaleKinds[static_cast<std::size_t>(ScaleKind::Pyramid)].name) == "pyramid",
              "kScaleKinds follows ScaleKind's order");

// A value cast from outside ScaleKind is refused, as the physics' enums refuse theirs.
const ScaleKindSpec& specOf(ScaleKind kind) {
  const auto index = static_cast<std::size_t>(kind);
  if (index >= std::size(kScaleKinds))
    throw std::invalid_argument("ScaleKind " + std::to_string(index) + " is not a kind of lab scale");
  return kScaleKinds[index];
}

struct ScaleOptions {
  ScaleKind kind = ScaleKind::CapsuleRagdolls;
  std::vector<int> sizes;                       // empty: the kind's defaults
  RunOptions run{.steps = kDefaultScaleSteps};  // steps and solver overrides
  std::vector<int> threads;                     // --threads: each size at each; empty: the scene's
  bool json = false;
  std::optional<std::filesystem::path> out;
  std::optional<std::filesystem::path> scenes;  // --save-scenes
};

void describeScale(CommandLine& line, ScaleOptions& o) {
  line.about("Generates a scene of each size and steps it: the cost per step and per body against size.");
  line.positional("KIND", "capsule-ragdolls (default), box-ragdolls or pyramid", false,
                  [&o](const std::string& word) {
                    for (std::size_t i = 0; i < std::size(kScaleKinds); ++i) {
                      if (word != kScaleKinds[i].name) continue;
                      o.kind = static_cast<ScaleKind>(i);
                      return std::string();
                    }
                    return "unknown KIND '" + word + "' (capsule-ragdolls, box-ragdolls or pyramid)";
                  });
  line.option(option::kSizes, o.sizes,
              "(a pyramid's at most " + std::to_string(scenes::kMaxPyramidBase) +
                  "; default 1,4,16,64,256,1024 ragdolls; 5,10,20,40 for a pyramid)");
  line.option(option::kSteps, o.run.steps, "at each size (default 60: 1 s)");
  line.option(option::kMethods, o.run.method, "(default: the generated scene's)");
  line.option(option::kIterations, o.run.iterations, "(default: the scene's)");
  line.option(option::kSubsteps, o.run.substeps, "(default: the scene's)");
  line.option(option::kThreads, o.threads, "(default 1); each size runs once at each, in turn");
  line.flag(option::kJson, o.json, true, "an array, one object per run, instead of the table");
  line.option(option::kOut, o.out, "scale.csv, scale.gp and the chart scale.png, .svg");
  line.option(option::kSaveScenes, o.scenes, "");
}

// Ragdolls stand on a square grid, 2 m apart (a ragdoll is 1.7 m tall at scale 1), each tipped
// 20 degrees one way or another so that they fall onto their neighbours: the same pile of
// touching ragdolls per square metre at every size.
std::string ragdollGrid(int n, const char* attributes) {
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  std::string xml;
  for (int i = 0; i < n; ++i) {
    const int row = i / side, column = i % side;
    const double x = 2.0 * (column - (side - 1) / 2.0), z = 2.0 * (row - (side - 1) / 2.0);
    const double tipX = (i % 2 == 0 ? 20.0 : -20.0), tipZ = ((i / 2) % 2 == 0 ? 20.0 : -20.0);
    xml += printed("  <ragdoll name=\"r%d\" %s pos=\"%g 1.2 %g\" euler=\"%g 0 %g\"/>\n", i, attributes, x, z,
                   tipX, tipZ);
  }
  return xml;
}

}  // namespace

std::string_view toString(ScaleKind kind) {
  return specOf(kind).name;
}

std::string scaleSceneXml(ScaleKind kind, int n) {
  const ScaleKindSpec& spec = specOf(kind);
  std::string xml =
      "<scene name=\"" + std::string(spec.name) + "-" + std::to_string(n) + "\">\n" + spec.settings;
  if (spec.ragdoll != nullptr)
    xml += ragdollGrid(n, spec.ragdoll);
  else
    xml += "  <pyramid name=\"pyramid\" pos=\"0 0 0\" base=\"" + std::to_string(n) +
           "\" size=\"1\" mass=\"1\"/>\n";
  return xml + "</scene>\n";
}

// The thread counts of one size's runs follow each other, so that their ratio is measured while the
// machine is as loaded for one as for the other.
std::vector<ScaleRow> runScale(ScaleKind kind, const std::vector<int>& sizes, const RunOptions& options,
                               const std::vector<int>& threads, std::ostream* progress) {
  std::vector<ScaleRow> rows;
  std::vector<std::optional<int>> counts(threads.begin(), threads.end());
  if (counts.empty()) counts.push_back(options.threads);
  for (const int n : sizes) {
    const std::string xml = scaleSceneXml(kind, n);
    for (const std::optional<int> count : counts) {
      scenes::Scene scene = scenes::loadSceneText(xml, std::string(toString(kind)) + ".xml");
      RunOptions run = options;
      run.threads = count;
      const RunResult r = runScene(scene, run, progress);
      rows.push_back(
          {.scene = std::string(toString(kind)),
           .n = n,
           .bodies = r.bodies,
           .solver = r.solver,
           .msPerStep = r.medianStepMs,
           .usPerBodyStep = r.bodies > 0 ? 1000.0 * r.medianStepMs / static_cast<double>(r.bodies) : 0.0,
           .maxJointGap = r.worst[runMetricIndex("joint-error")],
           .blewUp = !r.freezes.empty()});
    }
  }
  return rows;
}

std::string scaleJson(const std::vector<ScaleRow>& rows) {
  // An array with one object a line, so that a person can read it and grep can find a size.
  std::vector<std::string> objects;
  objects.reserve(rows.size());
  for (const ScaleRow& r : rows) {
    const Json j = {{"scene", r.scene},
                    {"n", r.n},
                    {"threads", r.solver.threads},
                    {"bodies", r.bodies},
                    {"ms_per_step", r.msPerStep},
                    {"us_per_body_step", r.usPerBodyStep},
                    {"max_joint_gap", r.maxJointGap}};
    objects.push_back(jsonLine(j));
    objects.back().pop_back();  // its newline, which follows the comma between two objects
  }
  return "[\n" + join(objects, ",\n") + (objects.empty() ? "" : "\n") + "]\n";
}

std::string scaleCsv(const std::vector<ScaleRow>& rows) {
  std::string s = "scene,n,threads,bodies,ms_per_step,us_per_body_step,max_joint_gap,blew_up\n";
  for (const ScaleRow& r : rows) {
    s += csvLine({csvField(r.scene), std::to_string(r.n), std::to_string(r.solver.threads),
                  std::to_string(r.bodies), csvNumber(r.msPerStep, 6), csvNumber(r.usPerBodyStep, 6),
                  csvNumber(r.maxJointGap, 6), r.blewUp ? "1" : "0"});
  }
  return s;
}

std::string scaleTable(const std::vector<ScaleRow>& rows) {
  std::string s;
  if (!rows.empty()) {
    const phys::SolverSettings& solver = rows.front().solver;
    s += "scale       " + rows.front().scene + ", " +
         settingLabel(solver.method, solver.iterations, solver.substeps) +
         " (iterations x substeps), median of the steps' own time\n";
  }
  s += printed("%8s %8s %8s %12s %16s %20s\n", "n", "threads", "bodies", "ms/step", "us/body-step",
               "max joint gap (m)");
  for (const ScaleRow& r : rows) {
    s += printed("%8d %8d %8zu %12s %16s %20s\n", r.n, r.solver.threads, r.bodies,
                 formatNumber(r.msPerStep, 4).c_str(), formatNumber(r.usPerBodyStep, 4).c_str(),
                 formatNumber(r.maxJointGap, 3).c_str());
  }
  return s;
}

namespace {

Chart scaleChart(const std::vector<ScaleRow>& rows) {
  const std::string scene = rows.empty() ? std::string() : rows.front().scene;
  Chart chart = logChart("Cost per body against size: " + scene, "bodies", "microseconds per body-step",
                         false, "scale");
  // One line a number of threads, in the order they ran; named by it when there are several.
  std::vector<int> counts;
  for (const ScaleRow& r : rows) addOnce(counts, r.solver.threads);
  for (const int threads : counts) {
    ChartSeries series{
        .title = counts.size() > 1
                     ? scene + ", " + count(static_cast<std::size_t>(threads), "thread", "threads")
                     : scene,
        .line = true,
        .markers = counts.size() > 1,
        .labels = threads == counts.front()};
    for (const ScaleRow& r : rows) {
      if (r.solver.threads != threads) continue;
      series.points.push_back({static_cast<double>(r.bodies), r.usPerBodyStep, "n=" + std::to_string(r.n)});
    }
    chart.series.push_back(series);
  }
  return chart;
}

// The runs, the table or JSON, and the files of --out.
int runScaleCommand(ScaleOptions o, std::ostream& out, std::ostream& err) {
  if (o.sizes.empty()) {
    o.sizes = o.kind == ScaleKind::Pyramid ? std::vector<int>{5, 10, 20, 40}
                                           : std::vector<int>{1, 4, 16, 64, 256, 1024};
  }
  // The generator's own limit, said as the option's before any scene is generated.
  for (const int n : o.sizes) {
    if (o.kind == ScaleKind::Pyramid && n > scenes::kMaxPyramidBase) {
      throw UsageError("--sizes: '" + std::to_string(n) + "' is larger than a pyramid's largest base row, " +
                       std::to_string(scenes::kMaxPyramidBase));
    }
  }
  if (o.out) prepareOutputFiles(*o.out, scaleFiles());  // before the runs, which can take minutes
  if (o.scenes) {
    // The generated scenes as files, so that `lab run` can show one size's stages.
    OutputFolder scenes(*o.scenes, "--save-scenes");
    for (const int n : o.sizes)
      scenes.write(std::string(toString(o.kind)) + "-" + std::to_string(n) + ".xml",
                   scaleSceneXml(o.kind, n));
    scenes.commit();
  }
  std::vector<ScaleRow> rows;
  try {
    rows = runScale(o.kind, o.sizes, o.run, o.threads, &err);
  } catch (const scenes::LoadError& e) {
    throw CommandFailure(std::string("scale: the generated scene: ") + e.what());  // a bug in the generator
  }
  out << (o.json ? scaleJson(rows) : scaleTable(rows));
  if (!o.out) return kExitOk;
  OutputFolder files(*o.out);
  files.write("scale.csv", scaleCsv(rows));
  const std::string problem = files.draw("scale.gp", scaleChart(rows), "no size has a finite cost");
  files.commit();
  if (!o.json) out << files.wroteLine();
  if (!problem.empty()) err << "lab: scale: the chart: " << problem << "\n";
  return files.failed() ? kExitFailure : kExitOk;
}

}  // namespace

std::vector<std::string> scaleFiles() {
  return {"scale.csv", "scale.gp", "scale.png", "scale.svg"};
}

constinit const CommandMain scaleMain = commandMainOf<ScaleOptions, describeScale, runScaleCommand>;

}  // namespace lab
