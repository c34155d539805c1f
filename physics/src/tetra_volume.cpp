// The tetra model's volume constraint (passes.h, keepTetraVolumes).
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "passes.h"

namespace phys::detail {
namespace {

// Six times the signed volume of the tetrahedron (a, b, c, d).
Real sixVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return glm::dot(b - a, glm::cross(c - a, d - a));
}

// The gradient of 6 V at each of the four points: its opposite face's normal, scaled by twice
// that face's area.
std::array<Vec3, 4> volumeGradient(const std::array<Vec3, 4>& x) {
  return {glm::cross(x[3] - x[1], x[2] - x[1]), glm::cross(x[2] - x[0], x[3] - x[0]),
          glm::cross(x[3] - x[0], x[1] - x[0]), glm::cross(x[1] - x[0], x[2] - x[0])};
}

std::array<Vec3, 4> tetraOf(const std::vector<Vec3>& positions, ParticleId first) {
  return {positions[first], positions[first + 1], positions[first + 2], positions[first + 3]};
}

// One Gauss-Seidel projection of C = 6 (V - V0), in proportion to inverse mass: a Newton step
// along the gradient at x (the projection of Gauss-Seidel, Jacobi and XPBD), or, for SHAKE, along
// the gradient at the substep's start, as SHAKE moves each stick along its direction there (a
// projection along the moving gradient made the SHAKE tumbler of stability/dzhanibekov.xml lose
// 41% of its energy in 12 s, where along the start's it keeps it).
void keepVolume(Particles& p, const Body& box, bool alongStart) {
  const ParticleId first = box.firstParticle;
  std::array<Vec3, 4> rest;
  for (int j = 0; j < 4; ++j) rest[j] = boxParticleLocal(BodyModel::Tetra, box.halfExtents, j);
  const Real restVolume = sixVolume(rest[0], rest[1], rest[2], rest[3]);
  const std::array<Vec3, 4> x = tetraOf(p.position, first);
  const std::array<Vec3, 4> gradient = volumeGradient(x);
  const std::array<Vec3, 4> direction = alongStart ? volumeGradient(tetraOf(p.previous, first)) : gradient;
  Real denominator = 0.0;
  for (int j = 0; j < 4; ++j) denominator += p.inverseMass[first + j] * glm::dot(gradient[j], direction[j]);
  // Every particle pinned, or the tetrahedron crushed to a point or a line: nothing to push along.
  if (!(denominator > 0.0)) return;
  const Real lambda = (restVolume - sixVolume(x[0], x[1], x[2], x[3])) / denominator;
  if (!std::isfinite(lambda)) return;  // the guard freezes such a body after the substep
  for (int j = 0; j < 4; ++j) {
    const Real w = p.inverseMass[first + j];
    if (w != 0.0) p.position[first + j] += lambda * w * direction[j];
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

void keepTetraVolumes(Particles& p, std::span<const Body> bodies, bool alongStart) {
  for (const Body& box : bodies) {
    if (box.model == BodyModel::Tetra && flat(box)) keepVolume(p, box, alongStart);
  }
}

}  // namespace phys::detail
