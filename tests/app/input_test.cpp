// The sandbox's input layer: held keys, presses, and the release of everything on focus loss
// (the seed's stuck-key bug).
#include <gtest/gtest.h>

#include "input.h"

namespace {

constexpr int kW = 87;     // GLFW_KEY_W
constexpr int kRight = 1;  // GLFW_MOUSE_BUTTON_RIGHT

TEST(InputState, AKeyIsHeldFromDownToUp) {
  sandbox::InputState in;
  EXPECT_FALSE(in.held(kW));
  in.keyDown(kW);
  EXPECT_TRUE(in.held(kW));
  in.keyUp(kW);
  EXPECT_FALSE(in.held(kW));
}

TEST(InputState, APressIsReportedForOneFrameOnly) {
  sandbox::InputState in;
  in.keyDown(kW);
  EXPECT_TRUE(in.pressed(kW));
  in.endFrame();
  EXPECT_FALSE(in.pressed(kW));
  in.keyDown(kW);  // a key repeat: still held, not a new press
  EXPECT_FALSE(in.pressed(kW));
  EXPECT_TRUE(in.held(kW));
}

TEST(InputState, LosingFocusReleasesEveryKeyAndButton) {
  sandbox::InputState in;
  in.keyDown(kW);
  in.keyDown(340);  // left shift
  in.buttonDown(kRight);
  in.focusLost();
  // The key-up events went to another window; nothing may stay held.
  EXPECT_FALSE(in.held(kW));
  EXPECT_FALSE(in.held(340));
  EXPECT_FALSE(in.buttonHeld(kRight));
  EXPECT_FALSE(in.pressed(kW));
  EXPECT_FALSE(in.anyHeld());
  // And the next press after focus returns is a press again.
  in.keyDown(kW);
  EXPECT_TRUE(in.pressed(kW));
}

TEST(InputState, CodesOutsideTheTableAreIgnored) {
  sandbox::InputState in;
  in.keyDown(-1);  // GLFW_KEY_UNKNOWN
  in.keyDown(100000);
  in.buttonDown(99);
  EXPECT_FALSE(in.anyHeld());
  EXPECT_FALSE(in.held(-1));
}

}  // namespace

#include <filesystem>
#include <fstream>
#include <sstream>

#include <GLFW/glfw3.h>

#include "controls.h"

namespace {

TEST(Controls, DocsListEveryControl) {
  std::ifstream in(std::filesystem::path(DATA_DIR) / "docs" / "sandbox.md");
  ASSERT_TRUE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  for (const sandbox::Control& c : sandbox::controls()) {
    const std::string row = "| " + std::string(c.keys) + " | " + std::string(c.action) + " |";
    EXPECT_NE(text.str().find(row), std::string::npos) << "docs/sandbox.md lacks the row " << row;
  }
}

TEST(Controls, TheSeedsKeysMapToTheirActions) {
  using sandbox::Action;
  using sandbox::actionForKey;
  EXPECT_EQ(actionForKey(GLFW_KEY_1, 0), Action::Scene1);
  EXPECT_EQ(actionForKey(GLFW_KEY_4, 0), Action::SceneTackle);
  EXPECT_EQ(actionForKey(GLFW_KEY_0, 0), Action::ClearScene);
  EXPECT_EQ(actionForKey(GLFW_KEY_TAB, 0), Action::CycleDrawMode);
  EXPECT_EQ(actionForKey(GLFW_KEY_C, 0), Action::ToggleMarkers);
  EXPECT_EQ(actionForKey(GLFW_KEY_G, 0), Action::ToggleGravityMode);
  EXPECT_EQ(actionForKey(GLFW_KEY_Y, 0), Action::GravityUp);
  EXPECT_EQ(actionForKey(GLFW_KEY_J, 0), Action::DampingDown);
  EXPECT_EQ(actionForKey(GLFW_KEY_SPACE, 0), Action::Pause);
  EXPECT_EQ(actionForKey(GLFW_KEY_F1, 0), Action::ToggleHelp);
  // Movement keys are held, not actions; Ctrl+S is the file menu's, not the S key's.
  EXPECT_FALSE(actionForKey(GLFW_KEY_W, 0).has_value());
  EXPECT_FALSE(actionForKey(GLFW_KEY_R, GLFW_MOD_CONTROL).has_value());
}

}  // namespace

namespace {

// A key pressed and released between two frames (a script's key, a tap on a slow frame) is held
// back until the frame has read it as down; any other release goes through.
TEST(KeyTaps, AReleaseInTheFrameOfItsPressWaitsForTheFrame) {
  sandbox::KeyTaps taps;
  taps.pressed(257);  // Enter
  EXPECT_TRUE(taps.holdRelease({257, 36, 0}));
  EXPECT_FALSE(taps.holdRelease({65, 38, 0})) << "pressed in an earlier frame";
  const auto released = taps.frameStarted();
  ASSERT_EQ(released.size(), 1u);
  EXPECT_EQ(released[0].key, 257);
  EXPECT_EQ(released[0].scancode, 36);
  EXPECT_TRUE(taps.frameStarted().empty());

  taps.pressed(257);
  EXPECT_TRUE(taps.frameStarted().empty()) << "held over the frame: nothing kept";
  EXPECT_FALSE(taps.holdRelease({257, 36, 0})) << "its release, a frame later, goes through";
}

}  // namespace
