// The panels (panels.h) driven through a headless ImGui context, as the user drives them: a slider
// typed into (Ctrl+click), a button pressed. No window and no GL: frames are built and thrown away.
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>  // to find where an item was drawn, for the mouse

#include <string>

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
  // What the status line shows (drawStatusAndCrosshair).
  std::string statusLine() const { return ui.message.empty() ? session.status() : ui.message; }

  // Moves the mouse over the item labelled `label` in the panels' column: down the column's left
  // side until ImGui says that item is hovered.
  void hover(const char* label) {
    frame();
    ImGuiWindow* panels = ImGui::FindWindowByName("Panels");
    ASSERT_NE(panels, nullptr);
    const ImGuiID id = panels->GetID(label);
    ImGuiIO& io = ImGui::GetIO();
    for (float y = panels->Pos.y; y < panels->Pos.y + panels->Size.y; y += 3.0f) {
      for (float x : {panels->Pos.x + 20.0f, panels->Pos.x + 120.0f}) {
        io.MousePos = ImVec2(x, y);
        frame();
        if (GImGui->HoveredId == id) return;
      }
    }
    FAIL() << "no item '" << label << "' in the panels";
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

}  // namespace
