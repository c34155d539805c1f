// World::metrics and World::stateHash: read-only figures of the current state.
#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include "passes.h"
#include "physics/world.h"
#include "require.h"
#include "state_hash.h"

namespace phys {
namespace {

// The larger of the two, and NaN if either is: std::max(a, NaN) returns a, which would report a
// world gone to NaN as calm.
Real maxOf(Real a, Real b) {
  return (a >= b || std::isnan(a)) ? a : b;
}

}  // namespace

std::string_view toString(Stage stage) {
  static constexpr std::array<std::string_view, kStageCount> kNames = {
      "animate", "integrate", "frames",   "broad-phase", "sweep",       "narrow-phase", "parting", "sticks",
      "links",   "contacts",  "friction", "velocities",  "restitution", "body-damping", "guard",   "islands"};
  detail::requireEnum(static_cast<int>(stage), static_cast<int>(kStageCount), "toString(Stage)", "stage",
                      "Stage");
  return kNames[static_cast<std::size_t>(stage)];
}

double Profile::staged() const {
  double sum = 0.0;
  for (const double ms : stage) sum += ms;
  return sum;
}

Profile& Profile::operator+=(const Profile& other) {
  for (std::size_t i = 0; i < kStageCount; ++i) stage[i] += other.stage[i];
  total += other.total;
  return *this;
}

Metrics World::metrics() const {
  Metrics m;
  const Real h = substepDt();
  // A sleeping body is at rest: no speed and no kinetic energy, though its x and x* keep the
  // motion it fell asleep with, to go on with when it wakes (Islands).
  const bool anyAsleep = islands_.anyAsleep();
  // Uniform gravity has potential -m g . x; the fixed-strength pull, m s |x - p|.
  auto potential = [this](Real mass, const Vec3& x) {
    return world_.gravityMode == GravityMode::Uniform
               ? -mass * glm::dot(world_.gravity, x)
               : mass * world_.gravityStrength * glm::length(x - world_.gravityPoint);
  };
  for (ParticleId i{}; i < particles_.size(); ++i) {
    const Real w = particles_.inverseMass[i];
    if (w == 0.0) continue;
    const Real mass = 1.0 / w;
    const Vec3& x = particles_.position[i];
    if (anyAsleep && islands_.sleeps(islands_.nodeOf(i))) {
      m.potentialEnergy += potential(mass, x);
      continue;
    }
    const Vec3& xPrevious = particles_.previous[i];
    const Vec3 v = (x - xPrevious) / h;
    const Real speed = glm::length(v);
    m.maxSpeed = maxOf(m.maxSpeed, speed);
    // Verlet knows the velocity half a substep back, at t - h/2; take the potential there too,
    // at the midpoint of x* and x. Pairing both at the same instant makes the energy of an
    // exact trajectory exact to O(h^2); pairing v(t - h/2) with x(t) would be off by O(h).
    m.kineticEnergy += 0.5 * mass * speed * speed;
    m.potentialEnergy += potential(mass, 0.5 * (x + xPrevious));
  }
  // Rigid bodies: as for particles, the velocity is the last substep's middle's, and the potential
  // is taken there too, between the pose before the substep and now.
  const RigidBodies& r = rigidBodies_;
  for (RigidId i{}; i < r.size(); ++i) {
    if (r.inverseMass[i] == 0.0) continue;
    const Real mass = 1.0 / r.inverseMass[i];
    if (anyAsleep && islands_.bodySleeps(r.body[i])) {
      m.potentialEnergy += potential(mass, r.position[i]);
      continue;
    }
    const Vec3 spin = glm::conjugate(r.orientation[i]) * r.angularVelocity[i];  // body frame
    m.kineticEnergy += 0.5 * mass * glm::dot(r.velocity[i], r.velocity[i]) +
                       0.5 * glm::dot(spin, spin / r.inverseInertia[i]);
    m.potentialEnergy += potential(mass, 0.5 * (r.position[i] + r.previousPosition[i]));
    // A bound on the fastest point (the centre's speed and the turning of the farthest corner),
    // as sleeping measures rest: loose for a spin about the long axis, never under.
    const Body& body = bodies_[r.body[i]];
    m.maxSpeed = maxOf(m.maxSpeed, glm::length(r.velocity[i]) +
                                       glm::length(r.angularVelocity[i]) * glm::length(body.halfExtents));
  }
  Real sumSquares = 0.0;
  for (const Stick& s : constraints_.sticks()) {
    const Real length = glm::length(particles_.position[s.b] - particles_.position[s.a]);
    Real violation = 0.0;
    if (length < s.minLength)
      violation = (s.minLength - length) / s.minLength;
    else if (length > s.maxLength)
      violation = (length - s.maxLength) / s.maxLength;
    m.maxConstraintError = maxOf(m.maxConstraintError, violation);
    sumSquares += violation * violation;
  }
  if (!constraints_.sticks().empty())
    m.rmsConstraintError = std::sqrt(sumSquares / static_cast<Real>(constraints_.sticks().size()));
  auto jointError = [&m](const Vec3& a, const Vec3& b, Real minLength, Real maxLength) {
    const Real length = glm::length(b - a);
    const Real violation = length < minLength ? minLength - length : std::max(0.0, length - maxLength);
    m.maxJointError = maxOf(m.maxJointError, violation);
  };
  for (const Link& link : constraints_.links())
    jointError(positionOf(link.a), positionOf(link.b), link.minLength, link.maxLength);
  for (const RigidLink& link : constraints_.rigidLinks())
    jointError(positionOf(link.a), positionOf(link.b), link.minLength, link.maxLength);
  for (const RigidJoint& j : constraints_.rigidJoints()) {
    jointError(r.position[j.a] + r.orientation[j.a] * j.pivotA,
               r.position[j.b] + r.orientation[j.b] * j.pivotB, 0.0, 0.0);
  }
  if (world_.ground) {
    for (const GroundContact& c : ground_.points()) {
      const Real depth = world_.groundHeight + c.lift - glm::dot(world_.groundNormal, positionOf(c.point));
      m.maxPenetration = maxOf(m.maxPenetration, depth);
    }
  }
  m.contacts = static_cast<int>(
      std::count(ground_.state().touched.begin(), ground_.state().touched.end(), std::uint8_t{1}));
  for (std::size_t k = 0; k < narrowPhase_.contacts().size(); ++k) {
    const BodyContact& c = narrowPhase_.contacts()[k];
    const Real gap = glm::dot(c.normal, positionOf(c.pointB) - positionOf(c.pointA)) - c.offset;
    m.maxPenetration = maxOf(m.maxPenetration, -gap);
    if (narrowPhase_.state().touched[k] != 0) ++m.contacts;
  }
  if (world_.ground) {
    // Every body's lowest point, whatever its contacts hold: a particle capsule's ground points are
    // where the passes put them, and one the passes held wrong (turned inside out, its points on
    // its top face: docs/physics.md, "Capsules") rested a radius under the ground reading 0 here.
    for (BodyId id{}; id < bodies_.size(); ++id)
      m.maxPenetration = maxOf(m.maxPenetration, world_.groundHeight - lowestHeight(id, bodies_[id]));
  }
  for (std::span<const RigidContact> list :
       {narrowPhase_.rigidContacts(), std::span<const RigidContact>(rigidGround_)}) {
    for (const RigidContact& c : list) {
      if (c.sideA == ContactSide::Ground) continue;  // measured above, from every body's lowest point
      const Vec3 a =
          detail::sidePosition(particles_, rigidBodies_, c.sideA, c.rigidA, c.localA, c.pointA, false);
      const Vec3 b =
          detail::sidePosition(particles_, rigidBodies_, c.sideB, c.rigidB, c.localB, c.pointB, false);
      m.maxPenetration = maxOf(m.maxPenetration, -glm::dot(c.normal, b - a));
    }
  }
  for (const std::uint8_t touched : narrowPhase_.rigidState().touched) m.contacts += touched;
  for (const std::uint8_t touched : rigidGroundState_.touched) m.contacts += touched;
  m.frozen = 0;
  for (const FreezeReport& f : freezes()) {
    // A rigid body counts as one.
    m.frozen += f.body != kNoBody ? std::max(1, bodies_[f.body].particleCount) : 1;
  }
  return m;
}

std::uint64_t World::stateHash() const {
  return detail::stateHash(particles_.position, particles_.previous, rigidBodies_.position,
                           rigidBodies_.velocity, rigidBodies_.angularVelocity, rigidBodies_.orientation,
                           std::span<const Character>(characters_));
}

}  // namespace phys
