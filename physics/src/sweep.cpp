// Stage::Sweep: no tunnelling (docs/physics.md, "Fast bodies"). Contacts between bodies are found
// once a step, after the first substep's integration, from the bodies' frames then; a body that
// moved farther in that substep than the thinner body's half thickness can already be past the
// other's middle, and the contact found there pushes it out on the far side (or, past the other
// entirely, finds nothing). So before the narrow phase, every pair whose bodies moved that much
// relative to each other is swept from where the substep started (sweptSat: the separating axes
// over the move, the frames not turning): where the two first touch and along which axis. A pair
// that would end more than that half thickness in along it is put back to touching, the
// correction shared by inverse mass like a contact's, each body moved whole (its particles or its
// pose, not its x*), so its velocity along the axis is lost as in an inelastic impact and its
// sliding kept. Pairs that moved less, or pass each other, are left exactly as they were: the
// stage changes no ordinary scene.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "passes.h"
#include "physics/collision.h"
#include "physics/world.h"
#include "stage_timer.h"

namespace phys {

void World::stopFastBodies() {
  if (bodies_.size() < 2 || broadPhase_.pairs().empty()) return;
  const detail::StageTimer timer(stageProfile(), Stage::Sweep);
  // The body's mean move in this substep, from its start (x* or the previous pose) to now.
  auto shiftOf = [&](BodyId id) { return detail::bodyMove(particles_, rigidBodies_, bodies_[id]); };
  // The broad phase's motions are over the step at the speeds it measured; what a substep can add
  // to them within the step (an impact, a joint) is bounded by the factor 2, and gravity's g dt h.
  const Real h = substepDt(), perSubstep = h / solver_.dt, gravityMove = gravityMagnitude() * solver_.dt * h;
  // A body moves whole, by its inverse mass's share: 1/kg; 0 when any of it is pinned or frozen.
  auto inverseMass = [&](BodyId id) -> Real {
    const Body& b = bodies_[id];
    if (b.model == BodyModel::Rigid) return rigidBodies_.inverseMass[b.rigid];
    Real mass = 0.0;
    for (int j = 0; j < b.particleCount; ++j) {
      const Real w = particles_.inverseMass[b.firstParticle + j];
      if (w == 0.0) return 0.0;
      mass += 1.0 / w;
    }
    return mass > 0.0 ? 1.0 / mass : 0.0;
  };
  auto move = [&](BodyId id, const Vec3& by) {
    const Body& b = bodies_[id];
    if (b.model == BodyModel::Rigid) {
      rigidBodies_.position[b.rigid] += by;
    } else {
      for (int j = 0; j < b.particleCount; ++j) particles_.position[b.firstParticle + j] += by;
    }
    frames_[id].center += by;
  };
  for (const auto& [a, b] : broadPhase_.pairs()) {
    const Real thinnest = detail::thinnestHalfExtent(frames_[a], frames_[b]);
    const Real estimate =
        2.0 * glm::length(broadPhase_.motion(a).shift - broadPhase_.motion(b).shift) * perSubstep;
    if (!(estimate + gravityMove > thinnest)) continue;  // written so that NaN skips too
    const Vec3 shiftA = shiftOf(a), shiftB = shiftOf(b);
    const Vec3 moved = shiftB - shiftA;  // b's move as a sees it
    const Real distance = glm::length(moved);
    if (!(distance > thinnest)) continue;
    Obb startA = frames_[a], startB = frames_[b];
    startA.center -= shiftA;
    startB.center -= shiftB;
    const SweptSat touch = sweptSat(startA, startB, moved);
    if (!touch.hit) continue;  // they do not meet in this substep (apart, or a near miss)
    const Vec3& n = touch.normal;
    const Real thin = std::min(projectedRadius(startA, n), projectedRadius(startB, n));
    if (!(-touch.gap <= thin)) continue;  // already that deep at the start: the contacts see its side
    const Real overlap = -glm::dot(moved, n) - std::max(touch.gap, 0.0);  // how far into a b ends along n
    if (!(overlap > thin)) continue;
    const Real wa = inverseMass(a), wb = inverseMass(b);
    if (wa + wb <= 0.0) continue;
    move(a, n * (-overlap * wa / (wa + wb)));
    move(b, n * (overlap * wb / (wa + wb)));
    ++swept_;
  }
}

}  // namespace phys
