#pragma once
// A GLFW window with an OpenGL 3.3 core context whose functions glad has loaded.
#include <string>

#include <glm/vec2.hpp>

struct GLFWwindow;

namespace engine {

struct WindowDesc {
  int width = 1280;  ///< unit: screen pixels
  int height = 720;  ///< unit: screen pixels
  std::string title = "Jakobsen sandbox";
  bool visible = true;  ///< false for tests and screenshots that need no window on screen
  bool vsync = true;
};

/// Empty when a display server is reachable by name (DISPLAY or WAYLAND_DISPLAY is set);
/// otherwise one line saying so.
std::string missingDisplayReason();

class Window {
 public:
  /// Opens the window and loads GL; throws engine::Error with GLFW's or glad's reason.
  explicit Window(const WindowDesc& desc);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }
  bool shouldClose() const;
  void swapBuffers();
  /// Framebuffer size in pixels (may differ from the window size on high-DPI screens).
  glm::ivec2 framebufferSize() const;
  /// Processes pending window-system events for every window.
  static void pollEvents();

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace engine
