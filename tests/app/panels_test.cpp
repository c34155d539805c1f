// The panels (panels.h) driven through a headless ImGui context, as the user drives them: a slider
// typed into (Ctrl+click), a button pressed. No window and no GL: frames are built and thrown away.
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>  // to find where an item was drawn, for the mouse

#include <algorithm>
#include <string>
#include <vector>

#include "exact_ghost.h"
#include "panels.h"
#include "project_session.h"

namespace {

class PanelsUi : public ::testing::Test {
 protected:
  static constexpr int kEnter = 1;

  void SetUp() override {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(1280.0f, 1600.0f);  // tall enough that the open sections need no scrolling
    io.DeltaTime = 1.0f / 60.0f;
    io.KeyMap[ImGuiKey_Enter] = kEnter;
    unsigned char* pixels = nullptr;
    int width = 0;
    int height = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  }
  void TearDown() override { ImGui::DestroyContext(); }

  void frame() {
    ImGui::NewFrame();
    sandbox::drawPanels(session, ui);
    ImGui::Render();
  }
  // The text the panels draw in a frame, as ImGui's log captures it: the panels' window ends the
  // log and hands it to the clipboard (ImGui's own, in memory, with no platform behind it).
  std::string frameText() {
    ImGui::NewFrame();
    ImGui::LogToClipboard();
    sandbox::drawPanels(session, ui);
    ImGui::Render();
    return ImGui::GetClipboardText();
  }
  // What the status line shows (drawStatusAndCrosshair).
  std::string statusLine() const { return ui.message.empty() ? session.status() : ui.message; }

  // Moves the mouse over the item labelled `label` in the panels' column: across the column, row
  // by row, until ImGui says that item is hovered.
  void hover(const char* label) {
    frame();
    ImGuiWindow* panels = ImGui::FindWindowByName("Panels");
    ASSERT_NE(panels, nullptr);
    hover(panels, panels->GetID(label), label);
  }
  // The same over item `index` of the open combo's list: the index-th item met going down it.
  void hoverListItem(int index) {
    frame();  // the list sizes itself to its items in its first frames
    frame();
    ImGuiWindow* list = ImGui::FindWindowByName("##Combo_00");
    ASSERT_NE(list, nullptr);
    ImGuiIO& io = ImGui::GetIO();
    std::vector<ImGuiID> met;
    for (float y = list->Pos.y; y < list->Pos.y + list->Size.y; y += 2.0f) {
      io.MousePos = ImVec2(list->Pos.x + 20.0f, y);
      frame();
      const ImGuiID id = GImGui->HoveredId;
      if (id != 0 && std::find(met.begin(), met.end(), id) == met.end()) met.push_back(id);
      if (met.size() == static_cast<std::size_t>(index) + 1) return;
    }
    FAIL() << "no item " << index << " in the open list";
  }
  void hover(ImGuiWindow* window, ImGuiID id, const char* label) {
    ImGuiIO& io = ImGui::GetIO();
    for (float y = window->Pos.y; y < window->Pos.y + window->Size.y; y += 3.0f) {
      for (float x = window->Pos.x + 20.0f; x < window->Pos.x + window->Size.x; x += 50.0f) {
        io.MousePos = ImVec2(x, y);
        frame();
        if (GImGui->HoveredId == id) return;
      }
    }
    FAIL() << "no item '" << label << "' in " << window->Name;
  }
  void click(bool ctrl = false) {
    ImGuiIO& io = ImGui::GetIO();
    io.KeyCtrl = ctrl;
    io.MouseDown[0] = true;
    frame();
    io.MouseDown[0] = false;
    frame();
    io.KeyCtrl = false;
  }
  // Ctrl+click on the slider, type `text` in its place, Enter.
  void typeInto(const char* slider, const std::string& text) {
    hover(slider);
    click(true);
    for (char c : text) ImGui::GetIO().AddInputCharacter(static_cast<unsigned char>(c));
    frame();
    ImGui::GetIO().KeysDown[kEnter] = true;
    frame();
    ImGui::GetIO().KeysDown[kEnter] = false;
    frame();
  }

  sandbox::Session session = testing_app::openSession("ragdoll");
  sandbox::UiState ui;
};

// A time scale typed into its slider stays in the slider's range, 0.05 to 4, as every other
// slider's typed value does: 0 stopped the clock with no "PAUSED", and a negative one ran up a debt
// of simulated time that froze the world for as long again after the scale was set right.
TEST_F(PanelsUi, ATypedTimeScaleStaysInTheSlidersRange) {
  typeInto("time scale", "-2");
  EXPECT_FLOAT_EQ(ui.timeScale, 0.05f);
  typeInto("time scale", "0");
  EXPECT_FLOAT_EQ(ui.timeScale, 0.05f);
  typeInto("time scale", "1e9");
  EXPECT_FLOAT_EQ(ui.timeScale, 4.0f);
  typeInto("time scale", "0.5");
  EXPECT_FLOAT_EQ(ui.timeScale, 0.5f);
}

// What a control of the panels did is what the status line says, not what came before it: Stop
// overlay left "overlay of 2 runs" there, and the ground friction and the gravity mode's list left
// the last command's words ("opened ragdoll.xml", "threw a box").
TEST_F(PanelsUi, TheStatusLineSaysWhatAControlDid) {
  std::vector<sandbox::OverlaySpec> specs(2);
  specs[0] = sandbox::parseOverlaySpec("iterations=2").spec;
  specs[1] = sandbox::parseOverlaySpec("iterations=4").spec;
  ASSERT_EQ(session.startOverlay(specs), "");
  ui.message = session.status();  // as its Start button does
  hover("Stop overlay");
  click();
  ASSERT_FALSE(session.overlayActive());
  EXPECT_EQ(statusLine(), "overlay off; the solver settings are as before it");

  ASSERT_EQ(session.spawnBox(phys::Vec3(0.0, 8.0, 0.0), phys::Vec3(0.0)), "");
  ui.message = session.status();
  typeInto("ground friction", "0.3");
  EXPECT_DOUBLE_EQ(session.scene().world.worldSettings().groundMaterial.staticFriction, 0.3f);
  EXPECT_EQ(statusLine(), "world settings applied without restart");

  ui.unfolded[2] = true;  // the World section
  ui.resetLayout = true;
  hover("gravity (G)");
  click();
  hoverListItem(1);  // "point"
  click();
  ASSERT_EQ(session.scene().world.worldSettings().gravityMode, phys::GravityMode::Point);
  EXPECT_EQ(statusLine(), "gravity: towards the point");
}

// The ground friction slider sets static friction and keeps the scene's dynamic share of it, also
// through 0 (it fell back to 5/6 there, and the scene's own ratio was lost for the session).
TEST_F(PanelsUi, GroundFrictionKeepsTheScenesRatioThroughZero) {
  phys::WorldSettings w = session.scene().world.worldSettings();
  w.groundMaterial.staticFriction = 0.8;
  w.groundMaterial.dynamicFriction = 0.2;
  ASSERT_EQ(session.setWorldSettings(w), "");
  typeInto("ground friction", "0");
  EXPECT_EQ(session.scene().world.worldSettings().groundMaterial.dynamicFriction, 0.0);
  typeInto("ground friction", "0.4");
  const phys::Material& ground = session.scene().world.worldSettings().groundMaterial;
  EXPECT_NEAR(ground.staticFriction, 0.4, 1e-6);
  EXPECT_NEAR(ground.dynamicFriction / ground.staticFriction, 0.25, 1e-12);
}

// The Simulation panel's "Step (N)" does what N does: after B or the timeline it shows the
// recording's next step. It took a new step instead, forking the recording there and dropping
// every later step.
TEST_F(PanelsUi, StepGoesAlongTheRecordingAsNDoes) {
  for (int i = 0; i < 100; ++i) session.step();
  ASSERT_EQ(session.rewindTo(50), "");
  ui.paused = true;
  hover("Step (N)");
  click();
  EXPECT_EQ(session.scene().world.stepCount(), 51);
  EXPECT_FALSE(ui.stepOnce);
  EXPECT_EQ(session.recording().last(), 100);
  EXPECT_EQ(statusLine(), session.status());

  // At the recording's end it asks for a new step, which the sandbox takes.
  ASSERT_EQ(session.rewindTo(100), "");
  click();
  EXPECT_TRUE(ui.stepOnce);
}

// The Simulation panel's "Pause (Space)" does what Space does in every state. During Play (which
// shows the recording paused) unticking it left Play going, where Space stops it, paused at the
// step shown.
TEST_F(PanelsUi, PauseDoesWhatSpaceDoes) {
  for (int i = 0; i < 100; ++i) session.step();
  ASSERT_EQ(session.rewindTo(10), "");
  ui.paused = true;
  hover("Play");
  click();
  ASSERT_TRUE(ui.replaying);
  ASSERT_TRUE(ui.paused);

  hover("Pause (Space)");
  click();
  EXPECT_FALSE(ui.replaying);
  EXPECT_TRUE(ui.paused);
  EXPECT_EQ(session.scene().world.stepCount(), 10);

  click();  // paused: runs
  EXPECT_FALSE(ui.paused);
  click();  // running: pauses
  EXPECT_TRUE(ui.paused);
  EXPECT_FALSE(ui.replaying);
}

// The Draw section says why the scene's exact answer is not drawn, in the ghost's words
// (ExactGhost::hiddenBecause, which the sandbox hands it each frame), and says nothing while it is
// drawn or while exact answers are off.
TEST_F(PanelsUi, TheDrawSectionSaysWhyTheExactAnswerIsHidden) {
  ASSERT_EQ(session.openBuiltin("projectile"), "");
  sandbox::ExactGhost ghost;
  ghost.reset(session.scene());
  ui.unfolded[3] = true;  // the Draw section
  ui.resetLayout = true;
  auto shownLine = [&]() {
    ui.exactHidden = ghost.hiddenBecause(session.scene().world);  // as Sandbox::renderFrame does
    const std::string text = frameText();
    EXPECT_NE(text.find("] exact answers"), std::string::npos) << "the Draw section is not drawn:\n" << text;
    const std::size_t at = text.find("exact answer hidden");
    return at == std::string::npos ? std::string() : text.substr(at, text.find('\n', at) - at);
  };
  EXPECT_EQ(shownLine(), "");

  ASSERT_EQ(session.changeGravity(1.0), "");
  ASSERT_EQ(session.changeDamping(0.1), "");
  EXPECT_EQ(shownLine(), "exact answer hidden: gravity and damping changed");
  session.clear();
  EXPECT_EQ(shownLine(), "exact answer hidden: the scene's bodies are gone");
  ui.draw.exact = false;  // nothing drawn, so nothing hidden to explain
  EXPECT_EQ(shownLine(), "");
}

}  // namespace
