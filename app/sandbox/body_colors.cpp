#include "body_colors.h"

#include <cmath>

namespace sandbox {

glm::vec3 bodyColor(const phys::World& world, phys::BodyId id, BodyColoring coloring) {
  const phys::Islands& islands = world.islands();
  switch (coloring) {
    case BodyColoring::Kind:
      return kBoxColor;
    case BodyColoring::Sleep:
      return islands.bodyAsleep(id) ? kSleepingColor : kBoxColor;
    case BodyColoring::Island: {
      // Hues a golden angle apart, so that neighbouring island numbers differ most; full
      // saturation at two thirds of full value, from the hue's place on the colour wheel.
      const float hue = std::fmod(static_cast<float>(islands.bodyIsland()[id]) * 0.618034f, 1.0f) * 6.0f;
      const float x = 1.0f - std::abs(std::fmod(hue, 2.0f) - 1.0f);
      const int sector = static_cast<int>(hue);
      const glm::vec3 rgb = sector == 0   ? glm::vec3(1, x, 0)
                            : sector == 1 ? glm::vec3(x, 1, 0)
                            : sector == 2 ? glm::vec3(0, 1, x)
                            : sector == 3 ? glm::vec3(0, x, 1)
                            : sector == 4 ? glm::vec3(x, 0, 1)
                                          : glm::vec3(1, 0, x);
      return 0.2f + 0.7f * rgb;
    }
  }
  return kBoxColor;
}

bool looksLike(const glm::vec3& color, unsigned char r, unsigned char g, unsigned char b) {
  const float sum = float(r) + float(g) + float(b);
  if (sum < 30.0f) return false;  // too dark to tell a hue
  const float colorSum = color.r + color.g + color.b;
  const float dr = float(r) / sum - color.r / colorSum;
  const float dg = float(g) / sum - color.g / colorSum;
  const float db = float(b) / sum - color.b / colorSum;
  return std::sqrt(dr * dr + dg * dg + db * db) < 0.06f;
}

}  // namespace sandbox
