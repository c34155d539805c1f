#include "controls.h"

#include <GLFW/glfw3.h>

namespace sandbox {
namespace {

constexpr Control kControls[] = {
    {"1", "scene 1: one ragdoll (ragdoll.xml)"},
    {"2", "scene 2: a pyramid of boxes that vary in size (pyramid.xml)"},
    {"3", "scene 3: three 3x3 layers of boxes (box-of-boxes.xml)"},
    {"4", "the tackle: a runner on the run cycle and a diving tackler (tackle.xml)"},
    {"0", "clear the scene of every body (settings stay)"},
    {"Tab", "draw mode: filled, wireframe, constraints (in red)"},
    {"C", "collision-vertex markers: green boxes on vertices moved by box-box contacts"},
    {"W / A / S / D", "move forward / left / back / right"},
    {"Q / E", "move down / up"},
    {"Shift", "move 4 times faster"},
    {"right mouse + move", "look around"},
    {"mouse wheel", "zoom: move towards or away from the point under the cursor (or the followed body)"},
    {"middle mouse + move, or Alt + right mouse + move",
     "orbit around the point at the crosshair (or the followed body)"},
    {"double-click",
     "follow the body under the cursor (the camera moves with it); on nothing, stop following"},
    {"Z",
     "frame the scene: move along the view until every body is in it (one larger than the 500 m the view "
     "reaches: its middle, and the status line says so)"},
    {"left mouse drag", "pick the body or particle under the cursor and pull it with a spring"},
    {"G", "gravity: uniform (down) or towards a point above the ground"},
    {"Y / H", "gravity stronger / weaker by 1 m/s^2"},
    {"U / J", "wind resistance (damping) up / down by 0.1 1/s"},
    {"Space", "pause / run"},
    {"N", "one step (while paused); after B or the timeline, the recording's next step"},
    {"B", "one step back: the recording's step before the one shown (pauses; Rewind panel)"},
    {"F", "throw a box from the crosshair along the view"},
    {"R", "throw a ragdoll from the crosshair along the view"},
    {"T", "throw a capsule ragdoll (Bullet's layout) from the crosshair along the view"},
    {"F5", "reload the scene file"},
    {"Ctrl+O / Ctrl+S", "open a scene / save the world as a scene"},
    {"F1", "show or hide this table"},
    {"F2", "hide or show the panels (the scene fills the window)"},
    {"F12", "screenshot: a PNG of the window next to the scene file"},
};

}  // namespace

std::span<const Control> controls() {
  return kControls;
}

std::optional<Action> actionForKey(int key, int mods) {
  if ((mods & (GLFW_MOD_CONTROL | GLFW_MOD_ALT | GLFW_MOD_SUPER)) != 0) return std::nullopt;
  switch (key) {
    case GLFW_KEY_1:
      return Action::Scene1;
    case GLFW_KEY_2:
      return Action::Scene2;
    case GLFW_KEY_3:
      return Action::Scene3;
    case GLFW_KEY_4:
      return Action::SceneTackle;
    case GLFW_KEY_0:
      return Action::ClearScene;
    case GLFW_KEY_TAB:
      return Action::CycleDrawMode;
    case GLFW_KEY_C:
      return Action::ToggleMarkers;
    case GLFW_KEY_G:
      return Action::ToggleGravityMode;
    case GLFW_KEY_Y:
      return Action::GravityUp;
    case GLFW_KEY_H:
      return Action::GravityDown;
    case GLFW_KEY_U:
      return Action::DampingUp;
    case GLFW_KEY_J:
      return Action::DampingDown;
    case GLFW_KEY_SPACE:
      return Action::Pause;
    case GLFW_KEY_N:
      return Action::StepOnce;
    case GLFW_KEY_B:
      return Action::StepBack;
    case GLFW_KEY_F5:
      return Action::Reload;
    case GLFW_KEY_F:
      return Action::SpawnBox;
    case GLFW_KEY_R:
      return Action::SpawnRagdoll;
    case GLFW_KEY_T:
      return Action::SpawnCapsuleRagdoll;
    case GLFW_KEY_F1:
      return Action::ToggleHelp;
    case GLFW_KEY_F2:
      return Action::TogglePanels;
    case GLFW_KEY_Z:
      return Action::FrameScene;
    case GLFW_KEY_F12:
      return Action::Screenshot;
    default:
      return std::nullopt;
  }
}

}  // namespace sandbox
