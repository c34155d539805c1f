#include "physics/body.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "require.h"

namespace phys {

std::string_view toString(BodyModel model) {
  detail::requireEnum(static_cast<int>(model), static_cast<int>(BodyModel::Rigid) + 1, "toString(BodyModel)",
                      "model", "BodyModel");
  static constexpr std::array<std::string_view, 3> kNames = {"corners", "tetra", "rigid"};
  return kNames[static_cast<std::size_t>(model)];
}

std::string_view toString(Shape shape) {
  detail::requireEnum(static_cast<int>(shape), static_cast<int>(Shape::Capsule) + 1, "toString(Shape)",
                      "shape", "Shape");
  return shape == Shape::Capsule ? "capsule" : "box";
}

std::optional<BodyModel> parseBodyModel(std::string_view name) {
  if (name == "corners") return BodyModel::Corners;
  if (name == "tetra") return BodyModel::Tetra;
  if (name == "rigid") return BodyModel::Rigid;
  return std::nullopt;
}

Vec3 boxCornerLocal(const Vec3& halfExtents, int k) {
  return {(k & 1) ? halfExtents.x : -halfExtents.x, (k & 2) ? halfExtents.y : -halfExtents.y,
          (k & 4) ? halfExtents.z : -halfExtents.z};
}

Real lowestAlong(Shape shape, const Vec3& halfExtents, const BodyPose& pose, const Vec3& up) {
  if (shape == Shape::Capsule) {
    // Body::capsuleRadius and capsuleHalfSegment, from the box the capsule is inscribed in.
    const Real radius = halfExtents.x, halfSegment = halfExtents.y - halfExtents.x;
    const Vec3 axis = pose.orientation * Vec3(0.0, halfSegment, 0.0);
    return glm::dot(up, pose.center) - std::abs(glm::dot(up, axis)) - radius;
  }
  Real lowest = std::numeric_limits<Real>::infinity();
  for (int k = 0; k < 8; ++k) {
    lowest = std::min(lowest, glm::dot(up, pose.center + pose.orientation * boxCornerLocal(halfExtents, k)));
  }
  return lowest;
}

Vec3 boxParticleLocal(BodyModel model, const Vec3& halfExtents, int j) {
  if (model == BodyModel::Corners) return boxCornerLocal(halfExtents, j);
  return boxCornerLocal(halfExtents, kTetraCorner[j]);
}

int boxParticleCount(BodyModel model) {
  if (model == BodyModel::Rigid) return 0;
  return model == BodyModel::Corners ? 8 : 4;
}

Vec3 solidBoxInertia(const Vec3& halfExtents, Real mass) {
  const Vec3 s = halfExtents * halfExtents;
  return Vec3(s.y + s.z, s.x + s.z, s.x + s.y) * (mass / 3.0);
}

// A cylinder of height H = 2 halfSegment and two hemispheres, sharing the mass by volume. About the
// axis: m_c r^2 / 2 + m_s 2 r^2 / 5. Across it: the cylinder's m_c (H^2 / 12 + r^2 / 4), and the
// hemispheres' m_s (2 r^2 / 5 + H^2 / 4 + 3 H r / 8) (each hemisphere's centre of mass sits 3r/8
// from its flat face, which is H / 2 from the centre).
Vec3 solidCapsuleInertia(Real radius, Real halfSegment, Real mass) {
  const Real r = radius, H = 2.0 * halfSegment;
  const Real cylinder = r * r * H, spheres = 4.0 / 3.0 * r * r * r;  // volumes over pi
  const Real mc = mass * cylinder / (cylinder + spheres), ms = mass - mc;
  const Real axial = mc * r * r / 2.0 + ms * 2.0 * r * r / 5.0;
  const Real across =
      mc * (H * H / 12.0 + r * r / 4.0) + ms * (2.0 * r * r / 5.0 + H * H / 4.0 + 3.0 * H * r / 8.0);
  return Vec3(across, axial, across);
}

Vec3 flooredInertia(const Vec3& inertia, Real floor) {
  const Real largest = std::max({inertia.x, inertia.y, inertia.z});
  return glm::max(inertia, Vec3(floor * largest));
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
