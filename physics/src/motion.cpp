// Motion: a world's moving state, taken out (World::motion) and given back (World::setMotion).
#include "physics/motion.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "physics/world.h"
#include "require.h"
#include "state_hash.h"

namespace phys {
namespace detail {

std::uint64_t stateHash(std::span<const Vec3> position, std::span<const Vec3> previous,
                        std::span<const Vec3> rigidPosition, std::span<const Vec3> rigidVelocity,
                        std::span<const Vec3> rigidAngularVelocity, std::span<const Quat> rigidOrientation) {
  std::uint64_t hash = 14695981039346656037ull;
  auto mix = [&hash](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      hash ^= bytes[i];
      hash *= 1099511628211ull;
    }
  };
  for (const std::span<const Vec3> values :
       {position, previous, rigidPosition, rigidVelocity, rigidAngularVelocity})
    mix(values.data(), values.size_bytes());
  for (const Quat& q : rigidOrientation) {
    const Real wxyz[4] = {q.w, q.x, q.y, q.z};
    mix(wxyz, sizeof(wxyz));
  }
  return hash;
}

}  // namespace detail

namespace {

bool allFinite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string sizes(std::size_t given, std::size_t wanted) {
  return std::to_string(given) + " given for " + std::to_string(wanted);
}

}  // namespace

std::string Motion::problem() const {
  if (!std::isfinite(time) || time < 0.0 || steps < 0) return "a non-finite or negative time or step count";
  for (const auto* values : {&position, &previous, &rigidPosition, &rigidVelocity, &rigidAngularVelocity}) {
    for (const Vec3& v : *values) {
      if (!allFinite(v)) return "a non-finite position or velocity";
    }
  }
  for (const Quat& q : rigidOrientation) {
    const Real length = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!(std::abs(length - 1.0) < kUnitTolerance)) return "an orientation not of unit length";
  }
  return {};
}

std::uint64_t Motion::hash() const {
  return detail::stateHash(position, previous, rigidPosition, rigidVelocity, rigidAngularVelocity,
                           rigidOrientation);
}

Motion World::motion() const {
  Motion m;
  m.position = particles_.position;
  m.previous = particles_.previous;
  m.rigidPosition = rigidBodies_.position;
  m.rigidOrientation = rigidBodies_.orientation;
  m.rigidVelocity = rigidBodies_.velocity;
  m.rigidAngularVelocity = rigidBodies_.angularVelocity;
  m.time = time_;
  m.steps = steps_;
  return m;
}

void World::setMotion(const Motion& m) {
  using detail::require;
  // A world that has stepped keeps contacts, warm starts, rest timers and the guard's last good
  // positions from its own motion; none of them would belong to the one given.
  require(steps_ == 0 && time_ == 0.0, "setMotion: the world has stepped (" + std::to_string(steps_) +
                                           " steps); give the motion to a world that has not");
  const std::size_t n = particles_.size(), r = rigidBodies_.size();
  require(m.position.size() == n && m.previous.size() == n,
          "setMotion: particle positions " + sizes(m.position.size(), n) + " particles, previous " +
              sizes(m.previous.size(), n));
  require(m.rigidPosition.size() == r && m.rigidOrientation.size() == r && m.rigidVelocity.size() == r &&
              m.rigidAngularVelocity.size() == r,
          "setMotion: rigid body poses or velocities for " + std::to_string(m.rigidPosition.size()) +
              " bodies, the world has " + std::to_string(r));
  const std::string problem = m.problem();
  require(problem.empty(), "setMotion: " + problem);
  particles_.position = m.position;
  particles_.previous = m.previous;
  std::copy(m.position.begin(), m.position.end(), guard_.checked().begin());
  rigidBodies_.position = rigidBodies_.previousPosition = m.rigidPosition;
  rigidBodies_.orientation = rigidBodies_.previousOrientation = m.rigidOrientation;
  rigidBodies_.velocity = m.rigidVelocity;
  rigidBodies_.angularVelocity = m.rigidAngularVelocity;
  time_ = m.time;
  steps_ = m.steps;
  updateBodyFrames();  // what raycast and the drawing read between steps
}

}  // namespace phys
