#include "input.h"

#include <algorithm>
#include <utility>

namespace sandbox {

void InputState::keyDown(int key) {
  if (!valid(key)) return;
  const auto k = static_cast<std::size_t>(key);
  if (!held_[k]) pressed_[k] = true;
  held_[k] = true;
}

void InputState::keyUp(int key) {
  if (valid(key)) held_[static_cast<std::size_t>(key)] = false;
}

void InputState::buttonDown(int button) {
  if (!validButton(button)) return;
  const auto b = static_cast<std::size_t>(button);
  if (!buttons_[b]) buttonPressed_[b] = true;
  buttons_[b] = true;
}

void InputState::buttonUp(int button) {
  if (validButton(button)) buttons_[static_cast<std::size_t>(button)] = false;
}

void InputState::focusLost() {
  held_.reset();
  pressed_.reset();
  buttons_.reset();
  buttonPressed_.reset();
}

void InputState::endFrame() {
  pressed_.reset();
  buttonPressed_.reset();
}

bool KeyTaps::holdRelease(const Release& release) {
  if (std::find(pressedSinceFrame_.begin(), pressedSinceFrame_.end(), release.key) ==
      pressedSinceFrame_.end())
    return false;
  held_.push_back(release);
  return true;
}

std::vector<KeyTaps::Release> KeyTaps::frameStarted() {
  pressedSinceFrame_.clear();
  return std::exchange(held_, {});
}

}  // namespace sandbox
