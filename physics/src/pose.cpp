#include "pose.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace phys::detail {
namespace {

glm::dmat3 gramSchmidt(const glm::dmat3& A) {
  Vec3 x = A[0], y = A[1];
  const Real lx = glm::length(x);
  x = lx > 0.0 ? x / lx : Vec3(1, 0, 0);
  y -= glm::dot(y, x) * x;
  const Real ly = glm::length(y);
  y = ly > 1e-12 ? y / ly
                 : glm::normalize(glm::cross(x, std::abs(x.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
  return glm::dmat3(x, y, glm::cross(x, y));
}

}  // namespace

glm::dmat3 nearestRotation(const glm::dmat3& A) {
  const Real det = glm::determinant(A);
  if (!(det > 0.0)) return gramSchmidt(A);
  // Scale to unit determinant first: the iteration then converges in a handful of steps.
  glm::dmat3 X = A / std::cbrt(det);
  for (int i = 0; i < 20; ++i) {
    const glm::dmat3 next = 0.5 * (X + glm::transpose(glm::inverse(X)));
    Real change = 0.0;
    for (int c = 0; c < 3; ++c) change += glm::length(next[c] - X[c]);
    X = next;
    if (change < 1e-14) break;
  }
  return X;
}

}  // namespace phys::detail
