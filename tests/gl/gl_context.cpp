#include "gl_context.h"

namespace testing_gl {

engine::Window& context() {
  static engine::Window window(engine::WindowDesc{256, 256, "gl_tests", false, false});
  return window;
}

}  // namespace testing_gl
