// Joints between bodies: links between embedded points. The correction is the weighted
// projection of REFERENCES.md for a point in each body, as for box-box contacts: with
// S = sum_A c_i^2 w_i + sum_B c_j^2 w_j and C the vector the gap must shrink by, A's particles
// move by +c_i w_i C / S and B's by -c_j w_j C / S. For a pin C is the whole gap, so one
// projection closes it exactly whatever its direction.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "passes.h"
#include "relax_lanes.h"

namespace phys::detail {
namespace {

// How far the link is outside its bounds at length `length`: > 0 beyond max (a pin's whole
// gap), < 0 short of min, 0 within.
Real violation(const Link& link, Real length) {
  if (length > link.maxLength) return length - link.maxLength;
  if (length < link.minLength) return length - link.minLength;
  return 0.0;
}

// One link's projection. `keep` is the violation it may keep (shrinkLinkSlack): its bounds are
// widened by that much on the side it is outside.
inline void solveLink(Particles& p, const Link& link, Real keep) {
  const Vec3 gap = embeddedPosition(p.position, link.b) - embeddedPosition(p.position, link.a);
  Vec3 correction = gap;  // a pin closes the whole gap
  if (!link.isPin() || keep != 0.0) {
    const Real length = glm::length(gap);
    const Real lo = keep < 0.0 ? std::max(0.0, link.minLength + keep) : link.minLength;
    const Real hi = keep > 0.0 ? link.maxLength + keep : link.maxLength;
    const Real target = length < lo ? lo : (length > hi ? hi : -1.0);
    if (target < 0.0 || length == 0.0) return;  // within its bounds, or no direction to push along
    correction = gap * ((length - target) / length);
  }
  const Real denominator = embeddedWeight(p.inverseMass, link.a) + embeddedWeight(p.inverseMass, link.b);
  if (denominator == 0.0) return;  // both ends pinned or frozen
  const Vec3 step = correction / denominator;
  shiftEmbedded(p.position, p.inverseMass, link.a, step);
  shiftEmbedded(p.position, p.inverseMass, link.b, -step);
}

}  // namespace

Real linkViolation(const std::vector<Vec3>& x, const Link& link) {
  return violation(link, glm::length(embeddedPosition(x, link.b) - embeddedPosition(x, link.a)));
}

int shrinkLinkSlack(const Particles& p, std::span<const Link> links, Real step, std::span<Real> slack) {
  int left = 0;
  for (std::size_t k = 0; k < links.size(); ++k) {
    Real& keep = slack[k];
    if (keep == 0.0) continue;
    // Never more than it started this substep with (at x*), on the same side, and `step` less.
    const Real start = linkViolation(p.previous, links[k]);
    keep = keep > 0.0 ? std::max(0.0, std::min(keep, start) - step)
                      : std::min(0.0, std::max(keep, start) + step);
    if (keep != 0.0) ++left;
  }
  return left;
}

void solveLinks(Particles& p, std::span<const Link> links, const LinkLayout& layout,
                std::span<const Real> slack, const Workers* workers) {
  // The usual pass, with no link created apart, is the projection alone, most of it in lanes.
  if (slack.empty()) {
    inLanePieces(linkLaneArguments(p, layout), workers,
                 [](const LinkLaneArguments& a) { solveLinkLanes(a); });
    for (const std::uint32_t k : layout.others()) solveLink(p, links[k], 0.0);
    return;
  }
  for (std::size_t k = 0; k < links.size(); ++k) solveLink(p, links[k], slack[k]);
}

}  // namespace phys::detail
