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

// The same point carried by the other inscribed tetrahedron (corners 1, 2, 4, 7: each of 0, 3, 5, 6
// with its x bit flipped). `a` is a corners body's rigid embedding (rigidEmbedding), weights
// c_j = (1 + s_j . u) / 4 over corners s_j; the mirrored corner's weight is c_j - s_jx u_x / 2,
// with u_x = sum_j s_jx c_j (the four s_j of a regular tetrahedron have sum s_j s_j^T = 4 I).
Embedding otherTetrahedron(const Embedding& a) {
  Real ux = 0.0;
  Real sx[4];
  for (int j = 0; j < 4; ++j) {
    sx[j] = (kTetraCorner[j] & 1) ? 1.0 : -1.0;
    ux += sx[j] * a.weight[j];
  }
  Embedding b = a;
  for (int j = 0; j < 4; ++j) {
    b.weight[j] = a.weight[j] - 0.5 * sx[j] * ux;
    b.particle[j] = sx[j] > 0.0 ? ParticleId(a.particle[j] - 1u) : ParticleId(a.particle[j] + 1u);
  }
  return b;
}

}  // namespace phys::detail
