// lab sweep and the accuracy it measures (app/lab/sweep.cpp, accuracy.cpp), in-process through
// sweepMain with string streams and a temporary --out folder. Runs are short (tens of steps, one
// timed repeat) so each test takes well under a second in Release.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accuracy.h"
#include "bodies.h"
#include "charts.h"
#include "command_line.h"
#include "commands.h"
#include "csv.h"
#include "expect_reader.h"
#include "fileio/files.h"
#include "gnuplot.h"
#include "lab.h"
#include "lab_test_util.h"
#include "peer.h"
#include "scale.h"
#include "scenes/scene.h"
#include "stability_report.h"
#include "sweep_core.h"
#include "sweep_plan.h"

namespace {

using lab::CsvRow;
using lab::CsvTable;
using lab::fieldNumber;
using Outcome = lab::CommandOutput;
using lab_testing::TempDir;

Outcome sweep(std::vector<std::string> args) {
  args.insert(args.end(), {"--data", DATA_DIR});
  return lab::runCaptured("sweep", args);
}

// A CSV the sweep wrote, whose every row must have the header's columns.
CsvTable readCsv(const std::filesystem::path& file) {
  CsvTable csv = lab::readCsv(file);
  EXPECT_EQ(csv.raggedRows, 0u) << file;
  return csv;
}

// The row of our method with these counts, or nullopt.
std::optional<CsvRow> findRow(const CsvTable& csv, const std::string& method, int iterations, int substeps) {
  for (const auto& row : csv.rows) {
    if (row.at("method") == method && row.at("iterations") == std::to_string(iterations) &&
        row.at("substeps") == std::to_string(substeps)) {
      return row;
    }
  }
  return std::nullopt;
}

const char* const kHeader =
    "scene,method,model,iterations,substeps,dt,steps,repeats,ms_per_step,ms_per_sim_second,error,ref_"
    "uncertainty,"
    "max_stick_error,max_joint_error,max_penetration,max_angular_speed,rms_tracking_error,error_first,pose_"
    "penetration,pose_"
    "joint_gap,energy_drift,frozen,blew_up,pareto,note";

TEST(Sweep, WritesOneRowPerCombinationWithFiniteFigures) {
  TempDir dir;
  const Outcome o = sweep({"falling-box", "--method", "gauss-seidel,xpbd", "--iterations", "2,4", "--steps",
                           "30", "--repeat", "1", "--no-peers", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  std::string header;
  for (const std::string& h : csv.header) header += (header.empty() ? "" : ",") + h;
  EXPECT_EQ(header, kHeader);
  ASSERT_EQ(csv.rows.size(), 4u);
  for (const char* method : {"gauss-seidel", "xpbd"}) {
    for (int iterations : {2, 4}) {
      const auto row = findRow(csv, method, iterations, 1);  // the scene's own substeps
      ASSERT_TRUE(row) << method << " " << iterations;
      EXPECT_EQ(row->at("model"), "corners");  // the file's boxes, named
      EXPECT_EQ(row->at("steps"), "30");
      for (const char* column :
           {"dt", "ms_per_step", "ms_per_sim_second", "error", "ref_uncertainty", "max_stick_error",
            "max_joint_error", "max_penetration", "max_angular_speed", "error_first", "pose_penetration",
            "pose_joint_gap", "energy_drift", "frozen"}) {
        EXPECT_TRUE(std::isfinite(fieldNumber(*row, column))) << method << " " << iterations << " " << column;
      }
      EXPECT_GT(fieldNumber(*row, "ms_per_step"), 0.0);
      EXPECT_EQ(row->at("frozen"), "0");
    }
  }
  // The report names the target it measured against.
  EXPECT_NE(o.out.find("reference: shake, 4 iterations x 128 substeps"), std::string::npos) << o.out;
}

// Each peer built in has a row at the scene's dt, with the figures measured from its bodies' poses
// by the same code as ours (pose_penetration, pose_joint_gap): a falling ragdoll's joints hold
// within centimetres in every engine, never exactly; none of our every-step figures.
TEST(Sweep, PeersHaveRowsWithTheirPosesMeasuredAsOurs) {
  TempDir dir;
  const Outcome o = sweep(
      {"ragdoll", "--methods", "xpbd", "--steps", "30", "--repeat", "1", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 1 + lab::peerEngines().size());
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const CsvRow& row = csv.rows[i];
    const std::string engine = i == 0 ? "xpbd" : lab::peerEngines()[i - 1];
    EXPECT_EQ(row.at("method"), engine);
    EXPECT_EQ(row.at("iterations").empty(), i > 0) << engine;
    const double gap = fieldNumber(row, "pose_joint_gap");
    EXPECT_GT(gap, 0.0) << engine;
    EXPECT_LT(gap, 0.1) << engine;
    EXPECT_GE(fieldNumber(row, "pose_penetration"), 0.0) << engine;
    EXPECT_LT(fieldNumber(row, "pose_penetration"), 0.1) << engine;
    EXPECT_LE(fieldNumber(row, "error_first"), fieldNumber(row, "error")) << engine;
    EXPECT_EQ(std::isnan(fieldNumber(row, "max_stick_error")), i > 0) << engine;
  }
}

// A loose particle is a point in our world and a 5 cm sphere in a peer's: each is measured as what
// it is, so ours resting on the ground reads no penetration (it read the sphere's 5 cm, the worst
// of every engine).
TEST(Sweep, OurLooseParticleIsMeasuredAsAPointAndAPeersAsItsSphere) {
  TempDir dir;
  const std::filesystem::path scene =
      dir.write("particle.xml",
                "<scene name=\"p\">\n  <ground/>\n  <particle name=\"p\" pos=\"0 0.05 0\" "
                "mass=\"1\"/>\n</scene>\n");
  const Outcome o = sweep({scene.string(), "--methods", "xpbd", "--iterations", "1", "--substeps", "1",
                           "--steps", "30", "--repeat", "1", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 1 + lab::peerEngines().size());
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const CsvRow& row = csv.rows[i];
    EXPECT_LT(fieldNumber(row, "pose_penetration"), 0.01) << row.at("method");
  }
}

// A peer that cannot express the scene (point gravity) is named on stdout with its reason and has
// no row in the files.
TEST(Sweep, APeerThatCannotRunIsNamedAndHasNoRow) {
  if (lab::peerEngines().empty()) GTEST_SKIP() << "no peer engine built in";
  TempDir dir;
  const Outcome o = sweep({"orbit", "--steps", "10", "--repeat", "1", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 1u);
  EXPECT_FALSE(csv.rows[0].at("iterations").empty());
  for (const std::string& engine : lab::peerEngines()) {
    const std::size_t at = o.out.find("peers       " + engine + " not run: ");
    ASSERT_NE(at, std::string::npos) << engine << "\n" << o.out;
    EXPECT_NE(o.out.find("point gravity", at), std::string::npos) << o.out;
  }
}

// A horizon that a smaller dt would take past the step limit is refused before anything runs.
TEST(Sweep, TooManyStepsAtASmallDtIsAUsageError) {
  TempDir dir;
  const Outcome o = sweep({"falling-box", "--steps", "10000000", "--dt", "0.016666666666666666,0.000001",
                           "--no-peers", "--out", dir.file("out").string()});
  EXPECT_EQ(o.code, lab::kExitUsage) << o.err;
  EXPECT_NE(o.err.find("at dt 1e-06"), std::string::npos) << o.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out/results.csv")));
}

// Every dt runs the horizon asked (--steps at the scene's dt), but a dt longer than it runs one
// whole step, and an analytic answer later than it stretches every run to reach it: a small dt
// then takes many steps. Each such dt is said before anything runs.
TEST(Sweep, ARunLongerThanTheHorizonAskedIsSaidBeforeRunning) {
  TempDir dir;
  const Outcome o = sweep({"pendulum", "--dt", "1,0.001", "--steps", "2", "--repeat", "1", "--no-peers",
                           "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, lab::kExitOk) << o.err;
  EXPECT_TRUE(
      o.out.starts_with("longer      dt 1 runs 1 step to cover 1 s (the horizon asked: 0.03333 s)\n"
                        "sweep       pendulum"))
      << o.out;
  EXPECT_EQ(o.out.find("dt 0.001 runs"), std::string::npos) << o.out;  // 33 steps: as asked
  EXPECT_NE(o.out.find("each 0.033 to 1 s simulated"), std::string::npos) << o.out;

  const Outcome answers = sweep({"projectile", "--dt", "0.001", "--steps", "2", "--repeat", "1", "--no-peers",
                                 "--out", dir.file("projectile").string()});
  ASSERT_EQ(answers.code, lab::kExitOk) << answers.err;
  EXPECT_TRUE(answers.out.starts_with(
      "longer      dt 0.001 runs 2000 steps to cover 2 s (the horizon asked: 0.03333 s)\n"))
      << answers.out;

  const Outcome asked =
      sweep({"pendulum", "--steps", "2", "--repeat", "1", "--no-peers", "--out", dir.file("asked").string()});
  EXPECT_EQ(asked.out.find("longer"), std::string::npos) << asked.out;
}

// The four methods are ways of relaxing sticks: a model that leaves the scene none steps alike
// under each, so it runs once, as xpbd (how rigid bodies are solved), not as equal rows under
// names that did nothing; a model that keeps sticks runs under each method asked.
TEST(Sweep, AModelWithNoStickRunsOnceAsXpbd) {
  TempDir dir;
  const Outcome o = sweep({"falling-box", "--model", "corners,rigid", "--method", "gauss-seidel,shake",
                           "--iterations", "1", "--substeps", "2", "--steps", "10", "--repeat", "1",
                           "--no-peers", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 3u);
  std::vector<std::string> seen;
  for (const CsvRow& row : csv.rows) seen.push_back(row.at("model") + " " + row.at("method"));
  EXPECT_EQ(seen, (std::vector<std::string>{"corners gauss-seidel", "corners shake", "rigid xpbd"}));
}

TEST(Sweep, ProjectileIsExactToRoundOffAtAnySetting) {
  // Verlet with the loader's start is exact for constant acceleration, and every method keeps a
  // free box's centre, so coarse and fine settings alike land on the analytic positions.
  TempDir dir;
  const Outcome o = sweep({"projectile", "--method", "gauss-seidel,jacobi,shake", "--iterations", "1,4",
                           "--substeps", "1,8", "--model", "corners,tetra", "--repeat", "1", "--no-peers",
                           "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 24u);
  for (const auto& row : csv.rows) {
    EXPECT_LT(fieldNumber(row, "error"), 1e-9) << row.at("method") << " " << row.at("model") << " "
                                               << row.at("iterations") << "x" << row.at("substeps");
    EXPECT_EQ(fieldNumber(row, "ref_uncertainty"), 0.0);  // analytic
  }
  EXPECT_NE(o.out.find("analytic: 7 positions"), std::string::npos) << o.out;
}

TEST(Sweep, FineSettingsBeatCoarseOnScenesVerletDoesNotSolveExactly) {
  TempDir dir;
  // The pendulum against its elliptic-function motion: method and substeps both matter.
  Outcome o = sweep({"pendulum-exact", "--method", "gauss-seidel,shake", "--substeps", "1,16", "--repeat",
                     "1", "--no-peers", "--out", dir.file("pendulum").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  CsvTable csv = readCsv(dir.file("pendulum/results.csv"));
  const double coarse = fieldNumber(*findRow(csv, "gauss-seidel", 1, 1), "error");
  const double fine = fieldNumber(*findRow(csv, "shake", 1, 16), "error");
  EXPECT_GT(coarse, 0.1);  // Jakobsen's projection at 60 Hz has bled much of the swing
  EXPECT_LT(fine, 1e-5);
  EXPECT_LT(fieldNumber(*findRow(csv, "gauss-seidel", 1, 16), "error"), coarse);
  EXPECT_LT(fine, fieldNumber(*findRow(csv, "shake", 1, 1), "error"));

  // The circular orbit: Verlet's phase error falls with the square of the substep.
  o = sweep({"circular-orbit", "--substeps", "1,16", "--repeat", "1", "--no-peers", "--out",
             dir.file("orbit").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  csv = readCsv(dir.file("orbit/results.csv"));
  const double one = fieldNumber(*findRow(csv, "gauss-seidel", 1, 1), "error");
  const double sixteen = fieldNumber(*findRow(csv, "gauss-seidel", 1, 16), "error");
  EXPECT_GT(one, 1e-4);
  EXPECT_LT(sixteen, one / 100.0);
}

// Below by more than round-off, as the sweep's front compares errors.
bool less(double a, double b) {
  return a < b * (1.0 - 1e-6);
}

TEST(Sweep, ParetoFrontHoldsTheUnbeatenRows) {
  TempDir dir;
  const Outcome o = sweep({"pendulum-exact", "--method", "gauss-seidel,shake", "--substeps", "1,2,4",
                           "--repeat", "1", "--no-peers", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  const CsvTable front = readCsv(dir.file("out/pareto.csv"));
  // Compared as the sweep compares them: errors below 1e-9 m are round-off, equal to 1e-9, and
  // errors within a millionth of each other the same.
  auto err = [](const CsvRow& r) { return std::max(fieldNumber(r, "error"), 1e-9); };
  auto beats = [&](const CsvRow& q, const CsvRow& r) {
    const double qc = fieldNumber(q, "ms_per_step");
    const double rc = fieldNumber(r, "ms_per_step");
    return qc <= rc && !less(err(r), err(q)) && (qc < rc || less(err(q), err(r)));
  };
  std::size_t marked = 0;
  for (const auto& r : csv.rows) {
    bool beaten = false;
    for (const auto& q : csv.rows) beaten = beaten || beats(q, r);
    EXPECT_EQ(r.at("pareto") == "1", !beaten) << r.at("method") << " " << r.at("substeps");
    marked += r.at("pareto") == "1" ? 1 : 0;
  }
  ASSERT_EQ(front.rows.size(), marked);
  ASSERT_GE(marked, 1u);
  for (std::size_t i = 1; i < front.rows.size(); ++i) {
    EXPECT_LE(fieldNumber(front.rows[i - 1], "ms_per_step"),
              fieldNumber(front.rows[i], "ms_per_step"));  // by cost
  }
}

// A peer has none of the run table's figures: under --error penetration it stays off the chart and
// the front (its `max_penetration`, its deepest body at the end, was charted beside our deepest
// contact over every step).
TEST(Sweep, APeerIsNotChartedByAFigureOfOurs) {
  if (lab::peerEngines().empty()) GTEST_SKIP() << "built without peers";
  TempDir dir;
  const Outcome o =
      sweep({"falling-box", "--methods", "xpbd", "--iterations", "1", "--substeps", "1", "--steps", "30",
             "--repeat", "1", "--error", "penetration", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 1 + lab::peerEngines().size());
  for (std::size_t i = 1; i < csv.rows.size(); ++i) EXPECT_NE(csv.rows[i].at("pareto"), "1") << i;
  std::ifstream script(dir.file("out/sweep.gp"));
  const std::string text((std::istreambuf_iterator<char>(script)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("(peer)"), std::string::npos) << text;
}

// Errors that differ by round-off are one error: of SHAKE's 1 to 8 iterations x 8 substeps on the
// exact pendulum, whose errors agree to 1e-8 of themselves, only the cheapest is on the front
// (all four were, each "buying" 1e-13 m at more cost).
TEST(Sweep, ErrorsThatDifferByRoundOffAreOneOnTheFront) {
  TempDir dir;
  const Outcome o = sweep({"pendulum-exact", "--methods", "shake", "--iterations", "1,2,4,8", "--substeps",
                           "8", "--repeat", "1", "--no-peers", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 4u);
  const double first = fieldNumber(csv.rows[0], "error");
  for (const CsvRow& r : csv.rows)
    ASSERT_NEAR(fieldNumber(r, "error"), first, 1e-7 * first) << "not round-off";
  const auto onFront =
      std::count_if(csv.rows.begin(), csv.rows.end(), [](const CsvRow& r) { return r.at("pareto") == "1"; });
  EXPECT_EQ(onFront, 1);
}

// --error FIGURE: the front and the chart measure a figure of the run table instead of the distance
// from the target; here the run cycle's pose tracking, where the front is made of other rows than
// the position error's would be.
TEST(Sweep, TheFrontCanMeasureAFigureOfTheRunTable) {
  TempDir dir;
  const Outcome o =
      sweep({"run-cycle", "--error", "tracking-error", "--iterations", "1,4", "--substeps", "1,4", "--steps",
             "30", "--repeat", "1", "--no-peers", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 4u);  // rigid parts alone: one method, xpbd
  auto beats = [&](const CsvRow& q, const CsvRow& r, const char* column) {
    const double qc = fieldNumber(q, "ms_per_step"), rc = fieldNumber(r, "ms_per_step");
    const double qe = fieldNumber(q, column), re = fieldNumber(r, column);
    return qc <= rc && !less(re, qe) && (qc < rc || less(qe, re));
  };
  for (const auto& r : csv.rows) {
    EXPECT_GT(fieldNumber(r, "rms_tracking_error"), 0.0);
    bool beaten = false;
    for (const auto& q : csv.rows) beaten = beaten || beats(q, r, "rms_tracking_error");
    EXPECT_EQ(r.at("pareto") == "1", !beaten) << r.at("iterations") << "x" << r.at("substeps");
  }
  std::ifstream script(dir.file("out/sweep.gp"));
  const std::string text((std::istreambuf_iterator<char>(script)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("tracking-error (deg)"), std::string::npos);
  EXPECT_NE(text.find("run-cycle: tracking-error against cost"), std::string::npos);
}

// The printed table's error column is the figure --error asks for, headed by its name: it showed
// the distance from the accuracy target, headed "error (m)", whatever the chart and the front measured.
TEST(Sweep, TheTableShowsTheFigureTheErrorOptionAsks) {
  TempDir dir;
  const Outcome o =
      sweep({"run-cycle", "--error", "tracking-error", "--iterations", "1", "--substeps", "1", "--steps",
             "20", "--repeat", "1", "--no-peers", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::size_t header = o.out.find("\nmethod ");
  ASSERT_NE(header, std::string::npos) << o.out;
  const std::string headerLine = o.out.substr(header + 1, o.out.find('\n', header + 1) - header - 1);
  EXPECT_NE(headerLine.find(" tracking-error "), std::string::npos) << headerLine;
  EXPECT_EQ(headerLine.find("error (m)"), std::string::npos) << headerLine;
  std::istringstream row(o.out.substr(o.out.find('\n', header + 1) + 1));
  std::string cells[8];
  for (std::string& cell : cells) row >> cell;  // method, model, iter, sub, dt, steps, ms/step, error
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 1u);
  EXPECT_EQ(cells[7], lab::formatNumber(fieldNumber(csv.rows[0], "rms_tracking_error"), 3)) << o.out;
}

// A sweep over several models (or dts) measures each against its own reference, and each
// reference's uncertainty is a line of the chart, named by its model: only the first one's was drawn.
TEST(Sweep, EachReferencesUncertaintyIsALineOfTheChart) {
  TempDir dir;
  const Outcome o =
      sweep({"falling-box", "--method", "gauss-seidel", "--iterations", "1", "--model", "corners,tetra",
             "--repeat", "1", "--no-peers", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 2u);
  const std::string script = lab_testing::readFile(dir.file("out/sweep.gp"));
  for (const CsvRow& r : csv.rows) {
    ASSERT_GT(fieldNumber(r, "ref_uncertainty"), 1e-9) << "a line is drawn above the floor";
    const std::string title = "'reference''s own uncertainty (" + r.at("model") + ", dt 0.0166667)'";
    EXPECT_NE(script.find(title), std::string::npos) << title << "\n" << script;
  }
}

// Its error is no figure: the CSV leaves it blank (it wrote inf, a number no output may hold) and
// says in blew_up why.
TEST(Sweep, ARunThatBlowsUpHasNoErrorAndSaysItBlewUp) {
  TempDir dir;
  const std::filesystem::path scene = dir.write("escape.xml", lab_testing::escapingScene());
  // A chart an earlier sweep drew there: with no error to draw, it would stand beside CSVs it
  // does not show, so it goes.
  std::filesystem::create_directories(dir.file("out"));
  const std::filesystem::path stale = dir.write("out/error-vs-cost.png", "an earlier sweep's chart");
  ASSERT_TRUE(std::filesystem::exists(stale));
  const Outcome o = sweep(
      {scene.string(), "--steps", "30", "--repeat", "1", "--no-peers", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_FALSE(std::filesystem::exists(stale));
  EXPECT_NE((o.out + o.err).find("no run has a finite error"), std::string::npos) << o.out << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 1u);
  EXPECT_EQ(csv.rows[0].at("error"), "");
  EXPECT_EQ(csv.rows[0].at("error_first"), "");
  EXPECT_EQ(csv.rows[0].at("blew_up"), "1");
  EXPECT_GT(fieldNumber(csv.rows[0], "frozen"), 0.0);
  EXPECT_EQ(csv.rows[0].at("pareto"), "0");
  EXPECT_NE(csv.rows[0].at("note").find("blew up"), std::string::npos);
  // The reference blew up as well: two of its runs frozen alike agreed to 0 m, which was printed
  // as its uncertainty. It is unknown, and said.
  EXPECT_NE(o.out.find("the reference itself blew up (the guard froze"), std::string::npos) << o.out;
  EXPECT_EQ(o.out.find("0 m at most"), std::string::npos) << o.out;
}

// Whether `text` holds "inf" as a figure (not as part of a word such as "infinity").
bool holdsInf(const std::string& text) {
  for (std::size_t at = text.find("inf"); at != std::string::npos; at = text.find("inf", at + 1)) {
    const bool wordBefore = at > 0 && std::isalpha(static_cast<unsigned char>(text[at - 1]));
    const bool wordAfter = at + 3 < text.size() && std::isalpha(static_cast<unsigned char>(text[at + 3]));
    if (!wordBefore && !wordAfter) return true;
  }
  return false;
}

// A run that blew up is said in words wherever a command prints its figures: the sweep's table
// and accuracy line, tune's figures and verdicts, compare's table, run's summary printed "inf" (or
// "n/a", as for a figure that is no number at all), and the chart drew the blown-up reference's
// uncertainty as "inf", which gnuplot read as a variable.
TEST(Sweep, EveryCommandSaysABlowUpInWords) {
  TempDir dir;
  const std::filesystem::path escape = dir.write("escape.xml", lab_testing::escapingScene());
  const std::filesystem::path box =
      dir.write("box.xml",
                "<scene name=\"escbox\"><world bound=\"10\"/><ground/>\n"
                "  <box name=\"b\" pos=\"0 5 0\" velocity=\"100 0 0\"/></scene>\n");
  // A box of 1e9 kg thrown at 1e200 m/s starts with inf J: run's summary printed "n/a J".
  const std::filesystem::path overflow = dir.write(
      "heavy.xml",
      "<scene name=\"heavy\"><box name=\"b\" pos=\"0 3 0\" mass=\"1e9\" velocity=\"1e200 0 0\"/></scene>\n");
  const Outcome swept = sweep(
      {escape.string(), "--steps", "30", "--repeat", "1", "--no-peers", "--out", dir.file("out").string()});
  const Outcome sweptBox =
      sweep({box.string(), "--steps", "30", "--repeat", "1", "--out", dir.file("box").string()});
  const Outcome tuned = lab::runCaptured("tune", {escape.string(), "--steps", "30", "--repeat", "1",
                                                  "--target", "error=0.1", "--data", DATA_DIR});
  const Outcome compared = lab::runCaptured("compare", {box.string(), "--steps", "30", "--repeat", "1"});
  const Outcome ran = lab::runCaptured("run", {overflow.string(), "--steps", "2"});
  for (const Outcome* o : {&swept, &sweptBox, &tuned, &compared, &ran}) {
    EXPECT_NE(o->out.find(lab::kBlewUp), std::string::npos) << o->out;
    EXPECT_FALSE(holdsInf(o->out)) << o->out;
    EXPECT_FALSE(holdsInf(o->err)) << o->err;
  }
  EXPECT_EQ(swept.code, 0) << swept.err;
  EXPECT_EQ(sweptBox.code, 0) << sweptBox.err;
  EXPECT_NE(swept.out.find("its uncertainty (change from 64 substeps): unknown, since the reference itself "
                           "blew up"),
            std::string::npos)
      << swept.out;
  EXPECT_NE(tuned.out.find("error blew up, "), std::string::npos) << tuned.out;
  EXPECT_NE(tuned.out.find("error blew up > 0.1 m"), std::string::npos) << tuned.out;
  EXPECT_NE(compared.out.find("| blew up | blew up |"), std::string::npos) << compared.out;
  EXPECT_NE(ran.out.find("energy       initial blew up, "), std::string::npos) << ran.out;
  if (std::filesystem::exists(dir.file("box/sweep.gp"))) {  // drawn when a peer's run has an error
    EXPECT_FALSE(holdsInf(lab_testing::readFile(dir.file("box/sweep.gp"))));
  }
}

// The rows of two sweeps of one plan measured the same at every point.
void expectSameFigures(const lab::PlanResult& a, const lab::PlanResult& b) {
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_EQ(a.rows[i].figures.error, b.rows[i].figures.error) << i;
    EXPECT_EQ(a.rows[i].figures.energyDrift, b.rows[i].figures.energyDrift) << i;
    EXPECT_EQ(a.rows[i].figures.posePenetration, b.rows[i].figures.posePenetration) << i;
  }
}

// A sweep builds every point from the scene file as read once: a file saved over after the first
// point (the sandbox's Save As during a long sweep) measured the new scene at every later point.
TEST(Sweep, ASceneFileSavedOverMidSweepChangesNoPoint) {
  TempDir dir;
  const std::string first =
      "<scene name=\"drop\"><box name=\"b\" pos=\"0 3 0\" velocity=\"1 0 0\"/></scene>\n";
  const std::string other =
      "<scene name=\"drop\"><world gravity=\"0 0 0\"/><box name=\"b\" pos=\"5 1 0\"/></scene>\n";
  const std::filesystem::path file = dir.write("drop.xml", first);
  const lab::PlanRequest request{.substeps = {1, 2, 4}, .steps = 20, .repeats = 1, .peers = false};
  lab::Plan plan = lab::makePlan(scenes::readSceneSource(file), request);
  plan.afterSetting = [&](std::size_t) { dir.write("drop.xml", other); };
  std::ostringstream progress;
  const lab::PlanResult saved = lab::runPlan(plan, progress, "sweep");
  ASSERT_EQ(lab_testing::readFile(file), other);
  // The same plan on the first scene, left alone.
  const lab::PlanResult alone = lab::runPlan(
      lab::makePlan(scenes::readSceneSource(dir.write("alone.xml", first)), request), progress, "sweep");
  ASSERT_EQ(saved.rows.size(), 3u);
  ASSERT_EQ(alone.rows.size(), 3u);
  expectSameFigures(saved, alone);
  EXPECT_GT(saved.rows[2].figures.error, 0.0);  // a real error, not two zeros agreeing
}

// The clip a scene's character plays is read with the scene: a clip file saved over after the first
// point measured the new clip at every later point.
TEST(Sweep, AClipFileSavedOverMidSweepChangesNoPoint) {
  TempDir dir;
  const std::string clips = std::string(DATA_DIR) + "/assets/clips/";
  const std::string run = lab_testing::readFile(clips + "run.bvh");
  const std::string dive = lab_testing::readFile(clips + "dive.bvh");
  const std::string scene =
      "<scene name=\"runner\"><ground/><ragdoll name=\"r\" pos=\"0 0.85 0\" model=\"rigid\"/>\n"
      "  <character ragdoll=\"r\" clip=\"move.bvh\" strength=\"0.9\" root-strength=\"1\"/></scene>\n";
  const lab::PlanRequest request{.substeps = {1, 2, 4}, .steps = 20, .repeats = 1, .peers = false};
  auto sweepOf = [&](const char* folder, const std::string& clip, bool savedOver) {
    std::filesystem::create_directory(dir.file(folder));
    const std::string at = std::string(folder) + "/";
    dir.write(at + "move.bvh", clip);
    lab::Plan plan = lab::makePlan(scenes::readSceneSource(dir.write(at + "runner.xml", scene)), request);
    if (savedOver) plan.afterSetting = [&](std::size_t) { dir.write(at + "move.bvh", dive); };
    std::ostringstream progress;
    return lab::runPlan(plan, progress, "sweep");
  };
  const lab::PlanResult saved = sweepOf("saved", run, true);
  ASSERT_EQ(lab_testing::readFile(dir.file("saved/move.bvh")), dive);
  const lab::PlanResult alone = sweepOf("alone", run, false);  // the same plan on the run, left alone
  const lab::PlanResult diving = sweepOf("diving", dive, false);
  ASSERT_EQ(saved.rows.size(), 3u);
  ASSERT_EQ(alone.rows.size(), 3u);
  ASSERT_EQ(diving.rows.size(), 3u);
  expectSameFigures(saved, alone);
  // The clips move the ragdoll apart: two equal sweeps are not two clips agreeing.
  EXPECT_NE(alone.rows[2].figures.error, diving.rows[2].figures.error);
}

// A box thrown at 1e308 m/s under a gravity of 1e308: its energy's drift is inf - inf. The CSV
// leaves it empty; the tables printed "-nan" and "drift nan J" before formatNumber said n/a.
TEST(Sweep, AFigureThatIsNotANumberIsPrintedNA) {
  TempDir dir;
  const std::filesystem::path scene = dir.write("thrown.xml",
                                                "<scene name=\"thrown\">\n"
                                                "  <world gravity=\"0 -1e308 0\" damping=\"1e308\"/>\n"
                                                "  <solver dt=\"1\"/>\n"
                                                "  <box name=\"a\" pos=\"2 1 0\" velocity=\"1e308 0 0\"/>\n"
                                                "</scene>\n");
  const Outcome swept = sweep(
      {scene.string(), "--steps", "2", "--repeat", "1", "--no-peers", "--out", dir.file("out").string()});
  ASSERT_EQ(swept.code, 0) << swept.err;
  EXPECT_EQ(readCsv(dir.file("out/results.csv")).rows.at(0).at("energy_drift"), "");
  const Outcome tuned = lab::runCaptured(
      "tune", {scene.string(), "--steps", "2", "--repeat", "1", "--target", "drift=1", "--data", DATA_DIR});
  for (const Outcome* o : {&swept, &tuned}) {
    EXPECT_NE(o->out.find("n/a"), std::string::npos) << o->out;
    EXPECT_EQ(o->out.find("nan"), std::string::npos) << o->out;
  }
}

// A box of 1e9 kg thrown at 1e200 m/s starts with inf J: its drift was written -inf, where only a
// blown-up run's error may read inf; the table printed it too.
TEST(Sweep, AnEnergyThatOverflowsLeavesTheDriftEmpty) {
  TempDir dir;
  const std::filesystem::path scene = dir.write(
      "heavy.xml",
      "<scene name=\"heavy\"><box name=\"b\" pos=\"0 3 0\" mass=\"1e9\" velocity=\"1e200 0 0\"/></scene>\n");
  const Outcome swept = sweep({scene.string(), "--steps", "5", "--repeat", "1", "--no-peers", "--methods",
                               "xpbd", "--out", dir.file("out").string()});
  ASSERT_EQ(swept.code, 0) << swept.err;
  EXPECT_EQ(readCsv(dir.file("out/results.csv")).rows.at(0).at("energy_drift"), "");
  EXPECT_EQ(swept.out.find("-inf"), std::string::npos) << swept.out;
}

// A figure wider than its column is still set apart from the next: a dt of six digits with an
// exponent (11 characters in a column of 10) ran into a step count of six figures.
TEST(Sweep, AFigureWiderThanItsColumnDoesNotRunIntoTheNext) {
  TempDir dir;
  const std::filesystem::path scene =
      dir.write("still.xml",
                "<scene name=\"still\"><world gravity=\"0 0 0\"/><box name=\"a\" pos=\"0 1 0\"/>\n"
                "  <expect kind=\"position\" body=\"a\" at=\"1.00001\" pos=\"0 1 0\"/></scene>\n");
  const Outcome o = sweep({scene.string(), "--steps", "61", "--dt", "1.00001e-05", "--repeat", "1",
                           "--no-peers", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  auto lineAt = [&](const char* start) {
    const std::size_t at = o.out.find(start);
    return at == std::string::npos ? std::string() : o.out.substr(at + 1, o.out.find('\n', at + 1) - at - 1);
  };
  const std::string header = lineAt("\nmethod "), line = lineAt("\ngauss-seidel ");  // the table's one row
  ASSERT_FALSE(header.empty() || line.empty()) << o.out;
  std::istringstream row(line);
  std::string method, model, iterations, substeps, dt, steps;
  row >> method >> model >> iterations >> substeps >> dt >> steps;
  EXPECT_EQ(dt, "1.00001e-05") << o.out;
  EXPECT_EQ(steps, readCsv(dir.file("out/results.csv")).rows.at(0).at("steps")) << o.out;
  // And the row is back in its columns where the figures after leave room: it ends where the
  // header does (then the Pareto front's mark).
  EXPECT_TRUE(line.size() == header.size() || line.substr(header.size()) == "  *") << header << "\n" << line;
}

// A rigid box (no particles) beside a corners box (8) has as many particles as two tetra boxes:
// counted by particles alone, the file was taken as all tetra, labelled so, and swept with tetra
// imposed on both, another world. Models mixed within a kind keep the file's own: "scene".
TEST(Sweep, ARigidBoxBesideACornersBoxIsSweptAsTheFileHasThem) {
  TempDir dir;
  const std::filesystem::path scene = dir.write("mixed.xml",
                                                "<scene name=\"mixed\"><ground/>\n"
                                                "  <box name=\"a\" pos=\"0 0.5 0\" model=\"rigid\"/>\n"
                                                "  <box name=\"b\" pos=\"3 0.5 0\" model=\"corners\"/>\n"
                                                "</scene>\n");
  EXPECT_EQ(lab::sceneModels(scenes::readSceneSource(scene)).asFile.label, "scene");
  const Outcome o = sweep(
      {scene.string(), "--steps", "5", "--repeat", "1", "--no-peers", "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  const CsvTable csv = readCsv(dir.file("out/results.csv"));
  ASSERT_EQ(csv.rows.size(), 1u);
  EXPECT_EQ(csv.rows[0].at("model"), "scene");
}

TEST(Sweep, DrawsTheChartWhenGnuplotIsThere) {
  if (lab::findGnuplot().empty()) GTEST_SKIP() << "gnuplot is not installed";
  TempDir dir;
  const Outcome o = sweep({"pendulum-exact", "--method", "gauss-seidel,shake", "--repeat", "1", "--no-peers",
                           "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  for (const char* f : {"results.csv", "pareto.csv", "sweep.gp", "error-vs-cost.png", "error-vs-cost.svg"}) {
    EXPECT_GT(std::filesystem::file_size(dir.file("out") / f), 0u) << f;
  }
  EXPECT_EQ(lab_testing::readFile(dir.file("out/error-vs-cost.png")).substr(1, 3), "PNG");
  EXPECT_NE(lab_testing::readFile(dir.file("out/error-vs-cost.svg")).find("<svg"), std::string::npos);
  EXPECT_EQ(o.err.find("gnuplot"), std::string::npos) << o.err;
}

// PATH set for the life of the object, then put back.
class ScopedPath {
 public:
  explicit ScopedPath(const std::string& path) {
    const char* old = std::getenv("PATH");
    if (old != nullptr) old_ = old;
    ::setenv("PATH", path.c_str(), 1);
  }
  ~ScopedPath() {
    if (old_)
      ::setenv("PATH", old_->c_str(), 1);
    else
      ::unsetenv("PATH");
  }
  ScopedPath(const ScopedPath&) = delete;
  ScopedPath& operator=(const ScopedPath&) = delete;

 private:
  std::optional<std::string> old_;
};

// A scene file where the sweep writes its results was deleted by the sweep's own output; it is
// refused before any run, as lab run --dump refuses the scene it runs.
TEST(Sweep, RefusesToWriteOverTheSceneItRuns) {
  TempDir dir;
  const std::string scene =
      lab_testing::readFile(std::filesystem::path(DATA_DIR) / "assets/scenes/falling-box.xml");
  const std::filesystem::path file = dir.write("results.csv", scene);
  const auto o = sweep({file.string(), "--iterations", "1", "--no-peers", "--out", dir.file("").string()});
  EXPECT_EQ(o.code, lab::kExitFailure) << o.err;
  EXPECT_NE(o.err.find("results.csv: is the scene " + file.string() + " being run"), std::string::npos)
      << o.err;
  EXPECT_EQ(lab_testing::readFile(file), scene);
  EXPECT_FALSE(std::filesystem::exists(dir.file("pareto.csv")));
}

TEST(Sweep, SaysSoAndStillWritesTheDataWithoutGnuplot) {
  TempDir dir;
  std::filesystem::create_directories(dir.file("empty-bin"));
  Outcome o;
  {
    const ScopedPath noGnuplot(dir.file("empty-bin").string());
    o = sweep({"pendulum-exact", "--repeat", "1", "--no-peers", "--out", dir.file("out").string()});
  }
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("gnuplot is not installed"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("sweep.gp"), std::string::npos) << o.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/results.csv")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/sweep.gp")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("out/error-vs-cost.png")));
}

// OutputFolder, the frame sweep, scale, converge and stability write --out through: what it
// lists, and which charts not drawn are failures.
lab::Chart onePointChart(const std::string& output) {
  lab::Chart chart = lab::logChart("t", "x", "y", false, output);
  chart.series.push_back({.title = "s", .points = {{1.0, 1.0, ""}}});
  return chart;
}

TEST(OutputFolder, ListsWhatItWroteAndAMissingGnuplotIsNoFailure) {
  TempDir dir;
  std::filesystem::create_directories(dir.file("empty-bin"));
  const ScopedPath noGnuplot(dir.file("empty-bin").string());
  lab::OutputFolder files(dir.file("out"));
  files.write("a.csv", "x\n");
  const std::string missing = files.draw("c.gp", onePointChart("c"), "none");
  EXPECT_NE(missing.find("gnuplot is not installed"), std::string::npos) << missing;
  // The script named where it will be, not where it was drawn.
  EXPECT_NE(missing.find(dir.file("out/c.gp").string() + " are written"), std::string::npos) << missing;
  EXPECT_EQ(files.draw("e.gp", lab::logChart("t", "x", "y", false, "e"), "no points"), "no points");
  EXPECT_FALSE(files.failed());
  EXPECT_FALSE(std::filesystem::exists(dir.file("out/a.csv")));  // nothing before the commit
  dir.write("out/c.svg", "the earlier run's chart");
  files.commit();
  EXPECT_FALSE(std::filesystem::exists(dir.file("out/c.svg"))) << "not drawn this time, so not left";
  // The pictures were not drawn, so they are not listed.
  const std::string out = dir.file("out").string();
  EXPECT_EQ(files.wroteLine(), "wrote       " + out + "/a.csv, " + out + "/c.gp, " + out + "/e.gp\n");
  EXPECT_EQ(lab_testing::readFile(dir.file("out/a.csv")), "x\n");
}

TEST(OutputFolder, ListsThePicturesGnuplotDrew) {
  if (lab::findGnuplot().empty()) GTEST_SKIP() << "no gnuplot on PATH (scripts/install-deps installs it)";
  TempDir dir;
  lab::OutputFolder files(dir.file("out"));
  EXPECT_EQ(files.draw("c.gp", onePointChart("c"), "none"), "");
  EXPECT_FALSE(files.failed());
  files.commit();
  const std::string out = dir.file("out").string();
  EXPECT_EQ(files.wroteLine(), "wrote       " + out + "/c.gp, " + out + "/c.png, " + out + "/c.svg\n");
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/c.png")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/c.svg")));
}

// A chart with no point to draw wrote a script of a lone `replot`: gnuplot failed on it after it
// had opened both pictures, which it left empty. Its script now runs and draws nothing.
TEST(OutputFolder, AChartWithNothingToDrawGetsAScriptThatRuns) {
  lab::Chart empty = lab::logChart("t", "x", "y", true, "e");
  empty.series.push_back({.title = "s", .points = {{0.0, 1.0, ""}, {1.0, std::nan(""), ""}}});
  empty.guides.push_back({1.0, "a guide"});
  const std::string script = lab::gnuplotScript(empty);
  EXPECT_EQ(script.find("replot"), std::string::npos) << script;
  EXPECT_EQ(script.find("set output"), std::string::npos) << script;
  EXPECT_NE(script.find("print 'nothing to draw"), std::string::npos) << script;
  if (lab::findGnuplot().empty()) GTEST_SKIP() << "no gnuplot on PATH (scripts/install-deps installs it)";
  TempDir dir;
  const std::filesystem::path file = dir.write("e.gp", script);
  EXPECT_EQ(lab::runGnuplot(file, dir.file("")), "");
  EXPECT_FALSE(std::filesystem::exists(dir.file("e.png")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("e.svg")));
}

// A gnuplot that fails, draws nothing, or draws pictures cut short (it says nothing of a write that
// failed and exits 0) is a failure; and the charts an earlier run drew go, so that none stands
// beside data it does not show.
TEST(OutputFolder, AGnuplotThatFailsIsAFailure) {
  TempDir dir;
  std::filesystem::create_directories(dir.file("bin"));
  const std::filesystem::path fake = dir.write("bin/gnuplot", "#!/bin/sh\necho broken\nexit 3\n");
  std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
  const ScopedPath failing(dir.file("bin").string());
  dir.write("out/c.png", "the earlier run's chart");
  lab::OutputFolder files(dir.file("out"));
  const std::string broken = files.draw("c.gp", onePointChart("c"), "none");
  EXPECT_NE(broken.find("broken"), std::string::npos) << broken;
  EXPECT_NE(broken.find("gnuplot failed on " + dir.file("out/c.gp").string() + " (exit status 3)"),
            std::string::npos)
      << broken;
  EXPECT_TRUE(files.failed());
  files.commit();
  EXPECT_FALSE(std::filesystem::exists(dir.file("out/c.png")))
      << "an earlier run's chart beside this run's data";

  const std::pair<const char*, const char*> quiet[] = {
      {"exit 0\n", "gnuplot did not draw c.png"},
      {"printf '\\211PNG' > c.png\nprintf '<svg>' > c.svg\nexit 0\n",
       "gnuplot's c.png is cut short (4 bytes)"}};
  for (const auto& [script, says] : quiet) {
    dir.write("bin/gnuplot", std::string("#!/bin/sh\n") + script);
    lab::OutputFolder again(dir.file("again"));
    const std::string problem = again.draw("c.gp", onePointChart("c"), "none");
    EXPECT_NE(problem.find(says), std::string::npos) << problem;
    EXPECT_TRUE(again.failed()) << script;
    again.commit();
    EXPECT_FALSE(std::filesystem::exists(dir.file("again/c.png"))) << script;
  }
  // A gnuplot ended by a signal says which, not a raw wait status.
  dir.write("bin/gnuplot", "#!/bin/sh\nkill -TERM $$\n");
  lab::OutputFolder killed(dir.file("killed"));
  const std::string signalled = killed.draw("c.gp", onePointChart("c"), "none");
  EXPECT_NE(signalled.find("(killed by signal 15"), std::string::npos) << signalled;
  // A chart with nothing to draw is said, not failed, whatever gnuplot would do.
  lab::OutputFolder other(dir.file("other"));
  EXPECT_EQ(other.draw("e.gp", lab::logChart("t", "x", "y", false, "e"), "no points"), "no points");
  EXPECT_FALSE(other.failed());
}

// The files of a run replace an earlier run's as one set: when one cannot be written (here a
// folder stands where it would go), none is, and the earlier run's files, charts included, stay
// as they were, not a mix of the two runs. The drawing leaves nothing behind either way.
TEST(OutputFolder, AFileThatCannotBeWrittenLeavesEveryEarlierFile) {
  TempDir dir;
  const std::filesystem::path out = dir.file("out");
  std::filesystem::create_directories(out / "b.csv");
  dir.write("out/a.csv", "the earlier run\n");
  dir.write("out/e.png", "the earlier chart");
  lab::OutputFolder files(out);
  files.write("a.csv", "this run\n");
  files.write("b.csv", "this run\n");
  EXPECT_EQ(files.draw("e.gp", lab::logChart("t", "x", "y", false, "e"), "no points"), "no points");
  try {
    files.commit();
    ADD_FAILURE() << "no CommandFailure";
  } catch (const lab::CommandFailure& e) {
    EXPECT_EQ(std::string(e.what()), "--out: " + (out / "b.csv").string() + ": is a folder, not a file");
  }
  EXPECT_EQ(lab_testing::readFile(out / "a.csv"), "the earlier run\n");
  EXPECT_EQ(lab_testing::readFile(out / "e.png"), "the earlier chart");
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator(out)) left.push_back(entry.path().filename());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"a.csv", "b.csv", "e.png"}));
}

// A chart is drawn from the files held for it (the script reads its data by name), and what
// gnuplot drew is held and written with them.
TEST(OutputFolder, RendersAScriptFromTheDataItHolds) {
  if (lab::findGnuplot().empty()) GTEST_SKIP() << "no gnuplot on PATH (scripts/install-deps installs it)";
  TempDir dir;
  lab::OutputFolder files(dir.file("out"));
  files.write("d.dat", "1 2\n2 3\n");
  files.write("d.gp",
              std::string(lab::kOutdirDefault) +
                  "set terminal svg\nset output outdir.'/d.svg'\nplot 'd.dat' using 1:2\nunset output\n");
  EXPECT_EQ(files.render("d.gp", {"d.svg"}), "");
  EXPECT_FALSE(std::filesystem::exists(dir.file("out/d.svg")));
  files.commit();
  EXPECT_GT(std::filesystem::file_size(dir.file("out/d.svg")), 100u);
  const std::string out = dir.file("out").string();
  EXPECT_EQ(files.wroteLine(), "wrote       " + out + "/d.dat, " + out + "/d.gp, " + out + "/d.svg\n");
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.file("out"))) ++entries;
  EXPECT_EQ(entries, 3u);  // no scratch folder left
}

TEST(OutputFolder, AFolderItCannotWriteIsNamedByItsOption) {
  TempDir dir;
  const std::filesystem::path file = dir.write("file", "not a folder");
  for (const char* option : {"--out", "--save-scenes"}) {
    try {
      lab::OutputFolder files(file / "out", option);
      ADD_FAILURE() << "no CommandFailure for " << option;
    } catch (const lab::CommandFailure& e) {
      EXPECT_EQ(std::string(e.what()).rfind(std::string(option) + ": " + (file / "out").string(), 0), 0u)
          << e.what();
    }
  }
}

// A chart and a front of a figure that is 0 at every setting (a tracking error without a character)
// were drawn as if they said something: refused before any run, as tune refuses such a target.
TEST(Sweep, AnErrorFigureTheSceneCannotMakeIsRefusedBeforeAnyRun) {
  TempDir dir;
  const lab::CommandOutput o = lab::runCaptured("sweep", {"pendulum", "--error", "tracking-error", "--out",
                                                          dir.file("out").string(), "--data", DATA_DIR});
  lab_testing::expectUsageError(
      o, "sweep", "--error tracking-error: scene pendulum has no character, so it is 0 at every setting");
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

TEST(Sweep, UsageErrorsNameTheArgument) {
  TempDir dir;
  const std::string out = dir.file("out").string();
  struct Case {
    std::vector<std::string> args;
    std::string named;  // what the message must mention
  };
  const std::vector<Case> cases = {
      {{"pendulum"}, "--out"},
      {{"--out", out}, "SCENE"},
      {{"pendulum", "chain", "--out", out}, "chain"},
      {{"pendulum", "--out", out, "--method", "gauss,shake"}, "'gauss'"},
      {{"pendulum", "--out", out, "--iterations", "0"}, "--iterations: '0'"},
      {{"pendulum", "--out", out, "--substeps", "1,,2"}, "--substeps"},
      {{"pendulum", "--out", out, "--substeps", "2.5"}, "--substeps: '2.5'"},
      {{"pendulum", "--out", out, "--dt", "2"}, "--dt: '2'"},
      {{"pendulum", "--out", out, "--repeat", "0"}, "--repeat: '0'"},
      {{"pendulum", "--out", out, "--steps", "1e3"}, "--steps: '1e3'"},
      {{"pendulum", "--out", out, "--method"}, "--methods needs"},
      {{"pendulum", "--out", out, "--frobnicate"}, "'--frobnicate'"},
      {{"pendulum", "--out", out, "--model", "corners"}, "--models: 'corners' is a box model"},
      {{"falling-box", "--out", out, "--model", "lean"}, "--models: 'lean' is a ragdoll model"},
      {{"falling-box", "--out", out, "--model", "cubes"}, "unknown model 'cubes'"},
      {{"falling-box", "--out", out, "--error", "wobble"},
       "--error: unknown figure 'wobble' (one of position, "},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.named);
    lab_testing::expectUsageError(sweep(c.args), "sweep", c.named);
  }
  const Outcome help = sweep({"--help"});
  EXPECT_EQ(help.code, 0);
  EXPECT_TRUE(help.out.starts_with("usage: lab sweep")) << help.out;
  EXPECT_FALSE(std::filesystem::exists(out));  // nothing ran
}

TEST(Sweep, ShowsProgressOnePerTenthWhenStderrIsNotATerminal) {
  TempDir dir;
  const Outcome o = sweep({"pendulum-exact", "--substeps", "1,2,3,4,5", "--repeat", "1", "--no-peers",
                           "--out", dir.file("out").string()});
  ASSERT_EQ(o.code, 0) << o.err;
  // 5 settings x (1 timed + 1 measured) + 1 target = 11 runs: a line per tenth, the last full.
  EXPECT_NE(o.err.find("sweep [##############################] 11/11 "), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find('\r'), std::string::npos);
  std::size_t lines = 0;
  for (char c : o.err) lines += c == '\n' ? 1 : 0;
  EXPECT_LE(lines, 10u) << o.err;
}

// ---- accuracy ---------------------------------------------------------------------------------

std::string sceneWithExpect(const std::string& expect) {
  return "<scene name=\"e\">\n"
         "  <world/>\n"
         "  <particle name=\"p\" pos=\"0 5 0\" mass=\"1\"/>\n"
         "  " +
         expect +
         "\n"
         "</scene>\n";
}

TEST(Accuracy, MalformedPositionExpectationsAreLoadErrors) {
  struct Case {
    std::string expect;
    std::string attribute;
    std::string message;
  };
  const std::vector<Case> cases = {
      {R"(<expect kind="position" body="q" at="1" pos="0 0 0"/>)", "body",
       "'q' names no box or loose particle"},
      {R"(<expect kind="position" at="1" pos="0 0 0"/>)", "body", "is required"},
      {R"(<expect kind="position" body="p" pos="0 0 0"/>)", "at", "is required"},
      {R"(<expect kind="position" body="p" at="-1" pos="0 0 0"/>)", "at", "must be a finite number > 0"},
      {R"(<expect kind="position" body="p" at="0.01" pos="0 0 0"/>)", "at", "not a whole number of steps"},
      // Within round-off of t = 0: step 0, a checkpoint no run reaches, read as a blow-up.
      {R"(<expect kind="position" body="p" at="1e-300" pos="0 0 0"/>)", "at",
       "'1e-300' s is before the first step of 0.0166667 s"},
      {R"(<expect kind="position" body="p" at="1000000" pos="0 0 0"/>)", "at",
       "'1000000' s at the scene's dt 0.0166667 s is more than 10000000 steps"},
      {R"(<expect kind="position" body="p" at="1" pos="0 0"/>)", "pos", "must be three finite numbers"},
      {R"(<expect kind="position" body="p" at="1" pos="0 nan 0"/>)", "pos", "must be three finite numbers"},
      {R"(<expect kind="position" body="p" at="1" pos="0 0 0" tolerance="1"/>)", "tolerance",
       "unknown attribute"},
      {R"(<expect kind="position" body="p" at="1" pos="0 0 0" at="2"/>)", "at", "given twice"},
      // Where no body can be: its error overflowed to the inf of a run that blew up.
      {R"(<expect kind="position" body="p" at="1" pos="1e308 0 0"/>)", "pos",
       "'1e308 0 0' is beyond the world's bound of 1e+06 m"},
  };
  for (const Case& c : cases) {
    const scenes::Scene scene = scenes::loadSceneText(sceneWithExpect(c.expect), "e.xml");
    try {
      (void)lab::accuracyTarget(scene, 1.0 / 60.0, 60);
      ADD_FAILURE() << "no error for " << c.expect;
    } catch (const scenes::LoadError& e) {
      EXPECT_EQ(e.line(), 4) << e.what();
      EXPECT_EQ(e.attribute(), c.attribute) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
      EXPECT_TRUE(std::string(e.what()).starts_with("e.xml:4: <expect")) << e.what();
    }
  }
  // A kind misspelt or left out was a check that never ran: the loader refuses it.
  for (const char* expect : {R"(<expect kind="positon" body="p" at="1" pos="0 0 0"/>)", R"(<expect/>)"}) {
    try {
      (void)scenes::loadSceneText(sceneWithExpect(expect), "e.xml");
      ADD_FAILURE() << "no error for " << expect;
    } catch (const scenes::LoadError& e) {
      EXPECT_EQ(e.attribute(), "kind") << e.what();
      EXPECT_TRUE(std::string(e.what()).starts_with("e.xml:4: <expect> attribute 'kind'")) << e.what();
    }
  }
  // Other kinds belong to other commands and are left alone.
  const scenes::Scene other =
      scenes::loadSceneText(sceneWithExpect(R"(<expect kind="pass" max-speed="1"/>)"), "e.xml");
  EXPECT_EQ(lab::accuracyTarget(other, 1.0 / 60.0, 8).kind, "reference");
}

TEST(Accuracy, SweepReportsABadExpectationLikeTheLoader) {
  TempDir dir;
  const std::filesystem::path scene =
      dir.write("bad.xml", sceneWithExpect(R"(<expect kind="position" body="p" at="1" pos="1 2"/>)"));
  const Outcome o = sweep({scene.string(), "--out", dir.file("out").string()});
  EXPECT_EQ(o.code, lab::kExitFailure);
  EXPECT_NE(o.err.find(scene.string() + ":4: <expect kind=\"position\"> attribute 'pos'"), std::string::npos)
      << o.err;
}

TEST(Accuracy, AnalyticTargetHoldsTheGivenPositionsAtTheirSteps) {
  const scenes::Scene scene = scenes::loadSceneText(
      sceneWithExpect(R"(<expect kind="position" body="p" at="0.5" pos="1 2 3"/>)"), "e.xml");
  const lab::AccuracyTarget t = lab::accuracyTarget(scene, 0.01, 10);
  EXPECT_EQ(t.kind, "analytic");
  ASSERT_EQ(t.checkpoints, std::vector<int>{50});
  EXPECT_EQ(lab::stepsFor(t, 10), 50);  // the run goes on to the answer's time
  EXPECT_EQ(t.expected[0][0], phys::Vec3(1, 2, 3));
  EXPECT_EQ(lab::accuracyError(t, {{phys::Vec3(1, 2, 3.5)}}), 0.5);
  EXPECT_TRUE(std::isinf(lab::accuracyError(t, {{phys::Vec3(1, std::nan(""), 3)}})));
  EXPECT_TRUE(
      std::isinf(lab::accuracyError(t, {{phys::Vec3(1, 2, 3), phys::Vec3(0.0)}})));  // body counts differ
  EXPECT_TRUE(std::isinf(lab::accuracyError(t, {})));
}

// A particle on either side of a box, whose own particles lie between them by id.
scenes::Scene boxBetweenParticles() {
  return scenes::loadSceneText(
      "<scene name=\"order\">\n  <world/>\n"
      "  <particle name=\"first\" pos=\"1 0 0\" mass=\"1\"/>\n"
      "  <box name=\"crate\" pos=\"0 5 0\" size=\"1\"/>\n"
      "  <particle name=\"last\" pos=\"2 0 0\" mass=\"1\"/>\n</scene>\n",
      "o.xml");
}

TEST(Accuracy, BodiesAreTheBoxesThenTheLooseParticlesInIdOrder) {
  const scenes::Scene scene = boxBetweenParticles();
  const phys::World& world = scene.world;
  const phys::Body& box = world.bodies()[0];
  const std::vector<phys::ParticleId> loose = lab::looseParticles(world);
  ASSERT_EQ(loose,
            (std::vector<phys::ParticleId>{phys::ParticleId(0), box.firstParticle + box.particleCount}));
  EXPECT_EQ(lab::bodySlot(scene, "crate"), 0u);
  EXPECT_EQ(lab::bodySlot(scene, "first"), 1u);
  EXPECT_EQ(lab::bodySlot(scene, "last"), 2u);
  EXPECT_EQ(lab::bodySlot(scene, "nobody"), std::nullopt);
  const std::vector<phys::Vec3> positions = lab::bodyPositions(world);
  ASSERT_EQ(positions.size(), 3u);
  EXPECT_EQ(positions[1], phys::Vec3(1, 0, 0));
  EXPECT_EQ(positions[2], phys::Vec3(2, 0, 0));
}

TEST(Accuracy, EachParticleBelongsToItsBoxOrToItsOwnPlaceAfterTheBoxes) {
  const scenes::Scene scene = boxBetweenParticles();
  const phys::Body& box = scene.world.bodies()[0];
  std::vector<std::size_t> expected(scene.world.particles().size(), 0u);
  expected.front() = 1u;
  expected.back() = 2u;
  ASSERT_EQ(expected.size(), static_cast<std::size_t>(box.particleCount) + 2u);
  EXPECT_EQ(lab::particleBodies(scene.world), expected);
}

TEST(Accuracy, ReferenceIsShakeUnlessTheSceneAsksForCompliance) {
  const scenes::Scene rigid = scenes::loadSceneText(lab_testing::namedBodiesScene(), "n.xml");
  phys::SolverSettings s = lab::referenceSettings(rigid.world, 0.02);
  EXPECT_EQ(s.method, phys::SolverMethod::Shake);
  EXPECT_EQ(s.substeps, lab::kReferenceSubsteps);
  EXPECT_EQ(s.iterations, lab::kReferenceIterations);
  EXPECT_EQ(s.dt, 0.02);
  scenes::Scene soft = scenes::loadSceneText(lab_testing::namedBodiesScene(), "n.xml");
  phys::SolverSettings withCompliance = soft.world.solverSettings();
  withCompliance.compliance = 1e-4;
  soft.world.setSolverSettings(withCompliance);
  EXPECT_EQ(lab::referenceSettings(soft.world, 0.02).method, phys::SolverMethod::Xpbd);

  // Four checkpoints spread over the run, the last step among them, and an error bar.
  const lab::AccuracyTarget t = lab::accuracyTarget(rigid, 1.0 / 60.0, 30);
  EXPECT_EQ(t.kind, "reference");
  EXPECT_EQ(t.checkpoints, (std::vector<int>{8, 15, 23, 30}));
  ASSERT_EQ(t.uncertainty.size(), 4u);
  for (double u : t.uncertainty) EXPECT_TRUE(std::isfinite(u));
}

}  // namespace

TEST(LabCsv, ALineIsItsFieldsWithCommasBetweenAndANewlineAfter) {
  EXPECT_EQ(lab::csvLine({"a", lab::csvField("b,c"), "", lab::csvNumber(0.5, 6)}), "a,\"b,c\",,0.5\n");
  EXPECT_EQ(lab::csvLine({""}), "\n");
  const std::vector<std::string> fields = lab::csvFields("a,\"b,c\",,0.5");
  EXPECT_EQ(fields, (std::vector<std::string>{"a", "b,c", "", "0.5"}));
}

TEST(LabGnuplot, SingleQuotedWritesEachQuoteInsideAsAsked) {
  EXPECT_EQ(lab::singleQuoted("it's", "''"), "'it''s'");        // gnuplot
  EXPECT_EQ(lab::singleQuoted("it's", "'\\''"), "'it'\\''s'");  // the shell
  EXPECT_EQ(lab::singleQuoted("", "''"), "''");
}

TEST(LabCharts, AScriptQuotesItsTextsAndWritesItsPointsExactly) {
  lab::Chart chart = lab::logChart("it's a chart", "x", "y", true, "out");
  chart.series.push_back(lab::ChartSeries{.title = "a 'b'", .points = {{0.1, 2.0, "p"}}});
  const std::string script = lab::gnuplotScript(chart);
  EXPECT_NE(script.find("set title 'it''s a chart'\n"), std::string::npos) << script;
  EXPECT_NE(script.find("title 'a ''b'''"), std::string::npos) << script;
  EXPECT_NE(script.find("0.10000000000000001 2 \"p\"\n"), std::string::npos) << script;
}
