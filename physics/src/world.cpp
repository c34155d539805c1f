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
#include "require.h"
#include "rigid_motion.h"

namespace phys {

using detail::require;
using detail::requireIndex;

namespace {

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

// Whether the new settings may step the world otherwise than the old: all but the thread count and
// the broad phase's strips, under which the state is the same bit for bit (docs/physics.md,
// "Threads"; BroadPhase.TheStripSettingsChangeNoPair). Those wake nothing, so the sandbox's threads
// slider (it sleeps by default) does not change the run.
bool changesTheStep(const SolverSettings& before, SolverSettings after) {
  after.threads = before.threads;
  after.broadPhase = before.broadPhase;
  return !(after == before);
}

}  // namespace

World::World(const WorldSettings& world, const SolverSettings& solver) {
  setWorldSettings(world);
  setSolverSettings(solver);
}

void World::setWorldSettings(const WorldSettings& settings) {
  const std::string why = validate(settings);
  require(why.empty(), "WorldSettings: " + why);
  // Kept unit length, and compared as kept: the same normal given again, whatever its length, or the
  // kept one given back, is no change (compared as given, a normal of length 2 woke everything).
  WorldSettings kept = settings;
  kept.groundNormal = glm::normalize(settings.groundNormal);
  if (settings.groundNormal == world_.groundNormal) kept.groundNormal = world_.groundNormal;
  if (!(kept == world_)) islands_.wakeAll();  // new gravity, ground or bounds: all must answer
  world_ = kept;
  ground_.combineMaterials(world_.groundMaterial);
}

void World::setSolverSettings(const SolverSettings& settings) {
  const std::string why = validate(settings);
  require(why.empty(), "SolverSettings: " + why);
  const Real hOld = substepDt(), hNew = settings.dt / settings.substeps;
  if (hNew != hOld) keepVelocities(hOld, hNew);
  const bool stiffer = settings.iterations * settings.substeps > solver_.iterations * solver_.substeps;
  const bool projectionOn = settings.jointProjection.enabled && !solver_.jointProjection.enabled;
  if (changesTheStep(solver_, settings)) islands_.wakeAll();  // what rested under the old may not
  solver_ = settings;
  workers_.setThreads(settings.threads);
  if (stiffer) settleWithoutVelocity();
  // Joints the passes left open, closed by the next substep's projection, would become speed (30 cm
  // open on Bullet's pile: 36 m/s at 1/120 s). Closed now, the poses move and the velocities stay.
  if (projectionOn && !constraints_.rigidJoints().empty())
    jointProjection_.project(rigidBodies_, constraints_.rigidJoints(), solver_.jointProjection);
  guardParticles();  // both can overflow under absurd gravity or speeds
  guard_.report();
}

// More passes per step relax what fewer left: a resting box's sag, a chain's stretch. Projected
// out in the next step, that stored error would turn into speed (a 1 m box going from 1 to 16
// substeps hopped 5 mm). So relax it now, moving x* with x: the shapes are restored and no
// velocity changes. Runs only when the settings change, never in the step.
void World::settleWithoutVelocity() {
  std::vector<Vec3> before = particles_.position;
  updateLayouts();
  // Links created apart keep their gaps: they close at their own pace (World::step).
  const std::span<const Real> slack = constraints_.linkSlack();
  for (int pass = 0; pass < 4 * solver_.iterations * solver_.substeps && pass < 200; ++pass) {
    tetraVolumes_.keep(particles_, false);
    constraints_.relaxSticks(particles_, SolverMethod::GaussSeidel, pass == 0, substepDt(), 0.0);
    constraints_.solveLinks(particles_, slack);
    detail::solveBodyContacts(particles_, narrowPhase_.contacts(), solver_.contactSlop,
                              narrowPhase_.state().push);
    if (world_.ground)
      detail::collideGround(particles_, ground_.points(), world_.groundNormal, world_.groundHeight,
                            ground_.state().push);
  }
  std::fill(narrowPhase_.state().push.begin(), narrowPhase_.state().push.end(), 0.0);
  for (std::size_t i = 0; i < particles_.size(); ++i)
    particles_.previous[i] += particles_.position[i] - before[i];
  std::fill(ground_.state().push.begin(), ground_.state().push.end(), 0.0);
}

// x - x* is the velocity half a substep back, times the substep: (x - x*) = v(t - h/2) h. A new
// substep h' needs v(t - h'/2) = v(t - h/2) + a (h - h') / 2. For a body in free flight a is
// gravity, and this keeps its trajectory exact. A body that touched the ground or another box
// in the last step is held up, its net acceleration about zero: it keeps its half-step velocity,
// or a smaller step would drive it into its support and it would rebound (up to 5 mm for a 1 m
// box going from 1 to 16 substeps).
void World::keepVelocities(Real hOld, Real hNew) {
  std::vector<std::uint8_t> supported(particles_.size(), 0);
  auto support = [&](BodyId body, const Embedding& point) {
    if (body != kNoBody) {
      const Body& box = bodies_[body];
      std::fill_n(supported.begin() + box.firstParticle, box.particleCount, std::uint8_t{1});
    } else {
      supported[point.particle[0]] = 1;
    }
  };
  const std::span<const GroundContact> groundPoints = ground_.points();
  for (std::size_t c = 0; c < groundPoints.size(); ++c) {
    if (ground_.state().touched[c] != 0) support(groundPoints[c].body, groundPoints[c].point);
  }
  const std::span<const BodyContact> bodyContacts = narrowPhase_.contacts();
  for (std::size_t k = 0; k < bodyContacts.size(); ++k) {
    if (narrowPhase_.state().touched[k] == 0) continue;
    support(bodyContacts[k].bodyA, bodyContacts[k].pointA);
    support(bodyContacts[k].bodyB, bodyContacts[k].pointB);
  }
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    Vec3 halfStepVelocity = (particles_.position[i] - particles_.previous[i]) / hOld;
    if (supported[i] == 0 && particles_.inverseMass[i] != 0.0) {
      halfStepVelocity += gravityAt(particles_.position[i]) * ((hOld - hNew) / 2);
    }
    particles_.previous[i] = particles_.position[i] - halfStepVelocity * hNew;
  }
  // A rigid body keeps its velocity of the substep's middle too: the same shift, unless a contact
  // held it in the last substep.
  std::vector<std::uint8_t> held(rigidBodies_.size(), 0);
  auto hold = [&](std::span<const RigidContact> contacts, const RigidContactState& state) {
    for (std::size_t k = 0; k < contacts.size() && k < state.lambdaNormal.size(); ++k) {
      if (state.lambdaNormal[k] <= 0.0) continue;
      if (contacts[k].sideA == ContactSide::Rigid) held[contacts[k].rigidA] = 1;
      if (contacts[k].sideB == ContactSide::Rigid) held[contacts[k].rigidB] = 1;
    }
  };
  hold(narrowPhase_.rigidContacts(), narrowPhase_.rigidState());
  hold(rigidGround_, rigidGroundState_);
  for (RigidId i{}; i < rigidBodies_.size(); ++i) {
    if (held[i] != 0 || rigidBodies_.inverseMass[i] == 0.0) continue;
    rigidBodies_.velocity[i] += gravityAt(rigidBodies_.position[i]) * ((hOld - hNew) / 2);
    rigidBodies_.angularVelocity[i] =
        detail::shiftedSpin(rigidBodies_.orientation[i], rigidBodies_.inverseInertia[i],
                            rigidBodies_.angularVelocity[i], hOld, hNew);
  }
}

void World::setFreezeCallback(std::function<void(const FreezeReport&)> callback) {
  guard_.setCallback(std::move(callback));
}

ParticleId World::addParticle(const ParticleDesc& desc) {
  const ParticleId id = pushParticle(desc);
  islands_.addParticle(desc.pinned);
  return id;
}

// A particle of its own or of a body (addBody gives the body's to Islands with the body).
ParticleId World::pushParticle(const ParticleDesc& desc) {
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
  guard_.addParticle(desc.position);
  particleName_.push_back(desc.name);
  particleBody_.push_back(kNoBody);
  movedByBoxContact_.push_back(0);
  constraints_.addParticle();
  ground_.add(embedParticle(id), world_.groundMaterial, kNoBody, world_.groundMaterial);
  return id;
}

void World::addStick(ParticleId a, ParticleId b, Real compliance) {
  requireIndex(a, particles_.size(), "addStick", "particle");
  requireIndex(b, particles_.size(), "addStick", "particle");
  require(a != b, "addStick: the two particles must differ");
  addStick(a, b, glm::length(particles_.position[b] - particles_.position[a]), compliance);
}

void World::addStick(ParticleId a, ParticleId b, Real length, Real compliance) {
  require(std::isfinite(length) && length > 0.0, "addStick: length must be finite and > 0 (m)");
  addRange(a, b, length, length, compliance);
}

void World::addRange(ParticleId a, ParticleId b, Real minLength, Real maxLength, Real compliance) {
  requireIndex(a, particles_.size(), "stick", "particle");
  requireIndex(b, particles_.size(), "stick", "particle");
  require(a != b, "stick: the two particles must differ");
  require(std::isfinite(minLength) && minLength >= 0.0, "stick: min length must be finite and >= 0 (m)");
  require(!std::isnan(maxLength) && maxLength > 0.0 && maxLength >= minLength,
          "stick: max length must be > 0 (m) and >= min length");
  require(std::isfinite(compliance) && compliance >= 0.0 && compliance <= kMaxCompliance,
          "stick: compliance must be from 0 to 1e6 (m/N)");
  constraints_.addStick({a, b, minLength, maxLength, compliance});
  joinBodies(a, b);
  islands_.joinParticles(a, b);
}

// An embedding must be an affine combination of existing particles; `who` prefixes the message.
void World::checkEmbedding(const Embedding& e, const std::string& who) const {
  require(e.count >= 1 && e.count <= 4, who + ": an embedding needs 1 to 4 particles");
  Real sum = 0.0;
  for (int i = 0; i < e.count; ++i) {
    requireIndex(e.particle[i], particles_.size(), who, "particle");
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
  // Created outside its bounds (a pin whose points were placed apart), it is brought within them
  // at most at maxDepenetrationSpeed, from the next step on (World::step).
  const Link link{a, b, minLength, maxLength};
  constraints_.addLink(link, detail::linkViolation(particles_.position, link));
  joinBodies(a.particle[0], b.particle[0]);
  for (const Embedding* end : {&a, &b}) {
    for (int i = 0; i < end->count; ++i) islands_.joinParticles(a.particle[0], end->particle[i]);
  }
}

void World::addJointFriction(BodyId a, BodyId b, Real rate) {
  requireIndex(a, bodies_.size(), "addJointFriction", "body");
  requireIndex(b, bodies_.size(), "addJointFriction", "body");
  require(bodies_[a].model != BodyModel::Rigid && bodies_[b].model != BodyModel::Rigid && a != b,
          "addJointFriction: bodies must differ and be particle bodies (a rigid joint has "
          "JointDesc::damping)");
  require(std::isfinite(rate) && rate >= 0.0, "addJointFriction: rate must be finite and >= 0 (1/s)");
  constraints_.addJointFriction({a, b, rate});
  islands_.join(islands_.nodeOf(a), islands_.nodeOf(b));
}

void World::setDrag(const Drag& drag) {
  if (drag.body != kNoBody) {
    requireIndex(drag.body, bodies_.size(), "setDrag", "body");
    require(bodies_[drag.body].model == BodyModel::Rigid,
            "setDrag: body must be a rigid body (a particle body's point is an embedding)");
    require(finite(drag.local), "setDrag: the point must be finite");
  } else {
    checkEmbedding(drag.point, "setDrag");
  }
  require(finite(drag.target), "setDrag: target must be finite");
  require(std::isfinite(drag.stiffness) && drag.stiffness >= 0.0,
          "setDrag: stiffness must be finite and >= 0 (N/m)");
  require(std::isfinite(drag.damping) && drag.damping >= 0.0,
          "setDrag: damping must be finite and >= 0 (N s/m)");
  drag_ = drag;
  dragBody_ = kNoBody;
  const HeldNodes held = heldNodes();
  for (int i = 0; i < held.count; ++i) islands_.wake(held.nodes[i]);
  if (drag.body != kNoBody) return;
  // The box that carries the point answers the pull as a rigid body; a point carried by anything
  // else (a loose particle, particles of several bodies) is moved through its carriers alone.
  dragBody_ = particleBody_[drag.point.particle[0]];
  for (int i = 1; i < drag.point.count; ++i) {
    if (particleBody_[drag.point.particle[i]] != dragBody_) dragBody_ = kNoBody;
  }
}

Drag World::dragAt(BodyId body, const Vec3& worldPoint) const {
  requireIndex(body, bodies_.size(), "dragAt", "body");
  require(finite(worldPoint), "dragAt: the point must be finite");
  Drag drag;
  drag.target = worldPoint;
  if (bodies_[body].model != BodyModel::Rigid) {
    drag.point = anchor(body, worldPoint);
    return drag;
  }
  const RigidId i = bodies_[body].rigid;
  drag.body = body;
  drag.local = glm::conjugate(rigidBodies_.orientation[i]) * (worldPoint - rigidBodies_.position[i]);
  return drag;
}

Vec3 World::dragPoint() const {
  require(drag_.has_value(), "dragPoint: no drag is set");
  if (drag_->body == kNoBody) return positionOf(drag_->point);
  const RigidId i = bodies_[drag_->body].rigid;
  return rigidBodies_.position[i] + rigidBodies_.orientation[i] * drag_->local;
}

void World::setDragTarget(const Vec3& target) {
  require(drag_.has_value(), "setDragTarget: no drag is set");
  require(finite(target), "setDragTarget: target must be finite");
  drag_->target = target;
}

Embedding World::anchor(BodyId id, const Vec3& worldPoint) const {
  requireIndex(id, bodies_.size(), "anchor", "body");
  require(bodies_[id].model != BodyModel::Rigid,
          "anchor: a rigid body carries no embedded point (pointOn gives its point for a joint)");
  require(finite(worldPoint), "anchor: the point must be finite");
  const Body& box = bodies_[id];
  const BodyPose pose = poseOf(id);
  return detail::rigidEmbedding(
      box, (glm::inverse(pose.orientation) * (worldPoint - pose.center)) / box.halfExtents);
}

BodyId World::addBody(const BodyDesc& desc) {
  require(
      desc.model == BodyModel::Corners || desc.model == BodyModel::Tetra || desc.model == BodyModel::Rigid,
      "addBody: model must be Corners, Tetra or Rigid (is " + std::to_string(static_cast<int>(desc.model)) +
          ")");
  require(desc.shape == Shape::Box || desc.shape == Shape::Capsule,
          "addBody: shape must be Box or Capsule (is " + std::to_string(static_cast<int>(desc.shape)) + ")");
  require(finite(desc.center) && finite(desc.velocity) && finite(desc.angularVelocity),
          "addBody: center, velocity and angular velocity must be finite");
  require(finite(desc.size) && desc.size.x > 0.0 && desc.size.y > 0.0 && desc.size.z > 0.0,
          "addBody: size must be finite and > 0 (m)");
  require(std::isfinite(desc.mass) && desc.mass > 0.0, "addBody: mass must be finite and > 0 (kg)");
  const Real qLength = glm::length(desc.orientation);
  require(std::isfinite(qLength) && qLength > 0.0,
          "addBody: orientation must be a finite non-zero quaternion");
  require(validate(desc.material).empty(), "addBody: " + validate(desc.material));
  require(desc.inertiaFloor >= 0.0 && desc.inertiaFloor <= 1.0, "addBody: inertia floor must be from 0 to 1");
  if (desc.shape == Shape::Capsule) {
    require(std::abs(desc.size.x - desc.size.z) <= 1e-9 * desc.size.x,
            "addBody: a capsule's size.x and size.z are both its diameter and must be equal (m)");
    require(desc.size.y >= desc.size.x,
            "addBody: a capsule's length size.y must be at least its diameter size.x (m)");
  }
  const Quat q = desc.orientation / qLength;
  if (desc.model == BodyModel::Rigid) return addRigidBody(desc, q);

  Body box;
  box.name = desc.name;
  box.model = desc.model;
  box.shape = desc.shape;
  box.halfExtents = desc.size * 0.5;
  box.material = desc.material;
  box.particleCount = boxParticleCount(desc.model);
  box.firstParticle = static_cast<ParticleId>(particles_.size());
  box.firstCorner = static_cast<std::uint32_t>(corners_.size());
  const BodyId id(bodies_.size());
  const std::size_t contactsBefore = ground_.size();

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
            "addBody: centre, size, velocity or mass too large to represent");
    for (int i = 0; i < j; ++i) {
      const Real length = glm::length(parts[j].position - parts[i].position);
      require(std::isfinite(length) && length > 0.0, "addBody: centre or size too large to represent");
    }
  }
  for (int j = 0; j < box.particleCount; ++j) {
    pushParticle(parts[j]);
    particleBody_.back() = id;
  }
  // The particles' own contact points go: the box touches the ground with its corners.
  ground_.truncate(contactsBefore);

  const std::span<const Pair> pairs = desc.model == BodyModel::Corners ? std::span<const Pair>(kCornerSticks)
                                                                       : std::span<const Pair>(kTetraSticks);
  box.firstStick = static_cast<std::uint32_t>(constraints_.sticks().size());
  box.stickCount = static_cast<int>(pairs.size());
  for (const Pair& p : pairs) addStick(box.firstParticle + p.a, box.firstParticle + p.b);

  for (int k = 0; k < 8; ++k) {
    Embedding corner;
    if (desc.model == BodyModel::Corners) {
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
    if (desc.shape == Shape::Box) ground_.add(corner, desc.material, id, world_.groundMaterial);
  }
  if (desc.shape == Shape::Box && desc.model == BodyModel::Tetra) ground_.followTetraBox();
  if (desc.shape == Shape::Capsule) {
    // A capsule touches the ground with the lowest points of its two end spheres, which move
    // over its surface as it turns: GroundContacts::placeCapsulePoints re-embeds them every substep.
    const Real halfSegment = box.capsuleHalfSegment();
    for (const Real end : {-1.0, 1.0}) {
      const Vec3 core(0.0, end * halfSegment, 0.0);
      const Vec3 lowest = core + glm::inverse(q) * (-world_.groundNormal) * box.capsuleRadius();
      ground_.add(detail::rigidEmbedding(box, lowest / box.halfExtents), desc.material, id,
                  world_.groundMaterial);
      ground_.followCapsuleEnd(end);
    }
  }
  box.collisionGroup = desc.collisionGroup;
  box.collisionMask = desc.collisionMask;
  return registerBody(box);
}

// The body into the list, and a place for it in every part that keeps something per body.
BodyId World::registerBody(const Body& body) {
  const BodyId id(bodies_.size());
  bodies_.push_back(body);
  layoutsStale_ = true;
  frames_.emplace_back();
  frameAsleep_.push_back(0);
  rigid_.emplace_back();
  stickSpin_.emplace_back();
  guard_.addBody();
  broadPhase_.addBody();
  parting_.addBody();
  islands_.addBody(body.particleCount);  // its particles were added just before
  tetraVolumes_.addBody(body);
  return id;
}

// A rigid body: one pose, its velocities, and a solid shape's mass properties. Refused, with
// nothing added, when its inertia cannot be represented (a mass or size near the ends of a double).
BodyId World::addRigidBody(const BodyDesc& desc, const Quat& q) {
  Body body;
  body.name = desc.name;
  body.model = BodyModel::Rigid;
  body.shape = desc.shape;
  body.halfExtents = desc.size * 0.5;
  body.material = desc.material;
  body.inertiaFloor = desc.inertiaFloor;
  body.firstParticle = static_cast<ParticleId>(particles_.size());
  body.firstStick = static_cast<std::uint32_t>(constraints_.sticks().size());
  body.firstCorner = static_cast<std::uint32_t>(corners_.size());
  body.rigid = static_cast<RigidId>(rigidBodies_.size());
  body.collisionGroup = desc.collisionGroup;
  body.collisionMask = desc.collisionMask;
  const Vec3 solid = desc.shape == Shape::Capsule
                         ? solidCapsuleInertia(body.capsuleRadius(), body.capsuleHalfSegment(), desc.mass)
                         : solidBoxInertia(body.halfExtents, desc.mass);
  const Vec3 inertia = flooredInertia(solid, desc.inertiaFloor);
  const Vec3 inverseInertia = 1.0 / inertia;
  require(
      finite(inertia) && finite(inverseInertia) && inertia.x > 0.0 && inertia.y > 0.0 && inertia.z > 0.0,
      "addBody: a rigid body's inertia must be finite and > 0 (its mass or size is too small or too large)");
  require(std::isfinite(1.0 / desc.mass), "addBody: mass too small to represent (kg)");
  for (int k = 0; k < 8; ++k) {
    require(finite(desc.center + q * boxCornerLocal(body.halfExtents, k)),
            "addBody: centre or size too large to represent");
  }
  const BodyId id(bodies_.size());
  // As for particles, the velocities kept are those of the last substep's middle, v(t - h/2): with
  // v(0) given, v(-h/2) = v - g h / 2, and free fall is then exact to round-off. The spin is shifted
  // the same way by Euler's equations' dw/dt; taken as it is, it would put the body's turn a
  // constant O(h) out of phase, and the rotation would be only first order in h (lab converge
  // measured the tumbling box's error halving with h, and falling as h^2 with the shift).
  const Real h = substepDt();
  const Vec3 velocity = desc.velocity - gravityAt(desc.center) * (h / 2);
  const Vec3 spin = detail::spinShiftedBack(q, inverseInertia, desc.angularVelocity, h);
  rigidBodies_.position.push_back(desc.center);
  rigidBodies_.orientation.push_back(q);
  guard_.addRigidBody(desc.center, q);
  rigidBodies_.previousPosition.push_back(desc.center - velocity * h);
  rigidBodies_.previousOrientation.push_back(detail::turned(q, -spin * h));
  rigidBodies_.velocity.push_back(velocity);
  rigidBodies_.angularVelocity.push_back(spin);
  rigidBodies_.inverseMass.push_back(1.0 / desc.mass);
  rigidBodies_.inverseInertia.push_back(inverseInertia);
  rigidBodies_.inverseInertiaWorld.push_back(detail::worldInverseInertia(q, inverseInertia));
  rigidBodies_.body.push_back(id);
  rigidBodies_.jointed.push_back(0);
  return registerBody(body);
}

Vec3 World::cornerPosition(BodyId id, int k) const {
  requireIndex(id, bodies_.size(), "cornerPosition", "body");
  if (k < 0 || k >= 8) [[unlikely]]
    throw std::invalid_argument("cornerPosition: corner " + std::to_string(k) + " must be from 0 to 7");
  return cornerOf(id, k);
}

Vec3 World::cornerOf(BodyId id, int k) const {
  const Body& body = bodies_[id];
  if (body.model != BodyModel::Rigid) return positionOf(corners_[body.firstCorner + k]);
  return rigidBodies_.position[body.rigid] +
         rigidBodies_.orientation[body.rigid] * boxCornerLocal(body.halfExtents, k);
}

BodyMass World::bodyMass(BodyId id) const {
  requireIndex(id, bodies_.size(), "bodyMass", "body");
  const Body& body = bodies_[id];
  BodyMass out;
  if (body.model == BodyModel::Rigid) {
    if (rigidBodies_.inverseMass[body.rigid] == 0.0) return out;
    out.mass = 1.0 / rigidBodies_.inverseMass[body.rigid];
    out.inertia = 1.0 / rigidBodies_.inverseInertia[body.rigid];
    return out;
  }
  for (int k = 0; k < body.particleCount; ++k) {
    const Real w = particles_.inverseMass[body.firstParticle + k];
    if (w == 0.0) return {};
    const Real m = 1.0 / w;
    const Vec3 r = boxParticleLocal(body.model, body.halfExtents, k);
    out.mass += m;
    out.inertia += m * Vec3(r.y * r.y + r.z * r.z, r.x * r.x + r.z * r.z, r.x * r.x + r.y * r.y);
  }
  return out;
}

std::pair<Vec3, Vec3> World::bodyVelocity(BodyId id) const {
  requireIndex(id, bodies_.size(), "bodyVelocity", "body");
  const Body& body = bodies_[id];
  if (body.model == BodyModel::Rigid)
    return {rigidBodies_.velocity[body.rigid], rigidBodies_.angularVelocity[body.rigid]};
  detail::MassProperties m;
  if (!detail::massProperties(particles_, body, m)) return {Vec3(0.0), Vec3(0.0)};
  const detail::RigidMotion motion = detail::rigidMotion(particles_, body, m);
  return {motion.linear / substepDt(), motion.angular / substepDt()};
}

std::pair<Vec3, Vec3> World::poseVelocity(BodyId id) const {
  requireIndex(id, bodies_.size(), "poseVelocity", "body");
  const Body& body = bodies_[id];
  const Real h = substepDt();
  const BodyPose pose = poseOf(id);
  if (body.model == BodyModel::Rigid) {
    if (rigidBodies_.inverseMass[body.rigid] == 0.0) return {Vec3(0.0), Vec3(0.0)};
    return rigidDescVelocity(id);
  }
  const ParticleId first = body.firstParticle, end = first + body.particleCount;
  auto moved = [&](ParticleId p) { return velocityOf(p) + gravityAt(particles_.position[p]) * (0.5 * h); };
  Real mass = 0.0;
  Vec3 momentum(0.0);
  for (ParticleId p = first; p < end; ++p) {
    if (particles_.inverseMass[p] == 0.0) return {Vec3(0.0), Vec3(0.0)};
    const Real m = 1.0 / particles_.inverseMass[p];
    mass += m;
    momentum += m * moved(p);
  }
  const Vec3 linear = momentum / mass;
  Vec3 angularMomentum(0.0);
  glm::dmat3 inertia(0.0);
  for (ParticleId p = first; p < end; ++p) {
    const Real m = 1.0 / particles_.inverseMass[p];
    const Vec3 r = particles_.position[p] - pose.center;
    angularMomentum += m * glm::cross(r, moved(p) - linear);
    inertia += m * (glm::dot(r, r) * glm::dmat3(1.0) - glm::outerProduct(r, r));
  }
  if (!(std::abs(glm::determinant(inertia)) > 0.0)) return {linear, Vec3(0.0)};
  return {linear, glm::inverse(inertia) * angularMomentum};
}

std::pair<Vec3, Vec3> World::rigidDescVelocity(BodyId id) const {
  requireIndex(id, bodies_.size(), "rigidDescVelocity", "body");
  const Body& body = bodies_[id];
  require(body.model == BodyModel::Rigid, "rigidDescVelocity: the body is not of the rigid model");
  const RigidId i = body.rigid;
  const Real h = substepDt();
  // The spin of a substep of length 0 is w(0) itself: the same shift a change of substep makes.
  return {rigidBodies_.velocity[i] + gravityAt(rigidBodies_.position[i]) * (h / 2),
          detail::shiftedSpin(rigidBodies_.orientation[i], rigidBodies_.inverseInertia[i],
                              rigidBodies_.angularVelocity[i], h, 0.0)};
}

Vec3 World::velocity(ParticleId id) const {
  requireIndex(id, particles_.size(), "velocity", "particle");
  return velocityOf(id);
}

Vec3 World::velocityOf(ParticleId id) const {
  return (particles_.position[id] - particles_.previous[id]) / substepDt();
}

const std::string& World::particleName(ParticleId id) const {
  requireIndex(id, particleName_.size(), "particleName", "particle");
  return particleName_[id];
}

Vec3 World::position(const Embedding& point) const {
  // Checked as a query is: the weights may be any (checkEmbedding's sum is the adders' rule).
  if (point.count < 1 || point.count > 4) [[unlikely]] {
    throw std::invalid_argument("position: an embedding needs 1 to 4 particles (has " +
                                std::to_string(point.count) + ")");
  }
  for (int i = 0; i < point.count; ++i)
    requireIndex(point.particle[i], particles_.size(), "position", "particle");
  return positionOf(point);
}

Vec3 World::positionOf(const Embedding& point) const {
  return detail::embeddedPosition(particles_.position, point);
}

Vec3 World::gravityAt(const Vec3& x) const {
  return detail::gravityAt(world_, x);
}

// |g| in the current mode (m/s^2): in point mode, its strength wherever a body is.
Real World::gravityMagnitude() const {
  return world_.gravityMode == GravityMode::Uniform ? glm::length(world_.gravity) : world_.gravityStrength;
}

BodyPose World::bodyPose(BodyId id) const {
  requireIndex(id, bodies_.size(), "bodyPose", "body");
  return poseOf(id);
}

Vec3 World::bodyCentre(BodyId id) const {
  requireIndex(id, bodies_.size(), "bodyCentre", "body");
  const Body& box = bodies_[id];
  if (box.model == BodyModel::Rigid) return rigidBodies_.position[box.rigid];
  return detail::particleCentre(particles_, box);  // what particleBodyPose takes for the centre
}

BodyPose World::poseOf(BodyId id) const {
  const Body& box = bodies_[id];
  if (box.model == BodyModel::Rigid)
    return {rigidBodies_.position[box.rigid], rigidBodies_.orientation[box.rigid]};
  return detail::particleBodyPose(particles_, box);
}

}  // namespace phys
