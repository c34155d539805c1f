#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

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
// The 2 x 2 block's impulses: K lambda = depth, both >= 0 (see collideCapsulePair).
void solvePair(Real kaa, Real kbb, Real kab, Real depthA, Real depthB, Real& la, Real& lb) {
  la = lb = 0.0;
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
}

void collideCapsulePair(Particles& p, const GroundContact& a, const GroundContact& b, Real depthA,
                        Real depthB, const Vec3& n, Real& pushA, Real& pushB) {
  pushA = pushB = 0.0;
  if (depthA <= 0.0 && depthB <= 0.0) return;
  const Real kaa = embeddedWeight(p.inverseMass, a.point), kbb = embeddedWeight(p.inverseMass, b.point);
  const Real kab = sharedWeight(p.inverseMass, a.point, b.point);
  Real la = 0.0, lb = 0.0;
  solvePair(kaa, kbb, kab, depthA, depthB, la, lb);
  if (la > 0.0) shiftEmbedded(p.position, p.inverseMass, a.point, la * n);
  if (lb > 0.0) shiftEmbedded(p.position, p.inverseMass, b.point, lb * n);
  // The push friction reads: what each point's own impulse alone would move it, as for a lone point.
  pushA = la * kaa;
  pushB = lb * kbb;
}

// Particles as one rigid body where they are at `x` (`particle`'s masses): their centre, total
// inverse mass and inverse inertia about the centre. False if one is pinned or they are flat, where
// the moves by weights serve.
struct RigidFit {
  Vec3 centre{0.0};
  Real inverseMass = 0.0;
  glm::dmat3 inverseInertia{0.0};
};

bool fitRigid(const Particles& p, const ParticleId* particle, const Vec3* x, int count, RigidFit& t) {
  Real mass = 0.0;
  for (int i = 0; i < count; ++i) {
    const Real w = p.inverseMass[particle[i]];
    if (w == 0.0) return false;
    mass += 1.0 / w;
    t.centre += x[i] / w;
  }
  t.centre /= mass;
  glm::dmat3 inertia(0.0);
  for (int i = 0; i < count; ++i) {
    const Vec3 r = x[i] - t.centre;
    inertia += (glm::dmat3(glm::dot(r, r)) - glm::outerProduct(r, r)) / p.inverseMass[particle[i]];
  }
  const Real det = glm::determinant(inertia);
  const Real scale = inertia[0][0] + inertia[1][1] + inertia[2][2];
  if (!(det > 1e-9 * scale * scale * scale)) return false;
  t.inverseMass = 1.0 / mass;
  t.inverseInertia = glm::inverse(inertia);
  return true;
}

// A capsule's particles as one rigid body where they are (fitRigid): a tetra capsule's 4 (its ground
// points' carriers) or a corners capsule's 8 (its box's corners, from corner 0, its surface point's
// first carrier: rigidEmbedding).
struct RigidCapsule : RigidFit {
  ParticleId particle[8] = {};
  int count = 0;
};

bool rigidCapsule(const Particles& p, const GroundContact& contact, RigidCapsule& t) {
  if (contact.surface.count > 0) {  // a corners capsule
    t.count = 8;
    for (int i = 0; i < 8; ++i)
      t.particle[i] = ParticleId(contact.surface.particle[0] + static_cast<std::uint32_t>(i));
  } else if (contact.point.count == 4) {
    t.count = 4;
    for (int i = 0; i < 4; ++i) t.particle[i] = contact.point.particle[i];
  } else {
    return false;
  }
  Vec3 x[8];
  for (int i = 0; i < t.count; ++i) x[i] = p.position[t.particle[i]];
  return fitRigid(p, t.particle, x, t.count, t);
}

// A tetra box's 4 particles as one rigid body where they were at `x` (e's order).
bool rigidBoxAt(const Particles& p, const Embedding& e, const Vec3* x, RigidFit& t) {
  return e.count == 4 && fitRigid(p, e.particle.data(), x, 4, t);
}

// A free tetra box's 8 corners (GroundContact::rigidBlock kTetraBoxCorners,
// GroundContacts::markFreeTetraBoxes) are pushed, and cut, by their weights, each by its depth (or slide) as
// the pass found it before any of them moved, and then what the pass did to the box's 4 particles is made a
// rigid body's move: the same momentum and angular momentum about their centre (the impulses the weights
// gave, sum m dx and sum m r x dx), as a translation and an exact turn. Pushed by the weights alone, the
// pushes lifted the box's bottom particles and left the top two where gravity took them (the two embedded
// bottom corners weigh them +1/2 and -1/2); the sticks lifted them after the push, without keeping angular
// momentum, and the chiral 4-particle body came out of each step turned a little: lying alone it walked, and
// on frictionless ground it spun up (docs/physics.md, "A tetra box lying still", which also has the forms
// tried and not kept). Measured all before any moves, a flat face's 4 equal depths give a rigid lift of
// exactly that depth, flat, and the sticks have nothing to undo.
struct BoxStart {
  Vec3 x[4];
};

BoxStart boxStart(const Particles& p, const Embedding& e) {
  BoxStart s;
  for (int i = 0; i < 4; ++i) s.x[i] = p.position[e.particle[i]];
  return s;
}

// The particles' moves since `start` made one rigid body's (above); nothing if none moved, or if
// the 4 are pinned or flat (rigidBoxAt), where the weights' moves stand.
void makeRigid(Particles& p, const Embedding& e, const BoxStart& start) {
  Vec3 moved[4];
  bool any = false;
  for (int i = 0; i < 4; ++i) {
    moved[i] = p.position[e.particle[i]] - start.x[i];
    any = any || moved[i] != Vec3(0.0);
  }
  RigidFit t;
  if (!any || !rigidBoxAt(p, e, start.x, t)) return;
  Vec3 momentum(0.0), moment(0.0);
  for (int i = 0; i < 4; ++i) {
    const Real m = 1.0 / p.inverseMass[e.particle[i]];
    momentum += m * moved[i];
    moment += m * glm::cross(start.x[i] - t.centre, moved[i]);
  }
  const Vec3 move = momentum * t.inverseMass;
  const Vec3 turned = t.inverseInertia * moment;
  const Real angle = glm::length(turned);
  const Vec3 axis = angle > 0.0 ? turned / angle : Vec3(0.0);
  const Real c = std::cos(angle), s = std::sin(angle);
  for (int i = 0; i < 4; ++i) {
    const Vec3 r = start.x[i] - t.centre;
    p.position[e.particle[i]] =
        t.centre + move + r * c + glm::cross(axis, r) * s + axis * (glm::dot(axis, r) * (1.0 - c));
  }
}

// The move by its weights that a box corner's friction makes of its slide (x - x*) along the ground:
// the whole slide back within mu_s times the pass's push, else mu_d times it; never reversed.
Vec3 boxCornerCut(const Particles& p, const GroundContact& contact, const Vec3& n, Real push) {
  if (push <= 0.0) return Vec3(0.0);
  Vec3 slide = embeddedPosition(p.position, contact.point) - embeddedPosition(p.previous, contact.point);
  slide -= glm::dot(slide, n) * n;
  const Real length = glm::length(slide);
  if (length == 0.0) return Vec3(0.0);
  const Material& mu = contact.combined;
  Real cut = 1.0;
  if (length > mu.staticFriction * push) cut = std::min(1.0, mu.dynamicFriction * push / length);
  return -cut * slide;
}

// A free tetra box's corners pushed by their depths, found before any moved, then made its rigid
// body's move (makeRigid). Out of the ground's loop, so that the loop stays as small as it was for
// every other point.
[[gnu::noinline]] void pushFreeTetraBox(Particles& p, std::span<const GroundContact> corners,
                                        const Real* depth, const Vec3& n, std::span<Real> push) {
  const BoxStart start = boxStart(p, corners[0].point);
  for (std::size_t k = 0; k < corners.size(); ++k) {
    push[k] = std::max(depth[k], Real{0.0});
    if (depth[k] > 0.0) moveEmbedded(p.position, p.inverseMass, corners[k].point, depth[k] * n);
  }
  makeRigid(p, corners[0].point, start);
}

// Its friction likewise: each corner's cut found before any moved, then made rigid.
[[gnu::noinline]] void cutFreeTetraBox(Particles& p, std::span<const GroundContact> corners, const Vec3& n,
                                       std::span<const Real> push) {
  const BoxStart start = boxStart(p, corners[0].point);
  Vec3 cut[kTetraBoxCorners];
  for (std::size_t k = 0; k < corners.size(); ++k) cut[k] = boxCornerCut(p, corners[k], n, push[k]);
  for (std::size_t k = 0; k < corners.size(); ++k) {
    if (cut[k] != Vec3(0.0)) moveEmbedded(p.position, p.inverseMass, corners[k].point, cut[k]);
  }
  makeRigid(p, corners[0].point, start);
}

// A capsule's 2 points of a rigid block (collideRigidBlock), not a tetra box's 8.
bool inCapsuleBlock(std::span<const GroundContact> contacts, std::size_t c) {
  auto capsuleBlock = [](const GroundContact& g) {
    return g.rigidBlock > 1 && g.rigidBlock < kTetraBoxCorners;
  };
  return capsuleBlock(contacts[c]) ||
         (c > 0 && capsuleBlock(contacts[c - 1]) && contacts[c - 1].body == contacts[c].body);
}

// Moves a rigid capsule's particles by `move` and turns them by `turned` about its centre.
void moveRigidly(Particles& p, const RigidCapsule& t, const Vec3& move, const Vec3& turned) {
  for (int i = 0; i < t.count; ++i) {
    Vec3& x = p.position[t.particle[i]];
    x += move + glm::cross(turned, x - t.centre);
  }
}

// The most points one rigid block holds: a capsule's 2.
constexpr int kMostRigidBlock = 2;

// A capsule's two ground points pushed as its particles would move as one rigid body, by
// impulses lambda_k n at the points: the centre by M^-1 sum lambda_k n, the particles turned about
// it by I^-1 sum r_k x lambda_k n (linearised). By their barycentric weights the pushes lift only
// its bottom particles (the two points weigh its top two +0.18 and -0.18 for a 0.2 m by 1 m
// capsule), and no sum of the two lifts the top two with the bottom two: every step its sticks
// lifted them after the pushes, and the chiral 4-particle body came out of each step turned a
// little, rocking +-0.1 rad and +-2.5 cm for ever (docs/physics.md, "A tetra capsule lying still").
// Pushed rigidly, a resting capsule's sticks have nothing to undo. A corners capsule's block by
// weights lifts its bottom face's 4 corners: on its side turned about its core its box came out of
// each pass sheared, the next pass's sticks undoing it along their present directions gave it spin
// (Gauss-Seidel keeps no angular momentum, measured at x*, through such corrections) towards its box's
// edge, and the face point the sheared face carried, off the push's line by 0.04 to 0.9 mm at 3 x 1,
// turned it towards its face: laid turned 10 to 40 degrees, it rolled to where the two balanced,
// 27 degrees at 3 x 1, 13 to 24 at 2 x 4 (docs/physics.md, "A capsule turned about its core").
// The impulses solve the same 2 x 2 complementarity problem as the block by weights,
// K_ij = 1/M + (r_i x n) . I^-1 (r_j x n).
bool collideRigidBlock(Particles& p, std::span<const GroundContact> block, const Real* depth, const Vec3& n,
                       Real* push) {
  RigidCapsule t;
  if (!rigidCapsule(p, block[0], t)) return false;
  const int count = static_cast<int>(block.size());
  Real deepest = 0.0;
  for (int k = 0; k < count; ++k) {
    push[k] = 0.0;
    deepest = std::max(deepest, depth[k]);
  }
  if (deepest <= 0.0) return true;
  Vec3 arm[kMostRigidBlock], turn[kMostRigidBlock];  // r_k x n and I^-1 (r_k x n)
  for (int k = 0; k < count; ++k) {
    arm[k] = glm::cross(embeddedPosition(p.position, block[k].point) - t.centre, n);
    turn[k] = t.inverseInertia * arm[k];
  }
  auto K = [&](int i, int j) { return t.inverseMass + glm::dot(arm[i], turn[j]); };
  Real lambda[kMostRigidBlock] = {};
  solvePair(K(0, 0), K(1, 1), K(0, 1), depth[0], depth[1], lambda[0], lambda[1]);
  Real total = 0.0;
  Vec3 turned(0.0);
  for (int k = 0; k < count; ++k) {
    total += lambda[k];
    turned += lambda[k] * turn[k];
    // Friction reads a push as the impulse times the point's mobility by weights, by which it moves
    // the point: by K_kk, a tetra box's corners had a quarter of their friction and it slid down a
    // slope that holds it (BoxModels.InclineHoldsWithFriction05AndSlidesAtCoulombRateWith02).
    push[k] = lambda[k] * embeddedWeight(p.inverseMass, block[k].point);
  }
  moveRigidly(p, t, total * t.inverseMass * n, turned);
  return true;
}

// A point of a rigid block's friction: its slide along the ground cut by a tangential impulse on the
// particles as one rigid body, as collideRigidBlock pushed them, bounded by mu times that pass's
// normal impulse (the push it recorded is the impulse times the point's K by weights). Cut by the
// point's weights instead, the cut bent the body that the push had kept whole, and the sticks, undoing
// it in the next pass when no push (so no friction) held the point, let a tetra capsule lying along
// a 10 degree slope its friction holds creep down it at 4.3 mm/s. A corners capsule's slide is its
// surface point's (FrictionPoint), not its face point's, which lies below it and slips as it rolls.
void cutRigidly(Particles& p, const GroundContact& contact, const RigidCapsule& t, const Vec3& n, Real push) {
  const Embedding& e = contact.point;
  const bool onSurface = contact.surface.count > 0;
  const FrictionPoint f = FrictionPoint::of(onSurface ? contact.surface : e, onSurface);
  const Vec3 at = f.at(p.position);
  Vec3 slide = at - f.at(p.previous);
  slide -= glm::dot(slide, n) * n;
  const Real length = glm::length(slide);
  const Real kWeights = embeddedWeight(p.inverseMass, e);
  if (length == 0.0 || kWeights <= 0.0) return;
  const Real normalImpulse = push / kWeights;
  const Vec3 along = slide / length;
  const Vec3 arm = glm::cross(at - t.centre, along);
  const Vec3 turn = t.inverseInertia * arm;
  const Real k = t.inverseMass + glm::dot(arm, turn);  // how far a unit impulse moves the point along
  if (!(k > 0.0)) return;
  const Material& mu = contact.combined;
  Real impulse = length / k;  // static: stop the slide entirely
  if (impulse > mu.staticFriction * normalImpulse)
    impulse = std::min(impulse, mu.dynamicFriction * normalImpulse);
  moveRigidly(p, t, -impulse * t.inverseMass * along, -impulse * turn);
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
    const std::size_t block = contacts[c].rigidBlock;
    // A free tetra box's corners, their pushes made its rigid body's move (markFreeTetraBoxes).
    if (block == kTetraBoxCorners && c + block <= contacts.size()) {
      Real depth[kTetraBoxCorners];
      for (std::size_t k = 0; k < block; ++k) depth[k] = depthOf(c + k);
      pushFreeTetraBox(p, contacts.subspan(c, block), depth, n, normalPush.subspan(c, block));
      c += block - 1;
      continue;
    }
    // A free capsule's two points as one rigid block (placeCapsulePoints), with both ends near.
    if (block > 1 && c + block <= contacts.size() && block <= kMostRigidBlock && !isFar(c) && !isFar(c + 1)) {
      Real depth[kMostRigidBlock];
      for (std::size_t k = 0; k < block; ++k) depth[k] = depthOf(c + k);
      if (collideRigidBlock(p, contacts.subspan(c, block), depth, n, &normalPush[c])) {
        c += block - 1;
        continue;
      }
    }
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
                         std::span<const Real> normalPush, std::span<const std::uint8_t> still,
                         bool freeTetraBoxes) {
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    if (!still.empty() && still[c] != 0) continue;
    // A free tetra box's corners, cut by their weights and made its rigid body's move, as pushed.
    // Only looked for when there is one: most points have no push, and are passed over on it alone,
    // without a read of their contact (a cache line each).
    const std::size_t block = freeTetraBoxes ? contacts[c].rigidBlock : 0;
    if (block == kTetraBoxCorners && c + block <= contacts.size()) {
      cutFreeTetraBox(p, contacts.subspan(c, block), n, normalPush.subspan(c, block));
      c += block - 1;
      continue;
    }
    Real push = normalPush[c];
    if (push <= 0.0) continue;
    // A rigid block's points (the block's first names how many), cut as it was pushed.
    // (The rigid body made only then: zeroing it for every point pushed cost Bullet's pile 2%.)
    if (inCapsuleBlock(contacts, c)) {
      if (RigidCapsule t; rigidCapsule(p, contacts[c], t)) {
        cutRigidly(p, contacts[c], t, n, push);
        continue;
      }
    }
    // A corners capsule's friction acts at its surface point, carried by both inscribed tetrahedra.
    const bool onSurface = contacts[c].surface.count > 0;
    const FrictionPoint f = FrictionPoint::of(onSurface ? contacts[c].surface : contacts[c].point, onSurface);
    const Embedding& e = *f.point;
    Vec3 slide = embeddedPosition(p.position, e) - embeddedPosition(p.previous, e);
    if (onSurface)
      slide =
          0.5 * (slide + (embeddedPosition(p.position, f.mirror) - embeddedPosition(p.previous, f.mirror)));
    slide -= glm::dot(slide, n) * n;
    const Real slideLength = glm::length(slide);
    if (slideLength == 0.0) continue;
    Real k = 0.0;
    if (onSurface) {
      // The push moved `point` (impulse push / K_point) and the cut moves `surface` (impulse
      // cut / K_surface): Coulomb bounds impulses, so the push is counted at the surface point's
      // K. Carried by one inscribed tetrahedron (K 5.02 w at a lying capsule's ends, its face point
      // 3.02 w) and bounded by the bare push, a corners capsule's friction was mu / 1.66: lying along
      // a 10 degree slope at mu 0.25 it slid 10.9 m in 10 s (docs/physics.md, "Capsules", "A capsule
      // on a slope").
      k = f.weight(p.inverseMass);
      const Real kPoint = embeddedWeight(p.inverseMass, contacts[c].point);
      if (kPoint > 0.0) push *= k / kPoint;
    }
    const Material& mu = contacts[c].combined;
    Real cut = 1.0;  // static: stop the slide entirely
    if (slideLength > mu.staticFriction * push) cut = std::min(1.0, mu.dynamicFriction * push / slideLength);
    if (!onSurface) {
      moveEmbedded(p.position, p.inverseMass, e, -cut * slide);
      continue;
    }
    // The mean point's impulse, cut slide / K, split evenly between the two (FrictionPoint::shift).
    if (k <= 0.0) continue;
    f.shift(p.position, p.inverseMass, (-cut * slide) / k);
  }
}

}  // namespace phys::detail
