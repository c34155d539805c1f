// Parting without velocity: deep overlaps a substep starts with, removed by moving bodies whole.
#include "physics/parting.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "room.h"
#include "union_find.h"

namespace phys {

void Parting::addBody() {
  const auto id = static_cast<BodyId>(parent_.size());
  parent_.push_back(id);
  root_.push_back(id);
  shift_.emplace_back(0.0);
  weight_.push_back(0.0);
  groundNeed_.push_back(0.0);
  groundPush_.push_back(0.0);
}

BodyId Parting::group(BodyId id) {
  return detail::findRoot(parent_, id);
}

void Parting::join(BodyId a, BodyId b) {
  detail::unite(parent_, a, b);
}

namespace {

// Whether any contact starts deeper than epsilon, whatever it joins: nearly always not, and then
// no group needs finding. Those within a group, and loose particles on the ground, are told apart
// only when one is.
bool anyDeeper(std::span<const Manifold> manifolds, const PartingGround& ground, const PartingRigid& rigid,
               Real epsilon) {
  auto deeper = [epsilon](Real depth) { return depth > epsilon; };
  if (std::any_of(manifolds.begin(), manifolds.end(), [&](const Manifold& m) { return deeper(m.overlap); }))
    return true;
  if (!ground.enabled) return false;
  return std::any_of(ground.allowance.begin(), ground.allowance.end(), deeper) ||
         std::any_of(rigid.groundOverlap.begin(), rigid.groundOverlap.end(), deeper);
}

}  // namespace

void Parting::reserve(std::size_t pairs, std::size_t bodies) {
  const std::size_t room = detail::kRoomPerBody * bodies;
  detail::keepRoom(need_, pairs, room);
  detail::keepRoom(push_, pairs, room);
}

// Overlaps deeper than the feature epsilon that a substep starts with (measured at x*: boxes
// spawned into each other or into the ground, not this substep's approach) are removed by moving
// boxes whole, x and x* alike: they part without gaining velocity, and without being bent, which
// their sticks would undo with a kick.
//
// Moved pair by pair, the seed's way, a pair was parted by pushing one box into the ground or a
// third box, and the projection that then removed that overlap made it a velocity of overlap / h
// (a box 25% into a box resting on the ground flew off at 7.5 m/s at one substep, 45 m/s at 16).
// So the moves are solved together: a translation t per box, by Gauss-Seidel over constraints on
// them, the ground immovable:
//   every touching pair   n . (t_B - t_A) >= its overlap if deeper than epsilon, else
//                         min(overlap, 0): it may close up to touching, no deeper;
//   every box             n_g . t >= its deepest corner's depth if deeper than epsilon, else
//                         min(depth, 0): it may not be pushed into the ground.
// Shallow overlap (a resting contact's millimetres) is left to the projections, as before:
// moving resting boxes whole would change how stacks settle. What the sweeps leave, and overlap
// pushed into boxes that were not touching, is parted in the next substeps, the projections'
// share of it at most at maxDepenetrationSpeed (World::step).
//
// Boxes joined by links or sticks (a ragdoll's parts) move as one: parted alone, a part stretched
// its joints, whose projections pulled it back into the overlap, and the fight became speed:
// Bullet's pile, whose neighbours' hands start 5.5 cm into each other, threw them at 120 m/s at
// 128 substeps. Overlaps within one such group are left to the projections.
void Parting::part(Particles& particles, std::span<const Body> bodies, std::span<const Manifold> manifolds,
                   std::span<BodyContact> contacts, std::span<Real> contactAllowance,
                   const PartingGround& ground, const PartingRigid& rigid, Real featureEpsilon,
                   const PartingSettings& settings) {
  const Real epsilon = featureEpsilon;
  if (!anyDeeper(manifolds, ground, rigid, epsilon)) return;
  for (BodyId id{}; id < bodies.size(); ++id) root_[id] = group(id);
  bool deep = false;
  need_.resize(manifolds.size());
  push_.resize(manifolds.size());
  for (std::size_t k = 0; k < manifolds.size(); ++k) {
    const Manifold& m = manifolds[k];
    if (root_[m.a] == root_[m.b]) {
      need_[k] = -std::numeric_limits<Real>::infinity();  // nothing to part: one group
      continue;
    }
    deep = deep || m.overlap > epsilon;
    need_[k] = m.overlap > epsilon ? m.overlap : std::min(m.overlap, 0.0);
  }
  const Vec3 up = ground.normal;
  if (ground.enabled) {
    // A box's depth is its deepest corner's, from the start depths step() measured.
    std::fill(groundNeed_.begin(), groundNeed_.end(), -std::numeric_limits<Real>::infinity());
    for (std::size_t c = 0; c < ground.contacts.size(); ++c) {
      if (ground.contacts[c].body == kNoBody) continue;  // a loose particle: boxes do not push it
      Real& depth = groundNeed_[root_[ground.contacts[c].body]];
      depth = std::max(depth, ground.allowance[c]);  // a group's depth is its deepest box's
    }
    for (std::size_t c = 0; c < rigid.ground.size(); ++c) {
      Real& depth = groundNeed_[root_[rigid.ground[c].bodyB]];
      depth = std::max(depth, rigid.groundOverlap[c]);
    }
    for (Real& depth : groundNeed_) {
      deep = deep || depth > epsilon;
      depth = depth > epsilon ? depth : std::min(depth, 0.0);
    }
  }
  if (!deep) return;

  // A group's weight is 1 / its mass, kept at its root (a box id), as are its shift and depth.
  std::fill(weight_.begin(), weight_.end(), 0.0);  // its mass, for now
  for (BodyId id{}; id < bodies.size(); ++id) {
    const Body& box = bodies[id];
    Real& mass = weight_[root_[id]];
    if (box.model == BodyModel::Rigid) {
      const Real w = rigid.bodies.inverseMass[box.rigid];
      mass = w == 0.0 ? std::numeric_limits<Real>::infinity() : mass + 1.0 / w;  // frozen: it stays
    }
    for (int j = 0; j < box.particleCount; ++j) {
      const Real w = particles.inverseMass[box.firstParticle + j];
      mass = w == 0.0 ? std::numeric_limits<Real>::infinity() : mass + 1.0 / w;  // pinned or frozen: it stays
    }
    shift_[id] = Vec3(0.0);
  }
  for (BodyId id{}; id < bodies.size(); ++id) {
    if (root_[id] == id) weight_[id] = 1.0 / weight_[id];
  }
  // Gauss-Seidel, pushing only, as long as that converges: the spawned scenes of the tests and the
  // suite do so in a few sweeps (to a micrometre, well below the slop the projections leave).
  // Each pair's correction is split between its two groups, so along a chain of N groups the push
  // spreads as by diffusion, in some N^2 sweeps: a row of Bullet's pile, 16 ragdolls each 5.4 cm
  // into the next, needs 306, and what 64 left became speed (docs/physics.md, "Where energy could
  // come from nowhere"). So after 64 the sweeps go on over-relaxed, each constraint's push from
  // then on accumulated (>= 0, so an overshoot can be taken back): omega = 1.7 is near the best
  // for such a chain, 2 / (1 + sin(pi / N)), and the pile's rows then converge in 36 more. What
  // is left when they stop waits for the next substep (PartingSettings has the figures).
  const int plainSweeps = settings.plainSweeps;
  const Real omega = settings.overRelaxation;
  Real lastCheck = std::numeric_limits<Real>::infinity();  // m: the worst correction at the last check
  std::fill(push_.begin(), push_.end(), 0.0);
  std::fill(groundPush_.begin(), groundPush_.end(), 0.0);
  for (int sweep = 0; sweep < plainSweeps + settings.overRelaxedSweeps; ++sweep) {
    const bool plain = sweep < plainSweeps;
    Real worst = 0.0;
    for (std::size_t k = 0; k < manifolds.size(); ++k) {
      const Manifold& m = manifolds[k];
      const BodyId ga = root_[m.a], gb = root_[m.b];
      const Real wa = weight_[ga], wb = weight_[gb];
      if (ga == gb || wa + wb == 0.0) continue;
      const Real missing = need_[k] - glm::dot(m.normal, shift_[gb] - shift_[ga]);
      if (plain) {
        if (missing <= 0.0) continue;
        shift_[ga] -= m.normal * (missing * wa / (wa + wb));
        shift_[gb] += m.normal * (missing * wb / (wa + wb));
        worst = std::max(worst, missing);
        continue;
      }
      const Real push = std::max(0.0, push_[k] + omega * missing / (wa + wb));
      const Real change = push - push_[k];
      push_[k] = push;
      shift_[ga] -= m.normal * (change * wa);
      shift_[gb] += m.normal * (change * wb);
      worst = std::max(worst, std::abs(change) * (wa + wb));
    }
    if (ground.enabled) {
      for (BodyId id{}; id < bodies.size(); ++id) {
        if (root_[id] != id || weight_[id] == 0.0) continue;
        // The ground does not move, so the group takes the whole correction.
        const Real missing = groundNeed_[id] - glm::dot(up, shift_[id]);
        if (plain) {
          if (missing <= 0.0) continue;
          shift_[id] += up * missing;
          worst = std::max(worst, missing);
          continue;
        }
        const Real push = std::max(0.0, groundPush_[id] + omega * missing);
        const Real change = push - groundPush_[id];
        groundPush_[id] = push;
        shift_[id] += up * change;
        worst = std::max(worst, std::abs(change));
      }
    }
    if (worst < settings.tolerance) break;
    // Over-relaxed, a chain's worst correction falls twentyfold in 16 sweeps; that of a pyramid of
    // 20 rows pressed deeper than epsilon by too few passes hardly falls, and 64 sweeps each
    // substep would only make its collapse slower to run.
    if (sweep + 1 >= plainSweeps && (sweep + 1 - plainSweeps) % settings.progressSweeps == 0) {
      if (!(worst < 0.5 * lastCheck)) break;
      lastCheck = worst;
    }
  }
  for (BodyId id{}; id < bodies.size(); ++id) {
    const Vec3 t = shift_[root_[id]];
    if (t == Vec3(0.0)) continue;
    const Body& box = bodies[id];
    if (box.model == BodyModel::Rigid) {
      rigid.bodies.position[box.rigid] += t;
      rigid.bodies.previousPosition[box.rigid] += t;
    }
    for (int j = 0; j < box.particleCount; ++j) {
      particles.position[box.firstParticle + j] += t;
      particles.previous[box.firstParticle + j] += t;
    }
  }
  // The start overlaps the depenetration limit is reckoned from move with the boxes, and so do
  // friction's anchors: a move the parting makes is not a slide for friction to take back.
  for (const Manifold& m : manifolds) {
    const Vec3 moved = shift_[root_[m.b]] - shift_[root_[m.a]];
    const Real parted = glm::dot(m.normal, moved);
    const std::span<Real> overlap = m.rigid ? rigid.contactOverlap : contactAllowance;
    for (std::uint32_t k = 0; k < m.contactCount; ++k) overlap[m.firstContact + k] -= parted;
    if (m.rigid || !m.kept) continue;
    for (std::uint32_t k = m.firstContact; k < m.firstContact + m.contactCount; ++k)
      contacts[k].anchor += moved - glm::dot(moved, contacts[k].normal) * contacts[k].normal;
  }
  for (std::size_t c = 0; c < ground.contacts.size() && ground.enabled; ++c) {
    const BodyId body = ground.contacts[c].body;
    if (body != kNoBody) ground.allowance[c] -= glm::dot(up, shift_[root_[body]]);
  }
  for (std::size_t c = 0; c < rigid.ground.size(); ++c) {
    rigid.groundOverlap[c] -= glm::dot(up, shift_[root_[rigid.ground[c].bodyB]]);
  }
}

}  // namespace phys
