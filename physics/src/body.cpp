#include "physics/body.h"

#include <cmath>

namespace phys {

std::string_view toString(BodyModel model) {
  return model == BodyModel::Tetra ? "tetra" : "corners";
}

std::string_view toString(Shape shape) {
  return shape == Shape::Capsule ? "capsule" : "box";
}

std::optional<BodyModel> parseBodyModel(std::string_view name) {
  if (name == "corners") return BodyModel::Corners;
  if (name == "tetra") return BodyModel::Tetra;
  return std::nullopt;
}

Vec3 boxCornerLocal(const Vec3& halfExtents, int k) {
  return {(k & 1) ? halfExtents.x : -halfExtents.x, (k & 2) ? halfExtents.y : -halfExtents.y,
          (k & 4) ? halfExtents.z : -halfExtents.z};
}

Vec3 boxParticleLocal(BodyModel model, const Vec3& halfExtents, int j) {
  if (model == BodyModel::Corners) return boxCornerLocal(halfExtents, j);
  return boxCornerLocal(halfExtents, kTetraCorner[j]);
}

int boxParticleCount(BodyModel model) {
  return model == BodyModel::Corners ? 8 : 4;
}

std::array<Real, 4> tetraWeights(const Vec3& u) {
  std::array<Real, 4> w{};
  for (int j = 0; j < 4; ++j) {
    const int k = kTetraCorner[j];
    const Vec3 sign{(k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : -1.0};
    w[j] = 0.25 * (1.0 + sign.x * u.x + sign.y * u.y + sign.z * u.z);
  }
  return w;
}

}  // namespace phys
