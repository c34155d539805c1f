#include "pose_measures.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "run_metrics.h"
#include "text.h"

namespace lab::peers {
namespace {

using phys::Vec3;

// The deepest point of a contact. Depths are measured with margin 0, so a contact found at all
// has its points at depth >= 0; bodies merely touching read 0.
double deepest(const phys::BoxContact& c) {
  double d = 0.0;
  for (int k = 0; k < c.count; ++k) d = std::max(d, c.points[static_cast<std::size_t>(k)].depth);
  return d;
}

// How deep two solids overlap, by the same functions World's narrow phase calls for the pair.
double pairDepth(const Body& a, const phys::Obb& oa, const Body& b, const phys::Obb& ob) {
  phys::BoxContact c;
  const bool capA = a.shape == Body::Shape::Capsule, capB = b.shape == Body::Shape::Capsule;
  bool touching = false;
  if (capA && capB)
    touching = phys::collideCapsules(phys::capsuleInBox(oa), phys::capsuleInBox(ob), 0.0, c);
  else if (capA)
    touching = phys::collideCapsuleBox(phys::capsuleInBox(oa), ob, 0.0, c);
  else if (capB)
    touching = phys::collideCapsuleBox(phys::capsuleInBox(ob), oa, 0.0, c);
  else
    touching = phys::collideBoxes(oa, ob, 0.0, c);
  return touching ? deepest(c) : 0.0;
}

// A solid's world-axis-aligned bounding box, as centre +- extent.
struct Bounds {
  int body = 0;
  Vec3 lo{0.0}, hi{0.0};
};

Bounds boundsOf(int i, const phys::Obb& o) {
  Vec3 extent(0.0);
  for (int j = 0; j < 3; ++j) extent += glm::abs(o.axes[j]) * o.halfExtents[j];
  return {i, o.center - extent, o.center + extent};
}

bool finitePose(const Vec3& c, const phys::Quat& q) {
  return phys::finite(c) && std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) &&
         std::isfinite(q.z);
}

}  // namespace

double bodyOverlap(const Description& scene, const std::vector<Vec3>& centres,
                   const std::vector<phys::Quat>& orientations) {
  const int n = static_cast<int>(scene.bodies.size());
  std::vector<phys::Obb> obbs(scene.bodies.size());
  std::vector<Bounds> bounds;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Body& b = scene.bodies[k];
    if (!b.solid()) continue;
    if (!finitePose(centres[k], orientations[k])) return kInf;
    // The box itself, or for a capsule the box it is inscribed in (phys::capsuleInBox reads the
    // capsule from it, as World does). The engines' quaternions are unit up to their round-off
    // (float in Bullet): normalized so the axes are, as the narrow phase assumes.
    obbs[k].center = centres[k];
    obbs[k].axes = glm::mat3_cast(glm::normalize(orientations[k]));
    obbs[k].halfExtents = b.halfExtents;
    bounds.push_back(boundsOf(i, obbs[k]));
  }
  // Sort and sweep on x: each body meets only those whose x range begins before its own ends.
  std::sort(bounds.begin(), bounds.end(), [](const Bounds& p, const Bounds& q) { return p.lo.x < q.lo.x; });
  double worst = 0.0;
  for (std::size_t s = 0; s < bounds.size(); ++s) {
    const Bounds& p = bounds[s];
    for (std::size_t t = s + 1; t < bounds.size() && bounds[t].lo.x <= p.hi.x; ++t) {
      const Bounds& q = bounds[t];
      if (q.lo.y > p.hi.y || p.lo.y > q.hi.y || q.lo.z > p.hi.z || p.lo.z > q.hi.z) continue;
      if (!scene.collides(p.body, q.body)) continue;
      const auto i = static_cast<std::size_t>(p.body), j = static_cast<std::size_t>(q.body);
      worst = std::max(worst, pairDepth(scene.bodies[i], obbs[i], scene.bodies[j], obbs[j]));
    }
  }
  return worst;
}

double posePenetration(const Description& scene, const std::vector<Vec3>& centres,
                       const std::vector<phys::Quat>& orientations) {
  return std::max(groundPenetration(scene, centres, orientations), bodyOverlap(scene, centres, orientations));
}

double jointGap(const Description& scene, const std::vector<Vec3>& centres,
                const std::vector<phys::Quat>& orientations) {
  auto point = [&](int body, const Vec3& local) {
    const auto k = static_cast<std::size_t>(body);
    return toWorld(centres[k], orientations[k], local);
  };
  double worst = 0.0;
  for (const Pin& p : scene.pins)
    keepLargest(worst, glm::length(point(p.b, p.localB) - point(p.a, p.localA)));
  for (const Distance& d : scene.distances) {
    if (!d.link) continue;
    const double length = glm::length(point(d.b, d.localB) - point(d.a, d.localA));
    keepLargest(worst, std::isfinite(length) ? std::max({0.0, d.min - length, length - d.max}) : kInf);
  }
  return worst;
}

}  // namespace lab::peers
