// Every project scene's <camera> frames its subject at the sandbox's default size (1280 x 720,
// panels shown): for the scene's first 5 s, every body and particle is in front of the camera and
// inside the scene's viewport, left of the panels' column (sandbox::sceneView) and clear of the
// menu bar and the status line, and the subject's screen bounds over those 5 s (where it moves:
// a pendulum's swing, a projectile's flight, a pile's fall) cover at least 5% of the window.
#include <algorithm>
#include <filesystem>
#include <limits>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "body_colors.h"
#include "engine/camera.h"
#include "panels.h"
#include "scenes/scene.h"

namespace {

namespace fs = std::filesystem;

constexpr float kWidth = 1280.0f, kHeight = 720.0f;
constexpr double kWatched = 5.0;      // unit: s of simulated time
constexpr double kLeastShare = 0.05;  // of the window's area
constexpr float kMargin = 4.0f;       // unit: pixels from the viewport's sides
constexpr float kTop = 24.0f;         // unit: pixels; below the menu bar
constexpr float kBottom = 28.0f;      // unit: pixels; above the status line

struct Bounds {
  float x0 = std::numeric_limits<float>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  bool behind = false;  // a point behind the camera
  void add(const glm::vec3& p, float x, float y) {
    (void)p;
    x0 = std::min(x0, x);
    y0 = std::min(y0, y);
    x1 = std::max(x1, x);
    y1 = std::max(y1, y);
  }
  float area() const { return std::max(x1 - x0, 0.0f) * std::max(y1 - y0, 0.0f); }
};

// The subject's screen bounds, in window pixels from the top-left corner: every body's corners
// and every loose particle.
Bounds screenBounds(const phys::World& w, const engine::FirstPersonCamera& camera,
                    const sandbox::ScreenRect& view) {
  const glm::mat4 viewMatrix = camera.view();
  const glm::mat4 projection = camera.projection(view.width / view.height);
  const glm::vec4 viewport(view.x, kHeight - view.y - view.height, view.width, view.height);
  Bounds b;
  auto add = [&](const glm::vec3& p) {
    const glm::vec4 eye = viewMatrix * glm::vec4(p, 1.0f);
    if (eye.z > -camera.nearPlane) b.behind = true;
    const glm::vec3 s = glm::project(p, viewMatrix, projection, viewport);
    b.add(p, s.x, kHeight - s.y);
  };
  std::vector<bool> inBody(w.particles().size(), false);
  for (phys::BodyId id{}; id < w.bodies().size(); ++id) {
    for (int k = 0; k < 8; ++k) add(glm::vec3(w.cornerPosition(id, k)));
    for (int k = 0; k < w.bodies()[id].particleCount; ++k) inBody[w.bodies()[id].firstParticle + k] = true;
  }
  // A loose particle is drawn as a cube of kParticleDrawSize.
  const float half = sandbox::kParticleDrawSize * 0.5f;
  for (std::size_t i = 0; i < w.particles().size(); ++i) {
    if (inBody[i]) continue;
    for (int k = 0; k < 8; ++k) {
      const glm::vec3 corner((k & 1) ? half : -half, (k & 2) ? half : -half, (k & 4) ? half : -half);
      add(glm::vec3(w.particles().position[i]) + corner);
    }
  }
  return b;
}

TEST(SceneCameras, EveryProjectSceneFramesItsSubject) {
  const sandbox::ScreenRect view = sandbox::sceneView(kWidth, kHeight, true);
  const fs::path dir = scenes::sceneDirectory(DATA_DIR);
  int scenesSeen = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".xml") continue;
    ++scenesSeen;
    scenes::Scene scene = scenes::loadSceneFile(entry.path());
    const auto camera = engine::FirstPersonCamera::lookingAt(scene.camera.eye, scene.camera.target);
    const std::string name = entry.path().stem().string();
    Bounds start = screenBounds(scene.world, camera, view), last = start;
    Bounds all = start;
    while (scene.world.time() < kWatched) {
      scene.world.step();
      last = screenBounds(scene.world, camera, view);
      all.behind |= last.behind;
      all.add({}, last.x0, last.y0);
      all.add({}, last.x1, last.y1);
    }
    const double window = static_cast<double>(kWidth) * kHeight;
    std::printf("%-16s start %5.1f%%  end %5.1f%%  all %5.1f%%  x %6.0f..%6.0f  y %6.0f..%6.0f\n",
                name.c_str(), 100.0 * start.area() / window, 100.0 * last.area() / window,
                100.0 * all.area() / window, all.x0, all.x1, all.y0, all.y1);
    EXPECT_FALSE(all.behind) << name;
    EXPECT_GE(all.x0, view.x + kMargin) << name;
    EXPECT_LE(all.x1, view.x + view.width - kMargin) << name;
    EXPECT_GE(all.y0, view.y + kTop) << name;
    EXPECT_LE(all.y1, view.y + view.height - kBottom) << name;
    EXPECT_GE(all.area(), kLeastShare * window) << name;
  }
  EXPECT_GE(scenesSeen, 19);
}

}  // namespace
