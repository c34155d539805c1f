// The settings file: what survives a save and load, what a hand-edited bad line does, and where
// the file lives.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "user_settings.h"

namespace {

namespace fs = std::filesystem;
using sandbox::UserSettings;

// A fresh folder per test, removed afterwards.
class UserSettingsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ =
        fs::temp_directory_path() / ("sandbox-settings-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) {
    fs::path file = dir_ / name;
    std::ofstream(file) << text;
    return file;
  }

  // Names of the files in dir_, to catch a temporary file left behind.
  std::vector<std::string> filesIn(const fs::path& folder) {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(folder))
      names.push_back(e.path().filename().string());
    return names;
  }

  fs::path dir_;
};

bool containsAll(const std::string& text, std::initializer_list<const char*> parts) {
  for (const char* p : parts) {
    if (text.find(p) == std::string::npos) return false;
  }
  return true;
}

TEST_F(UserSettingsTest, EveryFieldSurvivesSaveAndLoad) {
  UserSettings s;
  s.windowWidth = 1600;
  s.windowHeight = 900;
  s.showSimulation = false;
  s.showWorld = true;
  s.showDraw = false;
  s.showStats = false;
  s.lastScene = "/home/someone/my scenes/chain = long.xml";  // a space and an '=' in the value
  s.drawMode = "wireframe";
  s.markers = true;
  s.showRewind = false;
  s.showLab = false;
  s.colorBy = "island";
  s.throwSpeed = 12.5f;
  s.recordingBudgetMb = 64;
  s.recentFiles = {"/a/one.xml", "/b/two.xml", "relative/three.xml"};
  const fs::path file = dir_ / "nested" / "folder" / "settings.ini";  // the folders do not exist yet
  sandbox::saveUserSettings(s, file);

  const auto loaded = sandbox::loadUserSettings(file);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  const UserSettings& r = loaded.settings;
  EXPECT_EQ(r.windowWidth, 1600);
  EXPECT_EQ(r.windowHeight, 900);
  EXPECT_FALSE(r.showSimulation);
  EXPECT_TRUE(r.showWorld);
  EXPECT_FALSE(r.showDraw);
  EXPECT_FALSE(r.showStats);
  EXPECT_EQ(r.lastScene, s.lastScene);
  EXPECT_EQ(r.drawMode, "wireframe");
  EXPECT_TRUE(r.markers);
  EXPECT_FALSE(r.showRewind);
  EXPECT_FALSE(r.showLab);
  EXPECT_EQ(r.colorBy, "island");
  EXPECT_EQ(r.throwSpeed, 12.5f);
  EXPECT_EQ(r.recordingBudgetMb, 64);
  EXPECT_EQ(r.recentFiles, s.recentFiles);
  EXPECT_EQ(filesIn(dir_ / "nested" / "folder"), std::vector<std::string>{"settings.ini"});
}

TEST_F(UserSettingsTest, SavingTwiceReplacesTheFile) {
  const fs::path file = dir_ / "settings.ini";
  UserSettings s;
  s.recentFiles = {"/x.xml", "/y.xml"};
  sandbox::saveUserSettings(s, file);
  s.recentFiles = {"/z.xml"};
  s.drawMode = "constraints";
  sandbox::saveUserSettings(s, file);
  const auto loaded = sandbox::loadUserSettings(file);
  EXPECT_EQ(loaded.settings.recentFiles, std::vector<std::string>{"/z.xml"});
  EXPECT_EQ(loaded.settings.drawMode, "constraints");
}

TEST_F(UserSettingsTest, BadLinesAreSkippedWithTheirLineAndKey) {
  const fs::path file = write("settings.ini",
                              "# a comment\n"
                              "\n"
                              "width = abc\n"              // line 3
                              "height = 50\n"              // line 4: below 100
                              "drawMode = sketchy\n"       // line 5
                              "markers = yes\n"            // line 6
                              "colour = blue\n"            // line 7: unknown
                              "no equals sign here\n"      // line 8
                              "colorBy = rainbow\n"        // line 9
                              "throwSpeed = 41\n"          // line 10: beyond the slider
                              "recordingBudget = 8\n"      // line 11: below 16 MB
                              "  showStats = false  \r\n"  // good, with spaces and a CR
                              "lastScene = /s/ragdoll.xml\n"
                              "recent = /r/1.xml\n");
  const auto loaded = sandbox::loadUserSettings(file);
  const std::string name = file.string();
  ASSERT_EQ(loaded.warnings.size(), 9u);
  EXPECT_TRUE(containsAll(loaded.warnings[0], {":3:", "'width'", "'abc'"})) << loaded.warnings[0];
  EXPECT_TRUE(containsAll(loaded.warnings[1], {":4:", "'height'", "'50'"})) << loaded.warnings[1];
  EXPECT_TRUE(containsAll(loaded.warnings[2], {":5:", "'drawMode'", "'sketchy'"})) << loaded.warnings[2];
  EXPECT_TRUE(containsAll(loaded.warnings[3], {":6:", "'markers'", "'yes'"})) << loaded.warnings[3];
  EXPECT_EQ(loaded.warnings[4], name + ":7: unknown key 'colour'; kept in the file as it is");
  EXPECT_TRUE(containsAll(loaded.warnings[5], {":8:"})) << loaded.warnings[5];
  EXPECT_TRUE(
      containsAll(loaded.warnings[6], {":9:", "'colorBy'", "'rainbow'", "kind, body, island or sleep"}))
      << loaded.warnings[6];
  EXPECT_TRUE(containsAll(loaded.warnings[7], {":10:", "'throwSpeed'", "'41'", "from 0 to 40"}))
      << loaded.warnings[7];
  EXPECT_TRUE(containsAll(loaded.warnings[8], {":11:", "'recordingBudget'", "'8'", "from 16 to 8192"}))
      << loaded.warnings[8];
  for (const std::string& w : loaded.warnings) EXPECT_EQ(w.rfind(name + ":", 0), 0u) << w;

  const UserSettings defaults;
  const UserSettings& s = loaded.settings;
  EXPECT_EQ(s.windowWidth, defaults.windowWidth);
  EXPECT_EQ(s.windowHeight, defaults.windowHeight);
  EXPECT_EQ(s.drawMode, defaults.drawMode);
  EXPECT_EQ(s.markers, defaults.markers);
  EXPECT_FALSE(s.colorBy || s.throwSpeed || s.recordingBudgetMb);
  EXPECT_FALSE(s.showStats);
  EXPECT_EQ(s.lastScene, "/s/ragdoll.xml");
  EXPECT_EQ(s.recentFiles, std::vector<std::string>{"/r/1.xml"});
  EXPECT_TRUE(containsAll(loaded.warnings[0], {"using the default, which replaces the line on closing"}))
      << loaded.warnings[0];
}

// What this version does not understand (a key of a newer one, a typo, a comment) is written back
// as it was when the file is saved, and read back the same; a known key's bad value is replaced.
TEST_F(UserSettingsTest, LinesNotUnderstoodSurviveASave) {
  const fs::path file = write("settings.ini",
                              "# my own note\n"
                              "width = abc\n"
                              "futureKey = 3\n"
                              "no equals sign here\n"
                              "height = 800\n");
  const auto loaded = sandbox::loadUserSettings(file);
  EXPECT_EQ(loaded.settings.keptLines,
            (std::vector<std::string>{"# my own note", "futureKey = 3", "no equals sign here"}));
  sandbox::saveUserSettings(loaded.settings, file);
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(containsAll(text, {"# my own note\n", "futureKey = 3\n", "no equals sign here\n",
                                 "height = 800\n", "width = 1280\n"}))
      << text;
  EXPECT_EQ(text.find("abc"), std::string::npos) << text;
  const auto again = sandbox::loadUserSettings(file);
  EXPECT_EQ(again.settings.keptLines, loaded.settings.keptLines) << "kept once, not once more per save";
  EXPECT_EQ(again.settings.windowHeight, 800);
  EXPECT_EQ(again.warnings.size(), 2u) << "the unknown key and the line without '=' are still told";
}

TEST_F(UserSettingsTest, WindowSizeLimitsAreInclusive) {
  const auto loaded = sandbox::loadUserSettings(write("s.ini", "width = 100\nheight = 16384\n"));
  EXPECT_TRUE(loaded.warnings.empty());
  EXPECT_EQ(loaded.settings.windowWidth, 100);
  EXPECT_EQ(loaded.settings.windowHeight, 16384);
  EXPECT_EQ(sandbox::loadUserSettings(write("t.ini", "width = 16385\nheight = 12x\n")).warnings.size(), 2u);
}

TEST_F(UserSettingsTest, AMissingFileGivesTheDefaultsQuietly) {
  const auto loaded = sandbox::loadUserSettings(dir_ / "never-written.ini");
  EXPECT_TRUE(loaded.warnings.empty());
  const UserSettings defaults;
  EXPECT_EQ(loaded.settings.windowWidth, defaults.windowWidth);
  EXPECT_EQ(loaded.settings.drawMode, defaults.drawMode);
  EXPECT_TRUE(loaded.settings.recentFiles.empty());
}

// A file that is there but cannot be read is the user's still: the sandbox must not replace it with
// the defaults on exit (keepFile). Too large and a folder stand for every reason, permission
// included, that CI's root would not meet.
TEST_F(UserSettingsTest, AFileThatCannotBeReadIsMarkedToBeKept) {
  const fs::path large = write("large.ini", "width = 800\n" + std::string(std::size_t{2} << 20, '#') + "\n");
  fs::create_directories(dir_ / "folder.ini");
  for (const fs::path& file : {large, dir_ / "folder.ini"}) {
    const auto loaded = sandbox::loadUserSettings(file);
    EXPECT_TRUE(loaded.keepFile) << file;
    ASSERT_EQ(loaded.warnings.size(), 1u) << file;
    EXPECT_TRUE(containsAll(loaded.warnings[0], {file.string().c_str(), "leaving the file as it is"}))
        << loaded.warnings[0];
    EXPECT_EQ(loaded.settings.windowWidth, UserSettings().windowWidth);
  }
  EXPECT_FALSE(sandbox::loadUserSettings(dir_ / "never-written.ini").keepFile);
  EXPECT_FALSE(sandbox::loadUserSettings(write("bad.ini", "width = wide\n")).keepFile);  // read, line skipped
}

// A path that cannot even be looked at (a name too long, a folder that cannot be searched) is not
// taken for a first run: the system's reason is told and the file is left alone.
TEST_F(UserSettingsTest, APathThatCannotBeLookedAtIsToldWithItsReason) {
  const fs::path file = dir_ / std::string(300, 'a') / "sandbox.ini";
  const auto loaded = sandbox::loadUserSettings(file);
  EXPECT_TRUE(loaded.keepFile);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_TRUE(
      containsAll(loaded.warnings[0], {"cannot look at it: File name too long", "leaving the file as it is"}))
      << loaded.warnings[0];
}

TEST_F(UserSettingsTest, ALoadedRecentListIsDedupedAndCapped) {
  std::string text = "recent = /dup.xml\nrecent = /dup.xml\n";
  for (int i = 0; i < 20; ++i) text += "recent = /f" + std::to_string(i) + ".xml\n";
  const auto loaded = sandbox::loadUserSettings(write("s.ini", text));
  ASSERT_EQ(loaded.settings.recentFiles.size(), static_cast<std::size_t>(sandbox::kMaxRecentFiles));
  EXPECT_EQ(loaded.settings.recentFiles[0], "/dup.xml");
  EXPECT_EQ(loaded.settings.recentFiles[1], "/f0.xml");
}

TEST(UserSettingsRecent, AddPutsNewestFirstDedupesAndCaps) {
  UserSettings s;
  sandbox::addRecentFile(s, "/a.xml");
  sandbox::addRecentFile(s, "/b.xml");
  sandbox::addRecentFile(s, "/a.xml");
  EXPECT_EQ(s.recentFiles, (std::vector<std::string>{"/a.xml", "/b.xml"}));
  for (int i = 0; i < 20; ++i) sandbox::addRecentFile(s, "/f" + std::to_string(i) + ".xml");
  ASSERT_EQ(s.recentFiles.size(), static_cast<std::size_t>(sandbox::kMaxRecentFiles));
  EXPECT_EQ(s.recentFiles.front(), "/f19.xml");
  EXPECT_EQ(s.recentFiles.back(), "/f" + std::to_string(20 - sandbox::kMaxRecentFiles) + ".xml");
  sandbox::addRecentFile(s, "");  // nothing to remember
  EXPECT_EQ(s.recentFiles.front(), "/f19.xml");
}

TEST_F(UserSettingsTest, SavingUnderARegularFileThrowsNamingTheFile) {
  write("plain-file", "not a folder");
  const fs::path file = dir_ / "plain-file" / "sub" / "settings.ini";
  try {
    sandbox::saveUserSettings(UserSettings{}, file);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(file.string() + ": cannot create the folder ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("Not a directory"), std::string::npos) << e.what();
  }
  EXPECT_EQ(filesIn(dir_), std::vector<std::string>{"plain-file"});
}

TEST_F(UserSettingsTest, AFailedRenameRemovesTheTemporaryFile) {
  // The target is a folder with something in it, so writing the temporary file works and the
  // rename over it fails.
  const fs::path file = dir_ / "settings.ini";
  fs::create_directories(file / "inside");
  EXPECT_THROW(sandbox::saveUserSettings(UserSettings{}, file), std::runtime_error);
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"settings.ini"});
}

// Sets or unsets an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value != nullptr) {
      ::setenv(name, value, 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(UserSettingsConfigDirectory, XdgConfigHomeThenHomeThenNothing) {
  {
    ScopedEnv xdg("XDG_CONFIG_HOME", "/xdg/config");
    ScopedEnv home("HOME", "/home/someone");
    EXPECT_EQ(sandbox::configDirectory(), fs::path("/xdg/config/jakobsen-sandbox"));
  }
  {
    ScopedEnv xdg("XDG_CONFIG_HOME", "");  // set but empty counts as unset
    ScopedEnv home("HOME", "/home/someone");
    EXPECT_EQ(sandbox::configDirectory(), fs::path("/home/someone/.config/jakobsen-sandbox"));
  }
  {
    ScopedEnv xdg("XDG_CONFIG_HOME", nullptr);
    ScopedEnv home("HOME", "/home/someone");
    EXPECT_EQ(sandbox::configDirectory(), fs::path("/home/someone/.config/jakobsen-sandbox"));
  }
  {
    ScopedEnv xdg("XDG_CONFIG_HOME", nullptr);
    ScopedEnv home("HOME", nullptr);
    EXPECT_EQ(sandbox::configDirectory(), fs::path());
  }
}

}  // namespace
