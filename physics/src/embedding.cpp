#include "passes.h"

namespace phys::detail {

Vec3 embeddedPosition(const std::vector<Vec3>& x, const Embedding& e) {
  Vec3 p(0.0);
  for (int i = 0; i < e.count; ++i) p += e.weight[i] * x[e.particle[i]];
  return p;
}

Real embeddedWeight(const std::vector<Real>& inverseMass, const Embedding& e) {
  Real sum = 0.0;
  for (int i = 0; i < e.count; ++i) sum += e.weight[i] * e.weight[i] * inverseMass[e.particle[i]];
  return sum;
}

void shiftEmbedded(std::vector<Vec3>& x, const std::vector<Real>& inverseMass, const Embedding& e,
                   const Vec3& step) {
  for (int i = 0; i < e.count; ++i) {
    const Real w = inverseMass[e.particle[i]];
    if (w != 0.0) x[e.particle[i]] += (e.weight[i] * w) * step;  // a pinned one never moves
  }
}

// REFERENCES.md (Jakobsen, "a point embedded in a stick", generalised): xi += ci wi D / sum cj^2 wj.
void moveEmbedded(std::vector<Vec3>& x, const std::vector<Real>& inverseMass, const Embedding& e,
                  const Vec3& D) {
  const Real denominator = embeddedWeight(inverseMass, e);
  if (denominator == 0.0) return;  // every carrier pinned
  shiftEmbedded(x, inverseMass, e, D / denominator);
}

Embedding rigidEmbedding(const Body& box, const Vec3& u) {
  const std::array<Real, 4> w = tetraWeights(u);
  Embedding e;
  e.count = 4;
  for (int j = 0; j < 4; ++j) {
    e.particle[j] = box.firstParticle + (box.model == BodyModel::Tetra ? j : kTetraCorner[j]);
    e.weight[j] = w[j];
  }
  return e;
}

}  // namespace phys::detail
