// The sandbox program renders the default scene (the seed's ragdoll) to a PNG under Xvfb, and the
// pixels are where the scene, the camera and the style say they should be: sky in the corner,
// lit ground, the largest box where the physics puts it, and the ImGui panels in their column;
// loose particles, in the falling-box scene, which has some; and a rigid box, in rigid.xml.
#include <filesystem>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <imgui.h>

#include "body_colors.h"
#include "engine/camera.h"
#include "engine/image.h"
#include "engine/renderer.h"
#include "panels.h"
#include "sandbox_run.h"
#include "scenes/scene.h"

namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 90;  // 1.5 s: the bodies have landed and are tumbling

struct Rendered {
  engine::Image image;
  scenes::Scene scene;  // stepped as far as the sandbox stepped it
  engine::FirstPersonCamera camera;
};

// Runs the real program on a scene ("" for the default) and steps the same scene as far.
Rendered render(const std::string& sceneName) {
  const std::string png = (sceneName.empty() ? std::string("default-scene") : sceneName) + ".png";
  engine::Image image = testing_gl::runSandbox(sceneName + " --color-by kind", png, kFrames);
  scenes::Scene scene = scenes::loadSceneFile(
      scenes::resolveScene(sceneName.empty() ? scenes::kDefaultScene : std::string_view(sceneName),
                           scenes::sceneDirectory(DATA_DIR)));
  for (int i = 0; i < kFrames; ++i) scene.world.step();  // one step per screenshot frame
  const auto camera = engine::FirstPersonCamera::lookingAt(scene.camera.eye, scene.camera.target);
  return Rendered{std::move(image), std::move(scene), camera};
}

// Each scene is rendered once for the whole suite.
const Rendered& rendered() {
  static const Rendered result = render("");
  return result;
}
const Rendered& renderedFallingBox() {
  static const Rendered result = render("falling-box");
  return result;
}

// The box with the largest volume: the one most surely visible.
phys::BodyId largestBox(const phys::World& w) {
  phys::BodyId best{};
  for (phys::BodyId i{1}; i < w.bodies().size(); ++i) {
    const phys::Vec3 a = w.bodies()[i].halfExtents, b = w.bodies()[best].halfExtents;
    if (a.x * a.y * a.z > b.x * b.y * b.z) best = i;
  }
  return best;
}

glm::ivec2 toPixel(const Rendered& r, const glm::vec3& world) {
  return testing_gl::toSandboxPixel(r.image, r.camera, world);
}

glm::ivec3 to8bit(const glm::vec3& c) {
  return glm::ivec3(glm::round(c * 255.0f));
}

void expectColor(const glm::u8vec4& got, const glm::ivec3& want, int tolerance, const char* what) {
  EXPECT_NEAR(got.r, want.r, tolerance) << what;
  EXPECT_NEAR(got.g, want.g, tolerance) << what;
  EXPECT_NEAR(got.b, want.b, tolerance) << what;
}

TEST(RenderScene, WritesAWindowSizedPng) {
  EXPECT_EQ(rendered().image.width, 1280);
  EXPECT_EQ(rendered().image.height, 720);
}

TEST(RenderScene, SkyAboveTheSceneIsTheClearColour) {
  const Rendered& r = rendered();
  // Below the menu bar at the left: the camera looks down at the ragdoll, so the horizon is well
  // below this.
  expectColor(r.image.pixel(20, 40), to8bit(engine::RenderStyle{}.clearColor), 1, "sky");
}

TEST(RenderScene, GroundIsLitFromAbove) {
  const Rendered& r = rendered();
  const engine::RenderStyle style;
  const glm::ivec3 want = to8bit(engine::shade(style.groundColor, {0, 1, 0}, style.light));
  // Centres of grid cells, away from the lines, the box and the panel.
  for (const glm::vec3 p : {glm::vec3(1.5f, 0, 1.5f), glm::vec3(2.5f, 0, -1.5f), glm::vec3(3.5f, 0, -3.5f)}) {
    const glm::ivec2 px = toPixel(r, p);
    ASSERT_TRUE(px.x >= 0 && px.x < r.image.width && px.y >= 0 && px.y < r.image.height);
    expectColor(r.image.pixel(px.x, px.y), want, 3, "ground");
  }
}

TEST(RenderScene, DefaultSceneIsTheSeedsRagdoll) {
  EXPECT_EQ(scenes::kDefaultScene, "ragdoll");
  EXPECT_EQ(rendered().scene.world.bodies().size(), 10u);
}

// The 9 x 9 pixels about where the physics puts `box` are all box-coloured, and the pixel where it
// started is not: the screenshot shows the simulated state, not the initial one.
void expectDrawnWhereThePhysicsPutsIt(const Rendered& r, phys::BodyId box) {
  const phys::BodyPose pose = r.scene.world.bodyPose(box);
  const glm::ivec2 centre = toPixel(r, glm::vec3(pose.center));
  int boxLike = 0;
  for (int dy = -4; dy <= 4; ++dy) {
    for (int dx = -4; dx <= 4; ++dx) {
      const glm::u8vec4 p = r.image.pixel(centre.x + dx, centre.y + dy);
      boxLike += sandbox::looksLike(sandbox::kBoxColor, p.r, p.g, p.b) ? 1 : 0;
    }
  }
  EXPECT_EQ(boxLike, 81) << "box centre projects to " << centre.x << ", " << centre.y;
  const scenes::Scene initial = scenes::loadSceneFile(r.scene.file);
  const glm::ivec2 start = toPixel(r, glm::vec3(initial.world.bodyPose(box).center));
  const glm::u8vec4 p = r.image.pixel(start.x, start.y);
  EXPECT_FALSE(sandbox::looksLike(sandbox::kBoxColor, p.r, p.g, p.b));
}

TEST(RenderScene, BoxIsDrawnWhereThePhysicsPutsIt) {
  const Rendered& r = rendered();
  expectDrawnWhereThePhysicsPutsIt(r, largestBox(r.scene.world));
}

// A rigid body is drawn from its own pose, not from particles: `rigid.xml`'s crate, dropped onto
// two rigid logs, where the physics has it after 1.5 s.
TEST(RenderScene, ARigidBoxIsDrawnWhereThePhysicsPutsIt) {
  const Rendered r = render("rigid");
  const phys::World& w = r.scene.world;
  phys::BodyId crate = phys::kNoBody;
  for (phys::BodyId i{}; i < w.bodies().size(); ++i) {
    if (w.bodies()[i].name == "crate") crate = i;
  }
  ASSERT_NE(crate, phys::kNoBody);
  ASSERT_EQ(w.bodies()[crate].model, phys::BodyModel::Rigid);
  expectDrawnWhereThePhysicsPutsIt(r, crate);
}

TEST(RenderScene, LooseParticlesAreDrawn) {
  const Rendered& r = renderedFallingBox();
  const auto& world = r.scene.world;
  const phys::ParticleId firstLoose =
      world.bodies().back().firstParticle + world.bodies().back().particleCount;
  ASSERT_LT(firstLoose, world.particles().size());
  for (phys::ParticleId i = firstLoose; i < world.particles().size(); ++i) {
    const glm::ivec2 px = toPixel(r, glm::vec3(world.particles().position[i]) +
                                         glm::vec3(0.0f, sandbox::kParticleDrawSize * 0.25f, 0.0f));
    const glm::u8vec4 p = r.image.pixel(px.x, px.y);
    EXPECT_TRUE(sandbox::looksLike(sandbox::kParticleColor, p.r, p.g, p.b))
        << "particle " << i << " at pixel " << px.x << ", " << px.y << " is " << int(p.r) << " " << int(p.g)
        << " " << int(p.b);
  }
}

TEST(RenderScene, ThePanelsFillTheirColumnAndTheSceneIsBesideIt) {
  const Rendered& r = rendered();
  ImGui::CreateContext();
  ImGui::StyleColorsDark();
  const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  ImGui::DestroyContext();
  // The column is drawn at alpha 0.94 over the clear colour: the scene is never drawn under it.
  const glm::vec3 clear = engine::RenderStyle{}.clearColor;
  const glm::ivec3 want = to8bit(glm::vec3(bg.x, bg.y, bg.z) * 0.94f + clear * 0.06f);

  auto countIn = [&](int x0, int y0, int w, int h, int& background, int& bright) {
    background = bright = 0;
    for (int y = y0; y < y0 + h; ++y) {
      for (int x = x0; x < x0 + w; ++x) {
        const glm::u8vec4 p = r.image.pixel(x, y);
        if (std::abs(p.r - want.r) <= 2 && std::abs(p.g - want.g) <= 2 && std::abs(p.b - want.b) <= 2)
          ++background;
        if (p.r > 200 && p.g > 200 && p.b > 200) ++bright;
      }
    }
  };
  // Inside the column, clear of the menu bar above and the status line below.
  const sandbox::ScreenRect column = sandbox::panelColumn(1280.0f, 720.0f, 30.0f, 30.0f);
  EXPECT_NEAR(column.width, 345.6f, 1e-3f);  // 27% of the width
  const int x0 = static_cast<int>(column.x), y0 = static_cast<int>(column.y);
  const int w = static_cast<int>(column.width), h = static_cast<int>(column.height);
  int background = 0, bright = 0;
  countIn(x0, y0, w, h, background, bright);
  // Sliders and buttons take their share; the window's own background is still the most of it.
  EXPECT_GT(background, w * h / 3) << "the column's background should fill it";
  EXPECT_GT(bright, 200) << "the column should show text";
  // Just left of the column the scene shows, not the panels.
  countIn(x0 - 55, y0, 50, h, background, bright);
  EXPECT_LT(background, 50);
  EXPECT_EQ(sandbox::sceneView(1280.0f, 720.0f, true).width, column.x);
  EXPECT_EQ(sandbox::sceneView(1280.0f, 720.0f, false).width, 1280.0f);
}

}  // namespace
