#include "sandbox.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <utility>

#include <glad/gl.h>
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "body_colors.h"
#include "controls.h"
#include "engine/error.h"
#include "engine/image.h"
#include "fileio/files.h"
#include "recording_file.h"
#include "scene_bounds.h"
#include "screenshot.h"
#include "stats_text.h"

namespace sandbox {
namespace {

using Clock = std::chrono::steady_clock;

// Wall time the background steps may take before the window shows their world: a step begun is
// finished, so a frame shows the world at least this often unless a single step takes longer.
constexpr std::chrono::milliseconds kStepBudget{30};
constexpr float kCameraSpeed = 4.0f;  // unit: m/s; Shift makes it 4 times faster
constexpr float kLookDegreesPerPixel = 0.15f;
constexpr float kSpawnDistance = 2.0f;  // unit: m; in front of the eye, at the crosshair
constexpr float kZoomPerNotch = 0.85f;  // of the distance to the focus, per wheel notch in
constexpr float kOrbitDegreesPerPixel = 0.3f;

Sandbox* owner(GLFWwindow* w) {
  return static_cast<Sandbox*>(glfwGetWindowUserPointer(w));
}
void keyCallback(GLFWwindow* w, int key, int, int action, int mods) {
  owner(w)->onKey(key, action, mods);
}
void mouseButtonCallback(GLFWwindow* w, int button, int action, int) {
  owner(w)->onMouseButton(button, action);
}
void focusCallback(GLFWwindow* w, int focused) {
  owner(w)->onFocus(focused == GLFW_TRUE);
}
void scrollCallback(GLFWwindow* w, double, double y) {
  owner(w)->onScroll(y);
}
// In front of ImGui's key callback (which calls keyCallback in turn): a key tapped between two
// frames reaches ImGui as held for one (KeyTaps).
void imguiKeyCallback(GLFWwindow* w, int key, int scancode, int action, int mods) {
  KeyTaps& taps = owner(w)->keyTaps();
  if (action == GLFW_PRESS) taps.pressed(key);
  if (action == GLFW_RELEASE && taps.holdRelease({key, scancode, mods})) return;
  ImGui_ImplGlfw_KeyCallback(w, key, scancode, action, mods);
}

engine::WindowDesc windowDesc(const Options& options, const UserSettings& user) {
  engine::WindowDesc d;
  d.width = user.windowWidth;
  d.height = user.windowHeight;
  d.visible = !options.screenshot;
  d.vsync = true;
  return d;
}

// Clears `file` when it is there but unreadable, so that the exit does not write over it.
UserSettings loadRemembered(bool interactive, std::filesystem::path& file) {
  if (!interactive || file.empty()) return {};
  LoadedSettings loaded = loadUserSettings(file);
  for (const std::string& w : loaded.warnings) std::cerr << "sandbox: warning: " << w << '\n';
  if (loaded.keepFile) file.clear();
  return loaded.settings;
}

std::filesystem::path settingsPath(bool interactive) {
  const std::filesystem::path dir = interactive ? configDirectory() : std::filesystem::path();
  return dir.empty() ? dir : dir / "sandbox.ini";
}

}  // namespace

// No scene named (or none opened before the window): the last one used, if it still loads, else the
// default.
std::unique_ptr<Session> Sandbox::openUnnamed(const std::filesystem::path& data) const {
  std::filesystem::path file = scenePath(options_);
  if (options_.scene.empty() && !user_.lastScene.empty()) {
    std::error_code ec;  // a path too long or a folder not to be entered: said, and the default opens
    if (std::filesystem::exists(user_.lastScene, ec))
      file = user_.lastScene;
    else if (ec)
      std::cerr << "sandbox: " << settingsFile_.string() << ": lastScene '" << user_.lastScene
                << "': " << ec.message() << "; opening the default scene instead\n";
  }
  try {
    return std::make_unique<Session>(file, scenes::sceneDirectory(data), options_.threads);
  } catch (const std::exception& e) {
    if (file == scenePath(options_)) throw;
    std::cerr << "sandbox: " << e.what() << "; opening the default scene instead\n";
    return std::make_unique<Session>(scenePath(options_), scenes::sceneDirectory(data), options_.threads);
  }
}

Sandbox::Sandbox(const Options& options, std::unique_ptr<scenes::Scene> named)
    : options_(options),
      interactive_(!options.screenshot),
      settingsFile_(settingsPath(interactive_)),
      user_(loadRemembered(interactive_, settingsFile_)),
      window_(windowDesc(options, user_)) {
  const std::filesystem::path data = dataDir(options_);
  renderer_ = std::make_unique<engine::Renderer>(data / "shaders");
  view_ = std::make_unique<SceneView>(*renderer_, data / "assets" / "models");

  session_ = named ? std::make_unique<Session>(std::move(named), scenePath(options_),
                                               scenes::sceneDirectory(data), options_.threads)
                   : openUnnamed(data);
  camera_ =
      engine::FirstPersonCamera::lookingAt(session_->scene().camera.eye, session_->scene().camera.target);
  applyRemembered(user_, options_, ui_);
  session_->setRecordingBudget(static_cast<std::size_t>(ui_.recordingBudgetMb) << 20);
  fitToScene();
  // In the status line too: started from a desktop, nobody reads stderr.
  if (!view_->modelWarnings().empty()) ui_.message = "warning: " + view_->modelWarnings();
  if (options_.sweep) ui_.lab.start(session_->file());  // its section unfolded by applyRemembered
  if (!options_.overlay.empty()) {
    const std::string error = session_->startOverlay(options_.overlay);
    if (!error.empty()) throw std::invalid_argument("--overlay: " + error);
  }

  // Our callbacks first: ImGui's backend chains to the ones installed before it.
  glfwSetWindowUserPointer(window_.handle(), this);
  glfwSetKeyCallback(window_.handle(), keyCallback);
  glfwSetMouseButtonCallback(window_.handle(), mouseButtonCallback);
  glfwSetWindowFocusCallback(window_.handle(), focusCallback);
  glfwSetScrollCallback(window_.handle(), scrollCallback);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  // The panels sit in a column the sandbox places every frame, so there is no window layout to
  // remember (what is shown is in sandbox.ini): ImGui writes no imgui.ini.
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_.handle(), true);
  glfwSetKeyCallback(window_.handle(), imguiKeyCallback);  // Shutdown puts keyCallback back
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

Sandbox::~Sandbox() {
  // A save still running is waited for, and how it ended said where it can still be read: a
  // failure (a full disk) would otherwise go unseen, the old file kept.
  if (session_->savingProgress()) std::cerr << "sandbox: waiting for the recording's save to finish\n";
  if (const std::string saved = session_->finishSavingOnClose(); !saved.empty())
    std::cerr << "sandbox: " << saved << '\n';
  saveUserSettingsOnExit();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void Sandbox::saveUserSettingsOnExit() {
  if (settingsFile_.empty()) return;
  glfwGetWindowSize(window_.handle(), &user_.windowWidth, &user_.windowHeight);
  // A window shrunk to nothing would be refused (with a warning) on the next start.
  user_.windowWidth = std::clamp(user_.windowWidth, 640, 16384);
  user_.windowHeight = std::clamp(user_.windowHeight, 360, 16384);
  remember(ui_, user_);
  // A relative name whose working folder has gone keeps the last scene remembered before it.
  std::error_code ec;
  if (const std::filesystem::path file = std::filesystem::absolute(session_->file(), ec); !ec)
    user_.lastScene = file.string();
  try {
    saveUserSettings(user_, settingsFile_);
  } catch (const std::exception& e) {
    std::cerr << "sandbox: " << e.what() << '\n';
  }
}

void Sandbox::onKey(int key, int action, int mods) {
  if (action == GLFW_PRESS) {
    input_.keyDown(key);
    keyPresses_.emplace_back(key, mods);
  } else if (action == GLFW_RELEASE) {
    input_.keyUp(key);
  }
}

void Sandbox::onMouseButton(int button, int action) {
  if (action == GLFW_PRESS)
    input_.buttonDown(button);
  else if (action == GLFW_RELEASE)
    input_.buttonUp(button);
}

void Sandbox::onScroll(double amount) {
  scroll_ += amount;
}

void Sandbox::onFocus(bool focused) {
  if (focused) return;
  orbiting_ = false;
  // The key-up events go to whichever window has focus now: forget every held key and button,
  // so the camera cannot keep flying (the seed's stuck-key bug) nor a drag stay attached.
  input_.focusLost();
  looking_ = false;
  session_->release();
}

void Sandbox::openScene(const std::filesystem::path& file) {
  const std::string error = session_->open(file);
  if (!error.empty()) {
    errorText_ = error + "\n\nThe current world is kept.";
    showError_ = true;
    ui_.message = "could not open " + file.string();
    return;
  }
  std::error_code ec;  // a working folder that has gone: the name as it was given
  const std::filesystem::path absolute = std::filesystem::absolute(file, ec);
  addRecentFile(user_, (ec ? file : absolute).string());
  stopFollowing();
  trails_.clear();
  fitToScene();
  // A scene that sets its camera gets it; one that does not keeps the view the user had.
  if (session_->scene().camera.given) {
    camera_ =
        engine::FirstPersonCamera::lookingAt(session_->scene().camera.eye, session_->scene().camera.target);
  }
  ui_.message = session_->status();
  ui_.stepMs.clear();
  ui_.maxError.clear();
  ui_.rmsError.clear();
}

void Sandbox::perform(Action action) {
  Session& s = *session_;
  switch (action) {
    case Action::Scene1:
      openScene(scenes::resolveScene("ragdoll", scenes::sceneDirectory(dataDir(options_))));
      break;
    case Action::Scene2:
      openScene(scenes::resolveScene("pyramid", scenes::sceneDirectory(dataDir(options_))));
      break;
    case Action::Scene3:
      openScene(scenes::resolveScene("box-of-boxes", scenes::sceneDirectory(dataDir(options_))));
      break;
    case Action::SceneTackle:
      openScene(scenes::resolveScene("tackle", scenes::sceneDirectory(dataDir(options_))));
      break;
    case Action::ClearScene:
      s.clear();
      stopFollowing();
      trails_.clear();  // the bodies' paths went with them (the ghost hides itself: ExactGhost::holds)
      ui_.message = s.status();
      break;
    case Action::CycleDrawMode:
      ui_.draw.mode = nextDrawMode(ui_.draw.mode);
      break;
    case Action::ToggleMarkers:
      ui_.draw.markers = !ui_.draw.markers;
      break;
    case Action::ToggleGravityMode:
      s.toggleGravityMode();
      ui_.message = s.status();
      break;
    case Action::GravityUp:
      s.changeGravity(kGravityStep);
      ui_.message = s.status();
      break;
    case Action::GravityDown:
      s.changeGravity(-kGravityStep);
      ui_.message = s.status();
      break;
    case Action::DampingUp:
      s.changeDamping(kDampingStep);
      ui_.message = s.status();
      break;
    case Action::DampingDown:
      s.changeDamping(-kDampingStep);
      ui_.message = s.status();
      break;
    case Action::Pause:
      togglePause(ui_);
      break;
    case Action::StepOnce:
      stepOnce(s, ui_);
      break;
    case Action::Reload:
      openScene(s.file());
      break;
    case Action::SpawnBox:
    case Action::SpawnRagdoll:
    case Action::SpawnCapsuleRagdoll: {
      const phys::Vec3 forward(camera_.forward());
      const phys::Vec3 at = phys::Vec3(camera_.position) + forward * static_cast<double>(kSpawnDistance);
      if (action == Action::SpawnBox)
        s.spawnBox(at, forward * static_cast<double>(ui_.throwSpeed));
      else
        s.spawnRagdoll(at, forward * static_cast<double>(ui_.throwSpeed),
                       action == Action::SpawnCapsuleRagdoll);
      ui_.message = s.status();
      break;
    }
    case Action::ToggleHelp:
      ui_.showHelp = !ui_.showHelp;
      break;
    case Action::TogglePanels:
      ui_.panelsHidden = !ui_.panelsHidden;
      break;
    case Action::FrameScene:
      frameScene();
      break;
    case Action::StepBack: {
      ui_.paused = true;
      ui_.replaying = false;
      const long now = s.scene().world.stepCount();
      const std::string error =
          now > s.recording().first() ? s.rewindTo(now - 1) : "nothing recorded before this step";
      ui_.message = error.empty() ? s.status() : error;
      break;
    }
    case Action::Screenshot:
      screenshotDue_ = true;  // taken once the frame is drawn
      break;
  }
}

// --pause-at N: true (and paused) once the main run has taken N steps. Checked before every
// step, so a frame that runs several steps cannot carry the world past N.
bool Sandbox::pauseDue() {
  const long steps = session_->scene().world.stepCount();
  if (!options_.pauseAt || steps < *options_.pauseAt) return false;
  ui_.paused = true;
  ui_.message = "paused at step " + std::to_string(steps) + " (--pause-at)";
  options_.pauseAt.reset();
  return true;
}

void Sandbox::advancePhysics(double frameSeconds) {
  const double before = session_->scene().world.time();
  if (ui_.replaying) {
    playRecording(frameSeconds);
  } else if (!interactive_) {  // deterministic: one step per frame, whatever the clock says
    if (!ui_.paused && !pauseDue()) session_->step();
  } else {
    stepInBackground(frameSeconds);
  }
  if (!ui_.paused) ui_.stepOnce = false;  // a step asked for while running is one of the clock's anyway
  const phys::World& world = session_->scene().world;
  ui_.realTime.add(world.time() - before, frameSeconds, interactive_ && !ui_.paused);
  const phys::Metrics m = world.metrics();
  ui_.stepMs.add(static_cast<float>(world.profile().total), frameSeconds);
  ui_.maxError.add(static_cast<float>(m.maxConstraintError), frameSeconds);
  ui_.rmsError.add(static_cast<float>(m.rmsConstraintError), frameSeconds);
}

void Sandbox::playRecording(double frameSeconds) {
  const Recording& r = session_->recording();
  const phys::World& world = session_->scene().world;
  const long now = world.stepCount();
  if (!r.covers(now) || now >= r.last()) {
    ui_.replaying = false;
    accumulator_ = 0.0;
    return;
  }
  const double dt = world.solverSettings().dt;
  accumulator_ =
      std::min(accumulator_ + (interactive_ ? frameSeconds * ui_.timeScale : dt), kMaxStepsPerFrame * dt);
  const long steps = static_cast<long>(std::floor(accumulator_ / dt));
  if (steps < 1) return;
  accumulator_ -= static_cast<double>(steps) * dt;
  if (const std::string error = session_->rewindTo(std::min(now + steps, r.last())); !error.empty()) {
    ui_.message = error;
    ui_.replaying = false;
  }
}

// The time budget: the steps a frame owes run on another thread, at most kStepBudget of them
// at a time, while this one draws and reads input; the world shown is the last one they finished.
// So no setting can hold a frame: a step of 1.6 s makes the world slower than real time (the
// Stats panel says so), not the window. A command cancels the steps in flight (Session).
void Sandbox::stepInBackground(double frameSeconds) {
  const double dt = session_->scene().world.solverSettings().dt;
  if (const std::optional<StepsTaken> taken = session_->finishSteps()) {
    accumulator_ -= taken->steps * dt;
    if (taken->cut) accumulator_ = 0.0;  // drop the backlog rather than spiral
  }
  if (ui_.paused || pauseDue()) {
    // A step asked for with N finishes; steps the clock owed stop where they are.
    if (session_->stepping() && !stepWhilePaused_) session_->cancelSteps();
    // N's step: now, or once the one in flight is done (the press is kept till then).
    if (ui_.stepOnce && !session_->stepping()) {
      session_->startSteps(1, kStepBudget);
      stepWhilePaused_ = true;
      ui_.stepOnce = false;
    }
    accumulator_ = 0.0;
    return;
  }
  stepWhilePaused_ = false;
  accumulator_ = std::min(accumulator_ + frameSeconds * ui_.timeScale, kMaxStepsPerFrame * dt);
  if (session_->stepping()) return;
  int owed = static_cast<int>(std::floor(accumulator_ / dt));
  // --pause-at N: the steps in flight never carry the world past N.
  if (options_.pauseAt)
    owed = static_cast<int>(std::min<long>(owed, *options_.pauseAt - session_->scene().world.stepCount()));
  session_->startSteps(owed, kStepBudget);
}

ScreenRect Sandbox::sceneRect() const {
  int w = 1, h = 1;
  glfwGetWindowSize(window_.handle(), &w, &h);
  return sceneView(static_cast<float>(w), static_cast<float>(h), !ui_.panelsHidden);
}

void Sandbox::takeScreenshot() {
  screenshotDue_ = false;
  const std::filesystem::path file = screenshotPath(session_->file(), session_->scene().world.stepCount());
  try {
    glReadBuffer(GL_BACK);
    fileio::writeAtomically(file, engine::encodePng(engine::readFramebuffer(window_.framebufferSize())));
    ui_.message = "screenshot: wrote " + file.string();
  } catch (const std::exception& e) {
    ui_.message = std::string("screenshot not written: ") + e.what();
  }
}

std::pair<phys::Vec3, phys::Vec3> Sandbox::cursorRay() const {
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window_.handle(), &x, &y);
  int w = 1, h = 1;
  glfwGetWindowSize(window_.handle(), &w, &h);
  const ScreenRect view = sceneRect();
  // The scene's viewport in window pixels, from the bottom-left as unProject counts them.
  const glm::vec4 viewport(view.x, static_cast<float>(h) - view.y - view.height, view.width, view.height);
  const float aspect = view.width / std::max(view.height, 1.0f);
  const glm::vec3 win(static_cast<float>(x), static_cast<float>(h) - static_cast<float>(y), 0.0f);
  const glm::vec3 nearPoint = glm::unProject(win, camera_.view(), camera_.projection(aspect), viewport);
  const glm::vec3 farPoint =
      glm::unProject(glm::vec3(win.x, win.y, 1.0f), camera_.view(), camera_.projection(aspect), viewport);
  return {phys::Vec3(camera_.position), glm::normalize(phys::Vec3(farPoint - nearPoint))};
}

void Sandbox::moveCamera(float frameSeconds) {
  const ImGuiIO& io = ImGui::GetIO();
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window_.handle(), &x, &y);
  // Look only while the right button is held, and only if the press began outside the panels,
  // so ImGui stays usable with the mouse.
  const bool alt = input_.held(GLFW_KEY_LEFT_ALT) || input_.held(GLFW_KEY_RIGHT_ALT);  // Alt orbits
  if (input_.buttonPressed(GLFW_MOUSE_BUTTON_RIGHT) && !io.WantCaptureMouse && !alt) looking_ = true;
  if (!input_.buttonHeld(GLFW_MOUSE_BUTTON_RIGHT)) looking_ = false;
  if (looking_) {
    camera_.turn(static_cast<float>(x - lastCursorX_) * kLookDegreesPerPixel,
                 static_cast<float>(lastCursorY_ - y) * kLookDegreesPerPixel);
  }
  lastCursorX_ = x;
  lastCursorY_ = y;
  if (io.WantCaptureKeyboard) return;
  auto held = [this](int key) { return input_.held(key) ? 1.0f : 0.0f; };
  const bool fast = input_.held(GLFW_KEY_LEFT_SHIFT) || input_.held(GLFW_KEY_RIGHT_SHIFT);
  const float step = kCameraSpeed * (fast ? 4.0f : 1.0f) * frameSeconds;
  camera_.move((held(GLFW_KEY_D) - held(GLFW_KEY_A)) * step, (held(GLFW_KEY_E) - held(GLFW_KEY_Q)) * step,
               (held(GLFW_KEY_W) - held(GLFW_KEY_S)) * step);
}

glm::vec3 Sandbox::focusPoint(const glm::vec3& origin, const glm::vec3& direction) const {
  const phys::World& world = session_->scene().world;
  if (followed_) return glm::vec3(world.bodyPose(*followed_).center);
  // A ray from inside a body hits at its origin, the eye: no point to orbit or zoom about.
  if (const auto hit = world.raycast(phys::Vec3(origin), phys::Vec3(direction), 1000.0);
      hit && hit->distance >= camera_.nearPlane)
    return glm::vec3(hit->point);
  if (const auto bounds = sceneBounds(world)) {
    const glm::vec3 middle = 0.5f * (bounds->first + bounds->second);
    return origin + direction * std::max(glm::dot(middle - origin, direction), 1.0f);
  }
  return origin + direction * 5.0f;
}

void Sandbox::frameScene() {
  const auto bounds = sceneBounds(session_->scene().world);
  if (!bounds) {
    ui_.message = "nothing to frame: the scene is empty";
    return;
  }
  const ScreenRect view = sceneRect();
  const bool framed = camera_.frame(bounds->first, bounds->second, view.width / std::max(view.height, 1.0f));
  if (following()) followedAt_ = glm::vec3(session_->scene().world.bodyPose(*followed_).center);
  ui_.message = framed ? "framed the scene"
                       : "the scene is larger than the view reaches (" + figure("%.0f", camera_.farPlane) +
                             " m): looking at its middle";
}

void Sandbox::fitToScene() {
  ghost_.reset(session_->scene());
  const scenes::CameraStart& c = session_->scene().camera;
  ui_.draw.particleRadius = particleRadiusFor(glm::length(c.eye - c.target));
}

// An analytic scene's <expect kind="position" pos="x y z" at="t"> give where a body must be at
// time t: each is a green cross, so the simulated body is seen passing by (or missing) it. The
// one whose time is nearest the world's is drawn larger. The ghost (exact_ghost.h) is the answer
// at the world's time, a translucent green copy of the scene as its file starts it, under the run.
void Sandbox::drawExactAnswers(const glm::mat4& viewProjection) {
  const phys::World& world = session_->scene().world;
  // Nothing once the scene's bodies are gone or its settings changed (the panel says which).
  const ExactGhost::Drawn drawn = ghost_.beside(world);
  if (drawn.ghost != nullptr) {
    DrawOptions options = ui_.draw;
    options.contacts = options.markers = options.bounds = options.shadows = false;
    view_->draw(*drawn.ghost, viewProjection, options, Tint{kExactColor, kGhostAlpha});
  }
  const std::span<const std::pair<double, glm::vec3>> answers = drawn.answers;  // time, place
  const double now = world.time();
  const auto nearest = std::min_element(answers.begin(), answers.end(), [&](const auto& a, const auto& b) {
    return std::abs(a.first - now) < std::abs(b.first - now);
  });
  for (auto it = answers.begin(); it != answers.end(); ++it) {
    renderer_->lines().addPoint(it->second, ui_.draw.particleRadius * (it == nearest ? 5.0f : 3.0f),
                                kExactColor);
  }
}

void Sandbox::stopFollowing() {
  followed_.reset();
}

bool Sandbox::following() {
  // A rewind, a step back or a recording opened can take the followed body away between frames.
  if (followed_ && *followed_ >= session_->scene().world.bodies().size()) followed_.reset();
  return followed_.has_value();
}

void Sandbox::zoomOrbitFollow() {
  const ImGuiIO& io = ImGui::GetIO();
  const phys::World& world = session_->scene().world;
  if (following()) {
    const glm::vec3 at(world.bodyPose(*followed_).center);
    camera_.position += at - followedAt_;
    followedAt_ = at;
  }
  if (scroll_ != 0.0 && !io.WantCaptureMouse) {
    const auto [origin, direction] = cursorRay();
    camera_.dolly(focusPoint(glm::vec3(origin), glm::vec3(direction)),
                  std::pow(kZoomPerNotch, static_cast<float>(scroll_)));
  }
  scroll_ = 0.0;

  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window_.handle(), &x, &y);
  const bool alt = input_.held(GLFW_KEY_LEFT_ALT) || input_.held(GLFW_KEY_RIGHT_ALT);
  const bool orbitPressed = input_.buttonPressed(GLFW_MOUSE_BUTTON_MIDDLE) ||
                            (alt && input_.buttonPressed(GLFW_MOUSE_BUTTON_RIGHT));
  if (orbitPressed && !io.WantCaptureMouse) {
    orbiting_ = true;
    orbitPivot_ = focusPoint(camera_.position, camera_.forward());
  }
  if (!input_.buttonHeld(GLFW_MOUSE_BUTTON_MIDDLE) && !input_.buttonHeld(GLFW_MOUSE_BUTTON_RIGHT))
    orbiting_ = false;
  if (orbiting_) {
    if (followed_) orbitPivot_ = followedAt_;
    camera_.orbit(orbitPivot_, static_cast<float>(x - orbitCursorX_) * kOrbitDegreesPerPixel,
                  static_cast<float>(orbitCursorY_ - y) * kOrbitDegreesPerPixel);
  }
  orbitCursorX_ = x;
  orbitCursorY_ = y;

  // Double-click: follow the body under the cursor, or stop on nothing.
  if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && !io.WantCaptureMouse) {
    const auto [origin, direction] = cursorRay();
    const auto hit = world.raycast(origin, direction, 1000.0);
    if (hit && hit->box) {
      followed_ = *hit->box;
      followedAt_ = glm::vec3(world.bodyPose(*followed_).center);
      const std::string& name = world.bodies()[*followed_].name;
      ui_.message = "following " + (name.empty() ? "body " + std::to_string(*followed_) : name) +
                    "; double-click on nothing to stop";
    } else if (followed_) {
      followed_.reset();
      ui_.message = "stopped following";
    }
  }
}

void Sandbox::updateDrag() {
  const ImGuiIO& io = ImGui::GetIO();
  int width = 0, height = 0;
  glfwGetWindowSize(window_.handle(), &width, &height);
  if (width <= 0 || height <= 0) return;  // minimised: no cursor ray to pick with
  if (input_.buttonPressed(GLFW_MOUSE_BUTTON_LEFT) && !io.WantCaptureMouse) {
    const auto [origin, direction] = cursorRay();
    if (session_->pick(origin, direction)) ui_.message = "dragging: release the left button to let go";
  }
  if (!input_.buttonHeld(GLFW_MOUSE_BUTTON_LEFT)) {
    if (session_->dragging()) ui_.message = "let go";
    session_->release();
    return;
  }
  if (session_->dragging()) {
    const auto [origin, direction] = cursorRay();
    session_->dragAlong(origin, direction);
  }
}

void Sandbox::drawMenuBar() {
  if (!ImGui::BeginMainMenuBar()) return;
  const std::filesystem::path sceneDir = scenes::sceneDirectory(dataDir(options_));
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("Open...", "Ctrl+O")) openDialog_.open(FileDialogMode::Open, sceneDir, "Open scene");
    if (ImGui::MenuItem("Reload", "F5")) perform(Action::Reload);
    if (ImGui::MenuItem("Save As...", "Ctrl+S")) {
      saveDialog_.open(FileDialogMode::Save, session_->file().parent_path(), "Save world as scene");
    }
    if (ImGui::MenuItem("Open recording...")) showRecordingDialog(FileDialogMode::Open);
    if (ImGui::MenuItem("Save recording...")) showRecordingDialog(FileDialogMode::Save);
    if (ImGui::BeginMenu("Recent", !user_.recentFiles.empty())) {
      const std::vector<std::string> recent = user_.recentFiles;  // openScene() reorders the list
      for (const std::string& f : recent) {
        if (ImGui::MenuItem(f.c_str())) openScene(f);
      }
      ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Project scenes")) {
      for (const DirectoryEntry& e : listDirectory(sceneDir, ".xml")) {
        if (!e.isFolder && ImGui::MenuItem(e.name.c_str())) openScene(sceneDir / e.name);
      }
      ImGui::EndMenu();
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Quit")) glfwSetWindowShouldClose(window_.handle(), GLFW_TRUE);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    bool panelsShown = !ui_.panelsHidden;
    if (ImGui::MenuItem("Panels", "F2", &panelsShown)) ui_.panelsHidden = !panelsShown;
    const auto shown = sectionsShown(ui_);
    for (std::size_t i = 0; i < shown.size(); ++i) ImGui::MenuItem(kSectionTitles[i], nullptr, shown[i]);
    ImGui::MenuItem("Controls", "F1", &ui_.showHelp);
    ImGui::Separator();
    if (ImGui::MenuItem("Reset layout")) resetLayout(ui_);
    if (ImGui::MenuItem("Screenshot", "F12")) screenshotDue_ = true;
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

void Sandbox::showRecordingDialog(FileDialogMode mode) {
  const std::filesystem::path folder = session_->file().parent_path();
  if (mode == FileDialogMode::Open)
    openRecordingDialog_.open(mode, folder, "Open recording", kRecordingExtension);
  else
    saveRecordingDialog_.open(mode, folder, "Save recording", kRecordingExtension);
}

void Sandbox::recordingChosen(FileDialogMode mode, const std::filesystem::path& file) {
  const std::string error =
      mode == FileDialogMode::Open ? session_->openRecording(file) : session_->startSavingRecording(file);
  if (error.empty()) {
    if (mode == FileDialogMode::Open) {
      ui_.paused = true;  // at its first step, to be scrubbed or played
      trails_.clear();    // another run than the one the trails followed
    }
    ui_.message = session_->status();
  } else {
    errorText_ = error;
    showError_ = true;
  }
}

void Sandbox::drawDialogs() {
  if (const auto chosen = openRecordingDialog_.draw()) recordingChosen(FileDialogMode::Open, *chosen);
  if (const auto chosen = saveRecordingDialog_.draw()) recordingChosen(FileDialogMode::Save, *chosen);
  if (const auto chosen = openDialog_.draw()) openScene(*chosen);
  if (const auto chosen = saveDialog_.draw()) {
    scenes::CameraStart camera;
    camera.eye = camera_.position;
    camera.target = camera_.position + camera_.forward();
    const std::string error = session_->saveAs(*chosen, camera);
    if (error.empty()) {
      ghost_.fileSaved(session_->scene().world);  // Reload reads that file now: compare with it
      ui_.message = "saved " + chosen->string();
      addRecentFile(user_, std::filesystem::absolute(*chosen).string());
    } else {
      errorText_ = error + "\n\nNothing was written over the file.";
      showError_ = true;
    }
  }
  if (showError_) {
    ImGui::OpenPopup("Error");
    showError_ = false;
  }
  ImGui::SetNextWindowSize(ImVec2(560.0f, 0.0f), ImGuiCond_Appearing);
  if (ImGui::BeginPopupModal("Error", nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::TextWrapped("%s", errorText_.c_str());
    if (ImGui::Button("OK") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
      ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
}

void Sandbox::renderFrame() {
  // The scene is drawn left of the panels' column, never under it (sceneView).
  const glm::ivec2 size = window_.framebufferSize();
  int windowWidth = 1, windowHeight = 1;
  glfwGetWindowSize(window_.handle(), &windowWidth, &windowHeight);
  const ScreenRect view = sceneRect();
  const float toPixels = static_cast<float>(size.x) / static_cast<float>(std::max(windowWidth, 1));
  const glm::ivec4 viewport(static_cast<int>(view.x * toPixels), 0,
                            std::max(static_cast<int>(view.width * toPixels), 1), size.y);
  const glm::mat4 viewProjection =
      camera_.projection(static_cast<float>(viewport.z) / static_cast<float>(viewport.w)) * camera_.view();

  renderer_->beginFrame(size, viewport);
  const phys::WorldSettings& settings = session_->scene().world.worldSettings();
  if (settings.ground) {
    renderer_->drawGround(viewProjection, camera_.position, glm::vec3(settings.groundNormal),
                          static_cast<float>(settings.groundHeight));
  }
  // The exact answer first: translucent, it leaves no depth, so the run drawn after it is whole
  // where the two overlap and the ghost shows where they part.
  if (ui_.draw.exact) drawExactAnswers(viewProjection);
  if (session_->overlayActive()) {
    for (const Run& run : session_->runs())
      view_->draw(run.scene->world, viewProjection, ui_.draw, Tint{run.color});
  } else {
    view_->draw(session_->scene().world, viewProjection, ui_.draw);
  }
  if (ui_.draw.trails) {
    trails_.record(session_->scene().world, followed_);
    trails_.draw(renderer_->lines(), kTrailColor);
  } else {
    trails_.clear();
  }
  if (const auto line = session_->dragLine()) {
    renderer_->lines().addLine(glm::vec3(line->first), glm::vec3(line->second), glm::vec3(1.0f, 1.0f, 0.3f));
    renderer_->lines().addPoint(glm::vec3(line->second), 0.08f, glm::vec3(1.0f, 1.0f, 0.3f));
  }
  glDisable(GL_DEPTH_TEST);  // debug lines show through bodies, as in the seed's constraint mode
  renderer_->endFrame(viewProjection);

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  for (const KeyTaps::Release& r : keyTaps_.frameStarted())
    ImGui_ImplGlfw_KeyCallback(window_.handle(), r.key, r.scancode, GLFW_RELEASE, r.mods);
  drawMenuBar();
  ui_.exactHidden = ghost_.hiddenBecause(session_->scene().world);
  drawPanels(*session_, ui_);
  drawLegend(*session_, ui_);
  drawHelp(ui_);
  drawDialogs();
  drawStatusAndCrosshair(*session_, ui_);
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
    ui_.frameMs = frameSeconds * 1000.0f;

    // Keys act unless ImGui is taking typed text (a path in a dialog, an overlay setting).
    const bool typing = ImGui::GetCurrentContext() != nullptr && ImGui::GetIO().WantTextInput;
    for (const auto& [key, mods] : keyPresses_) {
      if (typing) continue;
      if ((mods & GLFW_MOD_CONTROL) != 0 && key == GLFW_KEY_O) {
        openDialog_.open(FileDialogMode::Open, scenes::sceneDirectory(dataDir(options_)), "Open scene");
      } else if ((mods & GLFW_MOD_CONTROL) != 0 && key == GLFW_KEY_S) {
        saveDialog_.open(FileDialogMode::Save, session_->file().parent_path(), "Save world as scene");
      } else if (const auto action = actionForKey(key, mods)) {
        perform(*action);
      }
    }
    keyPresses_.clear();
    if (ui_.reloadRequested) {
      ui_.reloadRequested = false;
      perform(Action::Reload);
    }
    if (std::exchange(ui_.openRecordingRequested, false)) showRecordingDialog(FileDialogMode::Open);
    if (const std::optional<std::string> saved = session_->finishSaving()) {
      ui_.message = session_->status();
      if (!saved->empty()) {
        errorText_ = *saved + "\n\nNothing was written over the file.";
        showError_ = true;
      }
    }
    if (std::exchange(ui_.saveRecordingRequested, false)) showRecordingDialog(FileDialogMode::Save);

    if (interactive_) {
      moveCamera(frameSeconds);
      updateDrag();
    }
    advancePhysics(frameSeconds);
    if (interactive_) zoomOrbitFollow();
    input_.endFrame();
    const glm::ivec2 size = window_.framebufferSize();
    if (size.x == 0 || size.y == 0 || glfwGetWindowAttrib(window_.handle(), GLFW_ICONIFIED) != 0) {
      // Minimised (a 0 x 0 framebuffer on some systems; on X11 the size stays and only the
      // attribute says so): nothing to draw, and vsync would not pace the loop, so wait for events
      // (the simulation goes on in the background, up to kMaxStepsPerFrame steps per wake-up).
      glfwWaitEventsTimeout(0.05);
      continue;
    }
    renderFrame();
    if (screenshotDue_) takeScreenshot();

    if (options_.screenshot && frame >= options_.frames) {
      glReadBuffer(GL_BACK);
      fileio::writeAtomically(*options_.screenshot,
                              engine::encodePng(engine::readFramebuffer(window_.framebufferSize())));
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
  CheckedFiles files = checkFiles(parsed.options);
  if (!files.error.empty()) {
    std::cerr << "sandbox: " << files.error << '\n';
    return 1;
  }
  const std::string noDisplay = engine::missingDisplayReason();
  if (!noDisplay.empty()) {
    std::cerr << "sandbox: " << noDisplay << '\n';
    return 1;
  }
  try {
    Sandbox app(parsed.options, std::move(files.scene));
    return app.run();
  } catch (const std::exception& e) {
    std::cerr << "sandbox: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace sandbox
