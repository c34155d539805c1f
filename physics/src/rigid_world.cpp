// The world's side of the rigid body model: which of a rigid body's points may reach the ground in
// the step, and where a capsule's point on the ground is (the passes are rigid_contacts.cpp).
#include <algorithm>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "passes.h"
#include "physics/world.h"

namespace phys {
namespace {

// A capsule's point nearest the ground at one end (-1 or +1 along its y axis), in its frame.
Vec3 capsuleLowestLocal(const Body& body, const Quat& q, const Vec3& groundNormal, Real end) {
  return Vec3(0.0, end * body.capsuleHalfSegment(), 0.0) +
         (glm::conjugate(q) * -groundNormal) * body.capsuleRadius();
}

}  // namespace

// Once per step, and again when the broad phase runs again: a box's corners and a capsule's end
// spheres that are nearer the ground than the body can go in the step (twice its speed, its turning
// and gravity's g dt^2, and the feature epsilon), so that a contact that closes within the step is
// there when it does. The passes push a point only once it touches.
void World::collectRigidGround() {
  rigidGround_.clear();
  if (!world_.ground || rigidBodies_.size() == 0) return;
  // Room for every corner of every rigid body, once, so that no step allocates for it.
  const std::size_t most = 8 * rigidBodies_.size();
  if (rigidGround_.capacity() < most) {
    rigidGround_.reserve(most);
    for (std::vector<Real>* v :
         {&rigidGroundState_.lambdaNormal, &rigidGroundState_.lambdaTangent, &rigidGroundState_.twist,
          &rigidGroundState_.approach, &rigidGroundState_.allowance})
      v->reserve(most);
    rigidGroundState_.touched.reserve(most);
    rigidGroundPatches_.reserve(rigidBodies_.size());
  }
  const Vec3 n = world_.groundNormal;
  const Real dt = solver_.dt, g = gravityMagnitude();
  for (RigidId i{}; i < rigidBodies_.size(); ++i) {
    const Body& body = bodies_[rigidBodies_.body[i]];
    const Vec3& x = rigidBodies_.position[i];
    const Quat& q = rigidBodies_.orientation[i];
    const Real reach = 2.0 *
                           (glm::length(rigidBodies_.velocity[i]) +
                            glm::length(rigidBodies_.angularVelocity[i]) * glm::length(body.halfExtents)) *
                           dt +
                       g * dt * dt + solver_.featureEpsilon;
    RigidContact c;
    c.bodyB = rigidBodies_.body[i];
    c.rigidB = i;
    c.normal = n;
    c.combined = combine(body.material, world_.groundMaterial);
    if (body.shape == Shape::Capsule) {
      for (const Real end : {-1.0, 1.0}) {
        const Vec3 lowest = capsuleLowestLocal(body, q, n, end);
        if (glm::dot(n, x + q * lowest) - world_.groundHeight >= reach) continue;
        c.localB = lowest;
        c.capsuleEnd = static_cast<std::int8_t>(end);
        c.capsuleLying = true;  // with the other end's point, if it is near too, one block
        rigidGround_.push_back(c);
      }
      continue;
    }
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner = boxCornerLocal(body.halfExtents, k);
      if (glm::dot(n, x + q * corner) - world_.groundHeight >= reach) continue;
      c.localB = corner;
      rigidGround_.push_back(c);
    }
  }
}

// Every substep, and again before each pass: a capsule's ground points move over its surface as it
// turns, to the lowest point of their end sphere.
void World::placeRigidCapsulePoints() {
  for (RigidContact& c : rigidGround_) {
    if (c.capsuleEnd == 0) continue;
    c.localB = capsuleLowestLocal(bodies_[c.bodyB], rigidBodies_.orientation[c.rigidB], world_.groundNormal,
                                  c.capsuleEnd);
  }
}

// The height over the ground plane's origin (n . x, m) of the body's lowest point now.
Real World::lowestHeight(BodyId id, const Body& body) const {
  const Vec3 n = world_.groundNormal;
  // A capsule by its core; a box by its corners as they are, which a particle box may have bent.
  if (body.shape == Shape::Capsule) {
    if (body.model == BodyModel::Rigid) return lowestAlong(Shape::Capsule, body.halfExtents, poseOf(id), n);
    // A particle capsule: the sphere of its radius around each end of its core as its particles
    // carry it, bent, twisted or inside out as they may be, as a box's corners are read below.
    // Not its pose's (a fit, through which a tetra capsule landing on an end read 8 mm deeper than
    // its carried core), nor its ground points' (placed at each substep's start, and on the wrong
    // face of a capsule turned inside out: docs/physics.md, "Capsules").
    const Real along = body.capsuleHalfSegment() / body.halfExtents.y;
    Real lowest = std::numeric_limits<Real>::infinity();
    for (const Real end : {-1.0, 1.0})
      lowest = std::min(lowest,
                        glm::dot(n, positionOf(detail::rigidEmbedding(body, Vec3(0.0, end * along, 0.0)))));
    return lowest - body.capsuleRadius();
  }
  Real lowest = std::numeric_limits<Real>::infinity();
  for (int k = 0; k < 8; ++k) lowest = std::min(lowest, glm::dot(n, cornerOf(id, k)));
  return lowest;
}

}  // namespace phys
