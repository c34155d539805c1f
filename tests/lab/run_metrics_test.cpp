// The figures of a run (app/lab/run_metrics.h) are defined in one table: each reaches `lab run
// --json`, sweep's results.csv, tune's targets and compare's table; the fastest spin, the
// figure added to show it, reads a known spin back; the tracking error is an RMS over the run.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "commands.h"
#include "csv.h"
#include "json.h"
#include "lab.h"
#include "lab_test_util.h"
#include "physics/character.h"
#include "root_mean_square.h"
#include "run.h"
#include "run_metrics.h"
#include "scenes/scene.h"
#include "text.h"

namespace {

using lab_testing::TempDir;

// One box spinning at 180 degrees a second (pi rad/s) about its y axis, a principal axis, with
// nothing to touch and no gravity: its spin stays pi rad/s exactly.
std::string spinningBox(const char* model) {
  return std::string(
             "<scene name='spin'>\n<world gravity='0 0 0'/>\n<solver dt='0.0166666666666667'/>\n"
             "<box name='b' pos='0 0 0' size='1 0.5 0.25' model='") +
         model + "' angular-velocity='0 180 0'/>\n</scene>\n";
}

lab::Json runJson(const std::filesystem::path& scene) {
  const lab::CommandOutput o = lab::runCaptured({"run", scene.string(), "--steps", "60", "--json"});
  EXPECT_EQ(o.code, lab::kExitOk) << o.err;
  return lab::Json::parse(o.out);
}

TEST(RunMetrics, EveryFigureReachesRunSweepTuneAndCompare) {
  const TempDir dir;
  const std::filesystem::path scene = dir.write("spin.xml", spinningBox("corners"));
  const lab::Json run = runJson(scene);
  const lab::CommandOutput sweep = lab::runCaptured({"sweep", scene.string(), "--steps", "5", "--repeat", "1",
                                                     "--no-peers", "--out", dir.file("sweep").string()});
  ASSERT_EQ(sweep.code, lab::kExitOk) << sweep.err;
  const std::vector<std::string> columns = lab::readCsv(dir.file("sweep/results.csv")).header;
  const lab::CommandOutput compare = lab::runCaptured({"compare", scene.string(), "--steps", "5"});
  ASSERT_EQ(compare.code, lab::kExitOk) << compare.err;
  const lab::CommandOutput tuneHelp = lab::runCaptured({"tune", "--help"});
  const lab::CommandOutput badTarget = lab::runCaptured({"tune", scene.string(), "--target", "bogus=1"});
  for (const lab::RunMetric& m : lab::kRunMetrics) {
    const std::string column = m.column;
    EXPECT_TRUE(run.contains(column + "_over_run")) << m.name;
    EXPECT_NE(std::find(columns.begin(), columns.end(), column), columns.end()) << m.name;
    const std::string heading = std::string("| ") + m.name +
                                (*m.unit == '\0' ? "" : std::string(" (") + m.unit + ")") +
                                (m.over == lab::OverRun::Rms ? ", RMS over the run |" : ", every step |");
    EXPECT_NE(compare.out.find(heading), std::string::npos) << heading << "\n" << compare.out;
    EXPECT_NE(tuneHelp.out.find(std::string("  ") + m.name + " "), std::string::npos) << m.name;
    EXPECT_NE(badTarget.err.find(std::string(" ") + m.name), std::string::npos) << badTarget.err;
  }
}

TEST(RunMetrics, TuneMeetsATargetOnTheFastestSpin) {
  const TempDir dir;
  const std::filesystem::path scene = dir.write("spin.xml", spinningBox("rigid"));
  const lab::CommandOutput o = lab::runCaptured(
      {"tune", scene.string(), "--target", "angular-speed=3.2", "--steps", "5", "--repeat", "1"});
  EXPECT_EQ(o.code, lab::kExitOk) << o.err;
  EXPECT_NE(o.out.find("angular-speed <= 3.2 rad/s"), std::string::npos) << o.out;
  // A bound below pi rad/s cannot be met by any setting: the spin is the scene's, not an error.
  const lab::CommandOutput missed = lab::runCaptured(
      {"tune", scene.string(), "--target", "angular-speed=3", "--steps", "5", "--repeat", "1"});
  EXPECT_EQ(missed.code, lab::kExitFailure) << missed.out;
}

// The rigid model keeps a principal-axis spin exactly. A particle box's spin is read from its
// particles' Verlet motion over the last substep, whose sticks pull each step's turn back onto
// the circle: it reads low by about (w h)^2 / 2 (0.14% at pi rad/s and 1/60 s); the tolerance is
// (w h)^2.
TEST(RunMetrics, TheFastestSpinReadsAKnownSpinBack) {
  const TempDir dir;
  const double turn = std::numbers::pi / 60.0;  // w h, rad a step
  for (const auto& [model, tolerance] :
       {std::pair{"rigid", 1e-9}, std::pair{"corners", turn * turn}, std::pair{"tetra", turn * turn}}) {
    const lab::Json j = runJson(dir.write(std::string(model) + ".xml", spinningBox(model)));
    EXPECT_NEAR(j["max_angular_speed_over_run"].get<double>() / std::numbers::pi, 1.0, tolerance) << model;
  }
}

// The tracking error is the one figure kept as a root mean square over the run: lab run's figure for
// the animated scene equals the RMS, over the steps and every character's parts, of
// phys::trackingError read by hand after each step of the same load (to round-off), less than the
// worst step's (the first second: 14 degrees, the parts turning from the ragdoll's rest to the
// clips' first poses).
TEST(RunMetrics, TheTrackingErrorIsItsRootMeanSquareOverTheRun) {
  const std::filesystem::path file = std::filesystem::path(DATA_DIR) / "assets" / "scenes" / "animated.xml";
  const lab::Json run = runJson(file);
  scenes::Scene scene = scenes::loadSceneFile(file, lab::imposedAtLoad(std::nullopt));
  double sum = 0.0, parts = 0.0, largest = 0.0;
  for (int step = 0; step < 60; ++step) {
    scene.world.step();
    double stepSum = 0.0, stepParts = 0.0;
    for (std::size_t k = 0; k < scene.world.characters().size(); ++k) {
      const double e = phys::trackingError(scene.world, k) * 180.0 / std::numbers::pi;
      const double n = double(scene.world.characters()[k].bones.size());
      stepSum += e * e * n;
      stepParts += n;
    }
    sum += stepSum / stepParts;
    largest = std::max(largest, std::sqrt(stepSum / stepParts));
    parts += 1.0;
  }
  const double rms = std::sqrt(sum / parts);
  EXPECT_NEAR(run["rms_tracking_error_over_run"].get<double>(), rms, 1e-9 * rms);
  EXPECT_GT(rms, 0.0);
  EXPECT_LT(rms, largest);
  // A scene without characters tracks nothing: 0, not NaN.
  const TempDir dir;
  EXPECT_EQ(runJson(dir.write("spin.xml", spinningBox("rigid")))["rms_tracking_error_over_run"].get<double>(),
            0.0);
}

// Samples of 1e200 are finite, so their RMS is too: squaring them as they come would overflow to
// infinity and read "blew up". Scaled by the largest, they keep their RMS, and so do samples too
// small to square (1e-200, whose square is 0).
TEST(RootMeanSquare, HugeAndTinyFiniteSamplesKeepTheirRms) {
  for (const double scale : {1e200, 1e300, 1.7e308, 1e-200, 1e-300}) {
    lab::RootMeanSquare rms;
    rms.add(0.6 * scale);
    rms.add(-0.8 * scale);
    EXPECT_NEAR(rms.value(), std::sqrt(0.5) * scale, 1e-15 * std::sqrt(0.5) * scale) << scale;
  }
  lab::RootMeanSquare growing;  // the largest arrives last: what came before is rescaled to it
  for (const double v : {1.0, 1e100, 1e200, 1e300}) growing.add(v);
  EXPECT_DOUBLE_EQ(growing.value(), 0.5e300);
  lab::RootMeanSquare weighted;
  weighted.add(1e200, 3.0);
  weighted.add(0.0, 1.0);
  EXPECT_DOUBLE_EQ(weighted.value(), std::sqrt(0.75) * 1e200);
}

// The scale is a power of two, which multiplies and divides exactly: ordinary samples give the
// same bits as the plain sqrt(sum x^2 / n), so no pinned figure moves.
TEST(RootMeanSquare, OrdinarySamplesGiveThePlainFormulaBitForBit) {
  const double samples[] = {0.0123, 3.5, -7.25e-3, 1e-9, 42.0, 0.1, 6.02e23, 1e-30, 2.5};
  double sum = 0.0, weights = 0.0;
  lab::RootMeanSquare rms;
  for (std::size_t i = 0; i < std::size(samples); ++i) {
    const double w = double(i % 3 + 1);
    sum += samples[i] * samples[i] * w;
    weights += w;
    rms.add(samples[i], w);
    EXPECT_EQ(rms.value(), std::sqrt(sum / weights)) << i;
  }
  EXPECT_EQ(lab::RootMeanSquare().value(), 0.0);
}

// A sample that is not finite is kept as it would be in a plain sum of squares: infinity makes
// the RMS infinite (blew up), NaN makes it NaN (n/a), whatever comes after.
TEST(RootMeanSquare, ASampleThatIsNotFiniteStays) {
  lab::RootMeanSquare inf, nan;
  inf.add(1.0);
  inf.add(-lab::kInf);
  inf.add(1e300);
  EXPECT_EQ(inf.value(), lab::kInf);
  nan.add(lab::kNaN);
  nan.add(lab::kInf);
  nan.add(1.0);
  EXPECT_TRUE(std::isnan(nan.value()));
}

// A run's RMS figure of huge but finite values is that value, not "blew up"; a value that is not
// finite still makes it infinite for the run.
TEST(RunMetrics, AnRmsFigureOfHugeFiniteValuesStaysFinite) {
  const std::size_t tracking = lab::runMetricIndex("tracking-error");
  ASSERT_EQ(lab::kRunMetrics[tracking].over, lab::OverRun::Rms);
  lab::RunMaxima maxima;
  std::array<double, lab::kRunMetricCount> figures{};
  figures[tracking] = 1e200;
  maxima.observe(figures);
  maxima.observe(figures);
  EXPECT_DOUBLE_EQ(maxima[tracking], 1e200);
  figures[tracking] = lab::kNaN;
  maxima.observe(figures);
  EXPECT_EQ(maxima[tracking], lab::kInf);
}

TEST(RunMetrics, KeepLargestHoldsInfinityOnceASampleIsNotFinite) {
  double worst = 0.0;
  lab::keepLargest(worst, 0.5);
  lab::keepLargest(worst, 0.25);
  EXPECT_EQ(worst, 0.5);
  lab::keepLargest(worst, std::nan(""));
  EXPECT_TRUE(std::isinf(worst));
  lab::keepLargest(worst, 1.0);  // a later small sample does not rescue a run that blew up
  EXPECT_TRUE(std::isinf(worst));
}

TEST(RunMetrics, NamesFindTheirRow) {
  EXPECT_EQ(lab::runMetricIndex("angular-speed"), lab::kRunMetricCount - 2);
  EXPECT_EQ(lab::runMetricIndex("tracking-error"), lab::kRunMetricCount - 1);
  EXPECT_EQ(lab::runMetricIndex("bogus"), lab::kRunMetricCount);
}

}  // namespace
