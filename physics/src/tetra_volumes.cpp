#include "physics/tetra_volumes.h"

#include <array>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "passes.h"

namespace phys {
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

// The sticks hold a tetrahedron's thickness t across a width w with a stiffness of (t / w)^2 per
// pass: from a quarter up, the passes hold it (a 1 x 0.5 x 1 m slab rests 1.6 mm down, a cube
// 0.2 mm). The volume is kept only below that, so that the lean ragdolls' parts (the torso's
// 0.2 / 0.34 is the flattest) rest as their sticks alone leave them: kept in every part, the
// passes' residue moved into the sticks, 1.4% off their length at rest after a fall, against 0.3%.
bool flat(const Body& body) {
  Vec3 e = body.halfExtents;
  if (e.x > e.y) std::swap(e.x, e.y);
  if (e.y > e.z) std::swap(e.y, e.z);
  if (e.x > e.y) std::swap(e.x, e.y);
  return e.x < 0.5 * e.y;
}

}  // namespace

// Bodies whose floors one thread looks at at a time: a few nanoseconds each, so that a world of a
// few hundred tetra bodies pays no fork.
constexpr std::size_t kFloorsPerPiece = 1024;

void TetraVolumes::addBody(const Body& body) {
  if (body.model != BodyModel::Tetra) return;
  const bool kept = body.shape == Shape::Box && flat(body);
  std::array<Vec3, 4> rest;
  for (int j = 0; j < 4; ++j) rest[j] = boxParticleLocal(BodyModel::Tetra, body.halfExtents, j);
  const Real restSixVolume = sixVolume(rest[0], rest[1], rest[2], rest[3]);
  (kept ? kept_ : floored_).push_back({body.firstParticle, restSixVolume});
}

// A Newton step of C = 6 (V - target) along the gradient, in proportion to inverse mass. Along the
// moving gradient, SHAKE's tumbler of stability/dzhanibekov.xml lost 41% of its energy in 12 s;
// along the start's, as SHAKE moves its sticks, it keeps it.
void TetraVolumes::project(Particles& p, const Kept& k, Real targetSixVolume, bool alongStart,
                           bool keepSpin) {
  const std::array<Vec3, 4> x = tetraOf(p.position, k.first);
  Vec3* at = &p.position[k.first];
  const detail::KeptMoment moment(p, k.first, 4, at, keepSpin);
  const std::array<Vec3, 4> gradient = volumeGradient(x);
  const std::array<Vec3, 4> direction = alongStart ? volumeGradient(tetraOf(p.previous, k.first)) : gradient;
  Real denominator = 0.0;
  for (int j = 0; j < 4; ++j) denominator += p.inverseMass[k.first + j] * glm::dot(gradient[j], direction[j]);
  // Every particle pinned (or asleep), or the tetrahedron crushed to a point or a line: nothing
  // to push along.
  if (!(denominator > 0.0)) return;
  const Real lambda = (targetSixVolume - sixVolume(x[0], x[1], x[2], x[3])) / denominator;
  if (!std::isfinite(lambda)) return;  // the guard freezes such a body after the substep
  for (int j = 0; j < 4; ++j) {
    const Real w = p.inverseMass[k.first + j];
    if (w != 0.0) p.position[k.first + j] += lambda * w * direction[j];
  }
  moment.keep(at);
}

// The sticks cannot tell a tetrahedron from its mirror image, so a deep landing's contacts, which
// push the embedded bottom corners up and, through their weights of -1/2, a top particle down,
// can pass it through its base; the sticks then hold it inside out, squashed or whole. So a body
// that is not flat and has fallen under kVolumeFloor of its volume, signed, is given its volume back:
// a floor, not its volume kept, so that no body the passes keep whole is moved.
void TetraVolumes::keep(Particles& p, bool alongStart, const Workers* workers, bool keepSpin) const {
  for (const Kept& k : kept_) project(p, k, k.restSixVolume, alongStart, keepSpin);
  auto floors = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Kept& k = floored_[i];
      const Real floor = kVolumeFloor * k.restSixVolume;
      const Real now = sixVolume(p.position[k.first], p.position[k.first + 1], p.position[k.first + 2],
                                 p.position[k.first + 3]);
      if (now / floor < 1.0) project(p, k, k.restSixVolume, alongStart, keepSpin);
    }
  };
  forEachRange(workers, floored_.size(), kFloorsPerPiece, floors);
}

}  // namespace phys
