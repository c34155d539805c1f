// The narrow phase: each pair the broad phase found (broad_phase.cpp) turned into a manifold whose
// points are embedded in the two bodies' particles, once per step, and measured again in each
// substep.
#include "physics/narrow_phase.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "passes.h"
#include "physics/collision.h"
#include "room.h"

namespace phys {
namespace {

// Where frame b is as seen from frame a: its centre and axes in a's axes, about a's centre.
Obb poseInFrameOf(const Obb& a, const Obb& b) {
  const glm::dmat3 toA = glm::transpose(a.axes);
  return {toA * (b.center - a.center), toA * b.axes, b.halfExtents};
}

// Whether the spheres around two bodies, a capsule's of its core's half length plus its radius and a
// box's through its corners, are within `margin` of each other: when they are not, neither are the
// shapes, and a capsule's pair needs no nearest points of cores (31% of the capsule pairs the broad
// phase hands on in Bullet's pile). Slightly generous, so that rounding never drops a pair the
// shapes' own test keeps.
bool spheresMeet(const Obb& a, bool capsuleA, const Obb& b, bool capsuleB, Real margin) {
  auto reach = [](const Obb& f, bool capsule) {
    return capsule ? std::max(f.halfExtents.y, f.halfExtents.x) : glm::length(f.halfExtents);
  };
  const Real r = (reach(a, capsuleA) + reach(b, capsuleB) + margin) * (1.0 + 1e-9);
  const Vec3 d = b.center - a.center;
  return glm::dot(d, d) <= r * r;
}

}  // namespace

// Pairs one thread collides at a time: a capsule pair costs some tenths of a microsecond, so a
// piece this size is worth what handing it to another thread costs.
constexpr std::size_t kPairsPerPiece = 256;
// Manifolds one thread finds again at a time (refresh): each is a pair that touches, and every
// capsule's is collided again, so it costs more than the average pair of the broad phase
// (five or six of which touch no other): a smaller piece pays. Bullet's pile's refresh (213
// manifolds on average) was one piece at 256 (docs/performance.md, "The narrow phase's short runs").
constexpr std::size_t kManifoldsPerPiece = 64;
// Manifolds whose start overlaps one thread measures at a time: a few tens of nanoseconds each, on
// points the narrow phase has just written, so below this many a run costs more on two threads
// than on one (the other core fetches the lines).
constexpr std::size_t kStartsPerPiece = 2048;
// How near a new contact point must be to an old one, on both bodies, to be taken for it
// (carrySlide): Jolt's contact cache keeps a point's state within 1 cm on both bodies
// (PhysicsSettings::mContactPointPreserveLambdaMaxDistSq). The points of a box resting on a box move
// by about a tenth of a millimetre a step, and the corners of a face's overlap are centimetres or
// more apart, so no two old points are that near one new one.
constexpr Real kSamePointDistance = 0.01;

// Contact points are made in every substep: their room is made in each step's first substep, from
// the last substep's count, before any is made.
void NarrowPhase::reserve(std::size_t pairs, std::size_t bodies, int threads) {
  const std::size_t room = detail::kRoomPerBody * bodies;
  pieces_.resize(static_cast<std::size_t>(std::max(threads, 1)) - 1);
  for (Piece& piece : pieces_) {
    detail::keepRoom(piece.manifolds, pairs, room);
    detail::keepRoom(piece.contacts, contacts_.size(), room);
    detail::keepRoom(piece.extras, contacts_.size(), room);
    detail::keepRoom(piece.rigidContacts, rigidContacts_.size(), room);
  }
  const std::size_t points = contacts_.size();
  detail::keepRoom(manifolds_, pairs, room);
  detail::keepRoom(spareManifolds_, pairs, room);
  detail::keepRoom(contacts_, points, room);
  detail::keepRoom(spareContacts_, points, room);
  detail::keepRoom(extras_, points, room);
  detail::keepRoom(spareExtras_, points, room);
  detail::keepRoom(rigidContacts_, rigidContacts_.size(), room);
  detail::keepRoom(spareRigidContacts_, rigidContacts_.size(), room);
  for (std::vector<Real>* v : {&rigidState_.lambdaNormal, &rigidState_.lambdaTangent, &rigidState_.twist,
                               &rigidState_.approach, &rigidState_.allowance})
    detail::keepRoom(*v, rigidContacts_.size(), room);
  detail::keepRoom(rigidState_.touched, rigidContacts_.size(), room);
  detail::keepRoom(state_.allowance, points, room);
  detail::keepRoom(state_.push, points, room);
  detail::keepRoom(state_.touched, points, room);
  detail::keepRoom(state_.approach, points, room);
}

// Each pair's contact by its shapes, normal from a towards b; boxes keep at most 4 points. Points
// up to the pair's speculative margin apart are kept, which the passes leave alone until they close.
bool NarrowPhase::collidePair(const NarrowPhaseInput& in, BodyId a, BodyId b, int previousAxis,
                              BoxContact& contact) const {
  const Real margin = speculativeMargin(in, a, b);
  const std::span<const Obb> frames = in.frames;
  const bool capsuleA = in.bodies[a].shape == Shape::Capsule, capsuleB = in.bodies[b].shape == Shape::Capsule;
  if (!capsuleA && !capsuleB) {
    // Between a rigid box and a particle box, the rigid one's faces (PreferFaces).
    const bool rigidA = in.bodies[a].model == BodyModel::Rigid,
               rigidB = in.bodies[b].model == BodyModel::Rigid;
    const PreferFaces prefer = rigidA == rigidB ? PreferFaces::None
                               : rigidA         ? PreferFaces::OfA
                                                : PreferFaces::OfB;
    if (!collideBoxes(frames[a], frames[b], in.featureEpsilon, margin, contact, previousAxis, prefer))
      return false;
    reduceToFourPoints(contact, in.featureEpsilon);
    return true;
  }
  if (!spheresMeet(frames[a], capsuleA, frames[b], capsuleB, margin)) return false;
  if (capsuleA && capsuleB)
    return collideCapsules(capsuleInBox(frames[a]), capsuleInBox(frames[b]), margin, contact);
  if (capsuleA) return collideCapsuleBox(capsuleInBox(frames[a]), frames[b], margin, contact);
  if (!collideCapsuleBox(capsuleInBox(frames[b]), frames[a], margin, contact)) return false;
  contact.sat.normal = -contact.sat.normal;  // it was from b towards a
  for (int i = 0; i < contact.count; ++i) std::swap(contact.points[i].onA, contact.points[i].onB);
  return true;
}

// How far apart two bodies' points can be and still close within the step: the feature epsilon,
// the most any point of one can move towards any point of the other at the speeds the broad phase
// measured (their mean motions' difference and each one's turning), and what gravity's g dt^2 can
// add against a body held still. Relative motion, not each body's travel: two limbs falling side by
// side at 7 m/s keep the epsilon, where their travel would have made a margin of 25 cm, and with
// it contacts on features that never meet in the step (a face of a limb the other only passes),
// which the passes then held as if the planes were there.
Real NarrowPhase::speculativeMargin(const NarrowPhaseInput& in, BodyId a, BodyId b) {
  const Real dt = in.dt;
  const Real g = in.gravity;
  const BodyMotion &ma = in.broadPhase.motion(a), &mb = in.broadPhase.motion(b);
  return in.featureEpsilon + glm::length(ma.shift - mb.shift) + ma.turn + mb.turn + g * dt * dt;
}

// Once per step: each pair's points, embedded in its two bodies, kept when they are
// nearer than the pair can close in the step (speculativeMargin), so that a contact that closes
// within the step is there when it does; the passes push a point only once it touches.
void NarrowPhase::build(const NarrowPhaseInput& in) {
  swapToSpare();
  inPieces(in, in.broadPhase.pairs().size(), kPairsPerPiece,
           [&](Sink& out, std::size_t begin, std::size_t end) { buildRange(in, begin, end, out); });
  sizeState();
}

void NarrowPhase::rebuild(const NarrowPhaseInput& in) {
  // The last substep's manifolds back where build() finds them, then build() as before.
  std::swap(contacts_, spareContacts_);
  std::swap(extras_, spareExtras_);
  std::swap(rigidContacts_, spareRigidContacts_);
  std::swap(manifolds_, spareManifolds_);
  build(in);
}

// The last substep's manifolds are in the pairs' order, (a, b) ascending, as the new pairs are:
// one walk from the run's first pair finds each pair's old manifold.
void NarrowPhase::buildRange(const NarrowPhaseInput& in, std::size_t begin, std::size_t end,
                             Sink& out) const {
  const std::span<const BroadPhase::Pair> pairs = in.broadPhase.pairs();
  auto pairOf = [](const Manifold& m) { return BroadPhase::Pair(m.a, m.b); };
  std::size_t old = 0;
  if (begin < end) {
    old = static_cast<std::size_t>(
        std::lower_bound(spareManifolds_.begin(), spareManifolds_.end(), pairs[begin],
                         [&](const Manifold& m, const BroadPhase::Pair& p) { return pairOf(m) < p; }) -
        spareManifolds_.begin());
  }
  BoxContact contact;
  for (std::size_t k = begin; k < end; ++k) {
    const BroadPhase::Pair& pair = pairs[k];
    // Two sleeping bodies: their island keeps them as they fell asleep (Islands).
    if (!in.asleep.empty() && in.asleep[pair.first] != 0 && in.asleep[pair.second] != 0) continue;
    while (old < spareManifolds_.size() && pairOf(spareManifolds_[old]) < pair) ++old;
    if (old < spareManifolds_.size() && pairOf(spareManifolds_[old]) == pair &&
        canCarry(in, spareManifolds_[old])) {
      carry(in, spareManifolds_[old], out);
      continue;
    }
    const auto [a, b] = pair;
    const bool had = old < spareManifolds_.size() && pairOf(spareManifolds_[old]) == pair;
    if (!collidePair(in, a, b, had ? spareManifolds_[old].axis : -1, contact)) continue;
    const std::size_t first = out.contacts.size();
    addManifold(in, a, b, contact, out);
    if (had)
      carrySlide(in, spareManifolds_[old], std::span(out.contacts).subspan(first),
                 std::span(out.extras).subspan(first));
  }
}

template <class Work>
void NarrowPhase::inPieces(const NarrowPhaseInput& in, std::size_t count, std::size_t perPiece, Work&& work) {
  Sink own{manifolds_, contacts_, extras_, rigidContacts_};
  const std::size_t pieces = in.workers == nullptr ? 1 : std::min(pieces_.size() + 1, count / perPiece);
  if (pieces <= 1) {
    work(own, 0, count);
    return;
  }
  // The first run into the narrow phase's own arrays, each other into its piece's.
  auto sink = [&](std::size_t k) {
    if (k == 0) return own;
    Piece& piece = pieces_[k - 1];
    piece.manifolds.clear();
    piece.contacts.clear();
    piece.extras.clear();
    piece.rigidContacts.clear();
    return Sink{piece.manifolds, piece.contacts, piece.extras, piece.rigidContacts};
  };
  auto range = [&](std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < last; ++k) {
      Sink out = sink(k);
      work(out, count * k / pieces, count * (k + 1) / pieces);
    }
  };
  in.workers->forEach(pieces, 1, range);
  for (std::size_t k = 1; k < pieces; ++k) append(pieces_[k - 1]);
}

void NarrowPhase::append(Piece& piece) {
  const auto points = static_cast<std::uint32_t>(contacts_.size());
  const auto rigidPoints = static_cast<std::uint32_t>(rigidContacts_.size());
  for (Manifold m : piece.manifolds) {
    m.firstContact += m.rigid ? rigidPoints : points;
    manifolds_.push_back(m);
  }
  contacts_.insert(contacts_.end(), piece.contacts.begin(), piece.contacts.end());
  extras_.insert(extras_.end(), piece.extras.begin(), piece.extras.end());
  rigidContacts_.insert(rigidContacts_.end(), piece.rigidContacts.begin(), piece.rigidContacts.end());
}

void NarrowPhase::swapToSpare() {
  std::swap(contacts_, spareContacts_);
  std::swap(extras_, spareExtras_);
  std::swap(rigidContacts_, spareRigidContacts_);
  std::swap(manifolds_, spareManifolds_);
  contacts_.clear();
  extras_.clear();
  rigidContacts_.clear();
  manifolds_.clear();
}

// Whether a kept manifold still holds: b has moved in a's frame by no more than the settings since
// it was made. Measured against when it was made, not the last step, so that a slow creep
// cannot carry it anywhere.
bool NarrowPhase::canCarry(const NarrowPhaseInput& in, const Manifold& m) const {
  if (!m.kept || !m.whole) return false;
  const Obb now = poseInFrameOf(in.frames[m.a], in.frames[m.b]);
  if (glm::length(now.center - m.madeAt.center) > in.reuse.maxShift) return false;
  for (int k = 0; k < 3; ++k) {
    if (glm::length(now.axes[k] - m.madeAt.axes[k]) > in.reuse.maxTurn) return false;
  }
  return true;
}

// A face-on-face manifold between a tetra box and a box, clipped again, hands each new point the
// slide its own old point had left from its anchor at x*, so that the slide is taken back as if the
// manifold had been carried. Anchored afresh where they are, the new points forgot it: a tetra
// box's face shears under its load within a step (its points are carried by weights of both
// signs, and the slanted sticks turn a squash into a stretch of the face along its particles'
// diagonal), so the passes leave a slide of up to 0.1 mm a step that no pass takes back; the box
// then moved more than the carry allows (SolverSettings::manifoldReuse) every step, so every step
// clipped again and forgot, and the box walked 0.23 m in 20 s at 3 x 1 (docs/physics.md, "A tetra
// box walking on a box").
//
// Point by point, as Jolt keeps a contact point's state: a new point is the old one that is within
// kSamePointDistance of it on both bodies (its embedded points, at x*), and a new point with none
// starts afresh. Only a point friction held in the last substep hands its slide on: one that slipped
// was sliding, and its slide, carried, outlived the slip. One shift and twist fitted to all the old
// points and handed to whichever points the clipping made kept two tetra boxes stacked face to face
// rocking at 10 x 1 (docs/physics.md).
void NarrowPhase::carrySlide(const NarrowPhaseInput& in, const Manifold& old,
                             std::span<const BodyContact> made,
                             std::span<BodyContactExtra> madeExtras) const {
  if (!old.kept || old.rigid) return;
  if (in.bodies[old.a].model != BodyModel::Tetra && in.bodies[old.b].model != BodyModel::Tetra) return;
  const auto& at = in.particles.previous;
  for (std::size_t i = 0; i < made.size(); ++i) {
    const BodyContact& c = made[i];
    const Vec3 onA = detail::embeddedPosition(at, c.pointA), onB = detail::embeddedPosition(at, c.pointB);
    Real nearest = kSamePointDistance;
    for (std::uint32_t k = old.firstContact; k < old.firstContact + old.contactCount; ++k) {
      const BodyContact& o = spareContacts_[k];
      if (!o.anchored || o.grip != Grip::Held) continue;
      const Vec3 oldA = detail::embeddedPosition(at, o.pointA), oldB = detail::embeddedPosition(at, o.pointB);
      const Real apart = std::max(glm::length(oldA - onA), glm::length(oldB - onB));
      if (apart > nearest) continue;
      nearest = apart;
      const Vec3 slide = oldB - oldA - o.anchor;
      madeExtras[i].carriedSlide = slide - glm::dot(slide, o.normal) * o.normal;
    }
  }
}

// A kept manifold into contacts_ and manifolds_ as it is, its normal turned with its face.
void NarrowPhase::carry(const NarrowPhaseInput& in, const Manifold& m, Sink& out) const {
  Manifold moved = m;
  if (m.rigid) {
    moved.firstContact = static_cast<std::uint32_t>(out.rigidContacts.size());
    out.rigidContacts.insert(out.rigidContacts.end(), spareRigidContacts_.begin() + m.firstContact,
                             spareRigidContacts_.begin() + m.firstContact + m.contactCount);
    turnRigidNormal(in, moved, out.rigidContacts.data() + moved.firstContact);
    out.manifolds.push_back(moved);
    return;
  }
  moved.firstContact = static_cast<std::uint32_t>(out.contacts.size());
  out.contacts.insert(out.contacts.end(), spareContacts_.begin() + m.firstContact,
                      spareContacts_.begin() + m.firstContact + m.contactCount);
  out.extras.insert(out.extras.end(), spareExtras_.begin() + m.firstContact,
                    spareExtras_.begin() + m.firstContact + m.contactCount);
  turnNormal(in, moved, out.contacts.data() + moved.firstContact);
  out.manifolds.push_back(moved);
}

// In the step's later substeps: the contacts that cannot be kept through the step are found again.
// A face resting on a face keeps its points, which are the corners of the clipped faces whatever
// the two boxes do in a step. An edge or a vertex on a face, two edges, and every contact of a
// capsule are where the features are about to change: a box that lands on an edge rocks onto its
// face within the step, and kept, its other corners went 0.4 mm past the slop into the box below
// unseen (docs/physics.md, "Contacts once per step").
void NarrowPhase::refresh(const NarrowPhaseInput& in) {
  const bool allKept =
      std::all_of(manifolds_.begin(), manifolds_.end(), [](const Manifold& m) { return m.kept; });
  if (allKept) {
    for (Manifold& m : manifolds_) {
      if (m.rigid)
        turnRigidNormal(in, m, rigidContacts_.data() + m.firstContact);
      else
        turnNormal(in, m, contacts_.data() + m.firstContact);
    }
    return;
  }
  swapToSpare();
  inPieces(in, spareManifolds_.size(), kManifoldsPerPiece,
           [&](Sink& out, std::size_t begin, std::size_t end) { refreshRange(in, begin, end, out); });
  sizeState();
}

void NarrowPhase::refreshRange(const NarrowPhaseInput& in, std::size_t begin, std::size_t end,
                               Sink& out) const {
  BoxContact contact;
  for (std::size_t k = begin; k < end; ++k) {
    const Manifold& m = spareManifolds_[k];
    if (!m.kept) {
      if (collidePair(in, m.a, m.b, m.axis, contact)) addManifold(in, m.a, m.b, contact, out);
      continue;
    }
    carry(in, m, out);
  }
}

// A kept contact's normal turns with the face it is the normal of: held fixed in the world while
// a resting box rocked by a hair, it pushed a little sideways, and a stack of ten at rest still
// moved at 1.4 mm/s after 20 s (0.1 mm/s with its contacts found every substep).
void NarrowPhase::turnNormal(const NarrowPhaseInput& in, Manifold& m, BodyContact* contacts) {
  const glm::dmat3& axes = in.frames[m.reference].axes;
  m.normal = axes * m.localNormal;
  // The anchors turn as the face does, so that a pair that turns together keeps them.
  const glm::dmat3 turn = axes * glm::transpose(m.turnedAxes);
  m.turnedAxes = axes;
  for (std::uint32_t k = 0; k < m.contactCount; ++k) {
    contacts[k].normal = m.normal;
    contacts[k].anchor = turn * contacts[k].anchor;
    contacts[k].slipEnd = turn * contacts[k].slipEnd;
  }
}

void NarrowPhase::turnRigidNormal(const NarrowPhaseInput& in, Manifold& m, RigidContact* contacts) {
  m.normal = in.frames[m.reference].axes * m.localNormal;
  for (std::uint32_t k = 0; k < m.contactCount; ++k) contacts[k].normal = m.normal;
}

void NarrowPhase::addManifold(const NarrowPhaseInput& in, BodyId a, BodyId b, const BoxContact& contact,
                              Sink& out) {
  const Body &bodyA = in.bodies[a], &bodyB = in.bodies[b];
  if (bodyA.model == BodyModel::Rigid || bodyB.model == BodyModel::Rigid) {
    addRigidManifold(in, a, b, contact, out);
    return;
  }
  const Material combined = combine(bodyA.material, bodyB.material);
  const std::size_t first = out.contacts.size();
  // Each point on the face whose particles lie there, also for a body turned inside out.
  const Obb frameA = detail::embeddingFrame(bodyA, in.frames[a], in.particles.position);
  const Obb frameB = detail::embeddingFrame(bodyB, in.frames[b], in.particles.position);
  for (int i = 0; i < contact.count; ++i) {
    BodyContact c;
    BodyContactExtra extra;
    Vec3 movedA(0.0), movedB(0.0);
    c.pointA = detail::surfacePoint(bodyA, frameA, contact.points[i].onA, &movedA);
    c.pointB = detail::surfacePoint(bodyB, frameB, contact.points[i].onB, &movedB);
    c.normal = contact.sat.normal;
    c.combined = combined;
    c.bodyA = a;
    c.bodyB = b;
    c.kind = static_cast<std::uint8_t>(contact.kind);
    if (bodyA.shape == Shape::Capsule || bodyB.shape == Shape::Capsule) {
      c.offset = glm::dot(c.normal, movedB - movedA);  // a box's points are on its faces already
      // Only a capsule's side: a box's point is moved onto its face by round-off alone (1e-17 to
      // 2e-16 m), which flagged most box sides of capsule-box contacts, and friction took the box
      // at a point carried by its inscribed tetrahedron instead of its face.
      if (bodyA.shape == Shape::Capsule && movedA != Vec3(0.0))
        extra.surfaceA = detail::rigidPoint(bodyA, frameA, contact.points[i].onA);
      if (bodyB.shape == Shape::Capsule && movedB != Vec3(0.0))
        extra.surfaceB = detail::rigidPoint(bodyB, frameB, contact.points[i].onB);
      c.frictionAtSurfaceA = extra.surfaceA.count > 0;
      c.frictionAtSurfaceB = extra.surfaceB.count > 0;
    }
    out.contacts.push_back(c);
    out.extras.push_back(extra);
  }
  pushManifold(in, a, b, contact, false, first, out);
}

// The pair's manifold over its points from `first`, kept through the step when it is face on face
// between two boxes: its reference face, and where b was in a's frame.
void NarrowPhase::pushManifold(const NarrowPhaseInput& in, BodyId a, BodyId b, const BoxContact& contact,
                               bool rigid, std::size_t first, Sink& out) {
  out.manifolds.push_back({a, b, rigid, static_cast<std::uint32_t>(first),
                           static_cast<std::uint32_t>(contact.count), contact.sat.normal});
  Manifold& m = out.manifolds.back();
  const bool boxes = in.bodies[a].shape == Shape::Box && in.bodies[b].shape == Shape::Box;
  m.axis = boxes ? contact.sat.axis : -1;
  m.kept = boxes && contact.kind == ContactKind::FaceFace;
  if (!m.kept) return;
  const Vec3 n = m.normal;
  // The reference face: the box one of whose axes the normal lies along (the better aligned).
  auto alignment = [&n](const Obb& f) {
    return std::max({std::abs(glm::dot(f.axes[0], n)), std::abs(glm::dot(f.axes[1], n)),
                     std::abs(glm::dot(f.axes[2], n))});
  };
  m.reference = alignment(in.frames[m.a]) >= alignment(in.frames[m.b]) ? m.a : m.b;
  m.localNormal = glm::transpose(in.frames[m.reference].axes) * n;
  m.turnedAxes = in.frames[m.reference].axes;
  m.madeAt = poseInFrameOf(in.frames[m.a], in.frames[m.b]);
  m.whole = contact.dropped == 0;
}

namespace {

// One side of a rigid pair's point: a rigid body's point in its frame (its frame is its pose), or a
// particle body's point carried rigidly by its particles.
void setSide(const Body& body, const Obb& frame, const Vec3& point, ContactSide& side, RigidId& rigid,
             Vec3& local, Embedding& embedded) {
  if (body.model == BodyModel::Rigid) {
    side = ContactSide::Rigid;
    rigid = body.rigid;
    local = glm::transpose(frame.axes) * (point - frame.center);
  } else {
    // A box's point on the face it lies on, carried by that face's corners as between particle
    // bodies: carried by the tetrahedron, whose weights reach -1/2 at a corner, the pushes sheared
    // the box and a corners box on a rigid one walked 2 cm in 5 s. A capsule's point rigidly (a
    // face point would sit off its round surface).
    side = ContactSide::Particles;
    embedded = body.shape == Shape::Box ? detail::surfacePoint(body, frame, point)
                                        : detail::rigidPoint(body, frame, point);
  }
}

}  // namespace

// A pair with a rigid body: its points into rigidContacts_, where the rigid passes solve them. Face
// on face between two boxes is kept through the step as for particle bodies.
void NarrowPhase::addRigidManifold(const NarrowPhaseInput& in, BodyId a, BodyId b, const BoxContact& contact,
                                   Sink& out) {
  const Body &bodyA = in.bodies[a], &bodyB = in.bodies[b];
  const Material combined = combine(bodyA.material, bodyB.material);
  const std::size_t first = out.rigidContacts.size();
  // Two points with a capsule: its core lies along the other's face or core, and the two are one
  // block in the passes (solvesAsBlock in rigid_contacts.cpp), as on the ground.
  const bool capsuleLying =
      contact.count == 2 && (bodyA.shape == Shape::Capsule || bodyB.shape == Shape::Capsule);
  // A rigid body's frame is its pose; a particle body's as addManifold embeds in it.
  const Obb frameA = detail::embeddingFrame(bodyA, in.frames[a], in.particles.position);
  const Obb frameB = detail::embeddingFrame(bodyB, in.frames[b], in.particles.position);
  for (int i = 0; i < contact.count; ++i) {
    RigidContact c;
    c.bodyA = a;
    c.bodyB = b;
    setSide(bodyA, frameA, contact.points[i].onA, c.sideA, c.rigidA, c.localA, c.pointA);
    setSide(bodyB, frameB, contact.points[i].onB, c.sideB, c.rigidB, c.localB, c.pointB);
    c.normal = contact.sat.normal;
    c.combined = combined;
    c.kind = static_cast<std::uint8_t>(contact.kind);
    c.capsuleLying = capsuleLying;
    out.rigidContacts.push_back(c);
  }
  pushManifold(in, a, b, contact, true, first, out);
}

void NarrowPhase::sizeState() {
  state_.push.assign(contacts_.size(), 0.0);
  state_.touched.assign(contacts_.size(), 0);
  state_.approach.assign(contacts_.size(), 0.0);
  state_.allowance.assign(contacts_.size(), 0.0);
}

// Every substep: each contact's overlap beyond the slop at x*, where the substep starts (what the
// parting and the depenetration limit are reckoned from), measured from its embedded points, and
// each pair's deepest.
//
// The points and the normal are of the frames now, so what they measure at x* is the gap across a
// plane that extends past the bodies. A body that passed another's edge in the substep (a near
// miss, which the sweep lets go) was on the far side of that plane at x* and reads as deep in,
// though the two were apart: the parting then threw it 1.15 m on, a box skimming 5 cm over a
// wall at 120 m/s. So where a pair moved, relative to each other, more than the thinnest half
// extent of the two in the substep (as the sweep's test: only then can one cross the other's
// plane) and an overlap reads deeper than the feature epsilon, which the parting would act on, the
// separating-axis test is run on the frames at x* (each moved back by its body's mean move, not
// turned); if those were apart, the two started apart, and the contact is taken to start as a
// resting one (overlap 0 at most). Slower pairs are left as they were: in a pile, the points and
// the fitted frames of deformed boxes disagree by a centimetre now and then (`ragdolls`: 45
// contacts in 40 steps read over 1 cm in while the frames were apart), and what the parting
// should make of that is its own question.
void NarrowPhase::measureStarts(const NarrowPhaseInput& in) {
  const Particles& particles = in.particles;
  // Whether bodies a and b, which read as deep in at x*, were apart there having passed each other.
  auto passed = [&](BodyId a, BodyId b) {
    Obb startA = in.frames[a], startB = in.frames[b];
    const Vec3 moveA = detail::bodyMove(particles, in.rigid, in.bodies[a]);
    const Vec3 moveB = detail::bodyMove(particles, in.rigid, in.bodies[b]);
    if (!(glm::length(moveB - moveA) > detail::thinnestHalfExtent(startA, startB))) return false;
    startA.center -= moveA;
    startB.center -= moveB;
    return !satTest(startA, startB).overlap;
  };
  rigidState_.resize(rigidContacts_.size());
  // Each manifold's points are its own: ranges of manifolds at once on the step's threads.
  auto range = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) measureStart(in, manifolds_[i], passed);
  };
  forEachRange(in.workers, manifolds_.size(), kStartsPerPiece, range);
  std::fill(state_.touched.begin(), state_.touched.end(), std::uint8_t{0});
}

// A kept point's friction anchor at the substep's start: as it was if friction held it at the
// last substep's end; where its last slip left it if it slipped; else where it is at x* (a point
// that parted is not pulled back where it was), less the slide a new point was handed (carrySlide).
void NarrowPhase::anchor(BodyContact& c, const BodyContactExtra& extra, const Vec3& startApart) {
  if (c.grip == Grip::Slipped) {
    c.anchor = c.slipEnd;
  } else if (c.grip == Grip::None) {
    c.anchor = startApart - glm::dot(startApart, c.normal) * c.normal;
    // A new point of a manifold clipped again keeps what its pair had slid (carrySlide).
    if (!c.anchored) c.anchor -= extra.carriedSlide - glm::dot(extra.carriedSlide, c.normal) * c.normal;
    c.anchored = true;
  }
  c.grip = Grip::None;
}

// One manifold's start overlaps (measureStarts says what they are).
template <class Passed>
void NarrowPhase::measureStart(const NarrowPhaseInput& in, Manifold& m, const Passed& passed) {
  const Particles& particles = in.particles;
  Real overlap = -std::numeric_limits<Real>::infinity();
  // The start overlaps, "for now": the parting moves them with the bodies, then the depenetration
  // limit makes them what each point may keep.
  std::span<Real> start =
      m.rigid ? std::span<Real>(rigidState_.allowance) : std::span<Real>(state_.allowance);
  for (std::uint32_t k = m.firstContact; k < m.firstContact + m.contactCount; ++k) {
    if (m.rigid) {
      start[k] = detail::startOverlap(particles, in.rigid, rigidContacts_[k], 0.0);  // never the ground
    } else {
      BodyContact& c = contacts_[k];
      const Vec3 startApart = detail::embeddedPosition(particles.previous, c.pointB) -
                              detail::embeddedPosition(particles.previous, c.pointA);
      const Real startGap = glm::dot(c.normal, startApart) - c.offset;
      if (m.kept) anchor(c, extras_[k], startApart);
      start[k] = -(startGap + in.contactSlop);
    }
    overlap = std::max(overlap, start[k]);
  }
  if (overlap > in.featureEpsilon && passed(m.a, m.b)) {
    for (std::uint32_t k = m.firstContact; k < m.firstContact + m.contactCount; ++k) {
      start[k] = std::min(start[k], 0.0);
    }
    overlap = std::min(overlap, 0.0);
  }
  m.overlap = overlap;
}

}  // namespace phys
