// The sandbox's draw modes, markers, method overlay and --pause-at, seen in the pixels of the
// real program's screenshots under Xvfb; and every project scene loading and rendering.
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "body_colors.h"
#include "panels.h"
#include "sandbox_run.h"
#include "scenes/scene.h"

namespace {

namespace fs = std::filesystem;
using testing_gl::countPixels;
using testing_gl::runSandbox;

// The part of a 1280x720 screenshot left of the panels' column, between the menu bar and the
// status line.
const sandbox::ScreenRect kScene = sandbox::sceneView(1280.0f, 720.0f, true);
const int kViewX = 0, kViewY = 30, kViewW = static_cast<int>(kScene.width), kViewH = 660;

bool red(int r, int g, int b) {
  return r > 180 && g < 60 && b < 60;
}
bool green(int r, int g, int b) {
  return g > 170 && r < 90 && b < 110;
}

scenes::Scene stepped(const std::string& name, int steps) {
  scenes::Scene s = scenes::loadSceneFile(scenes::resolveScene(name, scenes::sceneDirectory(DATA_DIR)));
  for (int i = 0; i < steps; ++i) s.world.step();
  return s;
}

engine::FirstPersonCamera startCamera(const scenes::Scene& s) {
  return engine::FirstPersonCamera::lookingAt(s.camera.eye, s.camera.target);
}

TEST(SandboxModes, EveryProjectSceneLoadsAndRenders) {
  constexpr int kFrames = 3;
  for (const auto& entry : fs::directory_iterator(scenes::sceneDirectory(DATA_DIR))) {
    if (entry.path().extension() != ".xml") continue;
    const std::string name = entry.path().stem().string();
    SCOPED_TRACE(name);
    const engine::Image image = runSandbox(name + " --color-by kind", "scene-" + name + ".png", kFrames);
    ASSERT_EQ(image.width, 1280);
    ASSERT_EQ(image.height, 720);
    // Each body whose centre lands in the view between the panels is drawn there: in a box's
    // colour or a particle's (one body may hide another, never the sky or the ground).
    const scenes::Scene scene = stepped(name, kFrames);
    const auto camera = startCamera(scene);
    const phys::World& w = scene.world;
    std::vector<glm::vec3> centres;
    std::vector<bool> inBox(w.particles().size(), false);
    for (phys::BodyId id{}; id < w.bodies().size(); ++id) {
      centres.emplace_back(w.bodyPose(id).center);
      for (int k = 0; k < w.bodies()[id].particleCount; ++k) inBox[w.bodies()[id].firstParticle + k] = true;
    }
    for (std::size_t i = 0; i < w.particles().size(); ++i) {
      if (!inBox[i])
        centres.push_back(glm::vec3(w.particles().position[i]) +
                          glm::vec3(0, sandbox::kParticleDrawSize / 4, 0));
    }
    int visible = 0, drawn = 0;
    for (const glm::vec3& c : centres) {
      const glm::ivec2 px = testing_gl::toSandboxPixel(image, camera, c);
      if (px.x < kViewX || px.x >= kViewX + kViewW || px.y < kViewY || px.y >= kViewY + kViewH) continue;
      // The crosshair's two lines cross at the centre of the scene.
      if (std::abs(px.x - kViewW / 2) < 10 && std::abs(px.y - image.height / 2) < 10) continue;
      ++visible;
      const glm::u8vec4 p = image.pixel(px.x, px.y);
      drawn += sandbox::looksLike(sandbox::kBoxColor, p.r, p.g, p.b) ||
               sandbox::looksLike(sandbox::kParticleColor, p.r, p.g, p.b);
    }
    EXPECT_GT(visible, 0);
    EXPECT_EQ(drawn, visible);
  }
}

TEST(SandboxModes, WireframeAndFilledDiffer) {
  const engine::Image filled = runSandbox("ragdoll --draw filled", "mode-filled.png", 30);
  const engine::Image wire = runSandbox("ragdoll --draw wireframe", "mode-wireframe.png", 30);
  int differ = 0;
  for (int y = kViewY; y < kViewY + kViewH; ++y) {
    for (int x = kViewX; x < kViewX + kViewW; ++x) differ += filled.pixel(x, y) != wire.pixel(x, y) ? 1 : 0;
  }
  EXPECT_GT(differ, 300);
}

TEST(SandboxModes, ConstraintsModeDrawsTheSticksRed) {
  const engine::Image constraints = runSandbox("ragdoll --draw constraints", "mode-constraints.png", 30);
  const engine::Image filled = runSandbox("ragdoll --draw filled", "mode-filled.png", 30);
  EXPECT_GT(countPixels(constraints, kViewX, kViewY, kViewW, kViewH, red), 100);
  EXPECT_LT(countPixels(filled, kViewX, kViewY, kViewW, kViewH, red), 5);
}

TEST(SandboxModes, MarkersShowGreenBoxesWhereBoxesCollide) {
  const engine::Image marked = runSandbox("box-of-boxes --markers --color-by kind", "markers-on.png", 20);
  const engine::Image plain = runSandbox("box-of-boxes --color-by kind", "markers-off.png", 20);
  EXPECT_GT(countPixels(marked, kViewX, kViewY, kViewW, kViewH, green), 50);
  EXPECT_LT(countPixels(plain, kViewX, kViewY, kViewW, kViewH, green), 5);
}

// --targets (Draw > target poses): the runner's target pose drawn over it as a pale cyan ghost, a
// colour nothing else in the scene has.
TEST(SandboxModes, TargetsDrawTheCharactersGhostInPaleCyan) {
  const auto cyan = [](int r, int g, int b) { return r < 150 && g > 200 && b > 220; };
  const engine::Image ghost = runSandbox("run-cycle --targets", "targets-on.png", 20);
  const engine::Image plain = runSandbox("run-cycle", "targets-off.png", 20);
  EXPECT_GT(countPixels(ghost, kViewX, kViewY, kViewW, kViewH, cyan), 100);
  EXPECT_LT(countPixels(plain, kViewX, kViewY, kViewW, kViewH, cyan), 5);
}

// The stack settles in about a second and sleeps half a second later: coloured by sleep, its boxes are
// grey-blue where they are orange by kind.
TEST(SandboxModes, ColourBySleepShowsTheSleepingStack) {
  constexpr int kFrames = 150;
  const engine::Image bySleep = runSandbox("stack --color-by sleep", "color-sleep.png", kFrames);
  const engine::Image byKind = runSandbox("stack --color-by kind", "color-kind.png", kFrames);
  scenes::LoadOptions sandbox;
  sandbox.sleepUnlessSaid = true;
  scenes::Scene s =
      scenes::loadSceneFile(scenes::resolveScene("stack", scenes::sceneDirectory(DATA_DIR)), sandbox);
  for (int i = 0; i < kFrames; ++i) s.world.step();
  ASSERT_EQ(s.world.islands().sleepingBodies(), s.world.bodies().size());
  const auto camera = startCamera(s);
  int sleeping = 0, orange = 0, checked = 0;
  for (phys::BodyId id{}; id < s.world.bodies().size(); ++id) {
    const glm::ivec2 p = testing_gl::toSandboxPixel(bySleep, camera, glm::vec3(s.world.bodyPose(id).center));
    if (p.x < kViewX || p.x >= kViewX + kViewW || p.y < kViewY || p.y >= kViewY + kViewH) continue;
    ++checked;
    // A centre under the crosshair is neither: only those drawn orange by kind are compared.
    const glm::u8vec4 a = bySleep.pixel(p.x, p.y), b = byKind.pixel(p.x, p.y);
    if (!sandbox::looksLike(sandbox::kBoxColor, b.r, b.g, b.b)) continue;
    ++orange;
    sleeping += sandbox::looksLike(sandbox::kSleepingColor, a.r, a.g, a.b) ? 1 : 0;
  }
  ASSERT_GT(checked, 3);
  EXPECT_GE(orange, checked - 1);
  EXPECT_EQ(sleeping, orange);
}

TEST(SandboxModes, TheOverlayDrawsEveryRunInItsOwnColour) {
  // The falling box lands at about frame 40; with restitution 0.8 it bounces back up, without
  // it stays down: after 62 frames the two runs' boxes are far apart.
  constexpr int kFrames = 62;
  const engine::Image image =
      runSandbox("falling-box --overlay restitution=0 restitution=0.8", "overlay.png", kFrames);
  auto run = [&](double restitution) {
    scenes::Scene s = stepped("falling-box", 0);
    phys::SolverSettings settings = s.world.solverSettings();
    settings.restitution = restitution;
    s.world.setSolverSettings(settings);
    for (int i = 0; i < kFrames; ++i) s.world.step();
    return s;
  };
  const scenes::Scene resting = run(0.0);
  const scenes::Scene bouncing = run(0.8);
  const auto camera = startCamera(resting);
  const glm::ivec2 a =
      testing_gl::toSandboxPixel(image, camera, glm::vec3(resting.world.bodyPose(phys::BodyId{0}).center));
  const glm::ivec2 b =
      testing_gl::toSandboxPixel(image, camera, glm::vec3(bouncing.world.bodyPose(phys::BodyId{0}).center));
  ASSERT_GT(std::abs(a.y - b.y), 40) << "the two runs' boxes should be apart on screen";
  // Run 0 is tinted orange (red over blue), run 1 blue (blue over red), both translucent.
  auto tint = [&](glm::ivec2 at) { return int(image.pixel(at.x, at.y).r) - int(image.pixel(at.x, at.y).b); };
  EXPECT_GT(tint(a), 40) << "run 0 at " << a.x << ", " << a.y;
  EXPECT_LT(tint(b), -40) << "run 1 at " << b.x << ", " << b.y;
}

TEST(SandboxModes, PauseAtStopsTheWorldAtThatStep) {
  const engine::Image image = runSandbox("falling-box --pause-at 10 --color-by kind", "pause-at.png", 40);
  const scenes::Scene at10 = stepped("falling-box", 10);
  const scenes::Scene at40 = stepped("falling-box", 40);
  const auto camera = startCamera(at10);
  auto boxAt = [&](const scenes::Scene& s) {
    const glm::ivec2 px =
        testing_gl::toSandboxPixel(image, camera, glm::vec3(s.world.bodyPose(phys::BodyId{0}).center));
    const glm::u8vec4 p = image.pixel(px.x, px.y);
    return sandbox::looksLike(sandbox::kBoxColor, p.r, p.g, p.b);
  };
  EXPECT_TRUE(boxAt(at10));
  EXPECT_FALSE(boxAt(at40));
}

// Each body throws a soft shadow on the ground from the key light (Draw > shadows): the ground
// around the resting ragdoll is darker with them than with --no-shadows, and nothing else is.
TEST(SandboxModes, BodiesThrowShadowsOnTheGround) {
  const engine::Image shadows = runSandbox("ragdoll --hide-panels", "shadows-on.png", 120);
  const engine::Image plain = runSandbox("ragdoll --hide-panels --no-shadows", "shadows-off.png", 120);
  int darker = 0, lighter = 0;
  for (int y = 30; y < 690; ++y) {
    for (int x = 0; x < 1280; ++x) {
      const glm::u8vec4 a = shadows.pixel(x, y), b = plain.pixel(x, y);
      if (a.r + 10 < b.r && a.g + 10 < b.g && a.b + 10 < b.b) ++darker;
      if (a.r > b.r + 10 || a.g > b.g + 10 || a.b > b.b + 10) ++lighter;
    }
  }
  EXPECT_GT(darker, 500);
  EXPECT_EQ(lighter, 0);
}

}  // namespace
