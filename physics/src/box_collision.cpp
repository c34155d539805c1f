// World's box-box collision, run once per step after the first substep's integration: fit each
// box's frame, then turn the contact points of each pair the broad phase found (broad_phase.cpp)
// into BodyContacts whose points are embedded in the two boxes' particles, measured again in each
// substep.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "passes.h"
#include "physics/world.h"

namespace phys {
namespace {

std::uint64_t pairKey(BoxId a, BoxId b) {
  const BoxId lo = std::min(a, b), hi = std::max(a, b);
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

Material combine(const Material& a, const Material& b) {
  return {std::sqrt(a.staticFriction * b.staticFriction), std::sqrt(a.dynamicFriction * b.dynamicFriction)};
}

}  // namespace

void World::ignoreCollision(BoxId a, BoxId b) {
  if (a >= boxes_.size() || b >= boxes_.size() || a == b) {
    throw std::invalid_argument("ignoreCollision: box ids must exist and differ");
  }
  const std::uint64_t key = pairKey(a, b);
  const auto at = std::lower_bound(ignoredPairs_.begin(), ignoredPairs_.end(), key);
  if (at == ignoredPairs_.end() || *at != key) ignoredPairs_.insert(at, key);
  pairsStale_ = true;
  layoutsStale_ = true;  // ignoredStart_
}

std::vector<std::pair<BoxId, BoxId>> World::ignoredCollisions() const {
  std::vector<std::pair<BoxId, BoxId>> out;
  out.reserve(ignoredPairs_.size());
  for (const std::uint64_t key : ignoredPairs_) {
    out.emplace_back(static_cast<BoxId>(key >> 32), static_cast<BoxId>(key & 0xffffffffu));
  }
  return out;
}

BoxId World::jointGroup(BoxId id) {
  while (jointGroup_[id] != id) {
    jointGroup_[id] = jointGroup_[jointGroup_[id]];  // path halving
    id = jointGroup_[id];
  }
  return id;
}

void World::joinGroups(ParticleId a, ParticleId b) {
  const std::int32_t ba = particleBody_[a], bb = particleBody_[b];
  if (ba < 0 || bb < 0 || ba == bb) return;
  const BoxId ra = jointGroup(static_cast<BoxId>(ba)), rb = jointGroup(static_cast<BoxId>(bb));
  if (ra != rb) jointGroup_[std::max(ra, rb)] = std::min(ra, rb);
}

bool World::collides(BoxId a, BoxId b) const {
  const Box& ba = boxes_[a];
  const Box& bb = boxes_[b];
  if ((ba.collisionGroup & bb.collisionMask) == 0 || (bb.collisionGroup & ba.collisionMask) == 0)
    return false;
  // The keys whose smaller id is `lo` are consecutive (sorted by it): a ragdoll part's few joints,
  // where a search of the whole world's list missed the cache at every step.
  const BoxId lo = std::min(a, b), hi = std::max(a, b);
  for (std::uint32_t k = ignoredStart_[lo]; k < ignoredStart_[lo + 1]; ++k) {
    if (static_cast<BoxId>(ignoredPairs_[k]) == hi) return false;
  }
  return true;
}

// Centre: the mean of the corners. Axes: the mean edge along each, made orthonormal. Cheaper
// than the polar decomposition boxPose uses, and as good for a box that keeps its shape.
void World::updateBoxFrames() {
  for (BoxId id = 0; id < boxes_.size(); ++id) {
    const Box& box = boxes_[id];
    Obb& f = frames_[id];
    Vec3 ex, ey;
    if (box.model == BoxModel::Tetra) {
      // The same sums from the 4 particles (at corners 0, 3, 5, 6): corner k is sum_j (1 + s_j .
      // s_k) / 4 p_j, so the mean corner is the mean particle and the x edges sum to
      // 2 sum_j s_jx p_j. A third of the work of embedding 8 corners.
      const Vec3* p = &particles_.position[box.firstParticle];
      f.center = (p[0] + p[1] + p[2] + p[3]) * 0.25;
      ex = (p[1] + p[2] - p[0] - p[3]) * 2.0;
      ey = (p[1] + p[3] - p[0] - p[2]) * 2.0;
    } else {
      const Vec3* c = &particles_.position[box.firstParticle];  // the corners are the particles
      f.center = (c[0] + c[1] + c[2] + c[3] + c[4] + c[5] + c[6] + c[7]) * 0.125;
      ex = (c[1] - c[0]) + (c[3] - c[2]) + (c[5] - c[4]) + (c[7] - c[6]);
      ey = (c[2] - c[0]) + (c[3] - c[1]) + (c[6] - c[4]) + (c[7] - c[5]);
    }
    const Real lx = glm::length(ex);
    ex = lx > 0.0 ? ex / lx : Vec3(1.0, 0.0, 0.0);
    ey -= glm::dot(ey, ex) * ex;
    const Real ly = glm::length(ey);
    ey = ly > 0.0 ? ey / ly
                  : glm::normalize(glm::cross(ex, std::abs(ex.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
    f.axes = glm::dmat3(ex, ey, glm::cross(ex, ey));
    f.halfExtents = box.halfExtents;
  }
}

// Each pair's contact by its shapes, normal from a towards b; boxes keep at most 4 points. Points
// up to `margin` apart are kept: speculative ones, which the passes leave alone until they close.
bool World::collidePair(BoxId a, BoxId b, Real margin, BoxContact& contact) const {
  const bool capsuleA = boxes_[a].shape == Shape::Capsule, capsuleB = boxes_[b].shape == Shape::Capsule;
  if (!capsuleA && !capsuleB) {
    if (!collideBoxes(frames_[a], frames_[b], solver_.featureEpsilon, margin, contact)) return false;
    reduceToFourPoints(contact, solver_.featureEpsilon);
    return true;
  }
  if (capsuleA && capsuleB)
    return collideCapsules(capsuleInBox(frames_[a]), capsuleInBox(frames_[b]), margin, contact);
  if (capsuleA) return collideCapsuleBox(capsuleInBox(frames_[a]), frames_[b], margin, contact);
  if (!collideCapsuleBox(capsuleInBox(frames_[b]), frames_[a], margin, contact)) return false;
  contact.sat.normal = -contact.sat.normal;  // it was from b towards a
  for (int i = 0; i < contact.count; ++i) std::swap(contact.points[i].onA, contact.points[i].onB);
  return true;
}

// A capsule's ground points: the lowest point of each end sphere, at the frame of this substep.
void World::placeCapsuleGroundPoints() {
  const Vec3 n = world_.groundNormal;
  for (const CapsuleGroundPoint& g : capsuleGround_) {
    GroundContact& contact = contactPoints_[g.contact];
    const auto id = static_cast<BoxId>(contact.body);
    const Box& box = boxes_[id];
    const Obb& f = frames_[id];
    const Vec3 lowest = f.center + f.axes[1] * (g.end * box.capsuleHalfSegment()) - n * box.capsuleRadius();
    Vec3 moved(0.0);
    contact.point = embedInBox(id, lowest, &moved);
    contact.lift = glm::dot(n, moved);
    if (box.model == BoxModel::Corners) contact.surface = rigidPoint(id, lowest);
  }
}

// A world point in the box's frame of this substep, in units of its half extents.
Vec3 World::frameCoordinates(BoxId id, const Vec3& point) const {
  const Obb& f = frames_[id];
  const Vec3 d = point - f.center;
  const Vec3& h = boxes_[id].halfExtents;
  return {glm::dot(d, f.axes[0]) / h.x, glm::dot(d, f.axes[1]) / h.y, glm::dot(d, f.axes[2]) / h.z};
}

// A world point carried rigidly by the box as it lies in its frame (detail::rigidEmbedding).
Embedding World::rigidPoint(BoxId id, const Vec3& point) const {
  return detail::rigidEmbedding(boxes_[id], frameCoordinates(id, point));
}

Embedding World::embedInBox(BoxId id, const Vec3& point, Vec3* moved) const {
  const Box& box = boxes_[id];
  const Obb& f = frames_[id];
  Vec3 u = frameCoordinates(id, point);
  // A tetra capsule's points lie on its round surface, inside its box: carried rigidly by its
  // tetrahedron. A corners capsule's go onto the nearest face below, whose 4 particles then hold
  // it up as they hold a box (through the inscribed tetrahedron, the other 4 hang on sticks: a
  // capsule lying on the ground sagged 15 mm at 3 x 1). `moved` gets how far the embedding
  // carries the point, as the box lies in its frame: from its rest shape, not its particles',
  // since a correction reckoned from their sag would feed back into it.
  if (moved != nullptr) *moved = Vec3(0.0);
  if (box.shape == Shape::Capsule && box.model == BoxModel::Tetra) return detail::rigidEmbedding(box, u);
  const Vec3 unclamped = u;
  u = glm::clamp(u, Vec3(-1.0), Vec3(1.0));
  Embedding e;
  e.count = 4;
  if (box.model == BoxModel::Tetra) {
    const std::array<Real, 4> w = tetraWeights(u);
    for (int j = 0; j < 4; ++j) {
      e.particle[j] = box.firstParticle + j;
      e.weight[j] = w[j];
    }
    return e;
  }
  // Corners model: contact points lie on the surface, so trilinear weights reduce to bilinear
  // ones on the face the point is nearest: put it on that face and weigh its 4 corners.
  int axis = 0;
  if (box.shape == Shape::Capsule) {
    // The face nearest in metres: by |u| alone, a side point of a long capsule near its end went
    // to the end face, 2.5 r along the capsule. (A box's points are on a face: either rule finds it.)
    for (int a = 1; a < 3; ++a) {
      if ((1.0 - std::abs(u[a])) * box.halfExtents[a] < (1.0 - std::abs(u[axis])) * box.halfExtents[axis])
        axis = a;
    }
  } else {
    for (int a = 1; a < 3; ++a) {
      if (std::abs(u[a]) > std::abs(u[axis])) axis = a;
    }
  }
  const int side = u[axis] >= 0.0 ? (1 << axis) : 0;
  const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
  if (moved != nullptr) {
    Vec3 carried = u;
    carried[axis] = u[axis] >= 0.0 ? 1.0 : -1.0;
    for (int k = 0; k < 3; ++k) *moved += f.axes[k] * ((carried[k] - unclamped[k]) * box.halfExtents[k]);
  }
  for (int j = 0; j < 4; ++j) {
    const bool plusU = (j & 1) != 0, plusV = (j & 2) != 0;
    const int corner = side | (plusU ? 1 << ua : 0) | (plusV ? 1 << va : 0);
    e.particle[j] = box.firstParticle + corner;
    e.weight[j] = 0.25 * (plusU ? 1.0 + u[ua] : 1.0 - u[ua]) * (plusV ? 1.0 + u[va] : 1.0 - u[va]);
  }
  return e;
}

// How far apart two bodies' points can be and still close within the step: the feature epsilon,
// the most any point of one can move towards any point of the other at the speeds the broad phase
// measured (their mean motions' difference and each one's turning), and what gravity's g dt^2 can
// add against a body held still. Relative motion, not each body's travel: two limbs falling side by
// side at 7 m/s keep the epsilon, where their travel would have made a margin of 25 cm, and with
// it contacts on features that never meet in the step (a face of a limb the other only passes),
// which the passes then held as if the planes were there.
Real World::speculativeMargin(BoxId a, BoxId b) const {
  const Real dt = solver_.dt;
  const Real g = gravityMagnitude();
  const Motion &ma = motion_[a], &mb = motion_[b];
  return solver_.featureEpsilon + glm::length(ma.shift - mb.shift) + ma.turn + mb.turn + g * dt * dt;
}

// Once per step (World::step): each pair's points, embedded in its two bodies, kept when they are
// nearer than the pair can close in the step (speculativeMargin), so that a contact that closes
// within the step is there when it does; the passes push a point only once it touches.
void World::buildBoxContacts() {
  bodyContacts_.clear();
  partPairs_.clear();
  BoxContact contact;
  for (const auto& [a, b] : pairs_) {
    if (collidePair(a, b, speculativeMargin(a, b), contact)) addPairContact(a, b, contact);
  }
  resizeBoxContactArrays();
}

// In the step's later substeps: the contacts that cannot be kept through the step are found again.
// A face resting on a face keeps its points, which are the corners of the clipped faces whatever
// the two boxes do in a step. An edge or a vertex on a face, two edges, and every contact of a
// capsule are where the features are about to change: a box that lands on an edge rocks onto its
// face within the step, and kept, its other corners went 0.4 mm past the slop into the box below
// unseen (docs/physics.md, "Contacts once per step").
void World::refreshBoxContacts() {
  const bool allKept =
      std::all_of(partPairs_.begin(), partPairs_.end(), [](const PartPair& pair) { return pair.kept; });
  if (allKept) {
    for (PartPair& pair : partPairs_) turnNormal(pair, bodyContacts_.data() + pair.firstContact);
    return;
  }
  std::swap(bodyContacts_, spareContacts_);
  std::swap(partPairs_, spareParts_);
  bodyContacts_.clear();
  partPairs_.clear();
  BoxContact contact;
  for (const PartPair& pair : spareParts_) {
    if (!pair.kept) {
      if (collidePair(pair.a, pair.b, speculativeMargin(pair.a, pair.b), contact))
        addPairContact(pair.a, pair.b, contact);
      continue;
    }
    PartPair moved = pair;
    moved.firstContact = static_cast<std::uint32_t>(bodyContacts_.size());
    bodyContacts_.insert(bodyContacts_.end(), spareContacts_.begin() + pair.firstContact,
                         spareContacts_.begin() + pair.firstContact + pair.contactCount);
    turnNormal(moved, bodyContacts_.data() + moved.firstContact);
    partPairs_.push_back(moved);
  }
  resizeBoxContactArrays();
}

// A kept contact's normal turns with the face it is the normal of: held fixed in the world while
// a resting box rocked by a hair, it pushed a little sideways, and a stack of ten at rest still
// moved at 1.4 mm/s after 20 s (0.1 mm/s with its contacts found every substep).
void World::turnNormal(PartPair& pair, BodyContact* contacts) const {
  pair.normal = frames_[pair.reference].axes * pair.localNormal;
  for (std::uint32_t k = 0; k < pair.contactCount; ++k) contacts[k].normal = pair.normal;
}

void World::addPairContact(BoxId a, BoxId b, const BoxContact& contact) {
  const Material combined = combine(boxes_[a].material, boxes_[b].material);
  const std::size_t first = bodyContacts_.size();
  for (int i = 0; i < contact.count; ++i) {
    BodyContact c;
    Vec3 movedA(0.0), movedB(0.0);
    c.pointA = embedInBox(a, contact.points[i].onA, &movedA);
    c.pointB = embedInBox(b, contact.points[i].onB, &movedB);
    c.normal = contact.sat.normal;
    c.combined = combined;
    c.boxA = static_cast<std::int32_t>(a);
    c.boxB = static_cast<std::int32_t>(b);
    c.kind = static_cast<std::uint8_t>(contact.kind);
    if (boxes_[a].shape == Shape::Capsule || boxes_[b].shape == Shape::Capsule) {
      c.offset = glm::dot(c.normal, movedB - movedA);  // a box's points are on its faces already
      if (movedA != Vec3(0.0)) c.surfaceA = rigidPoint(a, contact.points[i].onA);
      if (movedB != Vec3(0.0)) c.surfaceB = rigidPoint(b, contact.points[i].onB);
    }
    bodyContacts_.push_back(c);
  }
  const Vec3 n = contact.sat.normal;
  partPairs_.push_back(
      {a, b, static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(contact.count), n, 0.0, 0.0, 0.0});
  PartPair& pair = partPairs_.back();
  pair.kept =
      contact.kind == ContactKind::FaceFace && boxes_[a].shape == Shape::Box && boxes_[b].shape == Shape::Box;
  if (pair.kept) {
    // The reference face: the box one of whose axes the normal lies along (the better aligned).
    auto alignment = [&n](const Obb& f) {
      return std::max({std::abs(glm::dot(f.axes[0], n)), std::abs(glm::dot(f.axes[1], n)),
                       std::abs(glm::dot(f.axes[2], n))});
    };
    pair.reference = alignment(frames_[a]) >= alignment(frames_[b]) ? a : b;
    pair.localNormal = glm::transpose(frames_[pair.reference].axes) * n;
  }
}

void World::resizeBoxContactArrays() {
  bodyPush_.assign(bodyContacts_.size(), 0.0);
  bodyTouched_.assign(bodyContacts_.size(), 0);
  bodyApproach_.assign(bodyContacts_.size(), 0.0);
  bodyAllowance_.assign(bodyContacts_.size(), 0.0);
}

// Every substep: each contact's overlap beyond the slop at x*, where the substep starts (what the
// parting and the depenetration limit are reckoned from), measured from its embedded points, and
// each pair's deepest.
void World::measureBoxContactStarts() {
  for (PartPair& pair : partPairs_) {
    Real overlap = -std::numeric_limits<Real>::infinity();
    for (std::uint32_t k = pair.firstContact; k < pair.firstContact + pair.contactCount; ++k) {
      const BodyContact& c = bodyContacts_[k];
      const Real startGap = glm::dot(c.normal, detail::embeddedPosition(particles_.previous, c.pointB) -
                                                   detail::embeddedPosition(particles_.previous, c.pointA)) -
                            c.offset;
      bodyAllowance_[k] = -(startGap + solver_.contactSlop);  // the start overlap, for now
      overlap = std::max(overlap, bodyAllowance_[k]);
    }
    pair.overlap = overlap;
  }
  std::fill(bodyTouched_.begin(), bodyTouched_.end(), std::uint8_t{0});
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
void World::partWithoutVelocity() {
  const Real epsilon = solver_.featureEpsilon;
  for (BoxId id = 0; id < boxes_.size(); ++id) partRoot_[id] = jointGroup(id);
  bool deep = false;
  for (PartPair& pair : partPairs_) {
    if (partRoot_[pair.a] == partRoot_[pair.b]) {
      pair.need = -std::numeric_limits<Real>::infinity();  // nothing to part: one group
      continue;
    }
    deep = deep || pair.overlap > epsilon;
    pair.need = pair.overlap > epsilon ? pair.overlap : std::min(pair.overlap, 0.0);
  }
  const Vec3 up = world_.groundNormal;
  if (world_.ground) {
    // A box's depth is its deepest corner's, from the start depths step() measured.
    std::fill(partGround_.begin(), partGround_.end(), -std::numeric_limits<Real>::infinity());
    for (std::size_t c = 0; c < contactPoints_.size(); ++c) {
      if (contactPoints_[c].body < 0) continue;  // a loose particle: boxes do not push it
      Real& depth = partGround_[partRoot_[static_cast<std::size_t>(contactPoints_[c].body)]];
      depth = std::max(depth, groundAllowance_[c]);  // a group's depth is its deepest box's
    }
    for (Real& depth : partGround_) {
      deep = deep || depth > epsilon;
      depth = depth > epsilon ? depth : std::min(depth, 0.0);
    }
  }
  if (!deep) return;

  // A group's weight is 1 / its mass, kept at its root (a box id), as are its shift and depth.
  std::fill(partWeight_.begin(), partWeight_.end(), 0.0);  // its mass, for now
  for (BoxId id = 0; id < boxes_.size(); ++id) {
    const Box& box = boxes_[id];
    Real& mass = partWeight_[partRoot_[id]];
    for (int j = 0; j < box.particleCount; ++j) {
      const Real w = particles_.inverseMass[box.firstParticle + j];
      mass = w == 0.0 ? std::numeric_limits<Real>::infinity() : mass + 1.0 / w;  // pinned or frozen: it stays
    }
    partShift_[id] = Vec3(0.0);
  }
  for (BoxId id = 0; id < boxes_.size(); ++id) {
    if (partRoot_[id] == id) partWeight_[id] = 1.0 / partWeight_[id];
  }
  // Gauss-Seidel, pushing only, as long as that converges: the spawned scenes of the tests and the
  // suite do so in a few sweeps (to a micrometre, well below the slop the projections leave).
  // Each pair's correction is split between its two groups, so along a chain of N groups the push
  // spreads as by diffusion, in some N^2 sweeps: a row of Bullet's pile, 16 ragdolls each 5.4 cm
  // into the next, needs 306, and what 64 left became speed (docs/physics.md, "Where energy could
  // come from nowhere"). So after 64 the sweeps go on over-relaxed, each constraint's push from
  // then on accumulated (>= 0, so an overshoot can be taken back): omega = 1.7 is near the best
  // for such a chain, 2 / (1 + sin(pi / N)), and the pile's rows then converge in 36 more. What
  // is left when they stop waits for the next substep.
  constexpr int kPlainSweeps = 64;
  constexpr int kOverRelaxedSweeps = 64;
  constexpr Real kOverRelaxation = 1.7;
  constexpr Real kTolerance = 1e-6;  // m
  constexpr int kProgressSweeps = 16;
  Real lastCheck = std::numeric_limits<Real>::infinity();  // m: the worst correction 16 sweeps ago
  for (PartPair& pair : partPairs_) pair.push = 0.0;
  std::fill(partGroundPush_.begin(), partGroundPush_.end(), 0.0);
  for (int sweep = 0; sweep < kPlainSweeps + kOverRelaxedSweeps; ++sweep) {
    const bool plain = sweep < kPlainSweeps;
    Real worst = 0.0;
    for (PartPair& pair : partPairs_) {
      const BoxId ga = partRoot_[pair.a], gb = partRoot_[pair.b];
      const Real wa = partWeight_[ga], wb = partWeight_[gb];
      if (ga == gb || wa + wb == 0.0) continue;
      const Real missing = pair.need - glm::dot(pair.normal, partShift_[gb] - partShift_[ga]);
      if (plain) {
        if (missing <= 0.0) continue;
        partShift_[ga] -= pair.normal * (missing * wa / (wa + wb));
        partShift_[gb] += pair.normal * (missing * wb / (wa + wb));
        worst = std::max(worst, missing);
        continue;
      }
      const Real push = std::max(0.0, pair.push + kOverRelaxation * missing / (wa + wb));
      const Real change = push - pair.push;
      pair.push = push;
      partShift_[ga] -= pair.normal * (change * wa);
      partShift_[gb] += pair.normal * (change * wb);
      worst = std::max(worst, std::abs(change) * (wa + wb));
    }
    if (world_.ground) {
      for (BoxId id = 0; id < boxes_.size(); ++id) {
        if (partRoot_[id] != id || partWeight_[id] == 0.0) continue;
        // The ground does not move, so the group takes the whole correction.
        const Real missing = partGround_[id] - glm::dot(up, partShift_[id]);
        if (plain) {
          if (missing <= 0.0) continue;
          partShift_[id] += up * missing;
          worst = std::max(worst, missing);
          continue;
        }
        const Real push = std::max(0.0, partGroundPush_[id] + kOverRelaxation * missing);
        const Real change = push - partGroundPush_[id];
        partGroundPush_[id] = push;
        partShift_[id] += up * change;
        worst = std::max(worst, std::abs(change));
      }
    }
    if (worst < kTolerance) break;
    // Over-relaxed, a chain's worst correction falls twentyfold in 16 sweeps; that of a pyramid of
    // 20 rows pressed deeper than epsilon by too few passes hardly falls, and 64 sweeps each
    // substep would only make its collapse slower to run.
    if (sweep + 1 >= kPlainSweeps && (sweep + 1 - kPlainSweeps) % kProgressSweeps == 0) {
      if (!(worst < 0.5 * lastCheck)) break;
      lastCheck = worst;
    }
  }
  for (BoxId id = 0; id < boxes_.size(); ++id) {
    const Vec3 t = partShift_[partRoot_[id]];
    if (t == Vec3(0.0)) continue;
    const Box& box = boxes_[id];
    for (int j = 0; j < box.particleCount; ++j) {
      particles_.position[box.firstParticle + j] += t;
      particles_.previous[box.firstParticle + j] += t;
    }
  }
  // The start overlaps the depenetration limit is reckoned from move with the boxes.
  for (const PartPair& pair : partPairs_) {
    const Real parted = glm::dot(pair.normal, partShift_[partRoot_[pair.b]] - partShift_[partRoot_[pair.a]]);
    for (std::uint32_t k = 0; k < pair.contactCount; ++k) bodyAllowance_[pair.firstContact + k] -= parted;
  }
  for (std::size_t c = 0; c < contactPoints_.size() && world_.ground; ++c) {
    const std::int32_t body = contactPoints_[c].body;
    if (body >= 0) groundAllowance_[c] -= glm::dot(up, partShift_[partRoot_[static_cast<std::size_t>(body)]]);
  }
}

}  // namespace phys
