// The file browser: its folder listing, what the typed path means, and the dialog itself driven
// through a headless ImGui context (no window, no GL: frames are built and thrown away).
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>  // to find where the listing's rows are, for the mouse
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "file_dialog.h"
#include "temp_folder.h"

namespace {

namespace fs = std::filesystem;
using sandbox::DirectoryEntry;
using sandbox::FileDialog;
using sandbox::FileDialogMode;
using sandbox::TypedPath;

const fs::path kScenes = fs::path(DATA_DIR) / "assets" / "scenes";

std::vector<std::string> names(const std::vector<DirectoryEntry>& entries) {
  std::vector<std::string> out;
  out.reserve(entries.size());
  for (const auto& e : entries) out.push_back(e.isFolder ? e.name + "/" : e.name);
  return out;
}

using testing_app::TempFolder;

TEST(ListDirectory, ScenesFolderListsParentThenSortedXmlFiles) {
  std::string error = "stale";
  const auto entries = sandbox::listDirectory(kScenes, ".xml", &error);
  EXPECT_EQ(error, "");
  ASSERT_GE(entries.size(), 2u);
  EXPECT_EQ(entries.front().name, "..");
  EXPECT_TRUE(entries.front().isFolder);
  std::vector<std::string> files;
  for (const auto& e : entries) {
    if (e.isFolder) continue;
    EXPECT_TRUE(e.name.ends_with(".xml")) << e.name;
    files.push_back(e.name);
  }
  EXPECT_NE(std::find(files.begin(), files.end(), "ragdoll.xml"), files.end());
  EXPECT_TRUE(std::is_sorted(files.begin(), files.end()));
}

TEST(ListDirectory, FoldersFirstThenMatchingFilesEachSortedIgnoringCase) {
  TempFolder dir;
  fs::create_directory(dir.path / "beta");
  fs::create_directory(dir.path / "Alpha");
  for (const char* f : {"z.xml", "a.xml", "notes.txt", "Y.XML", "xml"}) dir.touch(f);
  EXPECT_EQ(names(sandbox::listDirectory(dir.path, ".xml")),
            (std::vector<std::string>{"../", "Alpha/", "beta/", "a.xml", "Y.XML", "z.xml"}));
  // No extension wanted: every file.
  EXPECT_EQ(
      names(sandbox::listDirectory(dir.path, "")),
      (std::vector<std::string>{"../", "Alpha/", "beta/", "a.xml", "notes.txt", "xml", "Y.XML", "z.xml"}));
}

TEST(ListDirectory, AMissingFolderGivesNothingAndSaysWhy) {
  std::string error;
  const fs::path missing = kScenes / "no-such-folder";
  EXPECT_TRUE(sandbox::listDirectory(missing, ".xml", &error).empty());
  EXPECT_NE(error.find(missing.string()), std::string::npos) << error;
  EXPECT_TRUE(sandbox::listDirectory(kScenes / "ragdoll.xml", ".xml", &error).empty());  // a file
  EXPECT_FALSE(error.empty());
  EXPECT_TRUE(sandbox::listDirectory(missing, ".xml").empty());  // no error wanted: still fine
}

TEST(ListDirectory, TheRootHasNoParentEntry) {
  const auto entries = sandbox::listDirectory("/", ".xml");
  ASSERT_FALSE(entries.empty());
  EXPECT_NE(entries.front().name, "..");
}

TEST(FileDialogTypedPath, OpenWantsAnExistingFile) {
  const TypedPath file = sandbox::resolveTypedPath(FileDialogMode::Open, kScenes, "ragdoll.xml");
  EXPECT_EQ(file.action, TypedPath::Action::Choose);
  EXPECT_EQ(file.path, kScenes / "ragdoll.xml");

  const TypedPath missing = sandbox::resolveTypedPath(FileDialogMode::Open, kScenes, "nope.xml");
  EXPECT_EQ(missing.action, TypedPath::Action::Refuse);
  EXPECT_NE(missing.message.find("nope.xml"), std::string::npos) << missing.message;

  const TypedPath folder = sandbox::resolveTypedPath(FileDialogMode::Open, kScenes, "..");
  EXPECT_EQ(folder.action, TypedPath::Action::EnterFolder);
  EXPECT_EQ(folder.path, fs::absolute(fs::path(DATA_DIR) / "assets").lexically_normal());

  const TypedPath absolute =
      sandbox::resolveTypedPath(FileDialogMode::Open, "/", (kScenes / "chain.xml").string());
  EXPECT_EQ(absolute.action, TypedPath::Action::Choose);
  EXPECT_EQ(absolute.path, kScenes / "chain.xml");

  EXPECT_EQ(sandbox::resolveTypedPath(FileDialogMode::Open, kScenes, "").action, TypedPath::Action::Refuse);
}

TEST(FileDialogTypedPath, SaveWantsAnExistingFolderAndAddsXml) {
  TempFolder dir;
  const TypedPath plain = sandbox::resolveTypedPath(FileDialogMode::Save, dir.path, "my-scene");
  EXPECT_EQ(plain.action, TypedPath::Action::Choose);
  EXPECT_EQ(plain.path, dir.path / "my-scene.xml");

  const TypedPath other = sandbox::resolveTypedPath(FileDialogMode::Save, dir.path, "my.scene");
  EXPECT_EQ(other.path, dir.path / "my.scene");  // an extension given is kept

  // A recording's dialog adds its own.
  EXPECT_EQ(sandbox::resolveTypedPath(FileDialogMode::Save, dir.path, "run", ".jrec").path,
            dir.path / "run.jrec");

  EXPECT_FALSE(plain.replaces);
  dir.touch("old.xml");
  const TypedPath old = sandbox::resolveTypedPath(FileDialogMode::Save, dir.path, "old.xml");
  EXPECT_EQ(old.action, TypedPath::Action::Choose);
  EXPECT_TRUE(old.replaces);  // the dialog asks first

  const TypedPath noFolder = sandbox::resolveTypedPath(FileDialogMode::Save, dir.path, "missing/x.xml");
  EXPECT_EQ(noFolder.action, TypedPath::Action::Refuse);
  EXPECT_NE(noFolder.message.find("missing"), std::string::npos) << noFolder.message;
}

// A path that cannot be looked at is not called missing: the system's reason is told (a name
// longer than a file system allows stands for an unsearchable folder too, which CI's root would
// not meet).
TEST(FileDialogTypedPath, APathThatCannotBeLookedAtIsToldWithItsReason) {
  TempFolder dir;
  const std::string tooLong = std::string(300, 'a') + "/x.xml";
  for (const FileDialogMode mode : {FileDialogMode::Open, FileDialogMode::Save}) {
    const TypedPath typed = sandbox::resolveTypedPath(mode, dir.path, tooLong);
    EXPECT_EQ(typed.action, TypedPath::Action::Refuse);
    EXPECT_NE(typed.message.find("cannot look at " + (dir.path / tooLong).string() + ": File name too long"),
              std::string::npos)
        << typed.message;
  }
}

// One ImGui context per test with a fake display and a built font atlas, which is all NewFrame()
// needs; no platform or renderer backend. Keys are mapped to made-up indices.
class FileDialogUi : public ::testing::Test {
 protected:
  static constexpr int kEnter = 1;
  static constexpr int kEscape = 2;

  void SetUp() override {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(800.0f, 600.0f);
    io.DeltaTime = 1.0f / 60.0f;
    io.KeyMap[ImGuiKey_Enter] = kEnter;
    io.KeyMap[ImGuiKey_Escape] = kEscape;
    unsigned char* pixels = nullptr;
    int width = 0;
    int height = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  }
  void TearDown() override { ImGui::DestroyContext(); }

  std::optional<fs::path> frame() {
    ImGui::NewFrame();
    auto chosen = dialog.draw();
    popupOpen = ImGui::IsPopupOpen(kTitle);  // asked inside the frame, from the same ID stack as draw()
    ImGui::Render();
    return chosen;
  }
  // Runs frames until the dialog has settled (popup open, path field focused) and half a second
  // has passed, so the next click is not counted as part of a double or triple click.
  void settle() {
    for (int i = 0; i < 30; ++i) ASSERT_FALSE(frame().has_value());
  }
  void type(const std::string& text) {
    for (char c : text) ImGui::GetIO().AddInputCharacter(static_cast<unsigned char>(c));
    ASSERT_FALSE(frame().has_value());
  }
  std::optional<fs::path> press(int key) {
    ImGui::GetIO().KeysDown[key] = true;
    auto chosen = frame();
    ImGui::GetIO().KeysDown[key] = false;
    auto after = frame();
    return chosen ? chosen : after;
  }

  // Where row `row` of the listing was drawn in the last frame: the child window "entries" starts
  // its rows at CursorStartPos, one text line (plus item spacing) apart.
  ImVec2 rowCenter(int row) {
    for (ImGuiWindow* w : GImGui->Windows) {
      if (std::strstr(w->Name, "/entries_") != nullptr) {
        const float pitch = ImGui::GetTextLineHeightWithSpacing();
        return ImVec2(w->DC.CursorStartPos.x + 20.0f,
                      w->DC.CursorStartPos.y + static_cast<float>(row) * pitch + ImGui::GetFontSize() * 0.5f);
      }
    }
    ADD_FAILURE() << "no listing window";
    return ImVec2(-1.0f, -1.0f);
  }
  // Presses and releases the left button over `row`, `times` times in quick succession; returns
  // whatever the dialog chose on the way.
  std::optional<fs::path> click(int row, int times = 1) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = rowCenter(row);
    std::optional<fs::path> chosen;
    for (int i = 0; i < times; ++i) {
      io.MouseDown[0] = true;
      if (auto c = frame()) chosen = c;
      io.MouseDown[0] = false;
      if (auto c = frame()) chosen = c;
    }
    return chosen;
  }

  static constexpr const char* kTitle = "Choose a scene";
  FileDialog dialog;
  bool popupOpen = false;  ///< after the last frame
};

TEST_F(FileDialogUi, AClosedDialogDrawsNothing) {
  EXPECT_FALSE(dialog.isOpen());
  EXPECT_FALSE(frame().has_value());
}

TEST_F(FileDialogUi, AnOpenDialogDrawsAndWaits) {
  dialog.open(FileDialogMode::Open, kScenes, kTitle);
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(frame().has_value());
  EXPECT_TRUE(dialog.isOpen());
  EXPECT_TRUE(popupOpen);
}

TEST_F(FileDialogUi, TypingANameAndEnterOpensIt) {
  dialog.open(FileDialogMode::Open, kScenes, kTitle);
  settle();
  type("ragdoll.xml");
  const auto chosen = press(kEnter);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(*chosen, fs::absolute(kScenes / "ragdoll.xml").lexically_normal());
  EXPECT_FALSE(dialog.isOpen());
  EXPECT_FALSE(frame().has_value());  // once only
}

TEST_F(FileDialogUi, TypingAFolderEntersItAndTheFieldKeepsTheKeyboard) {
  dialog.open(FileDialogMode::Open, fs::path(DATA_DIR) / "assets", kTitle);
  settle();
  type("scenes");
  EXPECT_FALSE(press(kEnter).has_value());
  EXPECT_TRUE(dialog.isOpen());
  settle();
  type("chain.xml");  // resolved against the folder just entered
  const auto chosen = press(kEnter);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(*chosen, fs::absolute(kScenes / "chain.xml").lexically_normal());
}

TEST_F(FileDialogUi, AMissingFileKeepsTheDialogOpen) {
  dialog.open(FileDialogMode::Open, kScenes, kTitle);
  settle();
  type("nope.xml");
  EXPECT_FALSE(press(kEnter).has_value());
  EXPECT_TRUE(dialog.isOpen());
}

TEST_F(FileDialogUi, SaveAddsXml) {
  TempFolder dir;
  dialog.open(FileDialogMode::Save, dir.path, kTitle);
  settle();
  type("mine");
  const auto chosen = press(kEnter);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(*chosen, fs::absolute(dir.path / "mine.xml").lexically_normal());
}

// A recording saved as "ragdoll.xml" wrote over the scene without a word. Save onto a file that
// exists now only says so; a second Save (the button reads Replace) writes over it, and another
// name typed in between, even of a file that exists too, is asked about afresh.
TEST_F(FileDialogUi, SaveAsksBeforeWritingOverAFile) {
  TempFolder dir;
  dir.touch("scene.xml");
  dir.touch("scene.xmlx");
  dir.touch("other.xml");
  dialog.open(FileDialogMode::Save, dir.path, kTitle, ".jrec");
  settle();
  type("scene.xml");
  EXPECT_FALSE(press(kEnter).has_value());
  EXPECT_TRUE(dialog.isOpen());
  EXPECT_NE(dialog.message().find("scene.xml exists"), std::string::npos) << dialog.message();
  settle();
  type("x");  // "scene.xmlx": the question was of scene.xml, and goes with it
  EXPECT_EQ(dialog.message(), "");
  EXPECT_FALSE(press(kEnter).has_value());  // asked again, of scene.xmlx
  EXPECT_NE(dialog.message().find("scene.xmlx exists"), std::string::npos) << dialog.message();
  settle();
  const auto second = press(kEnter);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(*second, fs::absolute(dir.path / "scene.xmlx").lexically_normal());

  dialog.open(FileDialogMode::Save, dir.path, kTitle);
  settle();
  type("other");
  EXPECT_FALSE(press(kEnter).has_value());
  settle();
  const auto replaced = press(kEnter);
  ASSERT_TRUE(replaced.has_value());
  EXPECT_EQ(*replaced, fs::absolute(dir.path / "other.xml").lexically_normal());
}

TEST_F(FileDialogUi, ClickingParentThenDoubleClickingAFileOpensIt) {
  dialog.open(FileDialogMode::Open, kScenes / "..", kTitle);  // assets: .., clips/, models/, scenes/
  settle();
  EXPECT_FALSE(click(3).has_value());  // scenes/: entered on one click
  settle();
  // The row of chain.xml in the listing, whatever other scenes the folder holds.
  const auto entries = sandbox::listDirectory(kScenes, ".xml");
  const auto chain = std::find_if(entries.begin(), entries.end(),
                                  [](const DirectoryEntry& e) { return e.name == "chain.xml"; });
  ASSERT_NE(chain, entries.end());
  const auto chosen = click(static_cast<int>(chain - entries.begin()), 2);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(*chosen, fs::absolute(kScenes / "chain.xml").lexically_normal());
  EXPECT_FALSE(dialog.isOpen());
}

TEST_F(FileDialogUi, ASingleClickOnAFileOnlyPicksIt) {
  dialog.open(FileDialogMode::Open, kScenes, kTitle);
  settle();
  EXPECT_FALSE(click(3).has_value());
  EXPECT_TRUE(dialog.isOpen());
  settle();
  const auto chosen = press(kEnter);  // nothing focused: Enter does nothing
  EXPECT_FALSE(chosen.has_value());
}

TEST_F(FileDialogUi, DoubleClickingAFolderDoesNotOpenTheFileThatTakesItsPlace) {
  TempFolder dir;
  fs::create_directory(dir.path / "sub");
  std::ofstream(dir.path / "sub" / "a.xml") << "x";
  dialog.open(FileDialogMode::Open, dir.path, kTitle);  // .., sub/
  settle();
  // The first click enters sub/; the second lands on a.xml, now row 1, and only picks it.
  EXPECT_FALSE(click(1, 2).has_value());
  EXPECT_TRUE(dialog.isOpen());
  settle();
  const auto chosen = click(1, 2);  // a double click on the picked file confirms
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(*chosen, fs::absolute(dir.path / "sub" / "a.xml").lexically_normal());
}

// A file picked in a folder whose path does not fit the 1023-byte field is picked by its name,
// which resolves against the folder shown: the full path cut short named another file (here
// "a.xml" for "a.xml.xml").
TEST_F(FileDialogUi, AFileInAFolderTooDeepForTheFieldIsPickedWhole) {
  TempFolder dir;
  fs::path deep = dir.path;
  while (deep.string().size() < 1015) deep /= std::string(100, 'd');
  fs::create_directories(deep);
  std::ofstream(deep / "a.xml.xml") << "x";
  std::ofstream(deep / "a.xml") << "x";
  ASSERT_GT((deep / "a.xml.xml").string().size(), 1023u);
  dialog.open(FileDialogMode::Open, deep, kTitle);  // .., a.xml, a.xml.xml
  settle();
  EXPECT_FALSE(click(2).has_value());
  settle();
  const auto chosen = click(2, 2);  // a double click on the picked file confirms
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(*chosen, fs::absolute(deep / "a.xml.xml").lexically_normal());
}

TEST_F(FileDialogUi, EscapeCancels) {
  dialog.open(FileDialogMode::Open, kScenes, kTitle);
  settle();
  EXPECT_FALSE(press(kEscape).has_value());
  EXPECT_FALSE(dialog.isOpen());
  EXPECT_FALSE(popupOpen);
}

}  // namespace
