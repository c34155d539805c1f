#include "user_settings.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "draw_options.h"
#include "fileio/files.h"

namespace sandbox {
namespace {

namespace fs = std::filesystem;

constexpr int kMinWindowSide = 100;
constexpr std::size_t kMaxSettingsBytes = std::size_t{1} << 20;  // a few hundred bytes in use
constexpr int kMaxWindowSide = 16384;
// The first line written, not kept as a comment of the user's when read back.
constexpr std::string_view kHeader = "# jakobsen-sandbox settings, rewritten on exit";
constexpr const char* kKept = "; kept in the file as it is";

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

bool parseWindowSide(std::string_view text, int& out) {
  int n = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc() || end != text.data() + text.size() || n < kMinWindowSide || n > kMaxWindowSide) {
    return false;
  }
  out = n;
  return true;
}

bool parseBool(std::string_view text, bool& out) {
  if (text != "true" && text != "false") return false;
  out = text == "true";
  return true;
}

bool parseDrawMode(std::string_view text, std::string& out) {
  if (text != "filled" && text != "wireframe" && text != "constraints") return false;
  out = std::string(text);
  return true;
}

bool parseColoring(std::string_view text, std::optional<std::string>& out) {
  if (!parseBodyColoring(text)) return false;
  out = std::string(text);
  return true;
}

bool parseThrowSpeed(std::string_view text, std::optional<float>& out) {
  float v = 0.0f;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !(v >= 0.0f && v <= kMaxThrowSpeed))
    return false;
  out = v;
  return true;
}

bool parseBudget(std::string_view text, std::optional<int>& out) {
  int n = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc() || end != text.data() + text.size() || n < kMinRecordingBudgetMb ||
      n > kMaxRecordingBudgetMb)
    return false;
  out = n;
  return true;
}

// A value holding a line break would end its line early and corrupt the next one on reading.
bool fitsOnOneLine(const std::string& value) {
  return value.find_first_of("\r\n") == std::string::npos;
}

// Everything that can go in the file, in the order it is written.
std::string toText(const UserSettings& s) {
  auto flag = [](bool b) { return b ? "true" : "false"; };
  std::string out = std::string(kHeader) + "\n";
  out += "width = " + std::to_string(s.windowWidth) + "\n";
  out += "height = " + std::to_string(s.windowHeight) + "\n";
  out += std::string("showSimulation = ") + flag(s.showSimulation) + "\n";
  out += std::string("showWorld = ") + flag(s.showWorld) + "\n";
  out += std::string("showDraw = ") + flag(s.showDraw) + "\n";
  out += std::string("showStats = ") + flag(s.showStats) + "\n";
  out += std::string("showRewind = ") + flag(s.showRewind) + "\n";
  out += std::string("showLab = ") + flag(s.showLab) + "\n";
  if (fitsOnOneLine(s.lastScene)) out += "lastScene = " + s.lastScene + "\n";
  out += "drawMode = " + s.drawMode + "\n";
  out += std::string("markers = ") + flag(s.markers) + "\n";
  if (s.colorBy) out += "colorBy = " + *s.colorBy + "\n";
  if (s.throwSpeed) {
    char speed[32];
    const auto [end, ec] = std::to_chars(speed, speed + sizeof speed, *s.throwSpeed);
    if (ec == std::errc()) out += "throwSpeed = " + std::string(speed, end) + "\n";
  }
  if (s.recordingBudgetMb) out += "recordingBudget = " + std::to_string(*s.recordingBudgetMb) + "\n";
  for (const std::string& path : s.recentFiles) {
    if (fitsOnOneLine(path)) out += "recent = " + path + "\n";
  }
  for (const std::string& line : s.keptLines) {
    if (fitsOnOneLine(line)) out += line + "\n";
  }
  return out;
}

}  // namespace

fs::path configDirectory() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  if (xdg != nullptr && *xdg != '\0') return fs::path(xdg) / "jakobsen-sandbox";
  const char* home = std::getenv("HOME");
  if (home != nullptr && *home != '\0') return fs::path(home) / ".config" / "jakobsen-sandbox";
  return {};
}

LoadedSettings loadUserSettings(const fs::path& file) {
  LoadedSettings out;
  UserSettings& s = out.settings;
  const std::string unread =
      "; using the defaults, and leaving the file as it is (this run's settings are not saved)";
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (status.type() == fs::file_type::not_found) return out;  // first run: nothing saved yet
  if (ec) {  // a folder on the way that cannot be searched: the file may well be there
    out.warnings.push_back(file.string() + ": cannot look at it: " + ec.message() + unread);
    out.keepFile = true;
    return out;
  }
  std::string content;
  try {
    content = fileio::readWhole(file, kMaxSettingsBytes);
  } catch (const fileio::FileError& e) {
    out.warnings.push_back(e.what() + unread);
    out.keepFile = true;
    return out;
  }
  std::istringstream in(content);
  std::string line;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    const std::string where = file.string() + ":" + std::to_string(lineNo) + ": ";
    const std::string_view text = trim(line);
    if (text.empty() || text == kHeader) continue;
    if (text.front() == '#') {
      s.keptLines.emplace_back(text);
      continue;
    }
    const auto eq = text.find('=');
    if (eq == std::string_view::npos) {
      out.warnings.push_back(where + "expected 'key = value'" + kKept);
      s.keptLines.emplace_back(text);
      continue;
    }
    const std::string key(trim(text.substr(0, eq)));
    const std::string_view value = trim(text.substr(eq + 1));
    bool ok = true;
    std::string expected;
    if (key == "width" || key == "height") {
      ok = parseWindowSide(value, key == "width" ? s.windowWidth : s.windowHeight);
      expected = "a whole number from 100 to 16384";
    } else if (key == "showSimulation" || key == "showWorld" || key == "showDraw" || key == "showStats" ||
               key == "showRewind" || key == "showLab" || key == "markers") {
      bool& target = key == "showSimulation" ? s.showSimulation
                     : key == "showWorld"    ? s.showWorld
                     : key == "showDraw"     ? s.showDraw
                     : key == "showStats"    ? s.showStats
                     : key == "showRewind"   ? s.showRewind
                     : key == "showLab"      ? s.showLab
                                             : s.markers;
      ok = parseBool(value, target);
      expected = "true or false";
    } else if (key == "drawMode") {
      ok = parseDrawMode(value, s.drawMode);
      expected = "filled, wireframe or constraints";
    } else if (key == "colorBy") {
      ok = parseColoring(value, s.colorBy);
      expected = "kind, body, island or sleep";
    } else if (key == "throwSpeed") {
      ok = parseThrowSpeed(value, s.throwSpeed);
      expected = "a speed in m/s from 0 to " + std::to_string(static_cast<int>(kMaxThrowSpeed));
    } else if (key == "recordingBudget") {
      ok = parseBudget(value, s.recordingBudgetMb);
      expected = "a whole number of MB from " + std::to_string(kMinRecordingBudgetMb) + " to " +
                 std::to_string(kMaxRecordingBudgetMb);
    } else if (key == "lastScene") {
      s.lastScene = std::string(value);  // empty is valid: the default scene
    } else if (key == "recent") {
      // Written newest first; a hand-edited file may repeat a path or list too many.
      if (value.empty()) {
        ok = false;
        expected = "a file path";
      } else if (std::find(s.recentFiles.begin(), s.recentFiles.end(), value) == s.recentFiles.end() &&
                 s.recentFiles.size() < static_cast<std::size_t>(kMaxRecentFiles)) {
        s.recentFiles.emplace_back(value);
      }
    } else {
      out.warnings.push_back(where + "unknown key '" + key + "'" + kKept);
      s.keptLines.emplace_back(text);
      continue;
    }
    if (!ok) {
      out.warnings.push_back(where + "bad value '" + std::string(value) + "' for '" + key + "' (expected " +
                             expected + "); using the default, which replaces the line on closing");
    }
  }
  return out;
}

void saveUserSettings(const UserSettings& settings, const fs::path& file) {
  const fs::path folder = file.parent_path();
  if (!folder.empty()) {
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec)
      throw fileio::FileError(file, "cannot create the folder " + folder.string() + ": " + ec.message());
  }
  fileio::writeAtomically(file, toText(settings));
}

void addRecentFile(UserSettings& settings, const std::string& path) {
  if (path.empty()) return;
  auto& recent = settings.recentFiles;
  recent.erase(std::remove(recent.begin(), recent.end(), path), recent.end());
  recent.insert(recent.begin(), path);
  if (recent.size() > static_cast<std::size_t>(kMaxRecentFiles)) recent.resize(kMaxRecentFiles);
}

}  // namespace sandbox
