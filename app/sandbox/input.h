#pragma once
// Keys and mouse buttons as the sandbox sees them: held or not, and pressed since the last
// frame. Fed from GLFW's callbacks (events, not polling), so a key released while another
// window had focus cannot be missed: losing focus releases everything. (The seed's engine
// polled key-down messages only and a key released elsewhere stayed held for ever.)
#include <bitset>
#include <vector>

namespace sandbox {

class InputState {
 public:
  /// GLFW key codes go up to GLFW_KEY_LAST (348); anything outside [0, kKeys) is ignored.
  static constexpr int kKeys = 512;
  static constexpr int kButtons = 8;  ///< GLFW_MOUSE_BUTTON_LAST + 1

  void keyDown(int key);
  void keyUp(int key);
  void buttonDown(int button);
  void buttonUp(int button);
  /// The window lost focus: every key and button counts as released from now on.
  void focusLost();
  /// Forgets this frame's presses; call once a frame after handling them.
  void endFrame();

  bool held(int key) const { return valid(key) && held_[static_cast<std::size_t>(key)]; }
  /// Went down since the last endFrame() (a key repeat does not count).
  bool pressed(int key) const { return valid(key) && pressed_[static_cast<std::size_t>(key)]; }
  bool buttonHeld(int button) const {
    return validButton(button) && buttons_[static_cast<std::size_t>(button)];
  }
  bool buttonPressed(int button) const {
    return validButton(button) && buttonPressed_[static_cast<std::size_t>(button)];
  }
  bool anyHeld() const { return held_.any() || buttons_.any(); }

 private:
  static bool valid(int key) { return key >= 0 && key < kKeys; }
  static bool validButton(int button) { return button >= 0 && button < kButtons; }

  std::bitset<kKeys> held_, pressed_;
  std::bitset<kButtons> buttons_, buttonPressed_;
};

/// A key pressed and released between two frames, as a script or a quick tap on a slow frame
/// does: Dear ImGui 1.86 reads keys as held or not when a frame starts, so it would never see the
/// key down and Enter in a dialog would be lost. The release of a key pressed since the last frame
/// waits for the frame to start; anything else goes through at once.
class KeyTaps {
 public:
  struct Release {
    int key = 0, scancode = 0, mods = 0;
  };
  void pressed(int key) { pressedSinceFrame_.push_back(key); }
  /// True when this release must wait (it is kept, and returned by frameStarted).
  bool holdRelease(const Release& release);
  /// The frame has read the keys: the releases kept, to be given now.
  std::vector<Release> frameStarted();

 private:
  std::vector<int> pressedSinceFrame_;
  std::vector<Release> held_;
};

}  // namespace sandbox
