// The ground's contact points and their state (physics/ground_contacts.h).
#include "physics/ground_contacts.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "particle_edges.h"
#include "passes.h"
#include "physics/narrow_phase.h"

namespace phys {
namespace {

// A loose particle has no material of its own: it slides as the ground says.
Material combined(const GroundContact& c, const Material& ground) {
  return c.body != kNoBody ? combine(c.material, ground) : ground;
}

}  // namespace

void GroundContacts::add(const Embedding& point, const Material& material, BodyId body,
                         const Material& ground) {
  GroundContact c{point, material, ground, body};
  c.combined = combined(c, ground);
  points_.push_back(c);
  state_.push.push_back(0.0);
  state_.touched.push_back(0);
  state_.hit.push_back(0);
  state_.approach.push_back(0.0);
  state_.allowance.push_back(0.0);
  still_.push_back(0);
  wasStill_.push_back(0);
  far_.push_back(0);
}

void GroundContacts::followCapsuleEnd(Real end) {
  capsuleEnds_.push_back({static_cast<std::uint32_t>(points_.size() - 1), points_.back().body, end});
}

void GroundContacts::truncate(std::size_t count) {
  points_.resize(count);
  state_.push.resize(count);
  state_.touched.resize(count);
  state_.hit.resize(count);
  state_.approach.resize(count);
  state_.allowance.resize(count);
  still_.resize(count);
  wasStill_.resize(count);
  far_.resize(count);
}

void GroundContacts::markStill(std::span<const Real> inverseMass) {
  anyStill_ = false;
  anyMarked_ = true;
  for (std::size_t c = 0; c < points_.size(); ++c) {
    const Embedding& e = points_[c].point;
    bool still = true;
    for (int i = 0; i < e.count && still; ++i) still = inverseMass[e.particle[i]] == 0.0;
    still_[c] = still && wasStill_[c] != 0 ? 1 : 0;
    wasStill_[c] = still ? 1 : 0;
    anyStill_ = anyStill_ || still_[c] != 0;
  }
}

void GroundContacts::unmarkMoving(std::span<const Real> inverseMass) {
  if (!anyMarked_) return;
  anyStill_ = false;
  for (std::size_t c = 0; c < points_.size(); ++c) {
    if (wasStill_[c] == 0) continue;
    const Embedding& e = points_[c].point;
    bool still = true;
    for (int i = 0; i < e.count && still; ++i) still = inverseMass[e.particle[i]] == 0.0;
    if (!still) {
      if (still_[c] != 0) state_.touched[c] = state_.hit[c] = 0;  // kept from the last step: cleared
      still_[c] = wasStill_[c] = 0;
    }
    anyStill_ = anyStill_ || still_[c] != 0;
  }
}

void GroundContacts::clearStill() {
  if (!anyMarked_) return;
  std::fill(still_.begin(), still_.end(), std::uint8_t{0});
  std::fill(wasStill_.begin(), wasStill_.end(), std::uint8_t{0});
  anyStill_ = anyMarked_ = false;
}

void GroundContacts::combineMaterials(const Material& ground) {
  for (GroundContact& c : points_) c.combined = combined(c, ground);
}

void GroundContacts::markTouching(std::size_t bodyCount, std::span<const Manifold> manifolds) {
  touching_.assign(bodyCount, 0);
  for (const Manifold& m : manifolds) touching_[m.a] = touching_[m.b] = 1;
}

namespace {

// Where the line through a corners capsule's lowest point along the ground's normal leaves its box
// below that point (the point itself when it is on the box's surface). The lowest point lies inside
// the box, off its faces unless the capsule lies with a face down. A push moves an embedded point's
// carriers as an impulse at that point would (their weights sum to 1), so it turns the body by the
// point's lever about the push's line, which runs through the end sphere's centre. Pushed at its
// projection onto the nearest face, up to 0.207 r off that line, the ground turned the capsule about
// its core towards its box's edge from either side, and there the nearest face switched from
// substep to substep, turning it back and forth: a lone capsule laid turned 10 to 40 degrees about
// its core rolled onto the edge and jittered there at 2.6 to 5 cm/s at 3 x 1, the seed capsule
// ragdoll's head at 1.3 cm/s (docs/physics.md, "Capsules", "A capsule lying on an edge"). On the
// line the lever is the true one's, and the point moves smoothly as the capsule turns.
Vec3 belowOnBox(const Body& box, const Obb& frame, const Vec3& lowest, const Vec3& n) {
  const Vec3 u = detail::frameCoordinates(box, frame, lowest);
  Real t = std::numeric_limits<Real>::infinity();  // unit: m, along -n
  for (int a = 0; a < 3; ++a) {
    const Real d = -glm::dot(n, frame.axes[a]) / box.halfExtents[a];  // frame coordinate per metre
    if (d > 0.0) t = std::min(t, (1.0 - u[a]) / d);
    if (d < 0.0) t = std::min(t, (-1.0 - u[a]) / d);
  }
  return lowest - n * std::max(t, Real{0.0});
}

}  // namespace

// Capsule ends one thread places at a time.
constexpr std::size_t kEndsPerPiece = 1024;

void GroundContacts::placeCapsulePoints(std::span<const Body> bodies, std::span<const Obb> frames,
                                        const Particles& particles, std::span<const Manifold> manifolds,
                                        std::span<const std::uint8_t> joined, const Vec3& groundNormal,
                                        Real groundHeight, Real restingMove, const Workers* workers) {
  if (capsuleEnds_.empty()) return;
  const Vec3 n = groundNormal;
  const std::span<const Vec3> position = particles.position;
  std::atomic<bool> unjoinedBlock{false};  // a capsule pushed as a rigid block, nothing joined to it
  // Each end writes its own point alone: ranges of them at once on the step's threads.
  auto range = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const CapsuleEnd& g = capsuleEnds_[k];
      if (anyStill_ && still_[g.point] != 0) continue;  // its body's frame has not moved
      const Body& box = bodies[g.body];
      const Obb& f = frames[g.body];
      const Vec3 lowest = f.center + f.axes[1] * (g.end * box.capsuleHalfSegment()) - n * box.capsuleRadius();
      // An end further above the ground than the capsule's half length keeps the point it had:
      // a point of the capsule, no lower than its lowest, so it stays above the ground as a point
      // placed now would, unless the substep's passes moved the capsule that far, and no pass
      // reads a point above the ground but to find it there (docs/performance.md, "Capsules' ground
      // points placed near the ground only"). Placing them all was 8% of Bullet's pile's step.
      const bool far = glm::dot(n, lowest) - groundHeight > box.capsuleRadius() + box.capsuleHalfSegment();
      far_[g.point] = far ? 1 : 0;
      GroundContact& contact = points_[g.point];
      if (far) {
        if (g.end < 0.0) contact.rigidBlock = 0;  // not a block while an end is far (collideGround)
        continue;
      }
      if (g.end < 0.0) {
        // A corners capsule's alone: the block is what keeps one lying still. A tetra capsule that
        // is a free body (nothing joined to it, no other body touching it) is pushed as one rigid
        // block instead while its box is whole: pushes by weights lift only its bottom particles,
        // and its sticks, lifting the top two after them, turned it every step (docs/physics.md,
        // "Capsules", "A tetra capsule lying still"). The block moves it as a free rigid body would
        // move, which a jointed part or one leaning on another is not: pushed so, a capsule ragdoll's
        // arms, one end on the ground and the other held by the shoulder, walked outwards 10 cm in
        // 20 s, and Bullet's pile slept later, with the block on every capsule and also on those
        // touching the ground alone. Those touched by another body are taken out below.
        const bool isWhole = detail::keepsItsVolume(box, position);
        contact.pairedWithNext = box.model == BodyModel::Corners &&
                                 glm::dot(n, detail::meanParticleMove(particles, box)) > -restingMove &&
                                 isWhole;
        // A corners capsule's block by weights lifts its bottom face's corners, and turned about its
        // core it was turned further by the sticks that lifted the rest after them, as a tetra
        // capsule was (collideRigidBlock): a free one resting is pushed as one rigid block as well.
        const bool unjoined = joined.empty() || joined[g.body] == 0;
        const bool rigidly = box.model == BodyModel::Tetra ? isWhole : contact.pairedWithNext;
        contact.rigidBlock = rigidly && unjoined ? 2 : 0;
        if (contact.rigidBlock != 0) unjoinedBlock.store(true, std::memory_order_relaxed);
      }
      const Obb e = detail::embeddingFrame(box, f, position);
      Vec3 moved(0.0);
      if (box.model == BodyModel::Corners) {
        const Vec3 below = belowOnBox(box, e, lowest, n);
        contact.point = detail::surfacePoint(box, e, below, &moved);
        moved += below - lowest;
      } else {
        contact.point = detail::surfacePoint(box, e, lowest, &moved);
      }
      contact.lift = glm::dot(n, moved);
      if (box.model == BodyModel::Corners) contact.surface = detail::rigidPoint(box, e, lowest);
    }
  };
  forEachRange(workers, capsuleEnds_.size(), kEndsPerPiece, range);
  if (!unjoinedBlock.load(std::memory_order_relaxed)) return;
  // The bodies another body acts on in this step: one of its manifolds (speculative ones too). Read
  // only when some block is left to take out: over every manifold each substep it cost `capsules`
  // (corners capsules only) 5% of its step.
  markTouching(bodies.size(), manifolds);
  for (const CapsuleEnd& g : capsuleEnds_) {
    if (g.end < 0.0 && touching_[g.body] != 0) points_[g.point].rigidBlock = 0;
  }
}

}  // namespace phys
