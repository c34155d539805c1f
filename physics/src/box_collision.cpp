// World's box-box collision, run once per substep after integration: fit each box's frame,
// find overlapping bounds by sweep and prune, then turn each overlap's contact points into
// BodyContacts whose points are embedded in the two boxes' particles.
#include <algorithm>
#include <cmath>
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
}

std::vector<std::pair<BoxId, BoxId>> World::ignoredCollisions() const {
  std::vector<std::pair<BoxId, BoxId>> out;
  out.reserve(ignoredPairs_.size());
  for (const std::uint64_t key : ignoredPairs_) {
    out.emplace_back(static_cast<BoxId>(key >> 32), static_cast<BoxId>(key & 0xffffffffu));
  }
  return out;
}

bool World::collides(BoxId a, BoxId b) const {
  const Box& ba = boxes_[a];
  const Box& bb = boxes_[b];
  if ((ba.collisionGroup & bb.collisionMask) == 0 || (bb.collisionGroup & ba.collisionMask) == 0) return false;
  if (ignoredPairs_.empty()) return true;
  return !std::binary_search(ignoredPairs_.begin(), ignoredPairs_.end(), pairKey(a, b));
}

// Centre: the mean of the corners. Axes: the mean edge along each, made orthonormal. Cheaper
// than the polar decomposition boxPose uses, and as good for a box that keeps its shape.
void World::updateBoxFrames() {
  for (BoxId id = 0; id < boxes_.size(); ++id) {
    const Box& box = boxes_[id];
    Vec3 c[8];
    for (int k = 0; k < 8; ++k) c[k] = position(corners_[box.firstCorner + k]);
    Obb& f = frames_[id];
    f.center = (c[0] + c[1] + c[2] + c[3] + c[4] + c[5] + c[6] + c[7]) * 0.125;
    Vec3 ex = (c[1] - c[0]) + (c[3] - c[2]) + (c[5] - c[4]) + (c[7] - c[6]);
    Vec3 ey = (c[2] - c[0]) + (c[3] - c[1]) + (c[6] - c[4]) + (c[7] - c[5]);
    const Real lx = glm::length(ex);
    ex = lx > 0.0 ? ex / lx : Vec3(1.0, 0.0, 0.0);
    ey -= glm::dot(ey, ex) * ex;
    const Real ly = glm::length(ey);
    ey = ly > 0.0 ? ey / ly : glm::normalize(glm::cross(ex, std::abs(ex.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
    f.axes = glm::dmat3(ex, ey, glm::cross(ex, ey));
    f.halfExtents = box.halfExtents;
  }
}

// Sweep and prune along x: the list stays sorted from one substep to the next, so insertion
// sort costs about one pass while boxes move little. A uniform grid would need a cell size,
// and boxes in one scene differ in size by orders of magnitude; sorting needs none.
void World::findBoxPairs() {
  const Real margin = solver_.featureEpsilon;
  for (Interval& it : sweep_) {
    const Obb& f = frames_[it.box];
    const Real reach = std::abs(f.axes[0].x) * f.halfExtents.x + std::abs(f.axes[1].x) * f.halfExtents.y +
                       std::abs(f.axes[2].x) * f.halfExtents.z + margin;
    it.min = f.center.x - reach;
    it.max = f.center.x + reach;
  }
  for (std::size_t i = 1; i < sweep_.size(); ++i) {
    const Interval moving = sweep_[i];
    std::size_t j = i;
    while (j > 0 && sweep_[j - 1].min > moving.min) {
      sweep_[j] = sweep_[j - 1];
      --j;
    }
    sweep_[j] = moving;
  }
  pairs_.clear();
  for (std::size_t i = 0; i < sweep_.size(); ++i) {
    const Obb& fi = frames_[sweep_[i].box];
    for (std::size_t j = i + 1; j < sweep_.size() && sweep_[j].min <= sweep_[i].max; ++j) {
      const BoxId a = sweep_[i].box, b = sweep_[j].box;
      const Obb& fj = frames_[b];
      // The other two axes of the bounds, then the filters.
      bool apart = false;
      for (int axis = 1; axis < 3 && !apart; ++axis) {
        Real ri = margin, rj = margin;
        for (int k = 0; k < 3; ++k) {
          ri += std::abs(fi.axes[k][axis]) * fi.halfExtents[k];
          rj += std::abs(fj.axes[k][axis]) * fj.halfExtents[k];
        }
        apart = std::abs(fi.center[axis] - fj.center[axis]) > ri + rj;
      }
      if (!apart && collides(a, b)) pairs_.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
}

Embedding World::embedInBox(BoxId id, const Vec3& point) const {
  const Box& box = boxes_[id];
  const Obb& f = frames_[id];
  const Vec3 d = point - f.center;
  Vec3 u(glm::dot(d, f.axes[0]) / box.halfExtents.x, glm::dot(d, f.axes[1]) / box.halfExtents.y,
         glm::dot(d, f.axes[2]) / box.halfExtents.z);
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
  for (int a = 1; a < 3; ++a) {
    if (std::abs(u[a]) > std::abs(u[axis])) axis = a;
  }
  const int side = u[axis] >= 0.0 ? (1 << axis) : 0;
  const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
  for (int j = 0; j < 4; ++j) {
    const bool plusU = (j & 1) != 0, plusV = (j & 2) != 0;
    const int corner = side | (plusU ? 1 << ua : 0) | (plusV ? 1 << va : 0);
    e.particle[j] = box.firstParticle + corner;
    e.weight[j] = 0.25 * (plusU ? 1.0 + u[ua] : 1.0 - u[ua]) * (plusV ? 1.0 + u[va] : 1.0 - u[va]);
  }
  return e;
}

void World::buildBoxContacts() {
  bodyContacts_.clear();
  BoxContact contact;
  for (const auto& [a, b] : pairs_) {
    if (!collideBoxes(frames_[a], frames_[b], solver_.featureEpsilon, contact)) continue;
    reduceToFourPoints(contact);
    const Material combined = combine(boxes_[a].material, boxes_[b].material);
    const std::size_t first = bodyContacts_.size();
    for (int i = 0; i < contact.count; ++i) {
      BodyContact c;
      c.pointA = embedInBox(a, contact.points[i].onA);
      c.pointB = embedInBox(b, contact.points[i].onB);
      c.normal = contact.sat.normal;
      c.combined = combined;
      c.boxA = static_cast<std::int32_t>(a);
      c.boxB = static_cast<std::int32_t>(b);
      c.kind = static_cast<std::uint8_t>(contact.kind);
      bodyContacts_.push_back(c);
    }
    separateWithoutVelocity(a, b, std::span<const BodyContact>(bodyContacts_).subspan(first));
  }
  bodyPush_.assign(bodyContacts_.size(), 0.0);
  bodyTouched_.assign(bodyContacts_.size(), 0);
  bodyApproach_.assign(bodyContacts_.size(), 0.0);
}

// A deep overlap the pair already had at the start of the substep (measured in x*: more than
// the feature epsilon, as when boxes are spawned into each other) is removed by moving both
// boxes whole, x and x* alike, in inverse proportion to their mass: they part without gaining
// velocity, and without being bent, which the sticks would undo with a kick. Projected by the
// contact constraints instead, 10 cm of overlap pops apart at metres per second. Shallow
// overlap (a resting contact's millimetres) is left to the constraints: moving a resting box
// whole would push the one under it into the ground.
void World::separateWithoutVelocity(BoxId a, BoxId b, std::span<const BodyContact> contacts) {
  Real overlap = 0.0;
  for (const BodyContact& c : contacts) {
    const Real gap = glm::dot(c.normal, detail::embeddedPosition(particles_.previous, c.pointB) -
                                            detail::embeddedPosition(particles_.previous, c.pointA));
    overlap = std::max(overlap, -(gap + solver_.contactSlop));
  }
  if (overlap <= solver_.featureEpsilon || contacts.empty()) return;
  auto inverseMass = [this](const Box& box) {
    Real mass = 0.0;
    for (int j = 0; j < box.particleCount; ++j) {
      const Real w = particles_.inverseMass[box.firstParticle + j];
      if (w == 0.0) return 0.0;  // pinned or frozen: the box does not move
      mass += 1.0 / w;
    }
    return 1.0 / mass;
  };
  const Real wa = inverseMass(boxes_[a]), wb = inverseMass(boxes_[b]);
  if (wa + wb == 0.0) return;
  const Vec3 n = contacts.front().normal;
  auto shift = [this](const Box& box, const Vec3& d) {
    for (int j = 0; j < box.particleCount; ++j) {
      particles_.position[box.firstParticle + j] += d;
      particles_.previous[box.firstParticle + j] += d;
    }
  };
  shift(boxes_[a], -n * (overlap * wa / (wa + wb)));
  shift(boxes_[b], n * (overlap * wb / (wa + wb)));
}

}  // namespace phys
