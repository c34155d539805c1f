#include "passes.h"

namespace phys::detail {

Vec3 embeddedPosition(const std::vector<Vec3>& x, const Embedding& e) {
  Vec3 p(0.0);
  for (int i = 0; i < e.count; ++i) p += e.weight[i] * x[e.particle[i]];
  return p;
}

// REFERENCES.md (Jakobsen, "a point embedded in a stick", generalised): xi += ci wi D / sum cj^2 wj.
void moveEmbedded(std::vector<Vec3>& x, const std::vector<Real>& inverseMass, const Embedding& e, const Vec3& D) {
  Real denominator = 0.0;
  for (int i = 0; i < e.count; ++i) denominator += e.weight[i] * e.weight[i] * inverseMass[e.particle[i]];
  if (denominator == 0.0) return;  // every carrier pinned
  const Vec3 scaled = D / denominator;
  for (int i = 0; i < e.count; ++i) {
    const Real w = inverseMass[e.particle[i]];
    if (w != 0.0) x[e.particle[i]] += (e.weight[i] * w) * scaled;  // a pinned one never moves
  }
}

}  // namespace phys::detail
