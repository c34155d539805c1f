#pragma once
// One hidden window with a GL 3.3 core context, shared by the GL tests of this binary (GLFW
// allows one initialisation at a time, and one context is all these tests need).
#include "engine/window.h"

namespace testing_gl {

engine::Window& context();

}  // namespace testing_gl
