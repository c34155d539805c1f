// The passes of contacts with a rigid body on at least one side (physics/rigid_contacts.h); each
// side answers an impulse as rigid_sides.h says.
#include "physics/rigid_contacts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "passes.h"
#include "rigid_block.h"
#include "rigid_motion.h"
#include "rigid_sides.h"

namespace phys {

void RigidContactState::resize(std::size_t n) {
  lambdaNormal.resize(n);
  lambdaTangent.resize(n);
  twist.resize(n);
  approach.resize(n);
  allowance.resize(n);
  touched.resize(n);
}

namespace detail {
namespace {

SideView viewA(const RigidPassInput& in, const RigidContact& c, bool fixed = false) {
  return viewOf(in, c.sideA, c.rigidA, c.localA, c.pointA, fixed);
}

SideView viewB(const RigidPassInput& in, const RigidContact& c, bool fixed = false) {
  return viewOf(in, c.sideB, c.rigidB, c.localB, c.pointB, fixed);
}

// Which sides of a patch a shock-propagation pass holds still: the lower of two bodies (the side
// the patch's normal leaves upwards from), so that each body is set on the one below it as on the
// ground.
struct Hold {
  bool a = false, b = false;
};

// Where a side's body is, for ordering: a rigid body's centre, a particle body's contact point.
Vec3 sideCentre(const RigidPassInput& in, ContactSide side, RigidId rigid, const Embedding& point) {
  return side == ContactSide::Rigid ? in.rigid.position[rigid]
                                    : embeddedPosition(in.particles.position, point);
}

Hold holdFor(const RigidPassInput& in, std::span<const RigidContact> contacts, const RigidContactState& state,
             std::size_t lo, std::size_t hi) {
  const RigidContact& c = contacts[lo];
  if (c.sideA == ContactSide::Ground) return {};
  if ((c.sideA == ContactSide::Rigid && in.rigid.jointed[c.rigidA] != 0) ||
      (c.sideB == ContactSide::Rigid && in.rigid.jointed[c.rigidB] != 0))
    return {};
  // Only a resting contact, one body on top of the other: an impact (a bullet into a wall, a box
  // dropped on a box) keeps both bodies' masses, or the lower would stop the upper dead.
  if (std::abs(glm::dot(c.normal, in.groundNormal)) < kShockMinUpright) return {};
  for (std::size_t k = lo; k < hi; ++k) {
    if (-state.approach[k] > in.restingSpeed) return {};
  }
  // The lower side is the one the normal (from A to B) leaves upwards from: B rests on A when it
  // points up. Not the two centres' heights as the passes have moved them: the first pass lifts a
  // body out of its fall onto the ground, or onto the body under it, before the body above it is
  // read, and once a substep's fall of g h^2 passes the centres' distance (a box 0.1 m thick on a
  // slab 1 m thick at 0.25 s) the upper body read as the lower, was held, and pushed the lower down
  // to it, every pass (docs/physics.md, "A slab and what rests on it at long steps").
  const bool aLower = glm::dot(c.normal, in.groundNormal) > 0.0;
  return {aLower, !aLower};
}

// n . (pB - pA): the ground is the plane n . x = height under B.
Real separation(const RigidPassInput& in, const RigidContact& c, const Vec3& pA, const Vec3& pB) {
  if (c.sideA == ContactSide::Ground) return glm::dot(c.normal, pB) - in.groundHeight;
  return glm::dot(c.normal, pB - pA);
}

}  // namespace

Vec3 sidePosition(const Particles& particles, const RigidBodies& r, ContactSide side, RigidId rigid,
                  const Vec3& local, const Embedding& point, bool previous) {
  switch (side) {
    case ContactSide::Rigid:
      return previous ? r.previousPosition[rigid] + r.previousOrientation[rigid] * local
                      : r.position[rigid] + r.orientation[rigid] * local;
    case ContactSide::Particles:
      return embeddedPosition(previous ? particles.previous : particles.position, point);
    case ContactSide::Ground:
      break;
  }
  return Vec3(0.0);
}

Real startOverlap(const Particles& particles, const RigidBodies& r, const RigidContact& c,
                  Real groundHeight) {
  const Vec3 b = sidePosition(particles, r, c.sideB, c.rigidB, c.localB, c.pointB, true);
  if (c.sideA == ContactSide::Ground) return groundHeight - glm::dot(c.normal, b);
  const Vec3 a = sidePosition(particles, r, c.sideA, c.rigidA, c.localA, c.pointA, true);
  return -glm::dot(c.normal, b - a);
}

void measureRigidGroundStarts(const RigidPassInput& in, std::span<const RigidContact> contacts,
                              RigidContactState& state) {
  state.resize(contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k)
    state.allowance[k] = startOverlap(in.particles, in.rigid, contacts[k], in.groundHeight);
}

void startRigidContacts(const RigidPassInput& in, std::span<const RigidContact> contacts,
                        RigidContactState& state, Real depenetration) {
  std::fill(state.lambdaNormal.begin(), state.lambdaNormal.end(), 0.0);
  std::fill(state.lambdaTangent.begin(), state.lambdaTangent.end(), 0.0);
  std::fill(state.twist.begin(), state.twist.end(), 0.0);
  std::fill(state.touched.begin(), state.touched.end(), std::uint8_t{0});
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const RigidContact& c = contacts[k];
    const Real startOverlap = state.allowance[k];
    state.allowance[k] = startOverlap > depenetration ? startOverlap - depenetration : 0.0;
    const SideView a = viewA(in, c), b = viewB(in, c);
    state.approach[k] = glm::dot(c.normal, velocityOf(in, b) - velocityOf(in, a));
  }
}

namespace {

// A patch's touching points (pushed in this substep) seen together: their centre on each side, now
// and at the substep's start, and their mean distance from it (the twist's lever).
struct PatchCentre {
  int count = 0;
  Vec3 nowA{0.0}, nowB{0.0}, startA{0.0}, startB{0.0};
  Vec3 localB{0.0};   // B's pressing points' mean in B's frame, for a rigid B
  Real radius = 0.0;  // unit: m
};

// A rigid side's centre is its pose applied to the mean of its points in its frame (the map is
// affine), and a turn keeps lengths, so the radius needs no pose at all: one rotation per side.
PatchCentre centreOf(const RigidPassInput& in, std::span<const RigidContact> contacts,
                     const RigidContactState& state, std::size_t lo, std::size_t hi, bool start) {
  PatchCentre p;
  Vec3 sumA(0.0), sumB(0.0), startSumA(0.0), startSumB(0.0);  // local points (rigid) or positions
  const RigidContact& first = contacts[lo];
  for (std::size_t k = lo; k < hi; ++k) {
    if (state.lambdaNormal[k] <= 0.0) continue;
    const RigidContact& c = contacts[k];
    if (c.sideA == ContactSide::Rigid) sumA += c.localA;
    if (c.sideA == ContactSide::Particles) {
      sumA += embeddedPosition(in.particles.position, c.pointA);
      if (start) startSumA += embeddedPosition(in.particles.previous, c.pointA);
    }
    if (c.sideB == ContactSide::Rigid) sumB += c.localB;
    if (c.sideB == ContactSide::Particles) {
      sumB += embeddedPosition(in.particles.position, c.pointB);
      if (start) startSumB += embeddedPosition(in.particles.previous, c.pointB);
    }
    ++p.count;
  }
  if (p.count == 0) return p;
  const Real share = 1.0 / p.count;
  auto place = [&](ContactSide side, RigidId rigid, const Vec3& sum, const Vec3& startSum, Vec3& now,
                   Vec3& then) {
    if (side == ContactSide::Rigid) {
      const Vec3 local = sum * share;
      now = in.rigid.position[rigid] + in.rigid.orientation[rigid] * local;
      if (start) then = in.rigid.previousPosition[rigid] + in.rigid.previousOrientation[rigid] * local;
    } else if (side == ContactSide::Particles) {
      now = sum * share;
      then = startSum * share;
    }
  };
  place(first.sideA, first.rigidA, sumA, startSumA, p.nowA, p.startA);
  place(first.sideB, first.rigidB, sumB, startSumB, p.nowB, p.startB);
  const Vec3 meanB = sumB * share;
  p.localB = meanB;
  for (std::size_t k = lo; k < hi; ++k) {
    if (state.lambdaNormal[k] <= 0.0) continue;
    const RigidContact& c = contacts[k];
    p.radius += c.sideB == ContactSide::Rigid
                    ? glm::length(c.localB - meanB)
                    : glm::length(embeddedPosition(in.particles.position, c.pointB) - p.nowB);
  }
  p.radius *= share;
  return p;
}

// One side of a patch, for an impulse at its centre: a rigid body answers at the centre's lever arm;
// a particle body through each touching point's particles, the impulse shared equally among them.
struct PatchSide {
  ContactSide side;
  RigidId rigid;
  bool fixed = false;
  Vec3 at{0.0};               // Rigid: the centre from the body's centre
  Real particleWeight = 0.0;  // Particles: how far the centre moves per unit of impulse (1/kg)
};

// A particle side's pressing points as its particles answer them, each particle once: its inverse
// mass, its weights in the points summed (s_j), and the same weights times each point's lever from
// the patch's centre across the normal (R_j). The points of one face are carried by the same four
// corners, so an impulse shared among them moves each corner by all of their weights at once.
// Reckoned point by point (sum over the points of sum c^2 w), a corners box's patch on a rigid box
// at 0.2 m off its centre moved 1.37 times as far as asked: each friction correction overshot, and
// the last pass of every substep left a slip that no anchor undid (docs/physics.md, "Failures at
// rest").
struct PatchParticles {
  static constexpr std::size_t kMost = 4 * PatchAnchor::kKeptPoints;
  std::size_t count = 0;
  std::array<ParticleId, kMost> id{};
  std::array<Real, kMost> inverseMass{}, weight{};
  std::array<Vec3, kMost> lever{};
  Real levers = 0.0;  // unit: m^2; sum of the points' squared levers across the normal
};

// The lever of a point at `at` from the patch's centre, across the normal n.
Vec3 leverAcross(const Vec3& at, const Vec3& centre, const Vec3& n) {
  const Vec3 r = at - centre;
  return r - glm::dot(r, n) * n;
}

PatchParticles patchParticles(const RigidPassInput& in, std::span<const RigidContact> contacts,
                              const RigidContactState& state, std::size_t lo, std::size_t hi, bool sideB,
                              const Vec3& centre) {
  PatchParticles out;
  const Vec3 n = contacts[lo].normal;
  for (std::size_t k = lo; k < hi; ++k) {
    if (state.lambdaNormal[k] <= 0.0) continue;
    const Embedding& e = sideB ? contacts[k].pointB : contacts[k].pointA;
    const Vec3 r = leverAcross(embeddedPosition(in.particles.position, e), centre, n);
    out.levers += glm::dot(r, r);
    for (int i = 0; i < e.count; ++i) {
      std::size_t j = 0;
      while (j < out.count && out.id[j] != e.particle[i]) ++j;
      if (j == out.count) {
        if (out.count == PatchParticles::kMost) continue;  // cannot happen: 4 a point, 8 points
        out.id[j] = e.particle[i];
        out.inverseMass[j] = in.particles.inverseMass[e.particle[i]];
        ++out.count;
      }
      out.weight[j] += e.weight[i];
      out.lever[j] += e.weight[i] * r;
    }
  }
  return out;
}

PatchSide patchSide(const RigidPassInput& in, std::span<const RigidContact> contacts,
                    const RigidContactState& state, std::size_t lo, std::size_t hi, bool sideB,
                    const Vec3& centre, int count, bool fixed) {
  const RigidContact& first = contacts[lo];
  PatchSide s{sideB ? first.sideB : first.sideA, sideB ? first.rigidB : first.rigidA, fixed};
  if (s.side == ContactSide::Rigid) s.at = centre - in.rigid.position[s.rigid];
  if (s.side != ContactSide::Particles) return s;
  // An impulse p shared equally moves particle j by w_j s_j p / N, and the centre, the points' mean,
  // by sum_j w_j s_j^2 p / N^2.
  const PatchParticles particles = patchParticles(in, contacts, state, lo, hi, sideB, centre);
  for (std::size_t j = 0; j < particles.count; ++j)
    s.particleWeight += particles.inverseMass[j] * particles.weight[j] * particles.weight[j];
  s.particleWeight /= static_cast<Real>(count) * count;
  return s;
}

Real patchInverseMass(const RigidPassInput& in, const PatchSide& s, const Vec3& d) {
  if (s.fixed) return 0.0;
  if (s.side == ContactSide::Rigid) return pointInverseMass(in.rigid, s.rigid, s.at, d);
  return s.particleWeight;
}

// Applies the impulse p (positional, kg m, or of velocity, N s) at the patch's centre.
void applyAtCentre(RigidPassInput& in, std::span<const RigidContact> contacts, const RigidContactState& state,
                   std::size_t lo, std::size_t hi, bool sideB, const PatchSide& s, const Vec3& p, int count,
                   bool velocity) {
  if (s.fixed) return;
  if (s.side == ContactSide::Rigid) {
    if (velocity)
      applyVelocityImpulse(in.rigid, s.rigid, s.at, p);
    else
      applyPositionalImpulse(in.rigid, s.rigid, s.at, p);
    return;
  }
  if (s.side != ContactSide::Particles) return;
  const Vec3 share = p / static_cast<Real>(count);
  for (std::size_t k = lo; k < hi; ++k) {
    if (state.lambdaNormal[k] <= 0.0) continue;
    const Embedding& e = sideB ? contacts[k].pointB : contacts[k].pointA;
    if (velocity)
      shiftEmbedded(in.particles.previous, in.particles.inverseMass, e, -share * in.h);
    else
      shiftEmbedded(in.particles.position, in.particles.inverseMass, e, share);
  }
}

// The velocity of the patch's centre on one side (m/s): a rigid body's at the centre, a particle
// body's the mean of its touching points'.
Vec3 patchVelocity(const RigidPassInput& in, std::span<const RigidContact> contacts,
                   const RigidContactState& state, std::size_t lo, std::size_t hi, bool sideB,
                   const PatchSide& s, int count) {
  if (s.side == ContactSide::Rigid) return pointVelocity(in.rigid, s.rigid, s.at);
  Vec3 v(0.0);
  if (s.side != ContactSide::Particles) return v;
  for (std::size_t k = lo; k < hi; ++k) {
    if (state.lambdaNormal[k] <= 0.0) continue;
    v += velocityOf(in, sideB ? viewB(in, contacts[k]) : viewA(in, contacts[k]));
  }
  return v / static_cast<Real>(count);
}

// The rigid sides' turn about the normal over the substep (rad), B's less A's.
Real twistOf(const RigidPassInput& in, const RigidContact& c) {
  Real twist = 0.0;
  if (c.sideB == ContactSide::Rigid)
    twist += glm::dot(c.normal,
                      turnBetween(in.rigid.previousOrientation[c.rigidB], in.rigid.orientation[c.rigidB]));
  if (c.sideA == ContactSide::Rigid)
    twist -= glm::dot(c.normal,
                      turnBetween(in.rigid.previousOrientation[c.rigidA], in.rigid.orientation[c.rigidA]));
  return twist;
}

// How far the rigid sides turn against each other about n per unit of angular impulse (1/(kg m^2)).
Real twistInverseMass(const RigidPassInput& in, const RigidContact& c, Hold hold) {
  Real w = 0.0;
  if (c.sideB == ContactSide::Rigid && !hold.b)
    w += glm::dot(c.normal, inverseInertiaTimes(in.rigid, c.rigidB, c.normal));
  if (c.sideA == ContactSide::Rigid && !hold.a)
    w += glm::dot(c.normal, inverseInertiaTimes(in.rigid, c.rigidA, c.normal));
  return w;
}

// Turns B by the angular impulse L about n (and A by -L): positionally, or as a change of spin.
void applyTwist(RigidPassInput& in, const RigidContact& c, Real L, bool velocity, Hold hold) {
  auto turn = [&](RigidId i, Real amount) {
    const Vec3 angle = inverseInertiaTimes(in.rigid, i, c.normal * amount);
    if (velocity)
      in.rigid.angularVelocity[i] += angle;
    else
      in.rigid.orientation[i] = nudged(in.rigid.orientation[i], angle);
  };
  if (c.sideB == ContactSide::Rigid && !hold.b && in.rigid.inverseMass[c.rigidB] != 0.0) turn(c.rigidB, L);
  if (c.sideA == ContactSide::Rigid && !hold.a && in.rigid.inverseMass[c.rigidA] != 0.0) turn(c.rigidA, -L);
}

// A patch's twist about its normal when a particle body is a side: each particle side's turn is read
// from its pressing points (their least-squares turn about the centre across n), and an angular
// impulse L reaches it as tangential impulses L (n x r_k) / sum |r|^2 at the points. Twisting the
// rigid sides alone leaves a corners box on a rigid box (held still by shock propagation) nothing
// against its turning (docs/physics.md, "Failures at rest").
struct ParticleTwist {
  std::array<PatchParticles, 2> side;  // A, B
  std::array<bool, 2> moves{};         // a particle side that is not held
  std::array<Vec3, 2> centre{};
};

ParticleTwist particleTwist(const RigidPassInput& in, std::span<const RigidContact> contacts,
                            const RigidContactState& state, std::size_t lo, std::size_t hi,
                            const PatchCentre& centre, Hold hold) {
  ParticleTwist t;
  const RigidContact& c = contacts[lo];
  const std::array<ContactSide, 2> sides{c.sideA, c.sideB};
  t.centre = {centre.nowA, centre.nowB};
  for (int s = 0; s < 2; ++s) {
    if (sides[s] != ContactSide::Particles) continue;
    t.moves[s] = !(s == 0 ? hold.a : hold.b);
    t.side[s] = patchParticles(in, contacts, state, lo, hi, s == 1, t.centre[s]);
  }
  return t;
}

bool hasParticleSide(const RigidContact& c) {
  return c.sideA == ContactSide::Particles || c.sideB == ContactSide::Particles;
}

// A particle side's turn about n over the substep so far (rad): sum_k n . (r_k x motion_k) / sum_k |r_k|^2.
Real particleTurn(const RigidPassInput& in, std::span<const RigidContact> contacts,
                  const RigidContactState& state, std::size_t lo, std::size_t hi, bool sideB,
                  const Vec3& centre, Real levers) {
  if (levers <= 0.0) return 0.0;
  const Vec3 n = contacts[lo].normal;
  Real turn = 0.0;
  for (std::size_t k = lo; k < hi; ++k) {
    if (state.lambdaNormal[k] <= 0.0) continue;
    const Embedding& e = sideB ? contacts[k].pointB : contacts[k].pointA;
    const Vec3 now = embeddedPosition(in.particles.position, e);
    const Vec3 moved = now - embeddedPosition(in.particles.previous, e);
    turn += glm::dot(n, glm::cross(leverAcross(now, centre, n), moved));
  }
  return turn / levers;
}

// The patch's twist over the substep, B's less A's, its particle sides' included (rad).
Real patchTwistOf(const RigidPassInput& in, std::span<const RigidContact> contacts,
                  const RigidContactState& state, std::size_t lo, std::size_t hi, const ParticleTwist& t) {
  Real twist = twistOf(in, contacts[lo]);
  for (int s = 0; s < 2; ++s) {
    if (t.side[s].count == 0) continue;
    const Real turn = particleTurn(in, contacts, state, lo, hi, s == 1, t.centre[s], t.side[s].levers);
    twist += s == 1 ? turn : -turn;
  }
  return twist;
}

// Turns B by the positional angular impulse L about n and A by -L: the rigid sides as applyTwist
// does, each particle side by tangential impulses at its pressing points.
void applyPatchTwist(RigidPassInput& in, std::span<const RigidContact> contacts,
                     const RigidContactState& state, std::size_t lo, std::size_t hi, Real L, Hold hold,
                     const ParticleTwist& t) {
  applyTwist(in, contacts[lo], L, false, hold);
  const Vec3 n = contacts[lo].normal;
  for (int s = 0; s < 2; ++s) {
    if (!t.moves[s] || t.side[s].levers <= 0.0) continue;
    const Real amount = (s == 1 ? L : -L) / t.side[s].levers;
    for (std::size_t k = lo; k < hi; ++k) {
      if (state.lambdaNormal[k] <= 0.0) continue;
      const Embedding& e = s == 1 ? contacts[k].pointB : contacts[k].pointA;
      const Vec3 r = leverAcross(embeddedPosition(in.particles.position, e), t.centre[s], n);
      shiftEmbedded(in.particles.position, in.particles.inverseMass, e, amount * glm::cross(n, r));
    }
  }
}

// One sweep of a patch's points along the normal; returns the patch's normal impulse so far in
// the substep. The impulse of a point may shrink again, down to 0, when the pushes after it lifted
// it further than it needs (the clamp of accumulated impulses): pushed only ever up, a box resting on
// its four corners at 4 iterations hovered 0.14 mm over the ground.
Real pushPatch(RigidPassInput& in, std::span<const RigidContact> contacts, RigidContactState& state,
               std::size_t lo, std::size_t hi, Hold hold) {
  Real normal = 0.0;
  for (std::size_t k = lo; k < hi; ++k) {
    const RigidContact& c = contacts[k];
    const SideView a = viewA(in, c, hold.a), b = viewB(in, c, hold.b);
    const Real gap = separation(in, c, positionOf(in, a), positionOf(in, b)) + state.allowance[k];
    if (gap < 0.0 || state.lambdaNormal[k] > 0.0) {
      const Real w = inverseMassAlong(in, a, c.normal) + inverseMassAlong(in, b, c.normal);
      if (w > 0.0) {
        const Real dLambda = std::max(-gap / w, -state.lambdaNormal[k]);
        push(in, a, -dLambda * c.normal);
        push(in, b, dLambda * c.normal);
        state.lambdaNormal[k] += dLambda;
        if (gap < 0.0) state.touched[k] = 1;
      }
    }
    normal += state.lambdaNormal[k];
  }
  return normal;
}

// A point of a rigid side (or of the ground, in the world) in its frame at the substep's start.
Vec3 heldAtStart(const RigidPassInput& in, ContactSide side, RigidId rigid, const Vec3& world) {
  if (side != ContactSide::Rigid) return world;
  return glm::conjugate(in.rigid.previousOrientation[rigid]) * (world - in.rigid.previousPosition[rigid]);
}

// Where an anchor's point of a rigid side (or of the ground) is now.
Vec3 heldNow(const RigidPassInput& in, ContactSide side, RigidId rigid, const Vec3& held) {
  if (side != ContactSide::Rigid) return held;
  return in.rigid.position[rigid] + in.rigid.orientation[rigid] * held;
}

// Makes `anchor` at B's point `onB` (in B's frame) where it was at the substep's start, unless it
// holds there already: a patch is anchored when it first holds or its pressing points change.
void holdAt(const RigidPassInput& in, const RigidContact& c, PatchAnchor& anchor, const Vec3& onB) {
  if (anchor.held && anchor.onB == onB) return;
  const Vec3 start = in.rigid.previousPosition[c.rigidB] + in.rigid.previousOrientation[c.rigidB] * onB;
  anchor.onA = heldAtStart(in, c.sideA, c.rigidA, start);
  anchor.onB = onB;
  anchor.held = true;
}

// A patch of three to eight points whose sides are rigid bodies or the ground (a face on a face or
// on the ground) is solved as one block (rigid_block.h): its points, its friction and its twist
// together; and a body resting on several held bodies (a box across two boxes of a pyramid) takes
// all of those patches in one block, so that each patch's push does not tip it on the others.
// Other patches are solved point by point: one or two points (an edge, a capsule's end on another
// body) tip nothing that a face could hold, and as blocks they made the rigid ragdolls' step 0.49
// to 0.81 ms. But a capsule's two points on the ground are one block: pushed one after the other,
// each push tipped it on the other end, and a capsule lying on the ground rested tilted, its low
// end under the ground by part of the g h^2 a substep takes it down (at 1 x 1: 1.2 mm at 1/60 s,
// 2.2 cm at 0.1 s, 0.44 m at 0.3 s; RigidBody.ALyingCapsuleRestsAtItsRadiusAtAnyStep). So are a
// capsule's two points lying along a rigid body (RigidContact::capsuleLying), for the same reason:
// on a box at 1 x 1, 0.59 mm low at 1/60 s and 7.9 mm at 0.1 s; at 3 passes, 8 cm and 20 degrees
// from level at 0.2 s (RigidBody.ACapsuleLyingOnABoxRestsAtItsRadiusAtAnyStep, docs/physics.md).
bool solvesAsBlock(const RigidContact& first, std::size_t count) {
  return (count >= 3 || (count == 2 && first.capsuleLying)) && count <= kMostBlockPoints &&
         first.sideA != ContactSide::Particles && first.sideB != ContactSide::Particles;
}

BlockBody blockBody(const RigidPassInput& in, ContactSide side, RigidId rigid, bool held) {
  if (side != ContactSide::Rigid || held || in.rigid.inverseMass[rigid] == 0.0) return {};
  return {true, rigid, in.rigid.inverseMass[rigid]};
}

// Two unit directions across the unit normal n, so that the friction rows see any slip.
void across(const Vec3& n, Vec3& t1, Vec3& t2) {
  t1 = glm::normalize(std::abs(n.x) < 0.6 ? glm::cross(n, Vec3(1.0, 0.0, 0.0))
                                          : glm::cross(n, Vec3(0.0, 1.0, 0.0)));
  t2 = glm::cross(n, t1);
}

constexpr std::size_t kNoRow = kMostBlockRows;

// How a patch's rows enter a block. On its own, its A is the block's A and its B the block's B.
// In a body's block only the body moves: it is the block's B, and when it is the patch's A its rows
// are turned round (it moves along -n).
struct PatchInBlock {
  const ContactPatch* patch = nullptr;
  Hold hold;
  bool alone = true;
  Real sign = 1.0;  // +1: the block's B is the patch's B; -1: the block's B is the patch's A
  std::size_t points = 0, friction = 0, twist = kNoRow;  // its rows
  Real radius = 0.0;                                     // unit: m; the twist's lever
  bool presses = false;                                  // a point presses, so it has its friction rows
  bool slides = false, turns = false;
};

// A row of the patch: what side A and side B of the patch do, put into the block.
std::size_t addPatchRow(ConstraintBlock& block, const PatchInBlock& p, const Vec3& linear, const Vec3& armA,
                        const Vec3& armB, Real error, Real lower = -ConstraintBlock::kFree,
                        Real upper = ConstraintBlock::kFree) {
  if (p.alone) return block.addRow(linear, armA, armB, error, lower, upper);
  return p.sign > 0.0 ? block.addRow(linear, Vec3(0.0), armB, error, lower, upper)
                      : block.addRow(-linear, Vec3(0.0), -armA, error, lower, upper);
}

// The lever arm of a side's point for the block: from its body's centre when it moves in the block.
Vec3 leverFor(const RigidPassInput& in, ContactSide side, RigidId rigid, bool held, const Vec3& point) {
  if (side != ContactSide::Rigid || held) return Vec3(0.0);
  return point - in.rigid.position[rigid];
}

// The patch's position rows: its points along n, and, once it presses, its anchor's slip along two
// directions and its twist.
void addPositionRows(const RigidPassInput& in, std::span<const RigidContact> contacts,
                     RigidContactState& state, ConstraintBlock& block, PatchInBlock& p) {
  const std::size_t lo = p.patch->first, hi = lo + p.patch->count;
  const RigidContact& c = contacts[lo];
  const Vec3 n = c.normal;
  Vec3 centre(0.0);  // of the pressing points on B, in B's frame
  int pressing = 0;
  std::array<bool, kMostBlockPoints> pressed{};
  p.points = block.rows();
  for (std::size_t k = lo; k < hi; ++k) {
    const RigidContact& q = contacts[k];
    const SideView va = viewA(in, q, p.hold.a), vb = viewB(in, q, p.hold.b);
    const Real gap = separation(in, q, positionOf(in, va), positionOf(in, vb)) + state.allowance[k];
    addPatchRow(block, p, n, glm::cross(va.at, n), glm::cross(vb.at, n), gap, -state.lambdaNormal[k]);
    if (gap < 0.0) state.touched[k] = 1;
    if (gap < 0.0 || state.lambdaNormal[k] > 0.0) {
      pressed[k - lo] = true;
      centre += q.localB;
      ++pressing;
    }
  }
  p.presses = pressing > 0;
  if (!p.presses) return;
  centre /= static_cast<Real>(pressing);
  p.radius = 0.0;
  for (std::size_t k = lo; k < hi; ++k) {
    if (pressed[k - lo]) p.radius += glm::length(contacts[k].localB - centre);
  }
  p.radius /= static_cast<Real>(pressing);
  PatchAnchor& anchor = state.anchors[p.patch->anchor];
  // Held where it stuck while the same points press; a patch whose points move over B (a ball or a
  // capsule rolling, its point on the ground placed anew each pass) holds only against the
  // substep's own motion, as the 2020 paper has it: held at the old point, a rolling ball was braked.
  holdAt(in, c, anchor, centre);
  const Vec3 onA = heldNow(in, c.sideA, c.rigidA, anchor.onA),
             onB = heldNow(in, c.sideB, c.rigidB, anchor.onB);
  const Vec3 slip = onB - onA;
  const Vec3 leverA = leverFor(in, c.sideA, c.rigidA, p.hold.a, onA);
  const Vec3 leverB = leverFor(in, c.sideB, c.rigidB, p.hold.b, onB);
  Vec3 t1, t2;
  across(n, t1, t2);
  p.friction = block.rows();
  for (const Vec3& t : {t1, t2})
    addPatchRow(block, p, t, glm::cross(leverA, t), glm::cross(leverB, t), glm::dot(slip, t));
  // One pressing point has no lever against a twist: the row would only ever be dropped.
  if (p.radius > 0.0) p.twist = addPatchRow(block, p, Vec3(0.0), n, n, twistOf(in, c));
}

// The patch's normal impulse in the substep with the solve's added (kg m).
Real normalWith(const RigidContactState& state, const PatchInBlock& p, std::span<const Real> delta) {
  Real normal = 0.0;
  for (std::uint32_t k = 0; k < p.patch->count; ++k)
    normal += state.lambdaNormal[p.patch->first + k] + delta[p.points + k];
  return normal;
}

// A patch's first solve in a substep starts its points from the normal impulses its last substep
// ended with (PatchAnchor::normal), while it has as many points. A point's impulse means the same
// whichever body is the block's B (addPatchRow turns the row with the sides). Friction and twist
// start from 0: started from the last substep's too, the stack of 40 at 1 x 1 leaned 4 cm in a
// minute instead of 1.4 (a friction impulse kept from a substep whose slip is gone pushes on).
void startWhereTheLastSubstepEnded(const RigidContactState& state, const PatchInBlock& p,
                                   std::span<Real> delta) {
  const PatchAnchor& anchor = state.anchors[p.patch->anchor];
  if (!anchor.fresh || anchor.points != p.patch->count) return;
  for (std::uint32_t k = 0; k < p.patch->count; ++k) delta[p.points + k] = anchor.normal[k];
}

// The patch's normal impulses in this substep so far, for the next substep's start.
void keepForTheNextSubstep(RigidContactState& state, const PatchInBlock& p) {
  PatchAnchor& anchor = state.anchors[p.patch->anchor];
  anchor.fresh = false;
  anchor.points = static_cast<std::uint8_t>(p.patch->count);
  for (std::uint32_t k = 0; k < p.patch->count; ++k)
    anchor.normal[k] = state.lambdaNormal[p.patch->first + k];
}

// One position pass over a block of patches (rigid_block.h): points pushed apart, each anchor's
// slip and each twist undone, all in one solve. A patch's friction rows are left out again (and its
// anchor let go) when their impulse would pass mu_s times its normal impulse, as the 2020 paper's
// static friction, and its twist's when that would pass mu_s times it times the patch's radius.
void solvePositionBlock(RigidPassInput& in, std::span<const RigidContact> contacts, RigidContactState& state,
                        std::span<PatchInBlock> run, const BlockBody& a, const BlockBody& b) {
  // A block with nothing to solve still keeps its impulses so far (none, in its first pass of a
  // substep), so that the next substep does not start from those of one before.
  auto keepAll = [&state, &run] {
    for (const PatchInBlock& p : run) keepForTheNextSubstep(state, p);
  };
  ConstraintBlock block(in.rigid, a, b);
  if (!block.moves()) return keepAll();
  bool anyPresses = false;  // else every point is apart and stays so: no impulse to find
  for (PatchInBlock& p : run) {
    addPositionRows(in, contacts, state, block, p);
    anyPresses = anyPresses || p.presses;
  }
  if (!anyPresses) return keepAll();
  block.build();
  std::array<Real, kMostBlockRows> delta{};
  for (const PatchInBlock& p : run) startWhereTheLastSubstepEnded(state, p, delta);
  block.solve(delta);
  bool dropped = false;
  for (PatchInBlock& p : run) {
    if (!p.presses) continue;
    const std::uint32_t lo = p.patch->first;
    const Real limit = contacts[lo].combined.staticFriction * normalWith(state, p, delta);
    p.slides = state.lambdaTangent[lo] + std::hypot(delta[p.friction], delta[p.friction + 1]) > limit;
    p.turns = p.twist != kNoRow && state.twist[lo] + std::abs(delta[p.twist]) > limit * p.radius;
    if (p.slides) {
      block.drop(p.friction);
      block.drop(p.friction + 1);
      state.anchors[p.patch->anchor].held = false;
    }
    if (p.turns) block.drop(p.twist);
    dropped = dropped || p.slides || p.turns;
  }
  if (dropped) block.solve(delta);
  block.apply(in.rigid, delta);
  for (const PatchInBlock& p : run) {
    const std::uint32_t lo = p.patch->first;
    for (std::uint32_t k = 0; k < p.patch->count; ++k) state.lambdaNormal[lo + k] += delta[p.points + k];
    keepForTheNextSubstep(state, p);
    if (!p.presses) continue;
    if (!p.slides) state.lambdaTangent[lo] += std::hypot(delta[p.friction], delta[p.friction + 1]);
    if (p.twist != kNoRow && !p.turns) state.twist[lo] += std::abs(delta[p.twist]);
  }
}

// The patches one block takes: as many as fit kMostBlockRows, each with up to kMostPatchRows rows.
using Run = std::array<PatchInBlock, kMostBlockRows / kMostPatchRows + 1>;

// The patches from `i` on that one block takes: the patch alone, or, when the first rests on a
// held body, every following patch of the same body on a held body, as many as the block holds
// (each with up to kMostPatchRows rows). Returns how many, and sets the block's two sides.
std::size_t gatherRun(const RigidPassInput& in, std::span<const RigidContact> contacts,
                      const RigidContactState& state, std::span<const ContactPatch> patches, std::size_t i,
                      Run& run, BlockBody& a, BlockBody& b) {
  auto resting = [&](const ContactPatch& patch, PatchInBlock& p) {
    const RigidContact& c = contacts[patch.first];
    p = {&patch, holdFor(in, contacts, state, patch.first, patch.first + patch.count)};
    if (!solvesAsBlock(c, patch.count)) return BodyId{kNoBody};
    if (c.sideA == ContactSide::Ground || p.hold.a) return c.bodyB;
    return p.hold.b ? c.bodyA : kNoBody;
  };
  const BodyId body = resting(patches[i], run[0]);
  const RigidContact& c = contacts[patches[i].first];
  std::size_t count = 1;
  if (body != kNoBody) {
    std::size_t rows = patches[i].count + 3;
    while (i + count < patches.size() && count < run.size()) {
      const ContactPatch& next = patches[i + count];
      if (resting(next, run[count]) != body || rows + next.count + 3 > kMostBlockRows) break;
      rows += next.count + 3;
      ++count;
    }
  }
  if (count == 1) {
    run[0].alone = true;
    a = blockBody(in, c.sideA, c.rigidA, run[0].hold.a);
    b = blockBody(in, c.sideB, c.rigidB, run[0].hold.b);
    return 1;
  }
  for (std::size_t k = 0; k < count; ++k) {
    run[k].alone = false;
    run[k].sign = contacts[run[k].patch->first].bodyB == body ? 1.0 : -1.0;
  }
  a = {};
  b = c.bodyB == body ? blockBody(in, c.sideB, c.rigidB, false) : blockBody(in, c.sideA, c.rigidA, false);
  return count;
}

}  // namespace

void findPatches(const RigidPassInput& in, std::span<const RigidContact> contacts,
                 std::vector<ContactPatch>& out) {
  out.clear();
  for (std::size_t k = 0; k < contacts.size();) {
    std::size_t end = k + 1;
    while (end < contacts.size() && contacts[end].bodyA == contacts[k].bodyA &&
           contacts[end].bodyB == contacts[k].bodyB)
      ++end;
    const RigidContact& c = contacts[k];
    Real upper = -std::numeric_limits<Real>::infinity();  // the ground's patches first
    BodyId body = c.bodyB;
    if (c.sideA != ContactSide::Ground) {
      const Real heightA = glm::dot(in.groundNormal, sideCentre(in, c.sideA, c.rigidA, c.pointA));
      const Real heightB = glm::dot(in.groundNormal, sideCentre(in, c.sideB, c.rigidB, c.pointB));
      upper = std::max(heightA, heightB);
      if (heightA > heightB) body = c.bodyA;
    }
    out.push_back({static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(end - k), upper,
                   static_cast<std::uint32_t>(out.size()), body});
    k = end;
  }
  // Equal heights by the upper body, then in the narrow phase's order (pairs by body id), so that
  // the order does not depend on the sort's implementation; std::sort, as std::stable_sort allocates.
  std::sort(out.begin(), out.end(), [](const ContactPatch& x, const ContactPatch& y) {
    if (x.height != y.height) return x.height < y.height;
    if (x.upper != y.upper) return x.upper < y.upper;
    return x.first < y.first;
  });
}

void carryAnchors(std::span<const RigidContact> contacts, std::span<const ContactPatch> patches,
                  RigidContactState& state) {
  std::swap(state.anchors, state.spareAnchors);
  state.anchors.resize(patches.size());
  const std::span<const PatchAnchor> before = state.spareAnchors;
  auto key = [](const PatchAnchor& a) { return std::pair(a.bodyA, a.bodyB); };
  for (const ContactPatch& patch : patches) {
    const RigidContact& c = contacts[patch.first];
    const std::pair pair(c.bodyA, c.bodyB);
    PatchAnchor& anchor = state.anchors[patch.anchor];
    // Most substeps keep the same patches in the same places; else the pairs are in ascending
    // order, as the narrow phase finds them (and the ground's by body).
    const PatchAnchor* found = nullptr;
    if (patch.anchor < before.size() && key(before[patch.anchor]) == pair) {
      found = &before[patch.anchor];
    } else {
      const auto it = std::lower_bound(before.begin(), before.end(), pair,
                                       [&](const PatchAnchor& a, const auto& p) { return key(a) < p; });
      if (it != before.end() && key(*it) == pair) found = &*it;
    }
    anchor = found ? *found : PatchAnchor{c.bodyA, c.bodyB};
    anchor.fresh = true;
  }
}

namespace {

// Whether a patch solved point by point keeps an anchor: a rigid body's on the ground. Between two
// bodies it holds against the substep's own motion, as the 2020 paper has it: anchored there too, a
// chain's links under a 200 kg box could not slip out from under it and sank 0.35 m where they sink
// 0.12 m (JointProjection.HoldsAChainTheContactsPullOpen).
bool anchorsByPoints(const RigidContact& c) {
  return c.sideA == ContactSide::Ground && c.sideB == ContactSide::Rigid;
}

// The slip that static friction undoes, B's centre less A's: from the patch's anchor, made at the
// centre's place at the substep's start when the patch first holds or its pressing points change, as
// a block's (addPositionRows). Held against each substep's own motion alone, a slip that one substep
// left was never undone: a rigid ragdoll lying on the edges and corners of its parts, whose joints
// and contacts pull against each other every substep, crept at 3 mm/s and gained 0.005 J/s
// (docs/physics.md, "Standing for a minute" and "Reaction").
Vec3 anchoredSlip(const RigidPassInput& in, std::span<const RigidContact> contacts, RigidContactState& state,
                  const ContactPatch& patch, const PatchCentre& centre) {
  const RigidContact& c = contacts[patch.first];
  PatchAnchor& anchor = state.anchors[patch.anchor];
  holdAt(in, c, anchor, centre.localB);
  return heldNow(in, c.sideB, c.rigidB, anchor.onB) - heldNow(in, c.sideA, c.rigidA, anchor.onA);
}

// How a patch side's centre slides (along t1, t2) and turns about n for a positional impulse
// (P1 t1 + P2 t2, L n) on it: a 3 x 3 response, columns by impulse. A rigid side answers at the
// centre's lever r: P / m + (I^-1 (r x P + L n)) x r and n . I^-1 (r x P + L n). A particle side as
// its particles do (PatchParticles): an impulse shared equally moves the centre by sum w s^2 / N^2,
// a twist L (n x r_k) / sum |r|^2 turns it by sum w |R|^2 / (sum |r|^2)^2, and each moves the other
// through the corners the points share (sum w s (n x R) / (N sum |r|^2), both ways).
using Response = std::array<std::array<Real, 3>, 3>;

void addRigidResponse(const RigidPassInput& in, RigidId rigid, const Vec3& r, const Vec3& n, const Vec3& t1,
                      const Vec3& t2, Response& k) {
  const std::array<Vec3, 3> impulse{t1, t2, Vec3(0.0)};
  for (int col = 0; col < 3; ++col) {
    const Vec3 turn = inverseInertiaTimes(in.rigid, rigid, col < 2 ? glm::cross(r, impulse[col]) : n);
    const Vec3 moved = impulse[col] * in.rigid.inverseMass[rigid] + glm::cross(turn, r);
    k[0][col] += glm::dot(t1, moved);
    k[1][col] += glm::dot(t2, moved);
    k[2][col] += glm::dot(n, turn);
  }
}

void addParticleResponse(const PatchParticles& p, int points, const Vec3& n, const Vec3& t1, const Vec3& t2,
                         Response& k) {
  const Real count = static_cast<Real>(points);
  Real slide = 0.0, turn = 0.0;
  Vec3 both(0.0);
  for (std::size_t j = 0; j < p.count; ++j) {
    slide += p.inverseMass[j] * p.weight[j] * p.weight[j];
    turn += p.inverseMass[j] * glm::dot(p.lever[j], p.lever[j]);
    both += p.inverseMass[j] * p.weight[j] * glm::cross(n, p.lever[j]);
  }
  k[0][0] += slide / (count * count);
  k[1][1] += slide / (count * count);
  if (p.levers <= 0.0) return;  // one point: no lever to turn it by
  turn /= p.levers * p.levers;
  both /= count * p.levers;
  k[2][2] += turn;
  k[0][2] += glm::dot(t1, both);
  k[2][0] += glm::dot(t1, both);
  k[1][2] += glm::dot(t2, both);
  k[2][1] += glm::dot(t2, both);
}

// Solves k x = b; false when k is singular (nothing on either side can move) or x is not finite.
bool solve3(const Response& k, const std::array<Real, 3>& b, std::array<Real, 3>& x) {
  const glm::dmat3 m(k[0][0], k[1][0], k[2][0], k[0][1], k[1][1], k[2][1], k[0][2], k[1][2], k[2][2]);
  const Real det = glm::determinant(m);
  if (!(std::abs(det) > 0.0)) return false;
  const glm::dvec3 solved = glm::inverse(m) * glm::dvec3(b[0], b[1], b[2]);
  x = {solved.x, solved.y, solved.z};
  return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
}

// Static friction of a patch with a particle body on a side: its centre's slide over the substep
// and its twist about n undone together, by one tangential impulse at the centre and one angular
// impulse, from the two sides' 3 x 3 responses, while the tangential impulse stays within mu_s
// times the patch's normal impulse and the angular one within that times its radius. Together,
// since one after the other each moves what the other undid, and a patch with a particle side has no
// anchor to pull back the slip the last pass leaves (docs/physics.md, "Failures at rest").
void holdParticlePatch(RigidPassInput& in, std::span<const RigidContact> contacts, RigidContactState& state,
                       std::size_t lo, std::size_t hi, const PatchCentre& centre, Hold hold, Real limit) {
  const RigidContact& c = contacts[lo];
  const Vec3 n = c.normal;
  Vec3 slide = (centre.nowB - centre.startB) - (centre.nowA - centre.startA);
  slide -= glm::dot(slide, n) * n;
  const ParticleTwist particles = particleTwist(in, contacts, state, lo, hi, centre, hold);
  const Real twist = centre.radius > 0.0 ? patchTwistOf(in, contacts, state, lo, hi, particles) : 0.0;
  if (slide == Vec3(0.0) && twist == 0.0) return;
  Vec3 t1, t2;
  across(n, t1, t2);
  Response k{};
  const std::array<ContactSide, 2> sides{c.sideA, c.sideB};
  const std::array<RigidId, 2> rigid{c.rigidA, c.rigidB};
  const std::array<bool, 2> held{hold.a, hold.b};
  const std::array<Vec3, 2> at{centre.nowA, centre.nowB};
  for (int s = 0; s < 2; ++s) {
    if (held[s]) continue;
    if (sides[s] == ContactSide::Rigid && in.rigid.inverseMass[rigid[s]] != 0.0)
      addRigidResponse(in, rigid[s], at[s] - in.rigid.position[rigid[s]], n, t1, t2, k);
    if (sides[s] == ContactSide::Particles)
      addParticleResponse(particles.side[s], centre.count, n, t1, t2, k);
  }
  // One pressing point has no lever against a twist: its slide alone is held.
  if (centre.radius <= 0.0) {
    k[2] = {0.0, 0.0, 1.0};
    k[0][2] = k[1][2] = 0.0;
  }
  std::array<Real, 3> x{};
  if (!solve3(k, {-glm::dot(slide, t1), -glm::dot(slide, t2), -twist}, x)) return;
  const Real tangential = std::hypot(x[0], x[1]);
  if (state.lambdaTangent[lo] + tangential > limit) return;  // it slides: the dynamic friction's
  if (state.twist[lo] + std::abs(x[2]) > limit * centre.radius) return;
  const Vec3 p = x[0] * t1 + x[1] * t2;  // on B; A takes -p
  const PatchSide a = patchSide(in, contacts, state, lo, hi, false, centre.nowA, centre.count, hold.a);
  const PatchSide b = patchSide(in, contacts, state, lo, hi, true, centre.nowB, centre.count, hold.b);
  // The twist first: its tangential impulses are along the levers the response was read at.
  if (x[2] != 0.0) applyPatchTwist(in, contacts, state, lo, hi, x[2], hold, particles);
  applyAtCentre(in, contacts, state, lo, hi, false, a, -p, centre.count, false);
  applyAtCentre(in, contacts, state, lo, hi, true, b, p, centre.count, false);
  state.lambdaTangent[lo] += tangential;
  state.twist[lo] += std::abs(x[2]);
}

// A patch of one or two points, or with a particle body on a side, point after point: each pushed
// along n, then the patch's static friction and twist at its centre.
void solvePatchByPoints(RigidPassInput& in, std::span<const RigidContact> contacts, RigidContactState& state,
                        const ContactPatch& patch, Hold hold) {
  const std::size_t lo = patch.first, hi = patch.first + patch.count;
  const Real normal = pushPatch(in, contacts, state, lo, hi, hold);
  if (normal <= 0.0) return;
  // Static friction: the patch centre's slip undone (on the ground from its anchor, else over the
  // substep), and its twist over the substep, while the patch's tangential impulse, and its
  // twist's over its radius, stay within mu_s times its normal impulse. Both are kept, summed over
  // the passes, on the patch's first point.
  const RigidContact& c = contacts[lo];
  const Real limit = c.combined.staticFriction * normal;
  const PatchCentre centre = centreOf(in, contacts, state, lo, hi, true);
  if (hasParticleSide(c)) return holdParticlePatch(in, contacts, state, lo, hi, centre, hold, limit);
  const bool anchored = anchorsByPoints(c);
  Vec3 slide = anchored ? anchoredSlip(in, contacts, state, patch, centre)
                        : (centre.nowB - centre.startB) - (centre.nowA - centre.startA);
  slide -= glm::dot(slide, c.normal) * c.normal;
  const Real length = glm::length(slide);
  if (length > 0.0) {
    const Vec3 t = slide / length;
    const PatchSide a = patchSide(in, contacts, state, lo, hi, false, centre.nowA, centre.count, hold.a);
    const PatchSide b = patchSide(in, contacts, state, lo, hi, true, centre.nowB, centre.count, hold.b);
    const Real w = patchInverseMass(in, a, t) + patchInverseMass(in, b, t);
    const Real dLambda = w > 0.0 ? length / w : 0.0;
    if (dLambda > 0.0 && state.lambdaTangent[lo] + dLambda <= limit) {
      applyAtCentre(in, contacts, state, lo, hi, false, a, dLambda * t, centre.count, false);
      applyAtCentre(in, contacts, state, lo, hi, true, b, -dLambda * t, centre.count, false);
      state.lambdaTangent[lo] += dLambda;
    } else if (anchored) {
      state.anchors[patch.anchor].held = false;  // it slides: the dynamic friction's
    }
  }
  const Real twist = twistOf(in, c);
  const Real w = twistInverseMass(in, c, hold);
  if (twist != 0.0 && w > 0.0 && centre.radius > 0.0) {
    const Real dL = -twist / w;  // angular impulse, kg m^2 (rad)
    if (state.twist[lo] + std::abs(dL) <= limit * centre.radius) {
      applyTwist(in, c, dL, false, hold);
      state.twist[lo] += std::abs(dL);
    }
  }
}

// Restitution of the patch at its centre: a patch that approached faster than the resting speed
// leaves at e times its mean approach, any other stops there. Point by point, a box landing flat
// took the bounce on its first corner and turned, and rose to 22 cm of the 25 that e = 0.5 gives
// from 1 m. False, and its anchor let go, when none of its points pressed in the substep.
bool restitutePatch(RigidPassInput& in, std::span<const RigidContact> contacts, RigidContactState& state,
                    const ContactPatch& patch, Hold hold, Real restitution) {
  const std::size_t lo = patch.first, hi = patch.first + patch.count;
  Real approach = 0.0;
  int touching = 0;
  for (std::size_t k = lo; k < hi; ++k) {
    if (state.lambdaNormal[k] <= 0.0) continue;
    approach -= state.approach[k];
    ++touching;
  }
  if (touching == 0) {
    state.anchors[patch.anchor].held = false;
    return false;
  }
  approach /= touching;
  const RigidContact& c = contacts[lo];
  // Velocity impulses leave the poses, and so the centre and its sides, as they are.
  const PatchCentre centre = centreOf(in, contacts, state, lo, hi, false);
  const PatchSide a = patchSide(in, contacts, state, lo, hi, false, centre.nowA, centre.count, hold.a);
  const PatchSide b = patchSide(in, contacts, state, lo, hi, true, centre.nowB, centre.count, hold.b);
  const Real speed =
      glm::dot(c.normal, patchVelocity(in, contacts, state, lo, hi, true, b, centre.count) -
                             patchVelocity(in, contacts, state, lo, hi, false, a, centre.count));
  const Real change = (approach > in.restingSpeed ? restitution * approach : 0.0) - speed;
  const Real w = patchInverseMass(in, a, c.normal) + patchInverseMass(in, b, c.normal);
  if (change != 0.0 && w > 0.0) {
    applyAtCentre(in, contacts, state, lo, hi, false, a, -(change / w) * c.normal, centre.count, true);
    applyAtCentre(in, contacts, state, lo, hi, true, b, (change / w) * c.normal, centre.count, true);
  }
  return true;
}

// After its restitution, a patch with a particle body on a side: each point that still closes
// stopped, then dynamic friction at the patch's centre, an impulse against the sliding of at most
// mu_d times the patch's normal impulse (lambda_n / h) and never more than stops it; the same for
// the twist.
void stopPatchByPoints(RigidPassInput& in, std::span<const RigidContact> contacts,
                       const RigidContactState& state, const ContactPatch& patch, Hold hold) {
  const std::size_t lo = patch.first, hi = patch.first + patch.count;
  const RigidContact& c = contacts[lo];
  Real normal = 0.0;
  for (std::size_t k = lo; k < hi; ++k) normal += std::max(state.lambdaNormal[k], 0.0);
  const PatchCentre centre = centreOf(in, contacts, state, lo, hi, false);
  const PatchSide a = patchSide(in, contacts, state, lo, hi, false, centre.nowA, centre.count, hold.a);
  const PatchSide b = patchSide(in, contacts, state, lo, hi, true, centre.nowB, centre.count, hold.b);
  for (std::size_t k = lo; k < hi; ++k) {
    if (state.lambdaNormal[k] <= 0.0) continue;
    const SideView pa = viewA(in, contacts[k], hold.a), pb = viewB(in, contacts[k], hold.b);
    const Real speed = glm::dot(c.normal, velocityOf(in, pb) - velocityOf(in, pa));
    const Real w = inverseMassAlong(in, pa, c.normal) + inverseMassAlong(in, pb, c.normal);
    if (speed >= 0.0 || w == 0.0) continue;
    const Vec3 p = (-speed / w) * c.normal;
    kick(in, pa, -p);
    kick(in, pb, p);
  }
  const Real limit = c.combined.dynamicFriction * normal / in.h;
  Vec3 slide = patchVelocity(in, contacts, state, lo, hi, true, b, centre.count) -
               patchVelocity(in, contacts, state, lo, hi, false, a, centre.count);
  slide -= glm::dot(slide, c.normal) * c.normal;
  const Real speed = glm::length(slide);
  if (speed > 0.0) {
    const Vec3 t = slide / speed;
    const Real w = patchInverseMass(in, a, t) + patchInverseMass(in, b, t);
    if (w > 0.0) {
      const Real impulse = std::min(speed / w, limit);
      applyAtCentre(in, contacts, state, lo, hi, false, a, impulse * t, centre.count, true);
      applyAtCentre(in, contacts, state, lo, hi, true, b, -impulse * t, centre.count, true);
    }
  }
  Real spin = 0.0;  // B's about the normal less A's (rad/s)
  if (c.sideB == ContactSide::Rigid) spin += glm::dot(c.normal, in.rigid.angularVelocity[c.rigidB]);
  if (c.sideA == ContactSide::Rigid) spin -= glm::dot(c.normal, in.rigid.angularVelocity[c.rigidA]);
  const Real w = twistInverseMass(in, c, hold);
  if (spin != 0.0 && w > 0.0 && centre.radius > 0.0) {
    const Real L = std::min(std::abs(spin) / w, limit * centre.radius);
    applyTwist(in, c, spin > 0.0 ? -L : L, true, hold);
  }
}

}  // namespace

void solveRigidContacts(const RigidPassInput& input, std::span<const RigidContact> contacts,
                        std::span<const ContactPatch> patches, RigidContactState& state) {
  RigidPassInput in = input;
  Run run;
  for (std::size_t i = 0; i < patches.size();) {
    BlockBody a, b;
    const std::size_t count = gatherRun(in, contacts, state, patches, i, run, a, b);
    if (solvesAsBlock(contacts[patches[i].first], patches[i].count))
      solvePositionBlock(in, contacts, state, std::span(run.data(), count), a, b);
    else
      solvePatchByPoints(in, contacts, state, patches[i], run[0].hold);
    i += count;
  }
}

void rigidVelocityPass(const RigidPassInput& input, std::span<const RigidContact> contacts,
                       std::span<const ContactPatch> patches, RigidContactState& state, Real restitution) {
  RigidPassInput in = input;
  for (const ContactPatch& patch : patches) {
    const Hold hold = holdFor(in, contacts, state, patch.first, patch.first + patch.count);
    if (restitutePatch(in, contacts, state, patch, hold, restitution))
      stopPatchByPoints(in, contacts, state, patch, hold);
  }
}

}  // namespace detail
}  // namespace phys
