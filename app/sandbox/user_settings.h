#pragma once
// What the sandbox remembers between runs: window size, which sections of the panels' column are
// shown, the last scene, the draw mode and the recent files. Stored as "key = value" lines in the
// user's config folder. Keys: width, height, showSimulation,
// showWorld, showDraw, showStats, lastScene, drawMode, markers, and one `recent = PATH` line per
// recent file, newest first; '#' starts a comment line.
#include <filesystem>
#include <string>
#include <vector>

namespace sandbox {

inline constexpr int kMaxRecentFiles = 8;

struct UserSettings {
  int windowWidth = 1280;  ///< unit: screen pixels
  int windowHeight = 720;  ///< unit: screen pixels
  bool showSimulation = true;
  bool showWorld = true;
  bool showDraw = true;
  bool showStats = true;
  std::string lastScene;                 ///< a path; empty: the default scene
  std::string drawMode = "filled";       ///< filled, wireframe or constraints
  bool markers = false;                  ///< the seed's green collision-vertex markers
  std::vector<std::string> recentFiles;  ///< newest first, at most kMaxRecentFiles
};

/// $XDG_CONFIG_HOME/jakobsen-sandbox, else $HOME/.config/jakobsen-sandbox; empty if neither is set.
std::filesystem::path configDirectory();

struct LoadedSettings {
  UserSettings settings;
  std::vector<std::string> warnings;  ///< "file:line: why" for each line that was skipped
};

/// Reads the file; a missing file gives the defaults and no warning. A bad line is skipped with
/// a warning and the rest is kept.
LoadedSettings loadUserSettings(const std::filesystem::path& file);
/// Writes through fileio::writeAtomically, creating the folder first; throws fileio::FileError
/// (a std::runtime_error) naming the file and the reason when it cannot.
void saveUserSettings(const UserSettings& settings, const std::filesystem::path& file);
/// Puts `path` first in the recent list, removing an older copy and keeping at most kMaxRecentFiles.
void addRecentFile(UserSettings& settings, const std::string& path);

}  // namespace sandbox
