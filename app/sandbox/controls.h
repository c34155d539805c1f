#pragma once
// Every key and mouse control of the sandbox, in one table: the F1 overlay shows it,
// docs/sandbox.md lists it (a test checks that each row is there), and actionForKey() maps
// keys to the actions of the table.
#include <optional>
#include <span>
#include <string_view>

namespace sandbox {

enum class Action {
  Scene1,             ///< the seed's scene 1: one ragdoll
  Scene2,             ///< the seed's scene 2: a pyramid of boxes of varying size
  Scene3,             ///< the seed's scene 3: three 3x3 layers of boxes
  SceneTackle,        ///< the tackle the seed was written for: a runner and a diving tackler
  ClearScene,         ///< remove every body, keep the settings
  CycleDrawMode,      ///< filled, wireframe, constraints
  ToggleMarkers,      ///< green boxes on vertices moved by box-box collisions
  ToggleGravityMode,  ///< uniform or towards a point
  GravityUp,
  GravityDown,
  DampingUp,  ///< the seed's wind resistance
  DampingDown,
  Pause,
  StepOnce,
  Reload,
  SpawnBox,
  SpawnRagdoll,
  SpawnCapsuleRagdoll,  ///< Bullet's layout (physics/capsule_ragdoll.h)
  ToggleHelp,
  TogglePanels,  ///< hide or show the side column (the scene fills the window)
  FrameScene,    ///< move the camera along its view until every body is in it
  StepBack,      ///< the recording's step before the one shown (pauses)
  Screenshot,    ///< a PNG of the window next to the scene file
};

struct Control {
  std::string_view keys;    ///< as the user presses them
  std::string_view action;  ///< what happens
};

/// Every control, in the order the help overlay shows them.
std::span<const Control> controls();

/// The action a key press (GLFW key code and modifier bits) triggers, if any. Movement keys
/// (W/A/S/D/Q/E, Shift) are held, not pressed, and are not actions.
std::optional<Action> actionForKey(int key, int mods);

/// Step of Y/H (m/s^2) and of U/J (1/s).
inline constexpr double kGravityStep = 1.0;
inline constexpr double kDampingStep = 0.1;

}  // namespace sandbox
