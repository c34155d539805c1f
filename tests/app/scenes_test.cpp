// Built-in scenes: each one builds, steps without NaN, and unknown names are refused.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "scenes/scene.h"

namespace {

TEST(Scenes, EachBuiltInSceneBuildsAndSteps) {
  ASSERT_FALSE(scenes::builtinSceneNames().empty());
  EXPECT_EQ(scenes::builtinSceneNames().front(), scenes::defaultSceneName());
  for (const std::string& name : scenes::builtinSceneNames()) {
    scenes::Scene scene = scenes::makeBuiltinScene(name);
    EXPECT_EQ(scene.name, name);
    EXPECT_GT(scene.world.particles().size(), 0u);
    for (int i = 0; i < 300; ++i) scene.world.step();
    for (const phys::Vec3& p : scene.world.particles().position) {
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << name;
      EXPECT_GE(p.y, scene.world.worldSettings().groundHeight - 1e-9) << name;
    }
  }
}

TEST(Scenes, UnknownNameListsTheKnownOnes) {
  try {
    scenes::makeBuiltinScene("nope");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'nope'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find(scenes::defaultSceneName()), std::string::npos);
  }
}

}  // namespace
