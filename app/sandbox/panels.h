#pragma once
// The sandbox's ImGui panels: Simulation, World, Draw and Stats in a column at the right of the
// scene, the overlay's legend, the F1 table of controls and the status line. Each slider writes the setting
// the scene file and the lab use (phys::SolverSettings, phys::WorldSettings) straight into the world: nothing
// restarts.
#include <array>
#include <optional>
#include <string>
#include <utility>

#include <glm/vec2.hpp>

#include "draw_options.h"
#include "history.h"
#include "lab_sweep.h"
#include "options.h"
#include "physics/settings.h"
#include "real_time.h"
#include "session.h"
#include "user_settings.h"

namespace sandbox {

/// A rectangle in window pixels, from the window's top-left corner.
struct ScreenRect {
  float x = 0.0f, y = 0.0f, width = 0.0f, height = 0.0f;
};

/// The side column the panels share, at the right edge from `top` (below the menu bar) down to
/// `bottom` pixels above the window's foot (the status line): 27% of the window's width
/// within 300 to 440 pixels, never more than half the window, so it stays inside at any size.
ScreenRect panelColumn(float windowWidth, float windowHeight, float top, float bottom);
/// Where the scene is drawn: the window left of the column, or all of it when the panels are
/// hidden. Nothing of the scene is ever under a panel.
ScreenRect sceneView(float windowWidth, float windowHeight, bool panelsShown);

/// The sections' headers, and the View menu's entries that show them (kSectionNames' order).
inline constexpr std::array<const char*, kSectionNames.size()> kSectionTitles = {
    "Simulation", "Rewind", "World", "Draw", "Stats", "Lab"};
/// The sections open at the start (kSectionNames' order): the settings and what they cost.
inline constexpr SectionFlags kDefaultUnfolded = {true, true, false, false, true, false};

/// Everything the panels show or change besides the session.
struct UiState {
  bool showSimulation = true, showWorld = true, showDraw = true, showStats = true;
  bool panelsHidden = false;                 ///< F2 or --hide-panels: the scene fills the window
  bool resetLayout = false;                  ///< View > Reset layout: every section shown, in its first state
  SectionFlags unfolded = kDefaultUnfolded;  ///< per kSectionNames: open at the start
  bool showRewind = true, showLab = true;
  LabSweep lab;                                                             ///< the Lab section's sweep
  int recordingBudgetMb = static_cast<int>(kDefaultRecordingBudget >> 20);  ///< Rewind's memory slider
  /// A number being typed into a solver slider (Ctrl+click), applied when the typing ends: the
  /// slider's label and the value so far.
  std::optional<std::pair<std::string, int>> typing;
  bool showHelp = false;
  bool paused = false;
  bool replaying = false;        ///< Rewind's Play: the recording shown step by step at the clock's pace
  bool stepOnce = false;         ///< set by Step or N; cleared when done
  bool reloadRequested = false;  ///< set by Reset; the sandbox reloads (and shows any error)
  /// Set by the Rewind section's Save and Open: the sandbox shows the file dialog.
  bool saveRecordingRequested = false, openRecordingRequested = false;
  float timeScale = 1.0f;                              ///< simulated seconds per real second
  float throwSpeed = static_cast<float>(kThrowSpeed);  ///< unit: m/s; F, R and T throw at it
  /// The ground's dynamic over static friction, as last seen with static friction above 0: the
  /// ground friction slider keeps it through 0, where the world's materials no longer hold it.
  double groundFrictionRatio = phys::Material{}.dynamicFriction / phys::Material{}.staticFriction;
  DrawOptions draw;
  /// Why the scene's exact answer is not drawn though it has one (ExactGhost::hiddenBecause):
  /// "gravity changed"; "" when it is drawn. The sandbox sets it every frame; the Draw section shows it.
  std::string exactHidden;
  /// The overlay panel's settings, as typed (any length: a setting cut short would run as another).
  std::array<std::string, kMaxOverlayRuns> overlayText;
  // For the Stats panel.
  float frameMs = 0.0f;  ///< unit: ms; the last frame
  History stepMs, maxError, rmsError;
  RealTimeMeter realTime;
  std::string message;  ///< the status line: what the last command did
};

/// Whether each section is shown (kSectionNames' order): its header's close button hides it, the
/// View menu shows it again.
std::array<bool*, kSectionNames.size()> sectionsShown(UiState& ui);
/// View > Reset layout: the column and every section shown, each folded as at the start.
void resetLayout(UiState& ui);

/// N, and the panels' Step: while paused on a step of the recording with more after it (after B or
/// the timeline), shows the next one, as recorded; else asks for a new step (ui.stepOnce), which
/// with a body held pulls it, and forks the recording there.
void stepOnce(Session& session, UiState& ui);
/// Space, and the panels' Pause: while Play shows the recording, stops it, paused at the step shown;
/// else pauses or runs.
void togglePause(UiState& ui);

/// The panels as the last run left them, with the command line's --draw, --markers and
/// --overlay on top (the overlay's fields get examples where the command line gave none).
void applyRemembered(const UserSettings& user, const Options& options, UiState& ui);
/// What of the panels the next run starts with.
void remember(const UiState& ui, UserSettings& user);

/// The side column: Simulation (with the method overlay), World, Draw and Stats, each a section
/// that folds, and that the View menu or its close button hides.
void drawPanels(Session& session, UiState& ui);
/// One line per overlay run (its colour, its settings, its step time), at the foot of the scene.
void drawLegend(const Session& session, const UiState& ui);
/// The table of controls (F1).
void drawHelp(UiState& ui);
/// The status line at the bottom and a crosshair at the centre of the scene, under every window.
void drawStatusAndCrosshair(const Session& session, const UiState& ui);
/// Height of the status line (pixels), which the column stops above.
float statusLineHeight();

}  // namespace sandbox
