#include "sandbox.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include <glad/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "body_colors.h"
#include "engine/error.h"
#include "engine/image.h"
#include "engine/physics_debug_draw.h"

namespace sandbox {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kMaxStepsPerFrame = 8;   // beyond this the sim slows down instead of spiralling
constexpr float kCameraSpeed = 4.0f;   // unit: m/s; Shift makes it 4 times faster
constexpr float kLookDegreesPerPixel = 0.15f;

// A missing or broken model must not stop the sandbox: fall back to a cube built in code.
engine::MeshData loadBoxModel(const std::filesystem::path& file) {
  try {
    return engine::loadMeshData(file);
  } catch (const engine::Error& e) {
    std::cerr << "warning: " << e.what() << "; drawing boxes with the built-in cube\n";
    return engine::unitCubeMesh();
  }
}

// Neighbouring boxes in one colour would merge into one block; each gets its own brightness,
// from 85% to 115% by the golden ratio, so the hue (what the tests look for) stays the same.
float boxShade(phys::BoxId id) {
  const float spread = std::fmod(static_cast<float>(id) * 0.618034f, 1.0f);
  return 0.85f + 0.3f * spread;
}

glm::mat4 boxModelMatrix(const phys::BoxPose& pose, const phys::Vec3& size) {
  const glm::mat4 rotation = glm::mat4_cast(glm::quat(pose.orientation));
  return glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(pose.center)) * rotation, glm::vec3(size));
}

}  // namespace

Sandbox::Sandbox(const Options& options)
    : options_(options),
      window_(engine::WindowDesc{1280, 720, "Jakobsen sandbox", true, !options.screenshot}) {
  const std::filesystem::path data = dataDir(options_);
  renderer_ = std::make_unique<engine::Renderer>(data / "shaders");
  boxMesh_ = std::make_unique<engine::GpuMesh>(loadBoxModel(data / "assets" / "models" / "box.obj"));
  loadScene();

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // layout is fixed until settings persistence lands
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_.handle(), true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

Sandbox::~Sandbox() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void Sandbox::loadScene() {
  // A scene that fails to load (at Reset, after the file was edited) leaves the current world
  // as it was; at start-up there is none, so the error ends the program.
  auto loaded = std::make_unique<scenes::Scene>(scenes::loadSceneFile(scenePath(options_)));
  scene_ = std::move(loaded);
  camera_ = engine::FirstPersonCamera::lookingAt(scene_->camera.eye, scene_->camera.target);
  accumulator_ = 0.0;
}

void Sandbox::stepOnceTimed() {
  const auto start = Clock::now();
  scene_->world.step();
  panel_.stepMs += std::chrono::duration<float, std::milli>(Clock::now() - start).count();
}

void Sandbox::advancePhysics(double frameSeconds) {
  panel_.stepMs = 0.0f;
  if (options_.screenshot) {  // deterministic: one step per frame, whatever the clock says
    if (!panel_.paused) stepOnceTimed();
    return;
  }
  if (panel_.stepOnce) {
    stepOnceTimed();
    panel_.stepOnce = false;
  }
  if (panel_.paused) {
    accumulator_ = 0.0;
    return;
  }
  const double dt = scene_->world.solverSettings().dt;
  accumulator_ += frameSeconds;
  int steps = 0;
  while (accumulator_ >= dt && steps < kMaxStepsPerFrame) {
    stepOnceTimed();
    accumulator_ -= dt;
    ++steps;
  }
  if (steps == kMaxStepsPerFrame) accumulator_ = 0.0;  // drop the backlog rather than spiral
}

void Sandbox::moveCamera(float frameSeconds) {
  GLFWwindow* w = window_.handle();
  const ImGuiIO& io = ImGui::GetIO();
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(w, &x, &y);
  const bool rightHeld = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  if (rightHeld && (looking_ || !io.WantCaptureMouse)) {
    if (looking_) {
      camera_.turn(static_cast<float>(x - lastCursorX_) * kLookDegreesPerPixel,
                   static_cast<float>(lastCursorY_ - y) * kLookDegreesPerPixel);
    }
    looking_ = true;
  } else {
    looking_ = false;
  }
  lastCursorX_ = x;
  lastCursorY_ = y;
  if (io.WantCaptureKeyboard) return;
  auto held = [w](int key) { return glfwGetKey(w, key) == GLFW_PRESS ? 1.0f : 0.0f; };
  const float speed = kCameraSpeed * (held(GLFW_KEY_LEFT_SHIFT) > 0.0f ? 4.0f : 1.0f) * frameSeconds;
  camera_.move((held(GLFW_KEY_D) - held(GLFW_KEY_A)) * speed, (held(GLFW_KEY_E) - held(GLFW_KEY_Q)) * speed,
               (held(GLFW_KEY_W) - held(GLFW_KEY_S)) * speed);
}

void Sandbox::renderFrame() {
  const glm::ivec2 size = window_.framebufferSize();
  if (size.x == 0 || size.y == 0) return;  // minimised
  const glm::mat4 viewProjection =
      camera_.projection(static_cast<float>(size.x) / static_cast<float>(size.y)) * camera_.view();
  const phys::World& world = scene_->world;

  renderer_->beginFrame(size);
  const phys::WorldSettings& settings = world.worldSettings();
  if (settings.ground) {
    renderer_->drawGround(viewProjection, camera_.position, glm::vec3(settings.groundNormal),
                          static_cast<float>(settings.groundHeight));
  }
  const auto boxes = world.boxes();
  std::vector<bool> inBox(world.particles().size(), false);
  for (phys::BoxId id = 0; id < boxes.size(); ++id) {
    renderer_->drawMesh(*boxMesh_, viewProjection, boxModelMatrix(world.boxPose(id), boxes[id].halfExtents * 2.0),
                        boxShade(id) * kBoxColor);
    for (int k = 0; k < boxes[id].particleCount; ++k) inBox[boxes[id].firstParticle + k] = true;
  }
  if (panel_.drawParticles) {
    const glm::mat4 scale = glm::scale(glm::mat4(1.0f), glm::vec3(kParticleDrawSize));
    for (std::size_t i = 0; i < world.particles().size(); ++i) {
      if (inBox[i]) continue;
      const glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(world.particles().position[i])) * scale;
      renderer_->drawMesh(*boxMesh_, viewProjection, model, kParticleColor);
    }
  }
  engine::PhysicsDebugDraw debugDraw(renderer_->lines());
  world.debugDraw(debugDraw, {panel_.drawSticks, false, panel_.drawContacts, panel_.drawContacts, panel_.drawBounds});
  glDisable(GL_DEPTH_TEST);  // debug lines show through bodies, as in the seed's constraint mode
  renderer_->endFrame(viewProjection);

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  drawPanel(*scene_, panel_);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

int Sandbox::run() {
  auto last = Clock::now();
  for (int frame = 1; !window_.shouldClose(); ++frame) {
    engine::Window::pollEvents();
    const auto now = Clock::now();
    const float frameSeconds = std::chrono::duration<float>(now - last).count();
    last = now;
    panel_.frameMs = frameSeconds * 1000.0f;

    if (panel_.resetRequested) {
      panel_.resetRequested = false;
      try {
        loadScene();
        panel_.loadError.clear();
      } catch (const std::exception& e) {  // LoadError, or anything else: keep what we have
        panel_.loadError = e.what();
        std::cerr << "sandbox: " << e.what() << " (keeping the current world)\n";
      }
    }
    advancePhysics(frameSeconds);
    if (!options_.screenshot) moveCamera(frameSeconds);
    renderFrame();

    if (options_.screenshot && frame >= options_.frames) {
      glReadBuffer(GL_BACK);
      engine::writePng(*options_.screenshot, engine::readFramebuffer(window_.framebufferSize()));
      std::cout << "wrote " << options_.screenshot->string() << " after " << frame << " frames\n";
      return 0;
    }
    window_.swapBuffers();
  }
  return 0;
}

int runSandbox(int argc, char** argv) {
  const ParsedOptions parsed = parseOptions(std::vector<std::string>(argv + 1, argv + argc));
  if (!parsed.error.empty()) {
    std::cerr << "sandbox: " << parsed.error << '\n' << usage();
    return 2;
  }
  if (parsed.options.help) {
    std::cout << usage();
    return 0;
  }
  const std::string noDisplay = engine::missingDisplayReason();
  if (!noDisplay.empty()) {
    std::cerr << "sandbox: " << noDisplay << '\n';
    return 1;
  }
  try {
    Sandbox app(parsed.options);
    return app.run();
  } catch (const std::exception& e) {
    std::cerr << "sandbox: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace sandbox
