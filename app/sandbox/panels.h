#pragma once
// The sandbox's ImGui panels: Simulation, World, Draw and Stats, the overlay's legend, the F1
// table of controls and the status line. Each slider writes the setting the scene file and the
// lab use (phys::SolverSettings, phys::WorldSettings) straight into the world: nothing restarts.
#include <array>
#include <string>

#include <glm/vec2.hpp>

#include "draw_options.h"
#include "history.h"
#include "options.h"
#include "real_time.h"
#include "session.h"
#include "user_settings.h"

namespace sandbox {

/// Where a panel first opens, in window pixels below the menu bar; the user may move it, and
/// imgui.ini remembers where. Screenshots always use these, so tests know where to look.
struct PanelPlace {
  glm::vec2 pos;  ///< top-left corner; x from the right edge when fromRight
  glm::vec2 size;
  bool fromRight = false;
};
inline constexpr PanelPlace kSimulationPanel{{10.0f, 30.0f}, {370.0f, 425.0f}};
inline constexpr PanelPlace kWorldPanel{{10.0f, 465.0f}, {370.0f, 150.0f}};
inline constexpr PanelPlace kStatsPanel{{380.0f, 30.0f}, {370.0f, 440.0f}, true};
inline constexpr PanelPlace kDrawPanel{{380.0f, 480.0f}, {370.0f, 135.0f}, true};

/// Everything the panels show or change besides the session.
struct UiState {
  bool showSimulation = true, showWorld = true, showDraw = true, showStats = true;
  bool showHelp = false;
  bool paused = false;
  bool stepOnce = false;         ///< set by Step or N; cleared when done
  bool reloadRequested = false;  ///< set by Reset; the sandbox reloads (and shows any error)
  float timeScale = 1.0f;        ///< simulated seconds per real second
  DrawOptions draw;
  std::array<char, 128> overlayText[kMaxOverlayRuns] = {};  ///< the overlay panel's settings
  // For the Stats panel.
  float frameMs = 0.0f;  ///< unit: ms; the last frame
  History stepMs, maxError, rmsError;
  RealTimeMeter realTime;
  std::string message;  ///< the status line: what the last command did
};

/// The panels as the last run left them, with the command line's --draw, --markers and
/// --overlay on top (the overlay's fields get examples where the command line gave none).
void applyRemembered(const UserSettings& user, const Options& options, UiState& ui);
/// What of the panels the next run starts with.
void remember(const UiState& ui, UserSettings& user);

void drawSimulationPanel(Session& session, UiState& ui);
void drawWorldPanel(Session& session, UiState& ui);
void drawDrawPanel(UiState& ui);
void drawStatsPanel(const Session& session, UiState& ui);
/// One line per overlay run: its colour, its settings, its step time.
void drawLegend(const Session& session);
/// The table of controls (F1).
void drawHelp(UiState& ui);
/// The status line at the bottom and a crosshair at the centre of the view.
void drawStatusAndCrosshair(const Session& session, const UiState& ui);

}  // namespace sandbox
