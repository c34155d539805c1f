// The Lab panel's sweep (lab_sweep.h): every setting of the grid measured by the lab's functions
// on a thread of its own, the Pareto front, and a cancel that stops it within a step (the stop
// itself is runSteps', tested in tests/lab/runner_test.cpp).
#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <thread>
#include <unistd.h>

#include <gtest/gtest.h>

#include "lab_sweep.h"
#include "scenes/scene.h"

namespace {

using namespace std::chrono_literals;

std::filesystem::path scene(const char* name) {
  return scenes::resolveScene(name, scenes::sceneDirectory(DATA_DIR));
}

TEST(LabSweep, MeasuresEverySettingOfTheGrid) {
  sandbox::LabSweep lab;
  lab.start(scene("pendulum-exact"));
  for (int i = 0; i < 120000 && lab.running(); ++i) std::this_thread::sleep_for(1ms);
  ASSERT_FALSE(lab.running());
  EXPECT_EQ(lab.error(), "");
  const std::vector<sandbox::LabPoint> points = lab.points();
  ASSERT_EQ(points.size(), 48u);  // 4 methods x 3 iterations x 4 substeps
  EXPECT_EQ(lab.done(), 48);
  for (const sandbox::LabPoint& p : points) {
    EXPECT_FALSE(p.blewUp);
    EXPECT_TRUE(std::isfinite(p.error) && p.error >= 0.0);
    EXPECT_GT(p.msPerStep, 0.0);
  }
  // Against the exact answer, more substeps are more accurate for a pendulum (first order).
  auto find = [&](phys::SolverMethod m, int it, int sub) {
    for (const sandbox::LabPoint& p : points) {
      if (p.method == m && p.iterations == it && p.substeps == sub) return p;
    }
    return sandbox::LabPoint{};
  };
  EXPECT_LT(find(phys::SolverMethod::GaussSeidel, 1, 8).error,
            find(phys::SolverMethod::GaussSeidel, 1, 1).error);
}

TEST(LabSweep, TheFrontIsWhatNothingBeatsInBoth) {
  using P = sandbox::LabPoint;
  const std::vector<P> points{{phys::SolverMethod::Jacobi, 1, 1, 1.0, 0.5, false},
                              {phys::SolverMethod::Xpbd, 1, 2, 2.0, 0.1, false},
                              {phys::SolverMethod::Shake, 1, 4, 3.0, 0.2, false},  // beaten by the one above
                              {phys::SolverMethod::GaussSeidel, 1, 8, 4.0, 0.01, false},
                              {phys::SolverMethod::Jacobi, 4, 8, 0.5, 0.0, true}};  // blew up: not on it
  const std::vector<P> front = sandbox::paretoFront(points);
  ASSERT_EQ(front.size(), 3u);
  EXPECT_EQ(front[0].msPerStep, 1.0);
  EXPECT_EQ(front[1].msPerStep, 2.0);
  EXPECT_EQ(front[2].msPerStep, 4.0);
}

TEST(LabSweep, CancelStopsItAndABadFileSaysWhy) {
  sandbox::LabSweep lab;
  lab.start(scene("ragdolls"));
  std::this_thread::sleep_for(20ms);
  lab.cancel();  // returns at once; the setting being measured is dropped after its step
  for (int i = 0; i < 600000 && lab.running(); ++i) std::this_thread::sleep_for(1ms);
  EXPECT_FALSE(lab.running());
  EXPECT_LT(lab.done(), 48);
  EXPECT_EQ(lab.error(), "");  // a cancel is no error, though it stopped a run within a setting
  lab.start("/nonexistent/scene.xml");
  for (int i = 0; i < 10000 && lab.running(); ++i) std::this_thread::sleep_for(1ms);
  EXPECT_NE(lab.error().find("/nonexistent/scene.xml"), std::string::npos) << lab.error();
  EXPECT_TRUE(lab.points().empty());
}

// The sweep reads the file once: the user may Save As over it while the sweep runs, and the points
// after that must still measure the scene the sweep started on.
TEST(LabSweep, AFileSavedOverWhileItRunsChangesNoPoint) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("lab-sweep-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path swept = dir / "swept.xml", untouched = dir / "untouched.xml";
  fs::copy_file(scene("pendulum-exact"), swept, fs::copy_options::overwrite_existing);
  fs::copy_file(scene("pendulum-exact"), untouched, fs::copy_options::overwrite_existing);
  sandbox::LabSweep lab, reference;
  lab.start(swept);
  for (int i = 0; i < 120000 && lab.running() && lab.done() < 1; ++i) std::this_thread::sleep_for(1ms);
  ASSERT_GE(lab.done(), 1);
  ASSERT_LT(lab.done(), 48);  // saved over while the sweep still had points to measure
  fs::copy_file(scene("projectile"), swept, fs::copy_options::overwrite_existing);
  reference.start(untouched);
  for (int i = 0; i < 240000 && (lab.running() || reference.running()); ++i) std::this_thread::sleep_for(1ms);
  ASSERT_FALSE(lab.running());
  ASSERT_FALSE(reference.running());
  EXPECT_EQ(lab.error(), "");
  const std::vector<sandbox::LabPoint> got = lab.points(), want = reference.points();
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].error, want[i].error) << "point " << i;
  fs::remove_all(dir);
}

}  // namespace
