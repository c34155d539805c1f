// F12's file name: next to the scene, named after it and the step, never over an earlier one.
#include <fstream>

#include <gtest/gtest.h>

#include "screenshot.h"
#include "temp_folder.h"

namespace {

TEST(ScreenshotPath, BesideTheSceneNamedByTheStepAndNeverOverAnother) {
  const testing_app::TempFolder dir;
  const std::filesystem::path scene = dir.path / "ragdolls.xml";
  EXPECT_EQ(sandbox::screenshotPath(scene, 240), dir.path / "ragdolls-step240.png");
  std::ofstream(dir.path / "ragdolls-step240.png") << "x";
  EXPECT_EQ(sandbox::screenshotPath(scene, 240), dir.path / "ragdolls-step240-2.png");
  std::ofstream(dir.path / "ragdolls-step240-2.png") << "x";
  EXPECT_EQ(sandbox::screenshotPath(scene, 240), dir.path / "ragdolls-step240-3.png");
  EXPECT_EQ(sandbox::screenshotPath(scene, 241), dir.path / "ragdolls-step241.png");
}

}  // namespace
