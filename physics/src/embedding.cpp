#include "passes.h"

namespace phys::detail {

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
