// The ground's contact points and their state (physics/ground_contacts.h).
#include "physics/ground_contacts.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "passes.h"

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
}

void GroundContacts::followCapsuleEnd(Real end) {
  capsuleEnds_.push_back({static_cast<std::uint32_t>(points_.size() - 1), end});
}

void GroundContacts::truncate(std::size_t count) {
  points_.resize(count);
  state_.push.resize(count);
  state_.touched.resize(count);
  state_.hit.resize(count);
  state_.approach.resize(count);
  state_.allowance.resize(count);
}

void GroundContacts::combineMaterials(const Material& ground) {
  for (GroundContact& c : points_) c.combined = combined(c, ground);
}

void GroundContacts::placeCapsulePoints(std::span<const Body> bodies, std::span<const Obb> frames,
                                        const Vec3& groundNormal) {
  const Vec3 n = groundNormal;
  for (const CapsuleEnd& g : capsuleEnds_) {
    GroundContact& contact = points_[g.point];
    const BodyId id = contact.body;
    const Body& box = bodies[id];
    const Obb& f = frames[id];
    const Vec3 lowest = f.center + f.axes[1] * (g.end * box.capsuleHalfSegment()) - n * box.capsuleRadius();
    Vec3 moved(0.0);
    contact.point = detail::surfacePoint(box, f, lowest, &moved);
    contact.lift = glm::dot(n, moved);
    if (box.model == BodyModel::Corners) contact.surface = detail::rigidPoint(box, f, lowest);
  }
}

}  // namespace phys
