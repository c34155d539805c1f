// Box-box contacts as constraints on particles: both contact points are embedded in their
// bodies, and each correction is the weighted projection of REFERENCES.md applied to the pair:
// lambda = -C / (sum_A c_i^2 w_i + sum_B c_j^2 w_j), x_i(A) -= c_i w_i lambda n,
// x_j(B) += c_j w_j lambda n. No matrix inverse, so nothing to go singular when faces align.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "passes.h"

namespace phys::detail {
namespace {

Real weightSum(const Particles& p, const Embedding& a, const Embedding& b) {
  return embeddedWeight(p.inverseMass, a) + embeddedWeight(p.inverseMass, b);
}

// Moves two points in opposite directions: a by -lambda, b by +lambda (a vector in position
// units per unit of weight), through their particles in `x`.
void movePair(std::vector<Vec3>& x, const Particles& p, const Embedding& a, const Embedding& b,
              const Vec3& lambda) {
  shiftEmbedded(x, p.inverseMass, a, -lambda);
  shiftEmbedded(x, p.inverseMass, b, lambda);
}

// Friction at a contact a side of which is a corners capsule (BodyContact::frictionAtSurfaceA, B:
// docs/physics.md, "Capsules", "A capsule on a slope, on a body"). Such a side's friction point is
// its surface point, not the face point of its box that the push moved, carried by both inscribed
// tetrahedra, as the ground's is (FrictionPoint).
namespace capsule_friction {

FrictionPoint side(bool atSurface, const Embedding& surface, const Embedding& point) {
  return atSurface ? FrictionPoint::of(surface, true) : FrictionPoint::of(point, false);
}

// Never anchored (only a face-on-face manifold between two boxes is: NarrowPhase::pushManifold).
void apply(Particles& p, const BodyContact& c, const BodyContactExtra& extra, Real push) {
  const FrictionPoint a = side(c.frictionAtSurfaceA, extra.surfaceA, c.pointA);
  const FrictionPoint b = side(c.frictionAtSurfaceB, extra.surfaceB, c.pointB);
  Vec3 slide = (b.at(p.position) - b.at(p.previous)) - (a.at(p.position) - a.at(p.previous));
  slide -= glm::dot(slide, c.normal) * c.normal;
  const Real slide2 = glm::dot(slide, slide);
  if (slide2 == 0.0) return;
  const Real denominator = a.weight(p.inverseMass) + b.weight(p.inverseMass);
  const Real pushed = weightSum(p, c.pointA, c.pointB);
  if (denominator == 0.0 || pushed == 0.0) return;
  // The push moved the face points, an impulse push / K_face; a cut of the slide at the surface
  // points by c metres is an impulse c / K_surface. Coulomb bounds the impulses, so the push is
  // counted at K_surface. Bounded by the bare push, a corners capsule's friction on a box was
  // mu / 1.66 of Coulomb's (K 5.02 w at a lying capsule's end's surface point by one tetrahedron,
  // 3.02 w at its face point): lying along a 10 degree slope at mu 0.25 it slid at 0.26 m/s^2.
  const Real normal = push * denominator / pushed;
  const Real held = c.combined.staticFriction * normal;
  Real cut = 1.0;
  if (slide2 > held * held) cut = std::min(1.0, c.combined.dynamicFriction * normal / std::sqrt(slide2));
  const Vec3 lambda = (cut / denominator) * slide;
  a.shift(p.position, p.inverseMass, lambda);
  b.shift(p.position, p.inverseMass, -lambda);
}

}  // namespace capsule_friction

}  // namespace

void solveBodyContacts(Particles& p, std::span<const BodyContact> contacts, Real slop, std::span<Real> push,
                       std::span<const Real> allowance) {
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const BodyContact& c = contacts[k];
    const Real allowed = allowance.empty() ? 0.0 : allowance[k];  // overlap it may keep
    const Vec3 apart = embeddedPosition(p.position, c.pointB) - embeddedPosition(p.position, c.pointA);
    const Real gap = glm::dot(c.normal, apart) - c.offset + slop + allowed;
    push[k] = 0.0;
    if (gap >= 0.0) continue;
    const Real denominator = weightSum(p, c.pointA, c.pointB);
    if (denominator == 0.0) continue;  // both sides pinned or frozen
    movePair(p.position, p, c.pointA, c.pointB, (-gap / denominator) * c.normal);
    push[k] = -gap;
  }
}

void markPushedParticles(std::span<const BodyContact> contacts, std::span<const std::uint8_t> touched,
                         std::span<std::uint8_t> moved) {
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    if (touched[k] == 0) continue;
    for (int i = 0; i < contacts[k].pointA.count; ++i) moved[contacts[k].pointA.particle[i]] = 1;
    for (int j = 0; j < contacts[k].pointB.count; ++j) moved[contacts[k].pointB.particle[j]] = 1;
  }
}

void applyBodyFriction(Particles& p, std::span<BodyContact> contacts,
                       std::span<const BodyContactExtra> extras, std::span<const Real> push) {
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    if (push[k] <= 0.0) continue;
    BodyContact& c = contacts[k];
    // Friction acts where the surfaces touch (BodyContactExtra::surfaceA, surfaceB), which only a
    // corners capsule's flags send it to read.
    if (c.frictionAtSurfaceA || c.frictionAtSurfaceB) {
      capsule_friction::apply(p, c, extras[k], push[k]);
      continue;
    }
    const Embedding& a = c.pointA;
    const Embedding& b = c.pointB;
    Vec3 slide;
    if (c.anchored) {
      // Held to its anchor: what the pair has slid since static friction took hold, this substep's
      // slide and what earlier ones left.
      c.grip = Grip::Held;
      slide = embeddedPosition(p.position, b) - embeddedPosition(p.position, a) - c.anchor;
    } else {
      const Vec3 motionA = embeddedPosition(p.position, a) - embeddedPosition(p.previous, a);
      const Vec3 motionB = embeddedPosition(p.position, b) - embeddedPosition(p.previous, b);
      slide = motionB - motionA;
    }
    slide -= glm::dot(slide, c.normal) * c.normal;
    // Squared lengths, so that a contact friction holds (most of a resting stack's) takes no root
    // (the same test as |slide| > held but within a rounding of the threshold).
    const Real slide2 = glm::dot(slide, slide);
    if (slide2 == 0.0) continue;
    const Real denominator = weightSum(p, a, b);
    if (denominator == 0.0) continue;
    const Real held = c.combined.staticFriction * push[k];
    Real cut = 1.0;
    if (slide2 > held * held) cut = std::min(1.0, c.combined.dynamicFriction * push[k] / std::sqrt(slide2));
    // Shrink the relative slide by cut: B moves back, A moves along, by their weights.
    movePair(p.position, p, a, b, (cut / denominator) * slide * -1.0);
    // It slipped: the anchor stays to the substep's end, so that each later pass cuts the whole
    // slide, as an unanchored point's would; where this slip left the pair is the next substep's
    // anchor unless a later pass holds it (NarrowPhase::anchor).
    if (c.anchored && cut < 1.0) {
      c.grip = Grip::Slipped;
      c.slipEnd = c.anchor + (1.0 - cut) * slide;
    }
  }
}

}  // namespace phys::detail
