// World::raycast: what a pick ray from the camera hits first.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "physics/world.h"

namespace phys {
namespace {

// Entry distance of the ray o + t d into the box |u_i| <= half_i (the ray in the box's frame),
// by the slab test: the ray is inside the box where it is inside all three slabs. 0 when o is
// inside; nullopt when the ray misses or the box is behind.
std::optional<Real> rayBox(const Vec3& o, const Vec3& d, const Vec3& half) {
  Real enter = 0.0, leave = std::numeric_limits<Real>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (std::abs(o[i]) > half[i]) return std::nullopt;  // parallel to the slab and outside it
      continue;
    }
    Real tNear = (-half[i] - o[i]) / d[i], tFar = (half[i] - o[i]) / d[i];
    if (tNear > tFar) std::swap(tNear, tFar);
    enter = std::max(enter, tNear);
    leave = std::min(leave, tFar);
    if (enter > leave) return std::nullopt;
  }
  return enter;
}

// Entry distance of the ray o + t d (d a unit vector) into the sphere of centre c and radius r:
// the smaller root of |o + t d - c|^2 = r^2. 0 when o is inside.
std::optional<Real> raySphere(const Vec3& o, const Vec3& d, const Vec3& c, Real r) {
  const Vec3 m = o - c;
  const Real outside = glm::dot(m, m) - r * r;
  if (outside <= 0.0) return 0.0;
  const Real b = glm::dot(m, d);
  if (b >= 0.0) return std::nullopt;  // outside and pointing away
  const Real discriminant = b * b - outside;
  if (discriminant < 0.0) return std::nullopt;
  return -b - std::sqrt(discriminant);
}

// Entry distance of the ray o + t d (d a unit vector, both in the capsule's frame) into the
// capsule whose core runs along y from -halfSegment to +halfSegment: the nearest of its side (the
// cylinder x^2 + z^2 = r^2 over the core's length) and its two end spheres. 0 when o is inside.
std::optional<Real> rayCapsule(const Vec3& o, const Vec3& d, Real halfSegment, Real r) {
  std::optional<Real> best;
  auto keep = [&best](std::optional<Real> t) {
    if (t && (!best || *t < *best)) best = t;
  };
  const Real a = d.x * d.x + d.z * d.z, b = o.x * d.x + o.z * d.z, c = o.x * o.x + o.z * o.z - r * r;
  if (c <= 0.0 && std::abs(o.y) <= halfSegment) return 0.0;  // inside the side
  if (a > 0.0 && c > 0.0) {
    const Real discriminant = b * b - a * c;
    if (discriminant >= 0.0) {
      const Real t = (-b - std::sqrt(discriminant)) / a;
      if (t >= 0.0 && std::abs(o.y + t * d.y) <= halfSegment) keep(t);
    }
  }
  keep(raySphere(o, d, Vec3(0.0, -halfSegment, 0.0), r));
  keep(raySphere(o, d, Vec3(0.0, halfSegment, 0.0), r));
  return best;
}

}  // namespace

// Every box and loose particle is tested in turn: a pick is one ray per click or mouse move, and
// a scene has hundreds of bodies at most, so no acceleration structure is worth keeping.
std::optional<RayHit> World::raycast(const Vec3& origin, const Vec3& direction, Real maxDistance) const {
  const Real length = glm::length(direction);
  if (!finite(origin) || !std::isfinite(length) || length == 0.0 || std::isnan(maxDistance) ||
      maxDistance < 0.0) {
    throw std::invalid_argument(
        "raycast: origin must be finite, direction finite and non-zero, maxDistance >= 0 (m)");
  }
  const Vec3 d = direction / length;
  std::optional<RayHit> best;
  auto consider = [&](std::optional<Real> t, std::optional<BodyId> box, std::optional<ParticleId> particle) {
    if (!t || !std::isfinite(*t) || *t > maxDistance || (best && *t >= best->distance)) return;
    best = RayHit{box, particle, *t, origin + *t * d};
  };
  for (BodyId id{}; id < bodies_.size(); ++id) {
    const BodyPose pose = poseOf(id);
    const Quat toBox = glm::conjugate(pose.orientation);
    const Body& box = bodies_[id];
    const Vec3 o = toBox * (origin - pose.center), local = toBox * d;
    consider(box.shape == Shape::Capsule ? rayCapsule(o, local, box.capsuleHalfSegment(), box.capsuleRadius())
                                         : rayBox(o, local, box.halfExtents),
             id, std::nullopt);
  }
  for (ParticleId i{}; i < particles_.size(); ++i) {
    if (particleBody_[i] != kNoBody) continue;  // a box's particle: the box is hit instead
    consider(raySphere(origin, d, particles_.position[i], kPickRadius), std::nullopt, i);
  }
  return best;
}

}  // namespace phys
