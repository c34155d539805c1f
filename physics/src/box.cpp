#include "physics/box.h"

#include <cmath>

namespace phys {
namespace {

// The tetra model's particles sit on the body diagonals towards alternate corners 0, 3, 5, 6
// (a regular tetrahedron for a cube), pulled in to 1/sqrt(3) of the way: four equal masses
// there have the second moment m/3 diag(hx^2, hy^2, hz^2) of a solid box, so the body turns like
// one. (The corners model's 8 corner masses have 3 times that; the ratios, hence a free body's
// tumbling, are the same.)
constexpr int kTetraCorner[4] = {0, 3, 5, 6};
const Real kTetraPull = 1.0;

}  // namespace

std::string_view toString(BoxModel model) { return model == BoxModel::Tetra ? "tetra" : "corners"; }

std::optional<BoxModel> parseBoxModel(std::string_view name) {
  if (name == "corners") return BoxModel::Corners;
  if (name == "tetra") return BoxModel::Tetra;
  return std::nullopt;
}

Vec3 boxCornerLocal(const Vec3& halfExtents, int k) {
  return {(k & 1) ? halfExtents.x : -halfExtents.x, (k & 2) ? halfExtents.y : -halfExtents.y,
          (k & 4) ? halfExtents.z : -halfExtents.z};
}

Vec3 boxParticleLocal(BoxModel model, const Vec3& halfExtents, int j) {
  if (model == BoxModel::Corners) return boxCornerLocal(halfExtents, j);
  return kTetraPull * boxCornerLocal(halfExtents, kTetraCorner[j]);
}

int boxParticleCount(BoxModel model) { return model == BoxModel::Corners ? 8 : 4; }

}  // namespace phys
