// The tetra model's volume constraint (passes.h, keepTetraVolumes).
#include <array>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "passes.h"

namespace phys::detail {
namespace {

// Six times the signed volume of the tetrahedron (a, b, c, d).
Real sixVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return glm::dot(b - a, glm::cross(c - a, d - a));
}

// One Gauss-Seidel projection of C = 6 (V - V0): each particle moved along the gradient of 6 V
// (its opposite face's normal, scaled by twice that face's area) in proportion to inverse mass.
void keepVolume(Particles& p, const Body& box) {
  const ParticleId first = box.firstParticle;
  std::array<Vec3, 4> rest;
  for (int j = 0; j < 4; ++j) rest[j] = boxParticleLocal(BodyModel::Tetra, box.halfExtents, j);
  const Real restVolume = sixVolume(rest[0], rest[1], rest[2], rest[3]);
  std::array<Vec3, 4> x;
  std::array<Real, 4> w;
  for (int j = 0; j < 4; ++j) {
    x[j] = p.position[first + j];
    w[j] = p.inverseMass[first + j];
  }
  const std::array<Vec3, 4> gradient = {
      glm::cross(x[3] - x[1], x[2] - x[1]), glm::cross(x[2] - x[0], x[3] - x[0]),
      glm::cross(x[3] - x[0], x[1] - x[0]), glm::cross(x[1] - x[0], x[2] - x[0])};
  Real denominator = 0.0;
  for (int j = 0; j < 4; ++j) denominator += w[j] * glm::dot(gradient[j], gradient[j]);
  // Every particle pinned, or the tetrahedron crushed to a point or a line: nothing to push along.
  if (!(denominator > 0.0)) return;
  const Real lambda = (restVolume - sixVolume(x[0], x[1], x[2], x[3])) / denominator;
  if (!std::isfinite(lambda)) return;  // the guard freezes such a body after the substep
  for (int j = 0; j < 4; ++j) {
    if (w[j] != 0.0) p.position[first + j] += lambda * w[j] * gradient[j];
  }
}

// A tetra body is flat when its thinnest side is under half its middle one. The sticks hold its
// tetrahedron's thickness t across a width w with a stiffness of (t / w)^2 per pass: a quarter or
// more, and the passes hold it (a 1 x 0.5 x 1 m slab rests 1.6 mm down, a cube 0.2 mm). The
// volume is kept only below that, so that the lean ragdolls' parts (the torso's 0.2 / 0.34 is the
// flattest) rest as their sticks alone leave them: kept in every part, the passes' residue moved
// into the sticks, 1.4% off their length at rest after a fall, against 0.3%.
bool flat(const Body& box) {
  Vec3 e = box.halfExtents;
  if (e.x > e.y) std::swap(e.x, e.y);
  if (e.y > e.z) std::swap(e.y, e.z);
  if (e.x > e.y) std::swap(e.x, e.y);
  return e.x < 0.5 * e.y;
}

}  // namespace

void keepTetraVolumes(Particles& p, std::span<const Body> bodies) {
  for (const Body& box : bodies) {
    if (box.model == BodyModel::Tetra && flat(box)) keepVolume(p, box);
  }
}

}  // namespace phys::detail
