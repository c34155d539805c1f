#pragma once
// The sandbox program: a window, the scene's world stepped at a fixed rate, the renderer, the
// ImGui panel and a first-person camera.
#include <memory>

#include "engine/camera.h"
#include "engine/gpu_mesh.h"
#include "engine/renderer.h"
#include "engine/window.h"
#include "options.h"
#include "panel.h"
#include "scenes/scene.h"

namespace sandbox {

class Sandbox {
 public:
  /// Opens the window and loads shaders, the box model and the scene; throws engine::Error or
  /// std::invalid_argument with a message for the user.
  explicit Sandbox(const Options& options);
  ~Sandbox();
  Sandbox(const Sandbox&) = delete;
  Sandbox& operator=(const Sandbox&) = delete;

  /// Runs until the window closes or, with --screenshot, until the PNG is written. Returns the
  /// process exit code.
  int run();

 private:
  void loadScene();
  void advancePhysics(double frameSeconds);
  void stepOnceTimed();
  void moveCamera(float frameSeconds);
  void renderFrame();

  Options options_;
  engine::Window window_;
  std::unique_ptr<engine::Renderer> renderer_;
  std::unique_ptr<engine::GpuMesh> boxMesh_;
  std::unique_ptr<scenes::Scene> scene_;
  engine::FirstPersonCamera camera_;
  PanelState panel_;
  double accumulator_ = 0.0;  // unit: s; real time not yet simulated
  double lastCursorX_ = 0.0, lastCursorY_ = 0.0;
  bool looking_ = false;
};

/// Whole program: parses arguments, runs, reports errors. Returns the exit code.
int runSandbox(int argc, char** argv);

}  // namespace sandbox
