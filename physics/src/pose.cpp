#include "pose.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
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

glm::dmat3 nearestRotation(const glm::dmat3& unscaled) {
  // A box flung 1e110 m apart has entries near 1e220, whose determinant overflows: far from 1,
  // the matrix is first scaled by a power of two near its largest entry. Not otherwise, since
  // cbrt then rounds differently and a ragdoll built from these poses would move by round-off.
  // No finite entry, or none but zeros: there is no shape to read a rotation from.
  Real largest = 0.0;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) largest = std::max(largest, std::abs(unscaled[c][r]));
  }
  if (!(largest > 0.0) || !std::isfinite(largest)) return glm::dmat3(1.0);
  constexpr Real kFar = 1e100;
  const bool far = largest > kFar || largest < 1.0 / kFar;
  const glm::dmat3 A = far ? unscaled * std::ldexp(1.0, -std::ilogb(largest)) : unscaled;
  const Real det = glm::determinant(A);
  if (!(det > 0.0)) return gramSchmidt(A);
  // Newton's iteration takes a singular value s to (s + 1/s) / 2, so unscaled it needs about
  // log2(s) steps before it converges: 20 were not enough for a 0.001 x 10 x 0.001 m box, whose
  // A has singular values 1e8 apart, and each save and reload of it turned it by 1.5e-5 rad.
  // Scaled by Higham's gamma = sqrt(|X^-1| / |X|) (Frobenius norms), which brings the largest
  // and smallest singular values together, it converges in under ten steps at any aspect ratio;
  // near convergence gamma is 1 to round-off and the last steps are plain Newton, quadratic.
  glm::dmat3 X = A / std::cbrt(det);
  auto frobenius = [](const glm::dmat3& M) {
    return std::sqrt(glm::dot(M[0], M[0]) + glm::dot(M[1], M[1]) + glm::dot(M[2], M[2]));
  };
  constexpr int kMaxIterations = 40;
  constexpr Real kScaleUntil = 1e-2;  // change per step below which gamma is left at 1
  Real change = 1.0;
  for (int i = 0; i < kMaxIterations && change >= 1e-14; ++i) {
    const glm::dmat3 inverseT = glm::transpose(glm::inverse(X));
    const Real gamma = change > kScaleUntil ? std::sqrt(frobenius(inverseT) / frobenius(X)) : 1.0;
    const glm::dmat3 next = 0.5 * (gamma * X + inverseT / gamma);
    change = 0.0;
    for (int c = 0; c < 3; ++c) change += glm::length(next[c] - X[c]);
    X = next;
  }
  // Two corners that have met leave A all but singular, and its inverse can overflow on the way:
  // the frame of its two longest edges is then as good an answer as there is.
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(X[c].x + X[c].y + X[c].z)) return gramSchmidt(A);
  }
  return X;
}

Vec3 particleCentre(const Particles& p, const Body& body) {
  const Vec3* x = &p.position[body.firstParticle];
  // Each particle's share summed, not the sum divided: the same digits for 4 or 8 particles (a
  // power of two), and no overflow for a body near the largest double (a bound of infinity).
  const Real share = 1.0 / static_cast<Real>(body.particleCount);
  Vec3 centre(0.0);
  for (int j = 0; j < body.particleCount; ++j) centre += x[j] * share;
  return centre;
}

BodyPose particleBodyPose(const Particles& p, const Body& body) {
  BodyPose pose;
  const Vec3* x = &p.position[body.firstParticle];
  pose.center = particleCentre(p, body);
  // A = sum (x_j - c) r_j^T is R S for a rigid motion.
  glm::dmat3 A(0.0);
  for (int j = 0; j < body.particleCount; ++j)
    A += glm::outerProduct(x[j] - pose.center, boxParticleLocal(body.model, body.halfExtents, j));
  pose.orientation = glm::normalize(glm::quat_cast(nearestRotation(A)));
  return pose;
}

}  // namespace phys::detail
