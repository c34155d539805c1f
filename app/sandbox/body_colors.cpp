#include "body_colors.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace sandbox {

glm::vec3 paletteColor(std::size_t k) {
  static constexpr glm::vec3 kPalette[] = {
      {0.90f, 0.50f, 0.15f}, {0.31f, 0.47f, 0.65f}, {0.35f, 0.63f, 0.31f}, {0.88f, 0.34f, 0.35f},
      {0.69f, 0.48f, 0.63f}, {0.93f, 0.79f, 0.28f}, {0.46f, 0.72f, 0.70f}, {0.61f, 0.46f, 0.38f},
      {1.00f, 0.62f, 0.66f}, {0.20f, 0.60f, 0.55f},
  };
  return kPalette[k % std::size(kPalette)];
}

std::vector<std::uint32_t> jointGroups(const phys::World& world) {
  const std::size_t n = world.bodies().size();
  std::vector<std::uint32_t> parent(n);
  for (std::uint32_t i = 0; i < n; ++i) parent[i] = i;
  auto root = [&](std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  auto join = [&](phys::BodyId a, phys::BodyId b) {
    if (a == phys::kNoBody || b == phys::kNoBody) return;
    const std::uint32_t ra = root(a), rb = root(b);
    parent[std::max(ra, rb)] = std::min(ra, rb);  // the first body is the root
  };
  const auto owner = world.particleBodies();
  for (const phys::Link& link : world.links()) join(owner[link.a.particle[0]], owner[link.b.particle[0]]);
  for (const phys::RigidLink& link : world.rigidLinks()) join(world.carrier(link.a), world.carrier(link.b));
  for (const phys::RigidJoint& j : world.rigidJoints())
    join(world.rigidBodies().body[j.a], world.rigidBodies().body[j.b]);
  std::vector<std::uint32_t> group(n), number(n, 0);
  std::uint32_t groups = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t r = root(i);
    if (r == i) number[i] = groups++;
    group[i] = number[r];
  }
  return group;
}

glm::vec3 bodyColor(const phys::World& world, phys::BodyId id, BodyColoring coloring,
                    std::span<const std::uint32_t> groups) {
  const phys::Islands& islands = world.islands();
  switch (coloring) {
    case BodyColoring::Kind:
      return kBoxColor;
    case BodyColoring::Body:
      return paletteColor(groups.empty() ? jointGroups(world)[id] : groups[id]);
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
