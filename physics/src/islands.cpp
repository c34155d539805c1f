#include "physics/islands.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>

#include "pose.h"
#include "require.h"
#include "union_find.h"

namespace phys {

NodeId Islands::addNode(bool fixed) {
  const NodeId id(asleep_.size());
  nodeBody_.push_back(kNoBody);
  nodeParticle_.push_back(ParticleId{});
  fixed_.push_back(fixed ? 1 : 0);
  lasting_.push_back(id);
  parent_.push_back(id);
  sleepGroup_.push_back(id);
  asleep_.push_back(0);
  rest_.push_back(0.0);
  lastSpeed_.push_back(0.0);
  rising_.push_back(0.0);
  mark_.push_back(Vec3(0.0));
  markRest_.push_back(0.0);
  halfSpeed_.push_back(0.0);
  marks_.push_back(0);
  islandAwake_.push_back(0);
  islandAsleep_.push_back(0);
  islandRest_.push_back(0.0);
  islandNumber_.push_back(0);
  wakeGroup_.push_back(0);
  if (!fixed) ++movableNodes_;
  counted_ = false;
  return id;
}

NodeId Islands::addParticle(bool fixed) {
  const NodeId id = addNode(fixed);
  nodeParticle_[id] = ParticleId(particleNode_.size());
  particleNode_.push_back(id);
  keepMaskRoom();
  return id;
}

NodeId Islands::addBody(int particleCount) {
  const NodeId id = addNode(false);
  nodeBody_[id] = BodyId(bodyNode_.size());
  bodyNode_.push_back(id);
  bodyAsleep_.push_back(0);
  bodyJoined_.push_back(0);
  bodyIsland_.push_back(0);
  particleNode_.insert(particleNode_.end(), static_cast<std::size_t>(particleCount), id);
  keepMaskRoom();
  return id;
}

// Room for mask() to take every particle's and body's masses, made as they are added (doubling,
// so that adding a particle does not allocate each time) and never in the step.
void Islands::keepMaskRoom() {
  if (maskedNodes_.capacity() < asleep_.size()) maskedNodes_.reserve(2 * asleep_.size());
  if (woken_.capacity() < asleep_.size()) woken_.reserve(2 * asleep_.size());
  if (maskedParticles_.capacity() < particleNode_.size()) maskedParticles_.reserve(2 * particleNode_.size());
  if (maskedRigid_.capacity() < bodyNode_.size()) maskedRigid_.reserve(2 * bodyNode_.size());
}

void Islands::mask(Particles& p, RigidBodies& r, std::span<const Body> bodies) {
  maskedNodes_.clear();
  maskedParticles_.clear();
  maskedRigid_.clear();
  for (NodeId n{}; n < asleep_.size(); ++n) {
    if (asleep_[n] == 0) continue;
    maskedNodes_.push_back(n);
    const BodyId id = nodeBody_[n];
    if (id == kNoBody) {
      maskedParticles_.push_back(std::exchange(p.inverseMass[nodeParticle_[n]], 0.0));
      continue;
    }
    const Body& body = bodies[id];
    for (int j = 0; j < body.particleCount; ++j)
      maskedParticles_.push_back(std::exchange(p.inverseMass[body.firstParticle + j], 0.0));
    if (body.model != BodyModel::Rigid) continue;
    const RigidId i = body.rigid;
    maskedRigid_.push_back({std::exchange(r.inverseMass[i], 0.0),
                            std::exchange(r.inverseInertia[i], Vec3(0.0)),
                            std::exchange(r.inverseInertiaWorld[i], glm::dmat3(0.0))});
  }
  masking_ = !maskedNodes_.empty();
}

void Islands::unmask(Particles& p, RigidBodies& r, std::span<const Body> bodies) {
  std::size_t particle = 0, rigid = 0;
  for (const NodeId n : maskedNodes_) {
    const BodyId id = nodeBody_[n];
    if (id == kNoBody) {
      p.inverseMass[nodeParticle_[n]] = maskedParticles_[particle++];
      continue;
    }
    const Body& body = bodies[id];
    for (int j = 0; j < body.particleCount; ++j)
      p.inverseMass[body.firstParticle + j] = maskedParticles_[particle++];
    if (body.model != BodyModel::Rigid) continue;
    const RigidMass& m = maskedRigid_[rigid++];
    r.inverseMass[body.rigid] = m.inverseMass;
    r.inverseInertia[body.rigid] = m.inverseInertia;
    r.inverseInertiaWorld[body.rigid] = m.inverseInertiaWorld;
  }
  maskedNodes_.clear();
  masking_ = false;
}

// The masses of the nodes just woken go back; the others' stay in the lists, moved up in place
// (a node's masses never move towards the end), in node order as mask() left them.
void Islands::unmaskWoken(Particles& p, RigidBodies& r, std::span<const Body> bodies) {
  std::size_t particle = 0, rigid = 0;                    // read
  std::size_t node = 0, keptParticle = 0, keptRigid = 0;  // write
  std::size_t next = 0;                                   // the next woken node, both lists in node order
  for (const NodeId n : maskedNodes_) {
    while (next < woken_.size() && woken_[next] < n) ++next;
    const bool giveBack = next < woken_.size() && woken_[next] == n;
    const BodyId id = nodeBody_[n];
    const int particles = id == kNoBody ? 1 : bodies[id].particleCount;
    for (int j = 0; j < particles; ++j, ++particle) {
      if (!giveBack) {
        maskedParticles_[keptParticle++] = maskedParticles_[particle];
        continue;
      }
      p.inverseMass[id == kNoBody ? nodeParticle_[n] : bodies[id].firstParticle + j] =
          maskedParticles_[particle];
    }
    if (id != kNoBody && bodies[id].model == BodyModel::Rigid) {
      const RigidMass m = maskedRigid_[rigid++];
      if (giveBack) {
        const RigidId i = bodies[id].rigid;
        r.inverseMass[i] = m.inverseMass;
        r.inverseInertia[i] = m.inverseInertia;
        r.inverseInertiaWorld[i] = m.inverseInertiaWorld;
      } else {
        maskedRigid_[keptRigid++] = m;
      }
    }
    if (!giveBack) maskedNodes_[node++] = n;
  }
  maskedNodes_.resize(node);
  maskedParticles_.resize(keptParticle);
  maskedRigid_.resize(keptRigid);
}

std::span<const NodeId> Islands::wakeTouched(std::span<const Manifold> manifolds) {
  woken_.clear();
  if (sleepingNodes_ == 0) return {};
  bool any = false;
  for (const Manifold& m : manifolds) {
    if (m.contactCount == 0) continue;
    const NodeId a = bodyNode_[m.a], b = bodyNode_[m.b];
    if (asleep_[a] == asleep_[b]) continue;  // both awake (two sleeping bodies are not collided)
    wakeGroup_[sleepGroup_[asleep_[a] != 0 ? a : b]] = 1;
    any = true;
  }
  if (!any) return {};
  for (NodeId n{}; n < asleep_.size(); ++n) {
    if (asleep_[n] == 0 || wakeGroup_[sleepGroup_[n]] == 0) continue;
    woken_.push_back(n);
  }
  for (const NodeId n : woken_) {
    wakeGroup_[sleepGroup_[n]] = 0;
    setAsleep(n, false);
  }
  return woken_;
}

void Islands::join(NodeId a, NodeId b) {
  // Whatever the join, its ends must answer it: a stick from a pin, or within one body, pulls on its
  // body too, and asleep the body would hold it stretched (a pinned node never sleeps).
  wake(a);
  wake(b);
  for (const NodeId n : {a, b}) {
    if (nodeBody_[n] != kNoBody) bodyJoined_[nodeBody_[n]] = 1;
  }
  if (fixed_[a] != 0 || fixed_[b] != 0 || a == b) return;
  detail::unite(lasting_, a, b);
  counted_ = false;
}

void Islands::joinParticles(ParticleId a, ParticleId b) {
  // A body's own sticks are added before the body's node (World::addBody): nothing to join.
  if (a >= particleNode_.size() || b >= particleNode_.size()) return;
  join(particleNode_[a], particleNode_[b]);
}

NodeId Islands::root(NodeId node) {
  return detail::findRoot(parent_, node);
}

void Islands::unite(NodeId a, NodeId b) {
  detail::unite(parent_, a, b);
}

void Islands::setAsleep(NodeId node, bool asleep) {
  if ((asleep_[node] != 0) == asleep) return;
  asleep_[node] = asleep ? 1 : 0;
  if (asleep) {
    ++sleepingNodes_;
  } else {
    --sleepingNodes_;
    rest_[node] = 0.0;  // woken: it must rest its whole time again before it sleeps
    lastSpeed_[node] = rising_[node] = 0.0;
    marks_[node] = 0;
  }
  if (nodeBody_[node] != kNoBody) bodyAsleep_[nodeBody_[node]] = asleep_[node];
  counted_ = false;
}

void Islands::wakeAll() {
  for (NodeId n{}; n < asleep_.size(); ++n) setAsleep(n, false);
  // New settings (sleeping turned on among them): every clock starts again.
  std::fill(rest_.begin(), rest_.end(), 0.0);
  std::fill(lastSpeed_.begin(), lastSpeed_.end(), 0.0);
  std::fill(rising_.begin(), rising_.end(), 0.0);
  std::fill(marks_.begin(), marks_.end(), std::uint8_t{0});
}

void Islands::wake(NodeId node) {
  if (asleep_[node] == 0) return;
  const NodeId group = sleepGroup_[node];
  for (NodeId n{}; n < asleep_.size(); ++n) {
    if (asleep_[n] != 0 && sleepGroup_[n] == group) setAsleep(n, false);
  }
}

NodeId Islands::particleNode(ParticleId id) const {
  detail::requireIndex(id, particleNode_.size(), "particleNode", "particle");
  return nodeOf(id);
}

NodeId Islands::bodyNode(BodyId id) const {
  detail::requireIndex(id, bodyNode_.size(), "bodyNode", "body");
  return nodeOf(id);
}

bool Islands::asleep(NodeId node) const {
  detail::requireIndex(node, asleep_.size(), "asleep", "node");
  return sleeps(node);
}

bool Islands::bodyAsleep(BodyId id) const {
  detail::requireIndex(id, bodyNode_.size(), "bodyAsleep", "body");
  return bodySleeps(id);
}

std::size_t Islands::sleepingBodies() const {
  return static_cast<std::size_t>(std::count(bodyAsleep_.begin(), bodyAsleep_.end(), std::uint8_t{1}));
}

// The speed of the node's fastest point over the last substep: a particle body's fastest particle;
// a rigid body's centre plus its spin times its half diagonal (a bound on any point's).
Real Islands::nodeSpeed(const IslandInput& in, NodeId node) const {
  const Particles& p = in.particles;
  auto particleSpeed = [&](ParticleId i) { return glm::length(p.position[i] - p.previous[i]) / in.h; };
  const BodyId id = nodeBody_[node];
  if (id == kNoBody) return particleSpeed(nodeParticle_[node]);
  const Body& body = in.bodies[id];
  if (body.model == BodyModel::Rigid) {
    const RigidId r = body.rigid;
    return glm::length(in.rigid.velocity[r]) +
           glm::length(in.rigid.angularVelocity[r]) * glm::length(body.halfExtents);
  }
  Real fastest = 0.0;
  for (int j = 0; j < body.particleCount; ++j)
    fastest = std::max(fastest, particleSpeed(body.firstParticle + j));
  return fastest;
}

// A particle body's mean particle, a rigid body's centre, a loose particle.
Vec3 Islands::nodeCentre(const IslandInput& in, NodeId node) const {
  const BodyId id = nodeBody_[node];
  if (id == kNoBody) return in.particles.position[nodeParticle_[node]];
  const Body& body = in.bodies[id];
  if (body.model == BodyModel::Rigid) return in.rigid.position[body.rigid];
  return detail::particleCentre(in.particles, body);
}

// True when the node's speed has risen step after step for 0.3 of the sleep time (0.15 s at the
// defaults), by 2% or more each step, above a hundredth of the sleeping speed: a body that starts
// from rest and speeds up by less than sleep.speed / sleep.time (0.1 m/s^2 at the defaults) stays
// under the sleeping speed for the whole sleep time and would sleep mid-fall (a column tipping
// over an edge, a stick balanced on a pin). What comes to rest slows down, or jitters about a
// speed: a settling pile's speeds rise for a few steps at a time, or by less than 2% a step (at
// 0.1% a step 902 of Bullet's pile of 1,496 bodies were still awake at 30 s). The floor keeps float
// noise about 0 from counting. A body on a slope just steeper than its friction speeds up
// uniformly, by a share of its speed that falls as it goes, and is still missed
// (docs/physics.md, "Islands and sleeping").
bool Islands::speedingUp(NodeId node, Real speed, const IslandInput& in) {
  constexpr Real kFloor = 0.01;  // of sleep.speed
  constexpr Real kRise = 0.02;   // of the step before's speed
  constexpr Real kRun = 0.3;     // of sleep.time
  const bool rose = speed > kFloor * in.sleep.speed && speed > (1.0 + kRise) * lastSpeed_[node];
  lastSpeed_[node] = speed;
  rising_[node] = rose ? rising_[node] + in.dt : 0.0;
  // A run of whole steps is kept from falling short of its length by rounding.
  return rising_[node] >= kRun * in.sleep.time - 1e-9;
}

// True when the node's centre moved faster over the half sleep time just ended than over the half
// before it, by more than a twentieth of the sleeping speed. Called once a step while the node
// rests, with its rest at the step's end; its centre is found at the marks alone: at the end of its
// rest's first step, then where its rest reaches each whole number of half sleep times (so the
// first half is a step short, and the speeds compared are means over each half's own length). Its
// rest reaches sleep.time at a mark, and a node sleeps only after the two halves of its rest were
// compared. A body that speeds up from rest by less than sleep.speed / sleep.time (0.1
// m/s^2 at the defaults) stays under the sleeping speed for the whole sleep time, and its speed's
// rise each step, a share that falls as 1/n at its n-th step, soon passes under the test of
// speedingUp: a box sliding slowly down a slope slept mid-slide. Its centre's mean speed rises by
// a times half the sleep time from one half to the next, however fast it already goes; what comes
// to rest slows down, and what jitters goes nowhere, so its centre's mean speeds stay small (the
// mean speed, not the fastest point's: a body turning in place, or trembling, moves its centre
// little). The margin, 0.05 sleep.speed, catches an acceleration above a tenth of sleep.speed /
// sleep.time (0.01 m/s^2); with less, the settling piles' centres, whose mean speeds rise by up to
// 0.0067 m/s from one half to the next, kept them awake longer (docs/physics.md, "Islands and
// sleeping").
bool Islands::fasterThanItsLastHalf(NodeId node, Real rest, const IslandInput& in) {
  constexpr Real kMargin = 0.05;  // of sleep.speed
  if (marks_[node] == 0) {        // its rest begins in this step: the first mark, at its end
    mark_[node] = nodeCentre(in, node);
    markRest_[node] = rest;
    marks_[node] = 1;
    return false;
  }
  // The next mark is where its rest reaches the next whole number of halves (the first half is
  // one step short, from the end of the rest's first step); kept from falling short by rounding.
  const Real half = 0.5 * in.sleep.time;
  if (half > 0.0 && rest < (std::floor(markRest_[node] / half + 1e-9) + 1.0) * half - 1e-9) return false;
  const Vec3 centre = nodeCentre(in, node);
  const Real speed = glm::length(centre - mark_[node]) / (rest - markRest_[node]);
  const bool faster = marks_[node] == 2 && speed > halfSpeed_[node] + kMargin * in.sleep.speed;
  mark_[node] = centre;
  markRest_[node] = faster ? 0.0 : rest;  // faster: its rest begins again from here
  halfSpeed_[node] = speed;
  marks_[node] = faster ? 1 : 2;
  return faster;
}

// This step's islands: the lasting joins, the sleeping islands as they fell asleep (their pairs
// were not collided), and the step's manifolds.
void Islands::uniteForStep(std::span<const Manifold> manifolds) {
  const std::size_t n = asleep_.size();
  for (NodeId i{}; i < n; ++i) parent_[i] = detail::findRoot(lasting_, i);
  for (NodeId i{}; i < n; ++i) {
    if (asleep_[i] != 0) unite(i, sleepGroup_[i]);
  }
  for (const Manifold& m : manifolds) {
    if (m.contactCount > 0) unite(bodyNode_[m.a], bodyNode_[m.b]);
  }
}

void Islands::count(std::span<const Manifold> manifolds) {
  uniteForStep(manifolds);
  number();
}

void Islands::update(const IslandInput& in) {
  const std::size_t n = asleep_.size();
  uniteForStep(in.manifolds);

  for (NodeId i{}; i < n; ++i) {
    islandAwake_[i] = islandAsleep_[i] = 0;
    islandRest_[i] = std::numeric_limits<Real>::infinity();
  }
  // Rest is timed only while sleeping is on: with it off the islands are counted, for the
  // sandbox and the lab, and nothing else is needed (and turning it on starts every clock at 0).
  // A node faster than sleep.speed does not rest, and its island does not sleep, whatever the sleep
  // time: with a time of 0 a rest of 0 would meet it (a box thrown up slept on its first step).
  // Held nodes likewise.
  constexpr Real kNever = -std::numeric_limits<Real>::infinity();
  for (NodeId i{}; i < n; ++i) {
    if (fixed_[i] != 0 || asleep_[i] != 0) continue;
    const Real speed = in.sleep.enabled ? nodeSpeed(in, i) : 0.0;
    const bool slow = in.sleep.enabled && speed < in.sleep.speed;
    const bool speeding = in.sleep.enabled && speedingUp(i, speed, in);
    if (!slow || speeding) marks_[i] = 0;  // its rest begins again, and its marks with it
    const bool resting = slow && !speeding && !fasterThanItsLastHalf(i, rest_[i] + in.dt, in);
    rest_[i] = resting ? rest_[i] + in.dt : 0.0;
    if (!slow) islandRest_[root(i)] = kNever;
  }
  for (const NodeId held : in.held) {
    rest_[held] = 0.0;
    marks_[held] = 0;
  }
  for (NodeId i{}; i < n; ++i) {
    if (fixed_[i] != 0) continue;
    const NodeId r = root(i);
    (asleep_[i] != 0 ? islandAsleep_[r] : islandAwake_[r]) = 1;
    islandRest_[r] = std::min(islandRest_[r], rest_[i]);
  }
  for (const NodeId held : in.held) islandRest_[root(held)] = kNever;
  for (NodeId i{}; i < n; ++i) {
    if (fixed_[i] != 0) continue;
    const NodeId r = root(i);
    if (islandAwake_[r] == 0) continue;  // asleep whole: stays so
    if (islandAsleep_[r] != 0) {
      setAsleep(i, false);  // an awake node touched it
    } else if (in.sleep.enabled && islandRest_[r] >= in.sleep.time) {
      setAsleep(i, true);
      sleepGroup_[i] = r;
    }
  }

  number();
}

// Counts and each body's island number, for the sandbox and the lab.
void Islands::number() {
  const std::size_t n = asleep_.size();
  islandCount_ = sleepingIslands_ = 0;
  constexpr std::uint32_t kUnnumbered = std::numeric_limits<std::uint32_t>::max();
  std::fill(islandNumber_.begin(), islandNumber_.end(), kUnnumbered);
  for (NodeId i{}; i < n; ++i) {
    if (fixed_[i] != 0) continue;
    const NodeId r = root(i);
    if (islandNumber_[r] == kUnnumbered) {
      islandNumber_[r] = static_cast<std::uint32_t>(islandCount_++);
      if (asleep_[i] != 0) ++sleepingIslands_;
    }
    if (nodeBody_[i] != kNoBody) bodyIsland_[nodeBody_[i]] = islandNumber_[r];
  }
  counted_ = true;
}

}  // namespace phys
