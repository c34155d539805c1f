#include "input.h"

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

}  // namespace sandbox
