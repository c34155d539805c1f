#include "physics/world.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include "passes.h"
#include "pose.h"

namespace phys {
namespace {

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
    {0, 1},
    {2, 3},
    {4, 5},
    {6, 7},
    {0, 2},
    {1, 3},
    {4, 6},
    {5, 7},
    {0, 4},
    {1, 5},
    {2, 6},
    {3, 7},
    // one diagonal per face: -x, +x, -y, +y, -z, +z
    {0, 6},
    {1, 7},
    {0, 5},
    {2, 7},
    {0, 3},
    {4, 7},
    // body diagonals
    {0, 7},
    {1, 6},
    {2, 5},
    {3, 4}};
// The tetra model: all 6 edges of the tetrahedron, rigid with 4 particles (3 * 4 - 6 = 6).
constexpr Pair kTetraSticks[6] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

Material combine(const Material& a, const Material& b) {
  return {std::sqrt(a.staticFriction * b.staticFriction), std::sqrt(a.dynamicFriction * b.dynamicFriction)};
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
  const bool stiffer = settings.iterations * settings.substeps > solver_.iterations * solver_.substeps;
  solver_ = settings;
  if (stiffer) settleWithoutVelocity();
  guardParticles();  // both can overflow under absurd gravity or speeds
}

// More passes per step relax what fewer left: a resting box's sag, a chain's stretch. Projected
// out in the next step, that stored error would turn into speed (a 1 m box going from 1 to 16
// substeps hopped 5 mm). So relax it now, moving x* with x: the shapes are restored and no
// velocity changes. Runs only when the settings change, never in the step.
void World::settleWithoutVelocity() {
  std::vector<Vec3> before = particles_.position;
  updateLayouts();
  // Links created apart keep their gaps: they close at their own pace (World::step).
  const std::span<const Real> slack =
      linksApart_ > 0 ? std::span<const Real>(linkSlack_) : std::span<const Real>();
  for (int pass = 0; pass < 4 * solver_.iterations * solver_.substeps && pass < 200; ++pass) {
    detail::relaxGaussSeidel(particles_, sticks_, stickLayout_);
    detail::solveLinks(particles_, links_, linkLayout_, slack);
    detail::solveBodyContacts(particles_, bodyContacts_, solver_.contactSlop, bodyPush_, movedByBoxContact_);
    if (world_.ground)
      detail::collideGround(particles_, contactPoints_, world_.groundNormal, world_.groundHeight,
                            normalPush_);
  }
  std::fill(bodyPush_.begin(), bodyPush_.end(), 0.0);
  for (std::size_t i = 0; i < particles_.size(); ++i)
    particles_.previous[i] += particles_.position[i] - before[i];
  std::fill(normalPush_.begin(), normalPush_.end(), 0.0);
}

// x - x* is the velocity half a substep back, times the substep: (x - x*) = v(t - h/2) h. A new
// substep h' needs v(t - h'/2) = v(t - h/2) + a (h - h') / 2. For a body in free flight a is
// gravity, and this keeps its trajectory exact. A body that touched the ground or another box
// in the last step is held up, its net acceleration about zero: it keeps its half-step velocity,
// or a smaller step would drive it into its support and it would rebound (up to 5 mm for a 1 m
// box going from 1 to 16 substeps).
void World::keepVelocities(Real hOld, Real hNew) {
  std::vector<std::uint8_t> supported(particles_.size(), 0);
  auto support = [&](std::int32_t body, const Embedding& point) {
    if (body >= 0) {
      const Box& box = boxes_[static_cast<std::size_t>(body)];
      std::fill_n(supported.begin() + box.firstParticle, box.particleCount, std::uint8_t{1});
    } else {
      supported[point.particle[0]] = 1;
    }
  };
  for (std::size_t c = 0; c < contactPoints_.size(); ++c) {
    if (touched_[c] != 0) support(contactPoints_[c].body, contactPoints_[c].point);
  }
  for (std::size_t k = 0; k < bodyContacts_.size(); ++k) {
    if (bodyTouched_[k] == 0) continue;
    support(bodyContacts_[k].boxA, bodyContacts_[k].pointA);
    support(bodyContacts_[k].boxB, bodyContacts_[k].pointB);
  }
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    Vec3 halfStepVelocity = (particles_.position[i] - particles_.previous[i]) / hOld;
    if (supported[i] == 0 && particles_.inverseMass[i] != 0.0) {
      halfStepVelocity += gravityAt(particles_.position[i]) * ((hOld - hNew) / 2);
    }
    particles_.previous[i] = particles_.position[i] - halfStepVelocity * hNew;
  }
}

void World::setFreezeCallback(std::function<void(const FreezeReport&)> callback) {
  onFreeze_ = std::move(callback);
}

void World::combineMaterials() {
  for (GroundContact& c : contactPoints_) {
    // A loose particle has no material of its own: it slides as the ground says.
    c.combined = c.body >= 0 ? combine(c.material, world_.groundMaterial) : world_.groundMaterial;
  }
}

ParticleId World::addParticle(const ParticleDesc& desc) {
  require(finite(desc.position), "addParticle: position must be finite");
  require(finite(desc.velocity), "addParticle: velocity must be finite");
  require(desc.pinned || (std::isfinite(desc.mass) && desc.mass > 0.0 && std::isfinite(1.0 / desc.mass)),
          "addParticle: mass must be finite and > 0 (kg) unless pinned");
  // Verlet's x - x* is the velocity half a substep back. For v(t0) = v to hold exactly under
  // the current gravity g, x* = x - (v - g h / 2) h; then free fall is exact to round-off.
  const Real h = substepDt();
  const Vec3 halfStepVelocity = desc.pinned ? Vec3(0.0) : desc.velocity - gravityAt(desc.position) * (h / 2);
  const auto id = static_cast<ParticleId>(particles_.size());
  particles_.position.push_back(desc.position);
  particles_.previous.push_back(desc.position - halfStepVelocity * h);
  particles_.inverseMass.push_back(desc.pinned ? 0.0 : 1.0 / desc.mass);
  checked_.push_back(desc.position);
  particleName_.push_back(desc.name);
  particleBody_.push_back(-1);
  movedByBoxContact_.push_back(0);
  jacobiDelta_.emplace_back(0.0);
  degree_.push_back(0.0);
  addContactPoint(embedParticle(id), world_.groundMaterial, -1);
  return id;
}

void World::addContactPoint(const Embedding& point, const Material& material, std::int32_t body) {
  contactPoints_.push_back(
      {point, material, body >= 0 ? combine(material, world_.groundMaterial) : world_.groundMaterial, body});
  normalPush_.push_back(0.0);
  touched_.push_back(0);
  groundHit_.push_back(0);
  groundApproach_.push_back(0.0);
  groundAllowance_.push_back(0.0);
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
  require(a < particles_.size() && b < particles_.size() && a != b,
          "stick: particle ids must exist and differ");
  require(std::isfinite(minLength) && minLength >= 0.0, "stick: min length must be finite and >= 0 (m)");
  require(!std::isnan(maxLength) && maxLength > 0.0 && maxLength >= minLength,
          "stick: max length must be > 0 (m) and >= min length");
  require(std::isfinite(compliance) && compliance >= 0.0 && compliance <= kMaxCompliance,
          "stick: compliance must be from 0 to 1e6 (m/N)");
  sticks_.push_back({a, b, minLength, maxLength, compliance});
  layoutsStale_ = true;
  joinGroups(a, b);
  lambda_.push_back(0.0);
  degree_[a] += 1.0;
  degree_[b] += 1.0;
}

// An embedding must be an affine combination of existing particles; `who` prefixes the message.
void World::checkEmbedding(const Embedding& e, const std::string& who) const {
  require(e.count >= 1 && e.count <= 4, who + ": an embedding needs 1 to 4 particles");
  Real sum = 0.0;
  for (int i = 0; i < e.count; ++i) {
    require(e.particle[i] < particles_.size(), who + ": particle ids must exist");
    require(std::isfinite(e.weight[i]), who + ": weights must be finite");
    sum += e.weight[i];
  }
  require(std::abs(sum - 1.0) < 1e-9, who + ": an embedding's weights must sum to 1");
}

void World::addLink(const Embedding& a, const Embedding& b, Real minLength, Real maxLength) {
  checkEmbedding(a, "addLink");
  checkEmbedding(b, "addLink");
  require(std::isfinite(minLength) && minLength >= 0.0, "addLink: min length must be finite and >= 0 (m)");
  require(!std::isnan(maxLength) && maxLength >= minLength, "addLink: max length must be >= min length (m)");
  links_.push_back({a, b, minLength, maxLength});
  layoutsStale_ = true;
  // Created outside its bounds (a pin whose points were placed apart), it is brought within them
  // at most at maxDepenetrationSpeed, from the next step on (World::step).
  linkSlack_.push_back(detail::linkViolation(particles_.position, links_.back()));
  if (linkSlack_.back() != 0.0) ++linksApart_;
  joinGroups(a.particle[0], b.particle[0]);
}

void World::setDrag(const Drag& drag) {
  checkEmbedding(drag.point, "setDrag");
  require(finite(drag.target), "setDrag: target must be finite");
  require(std::isfinite(drag.stiffness) && drag.stiffness >= 0.0,
          "setDrag: stiffness must be finite and >= 0 (N/m)");
  require(std::isfinite(drag.damping) && drag.damping >= 0.0,
          "setDrag: damping must be finite and >= 0 (N s/m)");
  drag_ = drag;
  // The box that carries the point answers the pull as a rigid body; a point carried by anything
  // else (a loose particle, particles of several bodies) is moved through its carriers alone.
  dragBox_ = particleBody_[drag.point.particle[0]];
  for (int i = 1; i < drag.point.count; ++i) {
    if (particleBody_[drag.point.particle[i]] != dragBox_) dragBox_ = -1;
  }
}

void World::setDragTarget(const Vec3& target) {
  require(drag_.has_value(), "setDragTarget: no drag is set");
  require(finite(target), "setDragTarget: target must be finite");
  drag_->target = target;
}

Embedding World::anchor(BoxId id, const Vec3& worldPoint) const {
  require(id < boxes_.size(), "anchor: box id must exist");
  require(finite(worldPoint), "anchor: the point must be finite");
  const Box& box = boxes_[id];
  const BoxPose pose = boxPose(id);
  return detail::rigidEmbedding(
      box, (glm::inverse(pose.orientation) * (worldPoint - pose.center)) / box.halfExtents);
}

BoxId World::addBox(const BoxDesc& desc) {
  require(finite(desc.center) && finite(desc.velocity) && finite(desc.angularVelocity),
          "addBox: center, velocity and angular velocity must be finite");
  require(finite(desc.size) && desc.size.x > 0.0 && desc.size.y > 0.0 && desc.size.z > 0.0,
          "addBox: size must be finite and > 0 (m)");
  require(std::isfinite(desc.mass) && desc.mass > 0.0, "addBox: mass must be finite and > 0 (kg)");
  const Real qLength = glm::length(desc.orientation);
  require(std::isfinite(qLength) && qLength > 0.0,
          "addBox: orientation must be a finite non-zero quaternion");
  require(validate(desc.material).empty(), "addBox: " + validate(desc.material));
  if (desc.shape == Shape::Capsule) {
    require(std::abs(desc.size.x - desc.size.z) <= 1e-9 * desc.size.x,
            "addBox: a capsule's size.x and size.z are both its diameter and must be equal (m)");
    require(desc.size.y >= desc.size.x,
            "addBox: a capsule's length size.y must be at least its diameter size.x (m)");
  }
  const Quat q = desc.orientation / qLength;

  Box box;
  box.name = desc.name;
  box.model = desc.model;
  box.shape = desc.shape;
  box.halfExtents = desc.size * 0.5;
  box.material = desc.material;
  box.particleCount = boxParticleCount(desc.model);
  box.firstParticle = static_cast<ParticleId>(particles_.size());
  box.firstCorner = static_cast<std::uint32_t>(corners_.size());
  const auto boxIndex = static_cast<std::int32_t>(boxes_.size());
  const std::size_t contactsBefore = contactPoints_.size();

  // Everything that can fail is checked before anything is added: a centre or size near the
  // largest double can overflow a corner to infinity.
  std::array<ParticleDesc, 8> parts;
  for (int j = 0; j < box.particleCount; ++j) {
    const Vec3 offset = q * boxParticleLocal(desc.model, box.halfExtents, j);
    parts[j] = {desc.center + offset,
                desc.velocity + glm::cross(desc.angularVelocity, offset),
                desc.mass / box.particleCount,
                false,
                {}};
    require(finite(parts[j].position) && finite(parts[j].velocity) && std::isfinite(1.0 / parts[j].mass),
            "addBox: centre, size, velocity or mass too large to represent");
    for (int i = 0; i < j; ++i) {
      const Real length = glm::length(parts[j].position - parts[i].position);
      require(std::isfinite(length) && length > 0.0, "addBox: centre or size too large to represent");
    }
  }
  for (int j = 0; j < box.particleCount; ++j) {
    addParticle(parts[j]);
    particleBody_.back() = boxIndex;
  }
  // The particles' own contact points go: the box touches the ground with its corners.
  contactPoints_.resize(contactsBefore);
  normalPush_.resize(contactsBefore);
  touched_.resize(contactsBefore);
  groundHit_.resize(contactsBefore);
  groundApproach_.resize(contactsBefore);
  groundAllowance_.resize(contactsBefore);

  const std::span<const Pair> pairs = desc.model == BoxModel::Corners ? std::span<const Pair>(kCornerSticks)
                                                                      : std::span<const Pair>(kTetraSticks);
  box.firstStick = static_cast<std::uint32_t>(sticks_.size());
  box.stickCount = static_cast<int>(pairs.size());
  for (const Pair& p : pairs) addStick(box.firstParticle + p.a, box.firstParticle + p.b);

  for (int k = 0; k < 8; ++k) {
    Embedding corner;
    if (desc.model == BoxModel::Corners) {
      corner.particle[0] = box.firstParticle + k;
      corner.weight[0] = 1.0;
      corner.count = 1;
    } else {
      const std::array<Real, 4> w = tetraWeights(boxCornerLocal(Vec3(1.0), k));
      for (int j = 0; j < 4; ++j) {
        corner.particle[j] = box.firstParticle + j;
        corner.weight[j] = w[j];
      }
      corner.count = 4;
    }
    corners_.push_back(corner);
    if (desc.shape == Shape::Box) addContactPoint(corner, desc.material, boxIndex);
  }
  if (desc.shape == Shape::Capsule) {
    // A capsule touches the ground with the lowest points of its two end spheres, which move
    // over its surface as it turns: placeCapsuleGroundPoints() re-embeds them every substep.
    const Real halfSegment = box.capsuleHalfSegment();
    for (const Real end : {-1.0, 1.0}) {
      const Vec3 core(0.0, end * halfSegment, 0.0);
      const Vec3 lowest = core + glm::inverse(q) * (-world_.groundNormal) * box.capsuleRadius();
      capsuleGround_.push_back({static_cast<std::uint32_t>(contactPoints_.size()), end});
      addContactPoint(detail::rigidEmbedding(box, lowest / box.halfExtents), desc.material, boxIndex);
    }
  }
  box.collisionGroup = desc.collisionGroup;
  box.collisionMask = desc.collisionMask;
  boxes_.push_back(box);
  layoutsStale_ = true;
  frames_.emplace_back();
  rigid_.emplace_back();
  partShift_.emplace_back(0.0);
  partWeight_.push_back(0.0);
  partGround_.push_back(0.0);
  partGroundPush_.push_back(0.0);
  crushedSince_.push_back(std::numeric_limits<Real>::infinity());
  sweep_.push_back({0.0, 0.0, static_cast<BoxId>(boxIndex)});
  bounds_.emplace_back();
  travel_.push_back(0.0);
  motion_.push_back({});
  pairFrames_.emplace_back();
  jointGroup_.push_back(static_cast<BoxId>(boxIndex));
  partRoot_.push_back(static_cast<BoxId>(boxIndex));
  pairsStale_ = true;
  return static_cast<BoxId>(boxIndex);
}

Vec3 World::velocity(ParticleId id) const {
  return (particles_.position.at(id) - particles_.previous.at(id)) / substepDt();
}

Vec3 World::position(const Embedding& point) const {
  return detail::embeddedPosition(particles_.position, point);
}

Vec3 World::gravityAt(const Vec3& x) const {
  if (world_.gravityMode == GravityMode::Uniform) return world_.gravity;
  const Vec3 towards = world_.gravityPoint - x;
  const Real distance = glm::length(towards);
  return distance > 0.0 ? towards * (world_.gravityStrength / distance) : Vec3(0.0);
}

// |g| in the current mode (m/s^2): in point mode, its strength wherever a body is.
Real World::gravityMagnitude() const {
  return world_.gravityMode == GravityMode::Uniform ? glm::length(world_.gravity) : world_.gravityStrength;
}

BoxPose World::boxPose(BoxId id) const {
  const Box& box = boxes_.at(id);
  BoxPose pose;
  const Vec3* x = &particles_.position[box.firstParticle];
  // Each particle's share summed, not the sum divided: the same digits for 4 or 8 particles (a
  // power of two), and no overflow for a body near the largest double (a bound of infinity).
  const Real share = 1.0 / static_cast<Real>(box.particleCount);
  for (int j = 0; j < box.particleCount; ++j) pose.center += x[j] * share;
  // Shape matching (Müller et al. 2005): A = sum (x_j - c) r_j^T is R S for a rigid motion.
  glm::dmat3 A(0.0);
  for (int j = 0; j < box.particleCount; ++j) {
    A += glm::outerProduct(x[j] - pose.center, boxParticleLocal(box.model, box.halfExtents, j));
  }
  pose.orientation = glm::normalize(glm::quat_cast(detail::nearestRotation(A)));
  return pose;
}

}  // namespace phys
