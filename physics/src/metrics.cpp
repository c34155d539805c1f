// World::metrics and World::stateHash: read-only figures of the current state.
#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include "passes.h"
#include "physics/world.h"

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
      "integrate", "frames",   "broad-phase", "narrow-phase", "parting",      "sticks",
      "links",     "contacts", "friction",    "restitution",  "body-damping", "guard"};
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
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const Real w = particles_.inverseMass[i];
    if (w == 0.0) continue;
    const Real mass = 1.0 / w;
    const Vec3& x = particles_.position[i];
    const Vec3& xPrevious = particles_.previous[i];
    const Vec3 v = (x - xPrevious) / h;
    const Real speed = glm::length(v);
    m.maxSpeed = maxOf(m.maxSpeed, speed);
    // Verlet knows the velocity half a substep back, at t - h/2; take the potential there too,
    // at the midpoint of x* and x. Pairing both at the same instant makes the energy of an
    // exact trajectory exact to O(h^2); pairing v(t - h/2) with x(t) would be off by O(h).
    m.kineticEnergy += 0.5 * mass * speed * speed;
    const Vec3 xHalf = 0.5 * (x + xPrevious);
    // Uniform gravity has potential -m g . x; the fixed-strength pull, m s |x - p|.
    m.potentialEnergy += world_.gravityMode == GravityMode::Uniform
                             ? -mass * glm::dot(world_.gravity, xHalf)
                             : mass * world_.gravityStrength * glm::length(xHalf - world_.gravityPoint);
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
  for (const Link& link : constraints_.links()) {
    const Real length = glm::length(position(link.b) - position(link.a));
    const Real violation =
        length < link.minLength ? link.minLength - length : std::max(0.0, length - link.maxLength);
    m.maxJointError = maxOf(m.maxJointError, violation);
  }
  if (world_.ground) {
    for (const GroundContact& c : ground_.points()) {
      const Real depth = world_.groundHeight + c.lift - glm::dot(world_.groundNormal, position(c.point));
      m.maxPenetration = maxOf(m.maxPenetration, depth);
    }
  }
  m.contacts = static_cast<int>(
      std::count(ground_.state().touched.begin(), ground_.state().touched.end(), std::uint8_t{1}));
  for (std::size_t k = 0; k < narrowPhase_.contacts().size(); ++k) {
    const BodyContact& c = narrowPhase_.contacts()[k];
    const Real gap = glm::dot(c.normal, position(c.pointB) - position(c.pointA)) - c.offset;
    m.maxPenetration = maxOf(m.maxPenetration, -gap);
    if (narrowPhase_.state().touched[k] != 0) ++m.contacts;
  }
  m.frozen = 0;
  for (const FreezeReport& f : freezes()) {
    const BodyId body = particleBody_[f.particle];
    m.frozen += body != kNoBody ? bodies_[body].particleCount : 1;
  }
  return m;
}

// FNV-1a, 64 bit, over the bytes of every position and previous position.
std::uint64_t World::stateHash() const {
  std::uint64_t hash = 14695981039346656037ull;
  auto mix = [&hash](const std::vector<Vec3>& values) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
    for (std::size_t i = 0; i < values.size() * sizeof(Vec3); ++i) {
      hash ^= bytes[i];
      hash *= 1099511628211ull;
    }
  };
  mix(particles_.position);
  mix(particles_.previous);
  return hash;
}

}  // namespace phys
