#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "passes.h"

namespace phys::detail {

void collideGround(Particles& p, std::span<const GroundContact> contacts, const Vec3& n, Real height,
                   std::span<Real> normalPush, std::span<const Real> allowance,
                   std::span<const std::uint8_t> still, std::span<const std::uint8_t> far) {
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    if (!still.empty() && still[c] != 0) continue;
    if (!far.empty() && far[c] != 0) {
      normalPush[c] = 0.0;
      continue;
    }
    const Embedding& e = contacts[c].point;
    const Real allowed = allowance.empty() ? 0.0 : allowance[c];  // depth it may keep
    const Real depth = height + contacts[c].lift - glm::dot(n, embeddedPosition(p.position, e)) - allowed;
    normalPush[c] = 0.0;
    if (depth <= 0.0) continue;
    moveEmbedded(p.position, p.inverseMass, e, depth * n);
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
    const Real push = normalPush[c];
    if (push <= 0.0 || (!still.empty() && still[c] != 0)) continue;
    const Embedding& e = contacts[c].surface.count > 0 ? contacts[c].surface : contacts[c].point;
    Vec3 slide = embeddedPosition(p.position, e) - embeddedPosition(p.previous, e);
    slide -= glm::dot(slide, n) * n;
    const Real slideLength = glm::length(slide);
    if (slideLength == 0.0) continue;
    const Material& mu = contacts[c].combined;
    Real cut = 1.0;  // static: stop the slide entirely
    if (slideLength > mu.staticFriction * push) cut = std::min(1.0, mu.dynamicFriction * push / slideLength);
    moveEmbedded(p.position, p.inverseMass, e, -cut * slide);
  }
}

}  // namespace phys::detail
