// The guard: what went bad is frozen where it was last good, and reported.
#include "physics/guard.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>

#include "physics/settings.h"

namespace phys {

void Guard::addBody() {
  crushedSince_.push_back(std::numeric_limits<Real>::infinity());
}

namespace {

// Whether any coordinate is beyond `limit` or not a number. A non-negative double's bits ordered
// as an integer order it as a number, NaN above infinity, so |x| <= limit is bits(|x|) <=
// bits(limit): bits(limit) - bits(|x|) goes negative for every coordinate that is not, and the
// sign bits of all of them or'd together answer. Integer subtraction and or, with no branch and
// no call, run in SIMD lanes (GCC 12 vectorises none of the comparisons of doubles written out).
bool anyBeyond(std::span<const Vec3> points, Real limit) {
  static_assert(sizeof(Vec3) == 3 * sizeof(Real) && alignof(Vec3) == alignof(Real));
  const Real* coordinates = reinterpret_cast<const Real*>(points.data());
  const auto limitBits = std::bit_cast<std::int64_t>(limit);
  constexpr std::int64_t kMagnitude = std::numeric_limits<std::int64_t>::max();  // all but the sign
  std::int64_t signs = 0;
  for (std::size_t i = 0; i < 3 * points.size(); ++i)
    signs |= limitBits - (std::bit_cast<std::int64_t>(coordinates[i]) & kMagnitude);
  return signs < 0;
}

// Particles one thread looks over at a time: a pass over their positions is a few microseconds.
constexpr std::size_t kParticlesPerPiece = 2048;

}  // namespace

// Every particle, pinned or not: World runs it after each substep and after a change of settings
// (World::guardParticles says why). Nearly always nothing is wrong, which one pass over the
// positions (within the bound) and the previous positions (finite) says in less than half the
// time that looking at each particle's case takes; only otherwise is each particle looked at.
void Guard::checkParticles(const GuardInput& in, Real bound, const Workers* workers) {
  const Particles& particles = in.particles;
  const std::span<const Vec3> position(particles.position), previous(particles.previous);
  const Real positionLimit = std::min(bound, std::numeric_limits<Real>::max());
  std::atomic<bool> anyBad{false};
  auto range = [&](std::size_t begin, std::size_t end) {
    if (anyBeyond(position.subspan(begin, end - begin), positionLimit) ||
        anyBeyond(previous.subspan(begin, end - begin), std::numeric_limits<Real>::max()))
      anyBad.store(true, std::memory_order_relaxed);
  };
  forEachRange(workers, particles.size(), kParticlesPerPiece, range);
  if (!anyBad.load()) return;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Vec3& x = particles.position[i];
    const auto id = static_cast<ParticleId>(i);
    if (particles.inverseMass[i] == 0.0) {
      // Pinned and frozen particles are never written, so this only catches a bug; say so.
      if (!finite(x)) freeze(in, id, "non-finite position of a pinned particle");
      continue;
    }
    if (!finite(x)) {
      freeze(in, id, "non-finite position");
    } else if (!finite(particles.previous[i])) {
      freeze(in, id, "non-finite velocity");  // x - x*, and so the metrics, must stay finite too
    } else if (!insideBound(x, bound)) {
      char reason[64];
      std::snprintf(reason, sizeof reason, "left the world bound of %g m", bound);
      freeze(in, id, reason);
    }
  }
}

// Past the limit for a moment is an impact; past it for kCrushedTime, a body that will not come
// back. Looked at every `interval` (WorldSettings::shapeCheckInterval), not every substep: a crush
// is a matter of seconds, and the sticks' lengths cost a pass over them.
void Guard::checkShapes(const GuardInput& in, Real interval) {
  nextShapeCheck_ = in.time + interval;
  const Real time = in.time;
  for (std::size_t b = 0; b < in.bodies.size(); ++b) {
    const Body& box = in.bodies[b];
    if (box.model == BodyModel::Rigid) continue;                       // no sticks to crush
    if (in.particles.inverseMass[box.firstParticle] == 0.0) continue;  // frozen
    Real& since = crushedSince_[b];
    const Real error = worstStickError(in, box);
    if (!(error > kCrushedStickError)) {
      since = std::numeric_limits<Real>::infinity();
      continue;
    }
    since = std::min(since, time);
    if (time - since < kCrushedTime) continue;
    char reason[96];
    std::snprintf(reason, sizeof reason, "crushed: a stick %.0f%% off its length, past %.0f%% for %g s",
                  100.0 * error, 100.0 * kCrushedStickError, kCrushedTime);
    freeze(in, box.firstParticle, reason);
  }
}

// The largest |length - rest| / rest (the violated bound, for a range) of the box's own sticks
// that are off by more than kCrushedStickError, or 0 if none is: compared squared, so no square
// root is taken while the box is sound.
Real Guard::worstStickError(const GuardInput& in, const Body& box) {
  Real worst = 0.0;
  const auto begin = in.sticks.begin() + box.firstStick;
  for (auto s = begin; s != begin + box.stickCount; ++s) {
    const Vec3 d = in.particles.position[s->b] - in.particles.position[s->a];
    const Real squared = glm::dot(d, d);
    const Real shortest = s->minLength * (1.0 - kCrushedStickError);
    const Real longest = s->maxLength * (1.0 + kCrushedStickError);
    if (squared >= shortest * shortest && squared <= longest * longest) continue;
    const Real length = std::sqrt(squared);
    worst = std::max(worst, length < s->minLength ? (s->minLength - length) / s->minLength
                                                  : (length - s->maxLength) / s->maxLength);
  }
  return worst;
}

void Guard::freeze(const GuardInput& in, ParticleId bad, const std::string& reason) {
  ParticleId first = bad;
  std::uint32_t count = 1;
  std::string name =
      in.particleNames[bad].empty() ? "particle " + std::to_string(bad) : in.particleNames[bad];
  if (const BodyId body = in.particleBodies[bad]; body != kNoBody) {
    const Body& box = in.bodies[static_cast<std::size_t>(body)];
    first = box.firstParticle;
    count = static_cast<std::uint32_t>(box.particleCount);
    name = box.name.empty() ? "box " + std::to_string(body) : box.name;
  }
  for (ParticleId i = first; i < first + count; ++i) {
    // Where the guard last found the whole body good (or where it was created): finite, and in
    // the bound unless it was created outside it. A frozen particle is never written again.
    in.particles.position[i] = in.particles.previous[i] = checked_[i];
    in.particles.inverseMass[i] = 0.0;
  }
  freezes_.push_back({name, reason, bad, in.time, in.particleBodies[bad]});
}

void Guard::checkRigidBodies(RigidBodies& rigid, std::span<const Body> bodies, Real bound, Real time) {
  for (RigidId i{}; i < rigid.size(); ++i) {
    if (rigid.inverseMass[i] == 0.0) continue;
    const Vec3& x = rigid.position[i];
    const Quat& q = rigid.orientation[i];
    std::string reason;
    if (!finite(x) || !std::isfinite(q.w) || !finite(Vec3(q.x, q.y, q.z))) {
      reason = "non-finite pose";
    } else if (!finite(rigid.velocity[i]) || !finite(rigid.angularVelocity[i])) {
      reason = "non-finite velocity";
    } else if (!insideBound(x, bound)) {
      char text[64];
      std::snprintf(text, sizeof text, "left the world bound of %g m", bound);
      reason = text;
    } else {
      continue;
    }
    // Not previousPosition: the parting may have moved it with the body, beyond the bound.
    rigid.position[i] = rigid.previousPosition[i] = checkedRigidPosition_[i];
    rigid.orientation[i] = rigid.previousOrientation[i] = checkedRigidOrientation_[i];
    rigid.velocity[i] = rigid.angularVelocity[i] = Vec3(0.0);
    rigid.inverseMass[i] = 0.0;
    rigid.inverseInertia[i] = Vec3(0.0);
    rigid.inverseInertiaWorld[i] = glm::dmat3(0.0);
    const BodyId body = rigid.body[i];
    const Body& b = bodies[body];
    freezes_.push_back(
        {b.name.empty() ? "box " + std::to_string(body) : b.name, reason, ParticleId{}, time, body});
  }
}

void Guard::report() {
  while (reported_ < freezes_.size()) {
    // Copies: the callback may step the world, which adds freezes and moves the list, or replace
    // itself.
    const FreezeReport freeze = freezes_[reported_++];
    if (const std::function<void(const FreezeReport&)> callback = onFreeze_; callback) callback(freeze);
  }
}

}  // namespace phys
