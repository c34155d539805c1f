#include "body_colors.h"

#include <cmath>

namespace sandbox {

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
