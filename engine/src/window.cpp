#include "engine/window.h"

#include <cstdlib>
#include <string>

#include <glad/gl.h>
#include <GLFW/glfw3.h>

#include "engine/error.h"

namespace engine {
namespace {

std::string lastGlfwError;  // GLFW reports errors through a callback; keep the last one

void onGlfwError(int code, const char* description) {
  lastGlfwError = "GLFW error " + std::to_string(code) + ": " + description;
}

bool nonEmptyEnv(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && value[0] != '\0';
}

}  // namespace

std::string missingDisplayReason() {
  if (nonEmptyEnv("DISPLAY") || nonEmptyEnv("WAYLAND_DISPLAY")) return {};
  return "no DISPLAY; use --screenshot under xvfb-run (e.g. xvfb-run -a sandbox --screenshot out.png)";
}

Window::Window(const WindowDesc& desc) {
  glfwSetErrorCallback(onGlfwError);
  if (glfwInit() != GLFW_TRUE) throw Error("cannot initialise GLFW: " + lastGlfwError);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, desc.visible ? GLFW_TRUE : GLFW_FALSE);
  window_ = glfwCreateWindow(desc.width, desc.height, desc.title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) {
    glfwTerminate();
    throw Error("cannot open a " + std::to_string(desc.width) + "x" + std::to_string(desc.height) +
                " window with an OpenGL 3.3 core context: " + lastGlfwError);
  }
  glfwMakeContextCurrent(window_);
  if (gladLoadGL(glfwGetProcAddress) == 0) {
    glfwDestroyWindow(window_);
    glfwTerminate();
    throw Error("cannot load OpenGL 3.3 core functions (glad)");
  }
  glfwSwapInterval(desc.vsync ? 1 : 0);
}

Window::~Window() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool Window::shouldClose() const {
  return glfwWindowShouldClose(window_) == GLFW_TRUE;
}

void Window::swapBuffers() {
  glfwSwapBuffers(window_);
}

glm::ivec2 Window::framebufferSize() const {
  glm::ivec2 size{0};
  glfwGetFramebufferSize(window_, &size.x, &size.y);
  return size;
}

void Window::pollEvents() {
  glfwPollEvents();
}

}  // namespace engine
