#pragma once
// What the sandbox remembers between runs: window size, which sections of the panels' column are
// shown, the last scene, the draw mode, the colouring, the throw speed, the recording's budget and
// the recent files. Stored as "key = value" lines in the user's config folder. Keys: width,
// height, showSimulation, showRewind, showWorld, showDraw, showStats, showLab, lastScene, drawMode,
// markers, colorBy, throwSpeed, recordingBudget, and one `recent = PATH` line per recent file,
// newest first; '#' starts a comment line. Lines it does not understand are kept as they were.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sandbox {

inline constexpr int kMaxRecentFiles = 8;
/// The World panel's throw speed slider's range (m/s) and the Rewind section's budget slider's (MB).
inline constexpr float kMaxThrowSpeed = 40.0f;
inline constexpr int kMinRecordingBudgetMb = 16, kMaxRecordingBudgetMb = 8192;

struct UserSettings {
  int windowWidth = 1280;  ///< unit: screen pixels
  int windowHeight = 720;  ///< unit: screen pixels
  bool showSimulation = true;
  bool showWorld = true;
  bool showDraw = true;
  bool showStats = true;
  bool showRewind = true;
  bool showLab = true;
  std::string lastScene;            ///< a path; empty: the default scene
  std::string drawMode = "filled";  ///< filled, wireframe or constraints
  bool markers = false;             ///< the seed's green collision-vertex markers
  // Unset until a run has written them: the panels' own defaults then hold.
  std::optional<std::string> colorBy;    ///< kind, body, island or sleep
  std::optional<float> throwSpeed;       ///< unit: m/s; 0 to kMaxThrowSpeed
  std::optional<int> recordingBudgetMb;  ///< unit: MB; kMinRecordingBudgetMb to kMaxRecordingBudgetMb
  std::vector<std::string> recentFiles;  ///< newest first, at most kMaxRecentFiles
  /// Lines of the file read that this version does not understand (an unknown key, a line that
  /// is not 'key = value', a comment), written back after the rest as they were: a key of a newer
  /// version, or a typo the user can still see and mend, is never lost by a save.
  std::vector<std::string> keptLines;
};

/// $XDG_CONFIG_HOME/jakobsen-sandbox, else $HOME/.config/jakobsen-sandbox; empty if neither is set.
std::filesystem::path configDirectory();

struct LoadedSettings {
  UserSettings settings;
  std::vector<std::string> warnings;  ///< "file:line: why" for each line that was skipped
  /// The file is there but could not be read (no permission, too large, a folder): writing it on
  /// exit would replace what the user had with the defaults, so it must be left as it is.
  bool keepFile = false;
};

/// Reads the file; a missing file gives the defaults and no warning. A line it does not
/// understand is kept (UserSettings::keptLines) with a warning; a known key's bad value is
/// skipped with a warning (its default is written in its place on saving), and the rest is
/// used. A file that cannot be read, or looked at, gives the defaults, a warning with the
/// system's reason, and keepFile.
LoadedSettings loadUserSettings(const std::filesystem::path& file);
/// Writes through fileio::writeAtomically, creating the folder first; throws fileio::FileError
/// (a std::runtime_error) naming the file and the reason when it cannot.
void saveUserSettings(const UserSettings& settings, const std::filesystem::path& file);
/// Puts `path` first in the recent list, removing an older copy and keeping at most kMaxRecentFiles.
void addRecentFile(UserSettings& settings, const std::string& path);

}  // namespace sandbox
