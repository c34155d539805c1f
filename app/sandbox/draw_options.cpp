#include "draw_options.h"

#include <algorithm>

#include "body_colors.h"

namespace sandbox {

std::string_view toString(DrawMode mode) {
  switch (mode) {
    case DrawMode::Filled:
      return "filled";
    case DrawMode::Wireframe:
      return "wireframe";
    case DrawMode::Constraints:
      return "constraints";
  }
  return "filled";
}

std::optional<DrawMode> parseDrawMode(std::string_view name) {
  for (DrawMode m : {DrawMode::Filled, DrawMode::Wireframe, DrawMode::Constraints}) {
    if (toString(m) == name) return m;
  }
  return std::nullopt;
}

std::string_view toString(BodyColoring coloring) {
  switch (coloring) {
    case BodyColoring::Kind:
      return "kind";
    case BodyColoring::Body:
      return "body";
    case BodyColoring::Island:
      return "island";
    case BodyColoring::Sleep:
      return "sleep";
  }
  return "body";
}

std::optional<BodyColoring> parseBodyColoring(std::string_view name) {
  if (name == "kind") return BodyColoring::Kind;
  if (name == "body") return BodyColoring::Body;
  if (name == "island") return BodyColoring::Island;
  if (name == "sleep") return BodyColoring::Sleep;
  return std::nullopt;
}

DrawMode nextDrawMode(DrawMode mode) {
  switch (mode) {
    case DrawMode::Filled:
      return DrawMode::Wireframe;
    case DrawMode::Wireframe:
      return DrawMode::Constraints;
    case DrawMode::Constraints:
      return DrawMode::Filled;
  }
  return DrawMode::Filled;
}

float particleRadiusFor(float cameraDistance) {
  // 0.008 of the distance: with a 60 degree field of view, 720 pixels span 1.15 times the
  // distance, so the sphere is about 10 pixels across there.
  return std::max(0.008f * cameraDistance, kParticleDrawSize * 0.5f);
}

}  // namespace sandbox
