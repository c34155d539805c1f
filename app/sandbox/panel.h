#pragma once
// The sandbox's ImGui panel: where it sits, and what it shows and changes.
#include <string>

#include <glm/vec2.hpp>

namespace scenes {
struct Scene;
}

namespace sandbox {

/// Placement of the panel, in window pixels from the top-left corner. Fixed for now (panel
/// layout persistence comes with the sandbox issue), so tests know where to look.
inline constexpr glm::vec2 kPanelPosition{10.0f, 10.0f};
inline constexpr glm::vec2 kPanelSize{360.0f, 400.0f};

/// What the panel can ask the sandbox to do this frame.
struct PanelState {
  bool paused = false;
  bool stepOnce = false;      ///< set by the Step button; cleared by the sandbox
  bool resetRequested = false;
  bool drawSticks = false;     ///< every stick, red (range sticks orange)
  bool drawContacts = false;   ///< points that touched the ground in the last step, green
  bool drawBounds = false;     ///< each box's axis-aligned bounding box, grey
  bool drawParticles = true;   ///< loose particles as small cubes
  float frameMs = 0.0f;       ///< unit: ms; last frame, for display
  float stepMs = 0.0f;        ///< unit: ms; physics time in the last frame
  std::string loadError;      ///< the last failed reload's message, shown until one succeeds
};

/// Draws the panel; edits of solver and world settings go straight into the scene's world.
void drawPanel(scenes::Scene& scene, PanelState& state);

}  // namespace sandbox
