#pragma once
// The sandbox program: a window, the session's scene stepped at a fixed rate, the renderer, the
// ImGui panels and menus, a first-person camera, and picking. Commands go to the Session (the
// command layer, session.h); this file wires keys, mouse and menus to it and draws.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "controls.h"
#include "engine/camera.h"
#include "engine/renderer.h"
#include "engine/window.h"
#include "exact_ghost.h"
#include "file_dialog.h"
#include "input.h"
#include "options.h"
#include "panels.h"
#include "scene_view.h"
#include "session.h"
#include "trails.h"
#include "user_settings.h"

namespace sandbox {

class Sandbox {
 public:
  /// Opens the window and loads shaders, models and the scene (`named`, the scene options.scene
  /// names as checkFiles opened it, or else the last one used or the default); throws
  /// engine::Error or scenes::LoadError with a message for the user.
  explicit Sandbox(const Options& options, std::unique_ptr<scenes::Scene> named = nullptr);
  ~Sandbox();
  Sandbox(const Sandbox&) = delete;
  Sandbox& operator=(const Sandbox&) = delete;

  /// Runs until the window closes or, with --screenshot, until the PNG is written. Returns the
  /// process exit code.
  int run();

  // GLFW callbacks (static trampolines in sandbox.cpp forward here).
  void onKey(int key, int action, int mods);
  KeyTaps& keyTaps() { return keyTaps_; }
  void onMouseButton(int button, int action);
  void onFocus(bool focused);
  void onScroll(double amount);

 private:
  std::unique_ptr<Session> openUnnamed(const std::filesystem::path& data) const;
  void saveUserSettingsOnExit();
  void perform(Action action);
  void openScene(const std::filesystem::path& file);
  bool pauseDue();
  void advancePhysics(double frameSeconds);
  void stepInBackground(double frameSeconds);
  void moveCamera(float frameSeconds);
  /// The wheel's zoom, the orbit and following a body (moveCamera does the first-person moves).
  void zoomOrbitFollow();
  /// What the wheel zooms to (along the ray under the cursor) and the orbit turns about (along
  /// the view): the followed body's centre, else the first body along the ray, else the ray's
  /// point nearest the middle of the scene.
  glm::vec3 focusPoint(const glm::vec3& origin, const glm::vec3& direction) const;
  void frameScene();
  void stopFollowing();
  /// Whether a body is followed; drops one that the world no longer has.
  bool following();
  /// What is sized to the scene opened (loose particles, by its camera's distance), and its ghost.
  void fitToScene();
  void drawExactAnswers(const glm::mat4& viewProjection);
  void updateDrag();
  /// The ray under the cursor, from the camera: origin and unit direction.
  std::pair<phys::Vec3, phys::Vec3> cursorRay() const;
  /// Rewind's Play: the recording's next steps, as many as the clock owes, shown as recorded.
  void playRecording(double frameSeconds);
  void renderFrame();
  void drawMenuBar();
  void drawDialogs();
  /// File > Open recording / Save recording, and the Rewind section's buttons.
  void showRecordingDialog(FileDialogMode mode);
  void recordingChosen(FileDialogMode mode, const std::filesystem::path& file);
  /// Where the scene is drawn in the window (left of the panels, or all of it).
  ScreenRect sceneRect() const;
  /// F12: the frame just drawn as a PNG next to the scene file, and a status line saying where.
  void takeScreenshot();

  Options options_;
  bool interactive_;  // false for --screenshot: nothing remembered, one step per frame
  std::filesystem::path settingsFile_;
  UserSettings user_;
  engine::Window window_;
  std::unique_ptr<engine::Renderer> renderer_;
  std::unique_ptr<SceneView> view_;
  std::unique_ptr<Session> session_;
  engine::FirstPersonCamera camera_;
  InputState input_;
  std::vector<std::pair<int, int>> keyPresses_;  // (key, mods) since the last frame
  KeyTaps keyTaps_;                              // what ImGui is told of keys, a frame at a time
  UiState ui_;
  FileDialog openDialog_, saveDialog_;
  FileDialog openRecordingDialog_, saveRecordingDialog_;
  std::string errorText_;  // shown in a modal until dismissed
  bool showError_ = false;
  double accumulator_ = 0.0;      // unit: s; simulated time owed to the clock
  bool stepWhilePaused_ = false;  // the background step is N's, which pausing does not cancel
  double lastCursorX_ = 0.0, lastCursorY_ = 0.0;
  double orbitCursorX_ = 0.0, orbitCursorY_ = 0.0;
  bool looking_ = false;
  bool screenshotDue_ = false;  // F12: taken after the next frame is drawn
  double scroll_ = 0.0;         // wheel notches since the last frame, towards the scene positive
  bool orbiting_ = false;
  glm::vec3 orbitPivot_{0.0f};
  std::optional<phys::BodyId> followed_;  // the body the camera moves with
  glm::vec3 followedAt_{0.0f};            // its centre when the camera last moved with it
  Trails trails_;
  ExactGhost ghost_;  // the exact answer of the scene opened, if it has one
};

/// Whole program: parses arguments, runs, reports errors. Returns the exit code.
int runSandbox(int argc, char** argv);

}  // namespace sandbox
