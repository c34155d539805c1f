#include "world_compare.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include "physics/character.h"

namespace testsupport {
namespace {

using phys::Quat;
using phys::Real;
using phys::Vec3;

constexpr Real kEpsilon = std::numeric_limits<Real>::epsilon();
// Keeps a tolerance of a body at the origin with a tiny size above zero, so a difference that
// is round-off in the last subnormal bit is not reported.
constexpr Real kFloor = std::numeric_limits<Real>::denorm_min();

// Numbers as the scene files print them (shortest text that reads back as the same double), so
// a message can be pasted into a file.
std::string text(Real value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string text(const Vec3& v) {
  return text(v.x) + " " + text(v.y) + " " + text(v.z);
}

std::string text(const glm::vec3& v) {
  return text(Vec3(v));
}

std::string text(const Quat& q) {
  return "w " + text(q.w) + ", xyz " + text(Vec3(q.x, q.y, q.z));
}

// "what: saved A, reloaded B" for values that must be equal.
template <typename T>
std::string unequal(const std::string& what, const T& saved, const T& reloaded) {
  return what + ": saved " + text(saved) + ", reloaded " + text(reloaded);
}

std::string unequalText(const std::string& what, const std::string& saved, const std::string& reloaded) {
  return what + ": saved '" + saved + "', reloaded '" + reloaded + "'";
}

Real distance(const Vec3& a, const Vec3& b) {
  return glm::length(a - b);
}

Real distance(Real a, Real b) {
  return std::abs(a - b);
}

// Empty when |saved - reloaded| <= tolerance; else a message naming what(), which is called
// only then: a world of thousands of bodies is compared without building a label for each.
template <typename What, typename Value>
std::string within(const What& what, const Value& saved, const Value& reloaded, Real tolerance) {
  const Real difference = distance(saved, reloaded);
  if (difference <= tolerance) return {};
  return unequal(what(), saved, reloaded) + ", |difference| " + text(difference) + " > tolerance " +
         text(tolerance);
}

// A label for within(): "<who()>: <field>".
template <typename Who>
auto field(const Who& who, const char* name) {
  return [&who, name] { return who() + ": " + name; };
}

std::string boxLabel(const phys::World& world, std::size_t id) {
  const std::string& name = world.bodies()[id].name;
  return "box #" + std::to_string(id) + (name.empty() ? "" : " '" + name + "'");
}

std::string particleLabel(const phys::World& world, std::size_t id) {
  const std::string& name = world.particleName(static_cast<phys::ParticleId>(id));
  return "particle #" + std::to_string(id) + (name.empty() ? "" : " '" + name + "'");
}

// The velocity a scene file would give the particle (scenes' loadVelocity): Verlet's
// (x - x*) / h is half a substep behind, and the loader adds gravity's half substep back.
Vec3 loadVelocity(const phys::World& world, std::size_t id) {
  const phys::SolverSettings& solver = world.solverSettings();
  const Real h = solver.dt / solver.substeps;
  const auto p = static_cast<phys::ParticleId>(id);
  return world.velocity(p) + world.gravityAt(world.particles().position[p]) * (h / 2);
}

// A box as one rigid body: the pose World::bodyPose fits, the velocity and spin that best match
// its particles' (least squares over equal masses: the mean velocity, and the spin that keeps
// the angular momentum about the centre), the mass its particles hold. Written here rather than
// taken from the writer, so the writer is checked against an independent reading of the world.
struct Rigid {
  phys::BodyPose pose;
  Vec3 velocity{0.0};
  Vec3 spin{0.0};
  Real mass = 0.0;
  bool frozen = false;  // the guard took its mass
  Real scale = 0.0;     // |centre| + |half extents|: the size of its particles' coordinates
  Real middleHalfExtent = 0.0;
  Real smallestHalfExtent = 0.0;
};

Rigid rigid(const phys::World& world, std::size_t id) {
  const phys::Body& box = world.bodies()[id];
  const phys::Particles& particles = world.particles();
  Rigid r;
  r.pose = world.bodyPose(static_cast<phys::BodyId>(id));
  r.scale = glm::length(r.pose.center) + glm::length(box.halfExtents);
  Real sorted[3] = {box.halfExtents.x, box.halfExtents.y, box.halfExtents.z};
  std::sort(sorted, sorted + 3);
  r.smallestHalfExtent = sorted[0];
  r.middleHalfExtent = sorted[1];
  if (box.model == phys::BodyModel::Rigid) {
    // Its own state: the velocity at load time is the substep's middle's plus g h / 2.
    const phys::RigidBodies& bodies = world.rigidBodies();
    const Real h = world.solverSettings().dt / world.solverSettings().substeps;
    r.frozen = bodies.inverseMass[box.rigid] == 0.0;
    r.mass = r.frozen ? 0.0 : 1.0 / bodies.inverseMass[box.rigid];
    r.velocity = bodies.velocity[box.rigid] + world.gravityAt(r.pose.center) * (h / 2);
    r.spin = bodies.angularVelocity[box.rigid];
    return r;
  }
  std::array<Vec3, 8> velocities{};
  for (int j = 0; j < box.particleCount; ++j) {
    const std::size_t p = box.firstParticle + j;
    if (particles.inverseMass[p] == 0.0) {
      r.frozen = true;
    } else {
      r.mass += 1.0 / particles.inverseMass[p];
    }
    velocities[j] = loadVelocity(world, p);
    r.velocity += velocities[j];
  }
  r.velocity /= static_cast<Real>(box.particleCount);
  glm::dmat3 inertia(0.0);
  Vec3 momentum(0.0);
  for (int j = 0; j < box.particleCount; ++j) {
    const Vec3 arm = r.pose.orientation * phys::boxParticleLocal(box.model, box.halfExtents, j);
    inertia += glm::dmat3(glm::dot(arm, arm)) - glm::outerProduct(arm, arm);
    momentum += glm::cross(arm, velocities[j] - r.velocity);
  }
  r.spin = glm::inverse(inertia) * momentum;
  return r;
}

// The angle (rad) of the turn from a to b, accurate near 0 where acos is not.
Real angleBetween(const Quat& a, const Quat& b) {
  const Quat d = glm::conjugate(glm::normalize(a)) * glm::normalize(b);
  return 2.0 * std::atan2(glm::length(Vec3(d.x, d.y, d.z)), std::abs(d.w));
}

class Comparison {
 public:
  Comparison(const scenes::Scene& saved, const scenes::Scene& reloaded, const Tolerance& tolerance)
      : saved_(saved),
        reloaded_(reloaded),
        s_(saved.world),
        r_(reloaded.world),
        tol_(tolerance),
        h_(s_.solverSettings().dt / s_.solverSettings().substeps) {}

  std::string run() {
    std::string d;
    if (!(d = scene()).empty()) return d;
    if (!(d = worldSettings()).empty()) return d;
    if (!(d = solverSettings()).empty()) return d;
    if (!(d = counts()).empty()) return d;
    if (!(d = names()).empty()) return d;
    for (std::size_t b = 0; b < s_.bodies().size(); ++b) {
      if (!(d = box(b)).empty()) return d;
    }
    for (std::size_t p = 0; p < s_.particles().size(); ++p) {
      if (owner_[p] == phys::kNoBody && !(d = particle(p)).empty()) return d;
    }
    for (std::size_t k = 0; k < s_.sticks().size(); ++k) {
      if (!(d = stick(k)).empty()) return d;
    }
    for (std::size_t k = 0; k < s_.links().size(); ++k) {
      if (!(d = link(k)).empty()) return d;
    }
    if (!(d = jointFrictions()).empty()) return d;
    if (!(d = particleJoints()).empty()) return d;
    if (!(d = characters()).empty()) return d;
    return noCollision();
  }

 private:
  std::string scene() const {
    // The writer names an unnamed scene; the loader requires a name.
    const std::string name = saved_.name.empty() ? "untitled" : saved_.name;
    if (name != reloaded_.name) return unequalText("scene name", name, reloaded_.name);
    if (saved_.description != reloaded_.description) {
      return unequalText("scene description", saved_.description, reloaded_.description);
    }
    if (saved_.camera.eye != reloaded_.camera.eye)
      return unequal("camera eye", saved_.camera.eye, reloaded_.camera.eye);
    if (saved_.camera.target != reloaded_.camera.target)
      return unequal("camera target", saved_.camera.target, reloaded_.camera.target);
    return {};
  }

  // Settings are written as the very doubles they hold: exact.
  std::string worldSettings() const {
    const phys::WorldSettings &a = s_.worldSettings(), &b = r_.worldSettings();
    if (a.gravityMode != b.gravityMode) {
      return unequalText("<world> gravity-mode", std::string(phys::toString(a.gravityMode)),
                         std::string(phys::toString(b.gravityMode)));
    }
    if (a.gravity != b.gravity) return unequal("<world> gravity", a.gravity, b.gravity);
    if (a.gravityPoint != b.gravityPoint)
      return unequal("<world> gravity-point", a.gravityPoint, b.gravityPoint);
    if (a.gravityStrength != b.gravityStrength)
      return unequal("<world> gravity-strength", a.gravityStrength, b.gravityStrength);
    if (a.damping != b.damping) return unequal("<world> damping", a.damping, b.damping);
    if (a.bound != b.bound) return unequal("<world> bound", a.bound, b.bound);
    if (a.ground != b.ground)
      return unequalText("<ground>", a.ground ? "present" : "absent", b.ground ? "present" : "absent");
    if (!a.ground) return {};  // without a ground, its height, normal and friction mean nothing
    if (a.groundHeight != b.groundHeight) return unequal("<ground> height", a.groundHeight, b.groundHeight);
    // The loader normalises the normal again, and a unit vector divided by its own length (1
    // give or take an ulp) may move by an ulp per component: 8 ulps of 1 in all.
    if (std::string d = within([] { return std::string("<ground> normal"); }, a.groundNormal, b.groundNormal,
                               8.0 * kEpsilon);
        !d.empty())
      return d;
    if (a.groundMaterial.staticFriction != b.groundMaterial.staticFriction) {
      return unequal("<ground> static-friction", a.groundMaterial.staticFriction,
                     b.groundMaterial.staticFriction);
    }
    if (a.groundMaterial.dynamicFriction != b.groundMaterial.dynamicFriction) {
      return unequal("<ground> dynamic-friction", a.groundMaterial.dynamicFriction,
                     b.groundMaterial.dynamicFriction);
    }
    return {};
  }

  std::string solverSettings() const {
    const phys::SolverSettings &a = s_.solverSettings(), &b = r_.solverSettings();
    if (a.method != b.method) {
      return unequalText("<solver> method", std::string(phys::toString(a.method)),
                         std::string(phys::toString(b.method)));
    }
    if (a.iterations != b.iterations) return unequal<Real>("<solver> iterations", a.iterations, b.iterations);
    if (a.substeps != b.substeps) return unequal<Real>("<solver> substeps", a.substeps, b.substeps);
    if (a.dt != b.dt) return unequal("<solver> dt", a.dt, b.dt);
    if (a.featureEpsilon != b.featureEpsilon)
      return unequal("<solver> epsilon", a.featureEpsilon, b.featureEpsilon);
    if (a.contactSlop != b.contactSlop) return unequal("<solver> slop", a.contactSlop, b.contactSlop);
    if (a.bodyDamping != b.bodyDamping) return unequal("<solver> body-damping", a.bodyDamping, b.bodyDamping);
    if (a.restitution != b.restitution) return unequal("<solver> restitution", a.restitution, b.restitution);
    if (a.compliance != b.compliance) return unequal("<solver> compliance", a.compliance, b.compliance);
    if (a.maxDepenetrationSpeed != b.maxDepenetrationSpeed) {
      return unequal("<solver> depenetration-speed", a.maxDepenetrationSpeed, b.maxDepenetrationSpeed);
    }
    if (a.threads != b.threads) return unequal<Real>("<solver> threads", a.threads, b.threads);
    if (a.sleep.enabled != b.sleep.enabled) {
      return unequalText("<solver> sleep", a.sleep.enabled ? "on" : "off", b.sleep.enabled ? "on" : "off");
    }
    if (a.sleep.speed != b.sleep.speed) return unequal("<solver> sleep-speed", a.sleep.speed, b.sleep.speed);
    if (a.sleep.time != b.sleep.time) return unequal("<solver> sleep-time", a.sleep.time, b.sleep.time);
    return {};
  }

  std::string counts() {
    auto count = [](const std::string& what, std::size_t a, std::size_t b) -> std::string {
      if (a == b) return {};
      return what + ": saved " + std::to_string(a) + ", reloaded " + std::to_string(b);
    };
    std::string d;
    if (!(d = count("particles", s_.particles().size(), r_.particles().size())).empty()) return d;
    if (!(d = count("boxes", s_.bodies().size(), r_.bodies().size())).empty()) return d;
    if (!(d = count("sticks", s_.sticks().size(), r_.sticks().size())).empty()) return d;
    if (!(d = count("links", s_.links().size(), r_.links().size())).empty()) return d;
    if (!(d = count("joint frictions", s_.jointFrictions().size(), r_.jointFrictions().size())).empty())
      return d;
    if (!(d = count("particle joints", s_.particleJoints().size(), r_.particleJoints().size())).empty())
      return d;
    owner_ = s_.particleBodies();
    if (!std::ranges::equal(owner_, r_.particleBodies()))
      return "the particles belong to different boxes after the reload";
    // Each saved box fitted once: sticks and links refer to their boxes' fits again and again.
    savedRigid_.reserve(s_.bodies().size());
    for (std::size_t b = 0; b < s_.bodies().size(); ++b) savedRigid_.push_back(rigid(s_, b));
    return {};
  }

  // Every name the saved scene knows is known after the reload, for the same body. The writer
  // may add names (every box gets one), so the reloaded list can be longer.
  std::string names() const {
    std::map<std::string, const scenes::NamedBody*> reloaded;
    for (const scenes::NamedBody& b : reloaded_.bodies) reloaded[b.name] = &b;
    for (const scenes::NamedBody& b : saved_.bodies) {
      const auto it = reloaded.find(b.name);
      const char* kind = b.kind == scenes::NamedBody::Kind::Body ? "box" : "particle";
      if (it == reloaded.end())
        return "the name '" + b.name + "' (" + kind + " #" + std::to_string(b.index) + ") is lost";
      if (it->second->kind != b.kind || it->second->index != b.index) {
        return "the name '" + b.name + "' names " + kind + " #" + std::to_string(b.index) + " when saved, " +
               (it->second->kind == scenes::NamedBody::Kind::Body ? "box" : "particle") + " #" +
               std::to_string(it->second->index) + " when reloaded";
      }
    }
    return {};
  }

  std::string box(std::size_t id) const {
    const phys::Body &a = s_.bodies()[id], &b = r_.bodies()[id];
    auto who = [&] { return boxLabel(s_, id); };
    if (!a.name.empty() && a.name != b.name) return unequalText(who() + ": name", a.name, b.name);
    if (a.model != b.model) {
      return unequalText(who() + ": model", std::string(phys::toString(a.model)),
                         std::string(phys::toString(b.model)));
    }
    if (a.shape != b.shape) {
      return unequalText(who() + ": shape", std::string(phys::toString(a.shape)),
                         std::string(phys::toString(b.shape)));
    }
    // A <box> size is twice the half extents, a <capsule>'s radius and length likewise: exact.
    if (a.halfExtents != b.halfExtents)
      return unequal(who() + ": half extents", a.halfExtents, b.halfExtents);
    if (a.material.staticFriction != b.material.staticFriction)
      return unequal(who() + ": static-friction", a.material.staticFriction, b.material.staticFriction);
    if (a.material.dynamicFriction != b.material.dynamicFriction)
      return unequal(who() + ": dynamic-friction", a.material.dynamicFriction, b.material.dynamicFriction);
    if (a.collisionGroup != b.collisionGroup)
      return unequal<Real>(who() + ": group", a.collisionGroup, b.collisionGroup);
    if (a.collisionMask != b.collisionMask)
      return unequal<Real>(who() + ": mask", a.collisionMask, b.collisionMask);

    const Rigid& was = savedRigid_[id];
    const Rigid now = rigid(r_, id);
    if (now.frozen) return who() + ": frozen after the reload (some particle has no mass)";
    std::string d;
    // The pose: what the writer wrote, rebuilt and fitted again.
    if (!(d = within(field(who, "centre"), was.pose.center, now.pose.center,
                     tol_.relative * was.scale + kFloor))
             .empty())
      return d;
    const Real angleTolerance = orientationTolerance(was);
    if (const Real turn = angleBetween(was.pose.orientation, now.pose.orientation);
        !(turn <= angleTolerance)) {
      return unequal(who() + ": orientation", was.pose.orientation, now.pose.orientation) + ", turned by " +
             text(turn) + " rad > tolerance " + text(angleTolerance);
    }
    // A frozen box is saved at rest with BodyDesc's mass: the guard took its own.
    const Real mass = was.frozen ? phys::BodyDesc{}.mass : was.mass;
    const Vec3 velocity = was.frozen ? Vec3(0.0) : was.velocity;
    const Vec3 spin = was.frozen ? Vec3(0.0) : was.spin;
    if (!(d = within(field(who, "mass"), mass, now.mass, tol_.relative * mass)).empty()) return d;
    // The particles' speeds, of which the fit's round-off is a share: the centre's, the spin's
    // at the corners, and gravity's half substep that the load velocity adds.
    const Real speed = glm::length(velocity) + glm::length(spin) * glm::length(a.halfExtents) +
                       glm::length(s_.gravityAt(was.pose.center)) * h_;
    const Real velocityTolerance = tol_.relative * speed + this->velocityTolerance(was.scale);
    if (!(d = within(field(who, "velocity"), velocity, now.velocity, velocityTolerance)).empty()) return d;
    // The spin is fitted from the corners' velocities about lever arms known only to the positions'
    // round-off, which is what bounds the orientation too: a spin's direction is known to that
    // angle. (Found by the fuzzer: a 1 cm box at 1e9 m spinning at 1.75e11 rad/s came back with
    // its y and z spin 1.6e5 rad/s off, an angle of 1e-6 against an orientation tolerance of 0.2.)
    const Real spinTolerance = tol_.relative * glm::length(spin) +
                               glm::length(spin) * orientationTolerance(was) +
                               velocityTolerance / std::max(was.middleHalfExtent, kFloor);
    return within(field(who, "spin (rad/s)"), spin, now.spin, spinTolerance);
  }

  Real orientationTolerance(const Rigid& body) const {
    return tol_.angle + tol_.relative * body.scale / std::max(body.middleHalfExtent, kFloor);
  }

  // How well a velocity is known at positions of this size (Tolerance::velocityUlps).
  Real velocityTolerance(Real positionScale) const {
    return tol_.velocityUlps * kEpsilon * positionScale / h_ + kFloor;
  }

  std::string particle(std::size_t id) const {
    auto who = [&] { return particleLabel(s_, id); };
    const std::string &a = s_.particleName(static_cast<phys::ParticleId>(id)),
                      &b = r_.particleName(static_cast<phys::ParticleId>(id));
    if (!a.empty() && a != b) return unequalText(who() + ": name", a, b);
    const phys::Particles &ps = s_.particles(), &pr = r_.particles();
    // A loose particle's position is written as the very double: exact.
    if (ps.position[id] != pr.position[id])
      return unequal(who() + ": position", ps.position[id], pr.position[id]);
    // Pinned, or frozen by the guard, which the file says as pinned.
    const bool wasPinned = ps.inverseMass[id] == 0.0, isPinned = pr.inverseMass[id] == 0.0;
    if (wasPinned != isPinned) {
      return unequalText(who() + ": pinned", wasPinned ? "true" : "false", isPinned ? "true" : "false");
    }
    if (wasPinned) return {};
    std::string d;
    // The mass is written as 1 / inverse mass and read back as its inverse: an ulp or two.
    if (!(d = within(field(who, "inverse mass"), ps.inverseMass[id], pr.inverseMass[id],
                     tol_.relative * ps.inverseMass[id]))
             .empty())
      return d;
    const Vec3 v = loadVelocity(s_, id);
    const Real speed = glm::length(v) + glm::length(s_.gravityAt(ps.position[id])) * h_;
    const Real tolerance = tol_.relative * speed + velocityTolerance(glm::length(ps.position[id]));
    return within(field(who, "velocity"), v, loadVelocity(r_, id), tolerance);
  }

  std::string stick(std::size_t k) const {
    const phys::Stick &a = s_.sticks()[k], &b = r_.sticks()[k];
    auto who = [&] {
      return "stick #" + std::to_string(k) + " (" + particleLabel(s_, a.a) + " to " + particleLabel(s_, a.b) +
             ")";
    };
    if (a.a != b.a || a.b != b.b) {
      return who() + ": joins particles #" + std::to_string(b.a) + " and #" + std::to_string(b.b) +
             " when reloaded";
    }
    if (a.compliance != b.compliance) return unequal(who() + ": compliance", a.compliance, b.compliance);
    if (owner_[a.a] == phys::kNoBody) {
      // A <stick> holds its length, min and max as written: exact (kNoMaxLength is infinity).
      if (a.minLength != b.minLength) return unequal(who() + ": min length", a.minLength, b.minLength);
      if (a.maxLength != b.maxLength) return unequal(who() + ": max length", a.maxLength, b.maxLength);
      return {};
    }
    // A box's bracing is rebuilt at the distances of its new particles, which the pose's
    // round-off moves by a few ulps of their coordinates.
    const Real tolerance = tol_.relative * savedRigid_[static_cast<std::size_t>(owner_[a.a])].scale + kFloor;
    std::string d;
    if (!(d = within(field(who, "min length"), a.minLength, b.minLength, tolerance)).empty()) return d;
    return within(field(who, "max length"), a.maxLength, b.maxLength, tolerance);
  }

  std::string link(std::size_t k) const {
    const phys::Link &a = s_.links()[k], &b = r_.links()[k];
    auto who = [&] {
      return "link #" + std::to_string(k) + " (" + endLabel(a.a) + " to " + endLabel(a.b) + ")";
    };
    if (endBody(a.a) != endBody(b.a) || endBody(a.b) != endBody(b.b)) {
      return who() + ": joins " + endLabel(b.a) + " and " + endLabel(b.b) + " when reloaded";
    }
    if (a.minLength != b.minLength) return unequal(who() + ": min length", a.minLength, b.minLength);
    if (a.maxLength != b.maxLength) return unequal(who() + ": max length", a.maxLength, b.maxLength);
    std::string d;
    if (!(d = point(field(who, "point a"), a.a, b.a)).empty()) return d;
    return point(field(who, "point b"), a.b, b.b);
  }

  // One end of a link: the world position of its point, saved and reloaded. A box's end is
  // anchored anew at the saved point in the rebuilt box: barycentric weights that grow with the
  // point's distance from the box in half extents, and the orientation's error over that lever.
  template <typename What>
  std::string point(const What& what, const phys::Embedding& saved, const phys::Embedding& reloaded) const {
    const Vec3 p = s_.position(saved), q = r_.position(reloaded);
    const phys::BodyId body = owner_[saved.particle[0]];
    if (body == phys::kNoBody) return p == q ? std::string() : unequal(what(), p, q);
    const Rigid& was = savedRigid_[static_cast<std::size_t>(body)];
    const Real lever = glm::length(p - was.pose.center);
    const Real tolerance = tol_.relative * (was.scale + glm::length(p)) *
                               (1.0 + lever / std::max(was.smallestHalfExtent, kFloor)) +
                           orientationTolerance(was) * lever + kFloor;
    return within(what, p, q, tolerance);
  }

  // The body an end is carried by: a box (>= 0) or a loose particle (-2 - its id).
  std::int64_t endBody(const phys::Embedding& e) const {
    const phys::BodyId body = owner_[e.particle[0]];
    return body == phys::kNoBody ? -2 - static_cast<std::int64_t>(e.particle[0]) : std::int64_t{body};
  }

  std::string endLabel(const phys::Embedding& e) const {
    const phys::BodyId body = owner_[e.particle[0]];
    return body == phys::kNoBody ? particleLabel(s_, e.particle[0])
                                 : boxLabel(s_, static_cast<std::size_t>(body));
  }

  // Joint friction is exact: two body ids and a rate the writer prints to the bit.
  std::string jointFrictions() const {
    const auto a = s_.jointFrictions(), b = r_.jointFrictions();
    for (std::size_t k = 0; k < a.size(); ++k) {
      const std::string who = "joint friction " + std::to_string(k);
      if (a[k].a != b[k].a || a[k].b != b[k].b) {
        return who + ": joins " + boxLabel(s_, a[k].a) + " and " + boxLabel(s_, a[k].b) + " when saved, " +
               boxLabel(r_, b[k].a) + " and " + boxLabel(r_, b[k].b) + " when reloaded";
      }
      if (a[k].rate != b[k].rate) return unequal(who + ": rate", a[k].rate, b[k].rate);
    }
    return {};
  }

  // A particle joint joins the same two bodies; its pivots, written in the world, come back in the
  // bodies' frames within 1e-9 m; its rest and its drive's target, written in degrees, within 1e-12 rad;
  // the drive's strength and stiffness to the bit.
  std::string particleJoints() const {
    const auto a = s_.particleJoints(), b = r_.particleJoints();
    for (std::size_t k = 0; k < a.size(); ++k) {
      const std::string who = "particle joint " + std::to_string(k);
      if (a[k].a != b[k].a || a[k].b != b[k].b) {
        return who + ": joins " + boxLabel(s_, a[k].a) + " and " + boxLabel(s_, a[k].b) + " when saved, " +
               boxLabel(r_, b[k].a) + " and " + boxLabel(r_, b[k].b) + " when reloaded";
      }
      if (glm::length(a[k].pivotA - b[k].pivotA) > 1e-9)
        return unequal(who + ": pivot in a", a[k].pivotA, b[k].pivotA);
      if (glm::length(a[k].pivotB - b[k].pivotB) > 1e-9)
        return unequal(who + ": pivot in b", a[k].pivotB, b[k].pivotB);
      if (const Real turn = angleBetween(a[k].rest, b[k].rest); turn > 1e-12)
        return who + ": the rest turned by " + std::to_string(turn) + " rad";
      const phys::JointDrive &x = s_.particleJointDrive(k), &y = r_.particleJointDrive(k);
      if (x.strength != y.strength) return unequal(who + ": drive strength", x.strength, y.strength);
      if (x.stiffness != y.stiffness) return unequal(who + ": drive stiffness", x.stiffness, y.stiffness);
      if (const Real turn = angleBetween(x.target, y.target); turn > 1e-12)
        return who + ": the drive's target turned by " + std::to_string(turn) + " rad";
    }
    return {};
  }

  // A character is saved as the clip it plays, by the file that clip
  // came from, with its clock, the strengths last set and as a reaction has ramped them, each part's
  // share, its reaction's settings and state, a queued change of clip, a fade under way, its clip
  // frame's origin and its root drive's stiffnesses: every number to the bit; its heading, written in
  // degrees, within 1e-12 rad.
  std::string characters() const {
    const auto a = s_.characters(), b = r_.characters();
    if (a.size() != b.size()) {
      return "characters: saved " + std::to_string(a.size()) + ", reloaded " + std::to_string(b.size());
    }
    auto clipName = [](const phys::Playback& p) { return p.clip ? p.clip->name : std::string("none"); };
    for (std::size_t k = 0; k < a.size(); ++k) {
      const phys::Character &x = a[k], &y = b[k];
      const std::string who = "character " + std::to_string(k) + " on '" + x.ragdoll + "'";
      if (x.ragdoll != y.ragdoll) return unequalText(who + ": ragdoll", x.ragdoll, y.ragdoll);
      if (clipName(x.now) != clipName(y.now))
        return unequalText(who + ": clip", clipName(x.now), clipName(y.now));
      const std::pair<const char*, std::pair<Real, Real>> numbers[] = {
          {"time", {x.now.time, y.now.time}},
          {"speed", {x.now.speed, y.now.speed}},
          {"loop", {Real(x.now.loop), Real(y.now.loop)}},
          {"strength", {x.goalStrength, y.goalStrength}},
          {"root-strength", {x.goalRootStrength, y.goalRootStrength}},
          {"balance", {x.goalBalance, y.goalBalance}},
          {"scale", {x.scale, y.scale}},
          {"react", {x.reaction.threshold, y.reaction.threshold}},
          {"fall-time", {x.reaction.fallTime, y.reaction.fallTime}},
          {"rest-time", {x.reaction.restTime, y.reaction.restTime}},
          {"arm-time", {x.reaction.armTime, y.reaction.armTime}},
          {"rest-speed", {x.reaction.restSpeed, y.reaction.restSpeed}},
          {"get-up-time", {x.reaction.getUpTime, y.reaction.getUpTime}},
          {"state", {Real(x.state), Real(y.state)}},
          {"state-time", {x.stateTime, y.stateTime}},
          {"still-time", {x.stillTime, y.stillTime}},
          {"strength-now", {x.strength, y.strength}},
          {"root-strength-now", {x.rootStrength, y.rootStrength}},
          {"balance-now", {x.balance, y.balance}},
          {"from-strength", {x.fromStrength, y.fromStrength}},
          {"from-balance", {x.fromBalance, y.fromBalance}},
          {"root stiffness", {x.rootStiffness, y.rootStiffness}},
          {"root angular stiffness", {x.rootAngularStiffness, y.rootAngularStiffness}},
      };
      for (const auto& [name, pair] : numbers) {
        if (pair.first != pair.second) return unequal(who + ": " + name, pair.first, pair.second);
      }
      if (x.rootOffset != y.rootOffset) return unequal(who + ": root-offset", x.rootOffset, y.rootOffset);
      if (x.origin != y.origin) return unequal(who + ": origin", x.origin, y.origin);
      if (x.blend != y.blend) return unequal(who + ": blend", x.blend, y.blend);
      if (x.blend < 1.0) {
        if (x.blendTime != y.blendTime) return unequal(who + ": blend-time", x.blendTime, y.blendTime);
        if (clipName(x.before) != clipName(y.before))
          return unequalText(who + ": from-clip", clipName(x.before), clipName(y.before));
        if (x.before.time != y.before.time) return unequal(who + ": from-time", x.before.time, y.before.time);
        if (x.beforeShift != y.beforeShift)
          return unequal(who + ": from-shift", x.beforeShift, y.beforeShift);
        if (x.holding != y.holding) return unequal<Real>(who + ": holding", Real(x.holding), Real(y.holding));
        if (x.holding && x.held.root != y.held.root)
          return unequal(who + ": held-root", x.held.root, y.held.root);
        for (std::size_t t = 0; x.holding && t < x.held.turns.size(); ++t) {
          if (x.held.turns[t] != y.held.turns[t]) return unequalText(who + ": held-turns", "saved", "other");
        }
      }
      if (const Real turn = angleBetween(x.frame, y.frame); turn > 1e-12)
        return unequal<Real>(who + ": heading, turned by (rad)", 0.0, turn);
      if (x.partStrength.size() != y.partStrength.size())
        return unequal<Real>(who + ": parts", Real(x.partStrength.size()), Real(y.partStrength.size()));
      for (std::size_t p = 0; p < x.partStrength.size(); ++p) {
        if (x.partStrength[p] != y.partStrength[p])
          return unequal(who + ": part " + std::to_string(p) + "'s strength", x.partStrength[p],
                         y.partStrength[p]);
      }
      if (clipName(x.reaction.getUp) != clipName(y.reaction.getUp))
        return unequalText(who + ": get-up", clipName(x.reaction.getUp), clipName(y.reaction.getUp));
      if (x.queued.has_value() != y.queued.has_value())
        return unequalText(who + ": then", x.queued ? "a clip" : "none", y.queued ? "a clip" : "none");
      if (!x.queued) continue;
      const phys::QueuedClip &qx = *x.queued, &qy = *y.queued;
      if (clipName(qx.playback) != clipName(qy.playback))
        return unequalText(who + ": then", clipName(qx.playback), clipName(qy.playback));
      if (qx.at != qy.at) return unequal(who + ": then-at", qx.at, qy.at);
      if (qx.blendTime != qy.blendTime) return unequal(who + ": then-blend", qx.blendTime, qy.blendTime);
      if (qx.playback.loop != qy.playback.loop)
        return unequal<Real>(who + ": then-loop", Real(qx.playback.loop), Real(qy.playback.loop));
    }
    return {};
  }

  std::string noCollision() const {
    const auto a = s_.ignoredCollisions(), b = r_.ignoredCollisions();
    if (a == b) return {};
    auto list = [](const std::vector<std::pair<phys::BodyId, phys::BodyId>>& pairs) {
      std::string out;
      for (const auto& [x, y] : pairs) out += " (" + std::to_string(x) + " " + std::to_string(y) + ")";
      return out.empty() ? std::string(" none") : out;
    };
    return "pairs kept from colliding: saved" + list(a) + ", reloaded" + list(b);
  }

  const scenes::Scene& saved_;
  const scenes::Scene& reloaded_;
  const phys::World& s_;
  const phys::World& r_;
  const Tolerance& tol_;
  const Real h_;                         // the substep (s), the same in both once the settings agree
  std::span<const phys::BodyId> owner_;  // the saved world's World::particleBodies()
  std::vector<Rigid> savedRigid_;        // per box of the saved world
};

}  // namespace

std::string compareScenes(const scenes::Scene& saved, const scenes::Scene& reloaded,
                          const Tolerance& tolerance) {
  return Comparison(saved, reloaded, tolerance).run();
}

}  // namespace testsupport
