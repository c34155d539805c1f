#include "physics/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "passes.h"
#include "pose.h"

namespace phys {
namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

struct Pair {
  int a, b;
};

// The corners model's bracing. 12 edges and one diagonal on each of the 6 faces make
// 18 = 3 * 8 - 6, the fewest sticks that hold 8 points rigid (a convex polyhedron with
// triangulated faces is rigid: Cauchy and Dehn), and the seed's count per box. The 4 body
// diagonals are on top: without them a shear of the whole box must travel through three sticks
// per relaxation pass to be corrected, with them through one.
constexpr Pair kCornerSticks[22] = {
    // edges along x, y and z (corner bits: 1 = x, 2 = y, 4 = z)
    {0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7},
    // one diagonal per face: -x, +x, -y, +y, -z, +z
    {0, 6}, {1, 7}, {0, 5}, {2, 7}, {0, 3}, {4, 7},
    // body diagonals
    {0, 7}, {1, 6}, {2, 5}, {3, 4}};
// The tetra model: all 6 edges of the tetrahedron, rigid with 4 particles (3 * 4 - 6 = 6).
constexpr Pair kTetraSticks[6] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

Material combine(const Material& a, const Material& b) {
  return {std::sqrt(a.staticFriction * b.staticFriction), std::sqrt(a.dynamicFriction * b.dynamicFriction)};
}

using Clock = std::chrono::steady_clock;
double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

World::World(const WorldSettings& world, const SolverSettings& solver) {
  setWorldSettings(world);
  setSolverSettings(solver);
}

void World::setWorldSettings(const WorldSettings& settings) {
  const std::string why = validate(settings);
  require(why.empty(), "WorldSettings: " + why);
  world_ = settings;
  world_.groundNormal = glm::normalize(settings.groundNormal);
  combineMaterials();
}

void World::setSolverSettings(const SolverSettings& settings) {
  const std::string why = validate(settings);
  require(why.empty(), "SolverSettings: " + why);
  const Real hOld = substepDt(), hNew = settings.dt / settings.substeps;
  if (hNew != hOld) keepVelocities(hOld, hNew);
  solver_ = settings;
}

// x - x* is the velocity half a substep back, times the substep: (x - x*) = v(t - h/2) h. A new
// substep h' needs v(t - h'/2) = v(t - h/2) + a (h - h') / 2, with a gravity: exact for a body in
// free flight. A body resting on the ground gets the same small term, g (h - h') h' / 2 in
// position, always less than the g h'^2 its next integration adds, which the ground takes up.
void World::keepVelocities(Real hOld, Real hNew) {
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    Vec3 halfStepVelocity = (particles_.position[i] - particles_.previous[i]) / hOld;
    if (particles_.inverseMass[i] != 0.0) halfStepVelocity += gravityAt(particles_.position[i]) * ((hOld - hNew) / 2);
    particles_.previous[i] = particles_.position[i] - halfStepVelocity * hNew;
  }
}

void World::setFreezeCallback(std::function<void(const FreezeReport&)> callback) { onFreeze_ = std::move(callback); }

void World::combineMaterials() {
  for (GroundContact& c : contactPoints_) c.combined = combine(c.material, world_.groundMaterial);
}

ParticleId World::addParticle(const ParticleDesc& desc) {
  require(finite(desc.position), "addParticle: position must be finite");
  require(finite(desc.velocity), "addParticle: velocity must be finite");
  require(desc.pinned || (std::isfinite(desc.mass) && desc.mass > 0.0),
          "addParticle: mass must be finite and > 0 (kg) unless pinned");
  // Verlet's x - x* is the velocity half a substep back. For v(t0) = v to hold exactly under
  // the current gravity g, x* = x - (v - g h / 2) h; then free fall is exact to round-off.
  const Real h = substepDt();
  const Vec3 halfStepVelocity = desc.pinned ? Vec3(0.0) : desc.velocity - gravityAt(desc.position) * (h / 2);
  const auto id = static_cast<ParticleId>(particles_.size());
  particles_.position.push_back(desc.position);
  particles_.previous.push_back(desc.position - halfStepVelocity * h);
  particles_.inverseMass.push_back(desc.pinned ? 0.0 : 1.0 / desc.mass);
  particleName_.push_back(desc.name);
  particleBody_.push_back(-1);
  movedByBoxContact_.push_back(0);
  jacobiDelta_.emplace_back(0.0);
  jacobiCount_.push_back(0.0);
  Embedding self;
  self.particle[0] = id;
  self.weight[0] = 1.0;
  self.count = 1;
  addContactPoint(self, world_.groundMaterial, -1);
  return id;
}

void World::addContactPoint(const Embedding& point, const Material& material, std::int32_t body) {
  contactPoints_.push_back({point, material, combine(material, world_.groundMaterial), body});
  normalPush_.push_back(0.0);
  touched_.push_back(0);
}

void World::addStick(ParticleId a, ParticleId b, Real compliance) {
  require(a < particles_.size() && b < particles_.size() && a != b,
          "addStick: particle ids must exist and differ");
  addStick(a, b, glm::length(particles_.position[b] - particles_.position[a]), compliance);
}

void World::addStick(ParticleId a, ParticleId b, Real length, Real compliance) {
  require(std::isfinite(length) && length > 0.0, "addStick: length must be finite and > 0 (m)");
  addRange(a, b, length, length, compliance);
}

void World::addRange(ParticleId a, ParticleId b, Real minLength, Real maxLength, Real compliance) {
  require(a < particles_.size() && b < particles_.size() && a != b, "stick: particle ids must exist and differ");
  require(std::isfinite(minLength) && minLength >= 0.0, "stick: min length must be finite and >= 0 (m)");
  require(!std::isnan(maxLength) && maxLength > 0.0 && maxLength >= minLength,
          "stick: max length must be > 0 (m) and >= min length");
  require(std::isfinite(compliance) && compliance >= 0.0, "stick: compliance must be finite and >= 0 (m/N)");
  sticks_.push_back({a, b, minLength, maxLength, compliance});
  lambda_.push_back(0.0);
}

BoxId World::addBox(const BoxDesc& desc) {
  require(finite(desc.center) && finite(desc.velocity) && finite(desc.angularVelocity),
          "addBox: center, velocity and angular velocity must be finite");
  require(finite(desc.size) && desc.size.x > 0.0 && desc.size.y > 0.0 && desc.size.z > 0.0,
          "addBox: size must be finite and > 0 (m)");
  require(std::isfinite(desc.mass) && desc.mass > 0.0, "addBox: mass must be finite and > 0 (kg)");
  const Real qLength = glm::length(desc.orientation);
  require(std::isfinite(qLength) && qLength > 0.0, "addBox: orientation must be a finite non-zero quaternion");
  require(validate(desc.material).empty(), "addBox: " + validate(desc.material));
  const Quat q = desc.orientation / qLength;

  Box box;
  box.name = desc.name;
  box.model = desc.model;
  box.halfExtents = desc.size * 0.5;
  box.material = desc.material;
  box.particleCount = boxParticleCount(desc.model);
  box.firstParticle = static_cast<ParticleId>(particles_.size());
  box.firstCorner = static_cast<std::uint32_t>(corners_.size());
  const auto boxIndex = static_cast<std::int32_t>(boxes_.size());
  const std::size_t contactsBefore = contactPoints_.size();

  for (int j = 0; j < box.particleCount; ++j) {
    const Vec3 offset = q * boxParticleLocal(desc.model, box.halfExtents, j);
    addParticle({desc.center + offset, desc.velocity + glm::cross(desc.angularVelocity, offset),
                 desc.mass / box.particleCount, false, {}});
    particleBody_.back() = boxIndex;
  }
  // The particles' own contact points go: the box touches the ground with its corners.
  contactPoints_.resize(contactsBefore);
  normalPush_.resize(contactsBefore);
  touched_.resize(contactsBefore);

  const std::span<const Pair> pairs = desc.model == BoxModel::Corners ? std::span<const Pair>(kCornerSticks)
                                                                       : std::span<const Pair>(kTetraSticks);
  for (const Pair& p : pairs) addStick(box.firstParticle + p.a, box.firstParticle + p.b);

  for (int k = 0; k < 8; ++k) {
    Embedding corner;
    if (desc.model == BoxModel::Corners) {
      corner.particle[0] = box.firstParticle + k;
      corner.weight[0] = 1.0;
      corner.count = 1;
    } else {
      // Barycentric weights of the corner in the rest tetrahedron: solve [r_j; 1] b = [c_k; 1].
      // The four rest points are never coplanar, so the matrix is always invertible.
      glm::dmat4 m(0.0);
      for (int j = 0; j < 4; ++j) m[j] = glm::dvec4(boxParticleLocal(desc.model, box.halfExtents, j), 1.0);
      const glm::dvec4 b = glm::inverse(m) * glm::dvec4(boxCornerLocal(box.halfExtents, k), 1.0);
      for (int j = 0; j < 4; ++j) {
        corner.particle[j] = box.firstParticle + j;
        corner.weight[j] = b[j];
      }
      corner.count = 4;
    }
    corners_.push_back(corner);
    addContactPoint(corner, desc.material, boxIndex);
  }
  box.collisionGroup = desc.collisionGroup;
  box.collisionMask = desc.collisionMask;
  boxes_.push_back(box);
  frames_.emplace_back();
  sweep_.push_back({0.0, 0.0, static_cast<BoxId>(boxIndex)});
  return static_cast<BoxId>(boxIndex);
}

void World::relax(Real h) {
  const bool ground = world_.ground;
  for (int it = 0; it < solver_.iterations; ++it) {
    auto start = Clock::now();
    switch (solver_.method) {
      case SolverMethod::GaussSeidel: detail::relaxGaussSeidel(particles_, sticks_); break;
      case SolverMethod::Jacobi: detail::relaxJacobi(particles_, sticks_, jacobiDelta_, jacobiCount_); break;
      case SolverMethod::Xpbd: detail::relaxXpbd(particles_, sticks_, lambda_, h); break;
      case SolverMethod::Shake: detail::relaxShake(particles_, sticks_); break;
    }
    profile_.constraints += millisecondsSince(start);
    // The ground first, then the box contacts: in a stack the ground's push then travels up
    // through the contacts within the same pass instead of one pass later.
    start = Clock::now();
    detail::solveBodyContacts(particles_, bodyContacts_, solver_.contactSlop, bodyPush_, movedByBoxContact_);
    if (ground) {
      detail::collideGround(particles_, contactPoints_, world_.groundNormal, world_.groundHeight, normalPush_);
    }
    profile_.contacts += millisecondsSince(start);
  }
}

void World::step() {
  const auto stepStart = Clock::now();
  profile_ = {};
  std::fill(touched_.begin(), touched_.end(), std::uint8_t{0});
  std::fill(movedByBoxContact_.begin(), movedByBoxContact_.end(), std::uint8_t{0});
  const Real h = substepDt();
  for (int s = 0; s < solver_.substeps; ++s) {
    auto start = Clock::now();
    detail::integrate(particles_, world_, h);
    profile_.integrate += millisecondsSince(start);

    // Contacts are found once per substep, from the integrated positions, and then kept
    // satisfied through the iterations (Macklin et al. 2019 find them once per frame).
    start = Clock::now();
    if (boxes_.size() >= 2) {
      updateBoxFrames();
      findBoxPairs();
      buildBoxContacts();
    }
    profile_.collide += millisecondsSince(start);

    std::fill(normalPush_.begin(), normalPush_.end(), 0.0);
    std::fill(lambda_.begin(), lambda_.end(), 0.0);
    relax(h);

    start = Clock::now();
    detail::applyBodyFriction(particles_, bodyContacts_, bodyPush_);
    if (world_.ground) {
      detail::applyGroundFriction(particles_, contactPoints_, world_.groundNormal, normalPush_);
      for (std::size_t c = 0; c < touched_.size(); ++c) {
        if (normalPush_[c] > 0.0) touched_[c] = 1;
      }
    }
    profile_.friction += millisecondsSince(start);

    time_ += h;
    start = Clock::now();
    guard();
    profile_.guard += millisecondsSince(start);
  }
  ++steps_;
  profile_.total = millisecondsSince(stepStart);
}

void World::guard() {
  const Real bound = world_.bound;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (particles_.inverseMass[i] == 0.0) continue;
    const Vec3& x = particles_.position[i];
    if (!finite(x)) {
      freeze(static_cast<ParticleId>(i), "non-finite position");
    } else if (std::abs(x.x) > bound || std::abs(x.y) > bound || std::abs(x.z) > bound) {
      freeze(static_cast<ParticleId>(i), "left the world bound of " + std::to_string(bound) + " m");
    }
  }
}

void World::freeze(ParticleId bad, const std::string& reason) {
  ParticleId first = bad, count = 1;
  std::string name = particleName_[bad].empty() ? "particle " + std::to_string(bad) : particleName_[bad];
  if (const std::int32_t body = particleBody_[bad]; body >= 0) {
    const Box& box = boxes_[static_cast<std::size_t>(body)];
    first = box.firstParticle;
    count = static_cast<ParticleId>(box.particleCount);
    name = box.name.empty() ? "box " + std::to_string(body) : box.name;
  }
  for (ParticleId i = first; i < first + count; ++i) {
    // x* was checked at the end of the previous substep, so it is a good place to stop.
    if (!finite(particles_.position[i])) particles_.position[i] = finite(particles_.previous[i]) ? particles_.previous[i] : Vec3(0.0);
    particles_.previous[i] = particles_.position[i];
    particles_.inverseMass[i] = 0.0;
  }
  freezes_.push_back({name, reason, bad, time_});
  if (onFreeze_) onFreeze_(freezes_.back());
}

Vec3 World::velocity(ParticleId id) const {
  return (particles_.position.at(id) - particles_.previous.at(id)) / substepDt();
}

Vec3 World::position(const Embedding& point) const { return detail::embeddedPosition(particles_.position, point); }

Vec3 World::gravityAt(const Vec3& x) const {
  if (world_.gravityMode == GravityMode::Uniform) return world_.gravity;
  const Vec3 towards = world_.gravityPoint - x;
  const Real distance = glm::length(towards);
  return distance > 0.0 ? towards * (world_.gravityStrength / distance) : Vec3(0.0);
}

BoxPose World::boxPose(BoxId id) const {
  const Box& box = boxes_.at(id);
  BoxPose pose;
  const Vec3* x = &particles_.position[box.firstParticle];
  for (int j = 0; j < box.particleCount; ++j) pose.center += x[j];
  pose.center /= static_cast<Real>(box.particleCount);
  // Shape matching (Müller et al. 2005): A = sum (x_j - c) r_j^T is R S for a rigid motion.
  glm::dmat3 A(0.0);
  for (int j = 0; j < box.particleCount; ++j) {
    A += glm::outerProduct(x[j] - pose.center, boxParticleLocal(box.model, box.halfExtents, j));
  }
  pose.orientation = glm::normalize(glm::quat_cast(detail::nearestRotation(A)));
  return pose;
}

}  // namespace phys
