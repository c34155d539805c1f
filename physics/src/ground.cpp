#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "passes.h"

namespace phys::detail {

namespace {

// sum_k c_ak c_bk w_k over the particles two embedded points share: how far point a moves along n
// when point b is pushed by a unit impulse (the weighted projection's coupling; K_aa is
// embeddedWeight).
Real sharedWeight(const std::vector<Real>& inverseMass, const Embedding& a, const Embedding& b) {
  Real sum = 0.0;
  for (int i = 0; i < a.count; ++i) {
    for (int j = 0; j < b.count; ++j) {
      if (a.particle[i] == b.particle[j]) sum += a.weight[i] * b.weight[j] * inverseMass[a.particle[i]];
    }
  }
  return sum;
}

// A capsule's two ground points share their particles (a corners capsule's both lie on its box's
// bottom face, a tetra capsule's on its 4 particles): pushed one after the other, the first push
// lifted the other end's carriers too, so the second end was pushed less, every pass the same way,
// and the box was pitched and sheared along its core; its sticks then moved both points along the
// core in the later passes, whose pushes were too small for friction to stop (docs/physics.md,
// "Capsules", "A capsule lying still"). Pushed as one block, the two impulses solve
// K lambda = depth with K_ab = sharedWeight, each >= 0 (a 2-point complementarity problem: both
// ends onto the plane, else the one whose push leaves the other above), and the two rise together.
// Only a corners capsule's (a tetra capsule gains nothing from it, and its piles slept later), and
// only while it rests on the ground with its box whole (GroundContacts::placeCapsulePoints): pushed
// so from its landing on, a thin capsule thrown down at 8 m/s, squashed through itself in a
// step, stayed crushed flat and chattered 4 cm deep, where pushed one after the other it comes out
// whole, inside out, and rests (CapsuleGround.AThinCapsuleThrownDownHardRestsAtItsRadiusEvenInsideOut).
void collideCapsulePair(Particles& p, const GroundContact& a, const GroundContact& b, Real depthA,
                        Real depthB, const Vec3& n, Real& pushA, Real& pushB) {
  pushA = pushB = 0.0;
  if (depthA <= 0.0 && depthB <= 0.0) return;
  const Real kaa = embeddedWeight(p.inverseMass, a.point), kbb = embeddedWeight(p.inverseMass, b.point);
  const Real kab = sharedWeight(p.inverseMass, a.point, b.point);
  Real la = 0.0, lb = 0.0;
  const Real det = kaa * kbb - kab * kab;
  if (det > 1e-12 * kaa * kbb) {  // both ends on the plane after
    la = (kbb * depthA - kab * depthB) / det;
    lb = (kaa * depthB - kab * depthA) / det;
  }
  if (la < 0.0 || lb < 0.0 || (la == 0.0 && lb == 0.0)) {
    // One alone: a's own push if it leaves b on or above the plane, else b's; with neither (the
    // two carried alike, det 0), the deeper one's, which lifts the other as far.
    la = lb = 0.0;
    const bool aAlone = depthA > 0.0 && kaa > 0.0 && depthB - kab * depthA / kaa <= 0.0;
    const bool bAlone = depthB > 0.0 && kbb > 0.0 && depthA - kab * depthB / kbb <= 0.0;
    const bool aDeeper = depthA >= depthB;
    if (aAlone || (!bAlone && aDeeper && kaa > 0.0))
      la = depthA / kaa;
    else if (kbb > 0.0)
      lb = depthB / kbb;
  }
  if (la > 0.0) shiftEmbedded(p.position, p.inverseMass, a.point, la * n);
  if (lb > 0.0) shiftEmbedded(p.position, p.inverseMass, b.point, lb * n);
  // The push friction reads: what each point's own impulse alone would move it, as for a lone point.
  pushA = la * kaa;
  pushB = lb * kbb;
}

}  // namespace

void collideGround(Particles& p, std::span<const GroundContact> contacts, const Vec3& n, Real height,
                   std::span<Real> normalPush, std::span<const Real> allowance,
                   std::span<const std::uint8_t> still, std::span<const std::uint8_t> far) {
  // Depth along n below the plane, less what the point may keep.
  auto depthOf = [&](std::size_t c) {
    const Real allowed = allowance.empty() ? 0.0 : allowance[c];  // depth it may keep
    return height + contacts[c].lift - glm::dot(n, embeddedPosition(p.position, contacts[c].point)) - allowed;
  };
  auto isFar = [&](std::size_t c) { return !far.empty() && far[c] != 0; };
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    if (!still.empty() && still[c] != 0) continue;
    // A capsule with an end far above the ground (standing) has one point to push: pushed alone.
    if (contacts[c].pairedWithNext && c + 1 < contacts.size() && !isFar(c) && !isFar(c + 1)) {
      collideCapsulePair(p, contacts[c], contacts[c + 1], depthOf(c), depthOf(c + 1), n, normalPush[c],
                         normalPush[c + 1]);
      ++c;
      continue;
    }
    normalPush[c] = 0.0;
    if (isFar(c)) continue;
    const Real depth = depthOf(c);
    if (depth <= 0.0) continue;
    moveEmbedded(p.position, p.inverseMass, contacts[c].point, depth * n);
    normalPush[c] = depth;
  }
}

void measureGroundStartDepth(const Particles& p, std::span<const GroundContact> contacts, const Vec3& n,
                             Real height, std::span<Real> depth) {
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    depth[c] = height + contacts[c].lift - glm::dot(n, embeddedPosition(p.previous, contacts[c].point));
  }
}

// Jakobsen 2001, "Friction", made Coulomb: a pass's push out of the ground is that pass's normal
// impulse times h / m, and its tangential cut is bounded by mu times it.
void applyGroundFriction(Particles& p, std::span<const GroundContact> contacts, const Vec3& n,
                         std::span<const Real> normalPush, std::span<const std::uint8_t> still) {
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    Real push = normalPush[c];
    if (push <= 0.0 || (!still.empty() && still[c] != 0)) continue;
    const bool onSurface = contacts[c].surface.count > 0;
    const Embedding& e = onSurface ? contacts[c].surface : contacts[c].point;
    // A corners capsule's surface point is carried by both inscribed tetrahedra, half each: the
    // one alone is chiral, and its cuts along a capsule's core twisted the box about the vertical,
    // so that one held on a slope turned off the fall line and rolled (22 cm across in 20 s), and
    // with friction right the seed's capsule ragdoll kept rocking its head. The two together are
    // symmetric, as a box's corners are (docs/physics.md, "Capsules", "A capsule on a slope").
    const Embedding mirror = onSurface ? otherTetrahedron(e) : Embedding{};
    Vec3 slide = embeddedPosition(p.position, e) - embeddedPosition(p.previous, e);
    if (onSurface)
      slide = 0.5 * (slide + (embeddedPosition(p.position, mirror) - embeddedPosition(p.previous, mirror)));
    slide -= glm::dot(slide, n) * n;
    const Real slideLength = glm::length(slide);
    if (slideLength == 0.0) continue;
    Real kE = 0.0, kMirror = 0.0;
    if (onSurface) {
      // The push moved `point` (impulse push / K_point) and the cut moves `surface` (impulse
      // cut / K_surface): Coulomb bounds impulses, so the push is counted at the surface point's
      // K. Carried by one inscribed tetrahedron (K 5.02 w at a lying capsule's ends, its face point
      // 3.02 w) and bounded by the bare push, a corners capsule's friction was mu / 1.66: lying along
      // a 10 degree slope at mu 0.25 it slid 10.9 m in 10 s (docs/physics.md, "Capsules", "A capsule
      // on a slope").
      kE = embeddedWeight(p.inverseMass, e);
      kMirror = embeddedWeight(p.inverseMass, mirror);
      const Real kPoint = embeddedWeight(p.inverseMass, contacts[c].point);
      // The mean of two points carried by disjoint particles: K = (K_e + K_mirror) / 4.
      if (kPoint > 0.0) push *= 0.25 * (kE + kMirror) / kPoint;
    }
    const Material& mu = contacts[c].combined;
    Real cut = 1.0;  // static: stop the slide entirely
    if (slideLength > mu.staticFriction * push) cut = std::min(1.0, mu.dynamicFriction * push / slideLength);
    if (!onSurface) {
      moveEmbedded(p.position, p.inverseMass, e, -cut * slide);
      continue;
    }
    // One impulse J on each of the two points moves their mean by (K_e + K_mirror) J / 2: the
    // cut's, J = 2 cut slide / (K_e + K_mirror), is the mean point's impulse cut slide / K split
    // evenly, so Coulomb's bound holds also when one side's particles weigh more (a pinned or
    // frozen corner), and with one side immovable the other carries the whole cut.
    const Real kSum = kE + kMirror;
    if (kSum <= 0.0) continue;
    const Vec3 impulse = -2.0 * cut * slide / kSum;
    shiftEmbedded(p.position, p.inverseMass, e, impulse);
    shiftEmbedded(p.position, p.inverseMass, mirror, impulse);
  }
}

}  // namespace phys::detail
