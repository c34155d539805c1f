// World's part of collision: the collision filters it is given, the joints that make bodies part
// as one, and each body's frame in every substep (what the broad and narrow phases and the ground
// read).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "particle_edges.h"
#include "passes.h"
#include "physics/world.h"
#include "require.h"

namespace phys {

void World::ignoreCollision(BodyId a, BodyId b) {
  detail::requireIndex(a, bodies_.size(), "ignoreCollision", "body");
  detail::requireIndex(b, bodies_.size(), "ignoreCollision", "body");
  if (a == b) throw std::invalid_argument("ignoreCollision: the two bodies must differ");
  broadPhase_.ignore(a, b);
  layoutsStale_ = true;  // the filters' index
  // Their contact goes: asleep, a box resting on the other would stay held by a contact that is no
  // longer there.
  islands_.wake(islands_.nodeOf(a));
  islands_.wake(islands_.nodeOf(b));
}

std::vector<std::pair<BodyId, BodyId>> World::ignoredCollisions() const {
  return broadPhase_.ignoredPairs();
}

// A stick or a link between two bodies' particles: the parting moves the two as one.
void World::joinBodies(ParticleId a, ParticleId b) {
  const BodyId ba = particleBody_[a], bb = particleBody_[b];
  if (ba == kNoBody || bb == kNoBody || ba == bb) return;
  parting_.join(ba, bb);
}

// Bodies whose frames one thread fits at a time: a few microseconds of work.
constexpr std::size_t kBodiesPerPiece = 256;

void World::updateBodyFrames() {
  // Each body's frame is its own: ranges of bodies at once on the step's threads. A sleeping body's
  // particles and pose do not move, so its frame, once fitted while it sleeps, stays as it is.
  const std::span<const std::uint8_t> asleep =
      islands_.anyAsleep() ? islands_.bodiesAsleep() : std::span<const std::uint8_t>();
  auto range = [this, asleep](std::size_t begin, std::size_t end) {
    for (BodyId id(begin); id < end; ++id) {
      const std::uint8_t sleeps = !asleep.empty() && asleep[id] != 0 ? 1 : 0;
      if (sleeps != 0 && frameAsleep_[id] != 0) continue;
      frameAsleep_[id] = sleeps;
      fitFrame(id);
    }
  };
  forEachRange(workers(), bodies_.size(), kBodiesPerPiece, range);
}

// Centre: the mean of the corners. Axes: the mean edge along each, made orthonormal. Cheaper
// than the polar decomposition bodyPose uses, and as good for a box that keeps its shape.
void World::fitFrame(BodyId id) {
  const Body& box = bodies_[id];
  Obb& f = frames_[id];
  if (box.model == BodyModel::Rigid) {  // its frame is its pose
    f.center = rigidBodies_.position[box.rigid];
    f.axes = glm::mat3_cast(rigidBodies_.orientation[box.rigid]);
    f.halfExtents = box.halfExtents;
    return;
  }
  const Vec3* p = &particles_.position[box.firstParticle];
  // A tetra body's mean corner is its mean particle; a corners box's corners are its particles.
  f.center = box.model == BodyModel::Tetra ? (p[0] + p[1] + p[2] + p[3]) * 0.25
                                           : (p[0] + p[1] + p[2] + p[3] + p[4] + p[5] + p[6] + p[7]) * 0.125;
  Vec3 ex = detail::edgeSum(box.model, p, 0), ey = detail::edgeSum(box.model, p, 1);
  const Real lx = glm::length(ex);
  ex = lx > 0.0 ? ex / lx : Vec3(1.0, 0.0, 0.0);
  ey -= glm::dot(ey, ex) * ex;
  const Real ly = glm::length(ey);
  ey = ly > 0.0 ? ey / ly
                : glm::normalize(glm::cross(ex, std::abs(ex.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
  f.axes = glm::dmat3(ex, ey, glm::cross(ex, ey));
  f.halfExtents = box.halfExtents;
}

}  // namespace phys
