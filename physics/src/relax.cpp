// The four ways to relax sticks. Each is one pass over all sticks; the caller repeats it.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "passes.h"

namespace phys::detail {
namespace {

// What every method needs to know of one stick before it corrects it.
struct StickState {
  Real w1, w2;  // inverse masses
  Vec3 d;       // x2 - x1
  Real length;  // |d|
  Real target;  // the length to move to
};

// Jakobsen's projection of one measured stick. A pinned end (w = 0) is never written: 0 times
// a non-finite correction would still be NaN, and a pinned particle must not move.
void project(Particles& p, const Stick& s, const StickState& m) {
  const Real k = (m.length - m.target) / (m.length * (m.w1 + m.w2));
  if (m.w1 != 0.0) p.position[s.a] += (m.w1 * k) * m.d;
  if (m.w2 != 0.0) p.position[s.b] -= (m.w2 * k) * m.d;
}

// False when the stick needs no correction: both ends pinned, or within its bounds.
bool measure(const Particles& p, const Stick& s, StickState& out) {
  out.w1 = p.inverseMass[s.a];
  out.w2 = p.inverseMass[s.b];
  if (out.w1 + out.w2 == 0.0) return false;
  out.d = p.position[s.b] - p.position[s.a];
  out.length = glm::length(out.d);
  out.target = stickTarget(s, out.length);
  return out.target >= 0.0;
}

}  // namespace

// Jakobsen 2001, "Advanced Character Physics", stick constraint, with the sign of the printed
// listing corrected (REFERENCES.md): s = (|d| - r) / (|d| (w1 + w2)); x1 += w1 s d; x2 -= w2 s d.
void relaxGaussSeidel(Particles& p, std::span<const Stick> sticks) {
  StickState m;
  for (const Stick& s : sticks) {
    if (!measure(p, s, m) || m.length == 0.0) continue;  // no direction to push along at 0
    project(p, s, m);
  }
}

// Jacobi: every stick's correction from the same positions, summed per particle. Each stick's
// pair of corrections is scaled by one factor, 1 / the larger number of sticks at either end,
// so the two stay equal and opposite in momentum (averaging each particle by its own count
// would not, and a free body would drift); the factor keeps a particle pulled by many sticks
// from overshooting (Müller et al. 2007 discuss both orders).
void relaxJacobi(Particles& p, std::span<const Stick> sticks, std::span<const Real> degree,
                 std::span<Vec3> delta) {
  std::fill(delta.begin(), delta.end(), Vec3(0.0));
  StickState m;
  for (const Stick& s : sticks) {
    if (!measure(p, s, m) || m.length == 0.0) continue;
    const Real k = (m.length - m.target) / (m.length * (m.w1 + m.w2) * std::max(degree[s.a], degree[s.b]));
    delta[s.a] += (m.w1 * k) * m.d;
    delta[s.b] -= (m.w2 * k) * m.d;
  }
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (p.inverseMass[i] != 0.0) p.position[i] += delta[i];
  }
}

// XPBD, Macklin, Müller and Chentanez 2016, eq. 18: dlambda = (-C - a~ lambda) / (sum w + a~),
// a~ = compliance / h^2; gradient of C = |x2 - x1| - r is -n for x1 and +n for x2. The world's
// compliance adds to each stick's: compliances in series add, as springs' inverse stiffnesses do.
void relaxXpbd(Particles& p, std::span<const Stick> sticks, std::span<Real> lambda, Real h, Real compliance) {
  const Real inverseH2 = 1.0 / (h * h);
  StickState m;
  for (std::size_t c = 0; c < sticks.size(); ++c) {
    const Stick& s = sticks[c];
    if (!measure(p, s, m) || m.length == 0.0) continue;
    const Real alpha =
        (s.compliance + compliance) * inverseH2;  // finite: both and h are bounded (settings.h)
    const Real dLambda = (-(m.length - m.target) - alpha * lambda[c]) / (m.w1 + m.w2 + alpha);
    lambda[c] += dLambda;
    const Vec3 n = m.d / m.length;
    if (m.w1 != 0.0) p.position[s.a] -= (m.w1 * dLambda) * n;
    if (m.w2 != 0.0) p.position[s.b] += (m.w2 * dLambda) * n;
  }
}

// SHAKE for one stick: move x1 by -w1 g r and x2 by +w2 g r, where r is the stick at the start
// of the substep, with g the root of |d + (w1 + w2) g r|^2 = L^2 nearest zero. Where no root
// exists (the stick turned too far within one substep), fall back to Jakobsen's projection.
void relaxShake(Particles& p, std::span<const Stick> sticks) {
  StickState m;
  for (const Stick& s : sticks) {
    if (!measure(p, s, m)) continue;
    const Real w1 = m.w1, w2 = m.w2, w = w1 + w2, length = m.length, target = m.target;
    const Vec3& d = m.d;
    const Vec3 r = p.previous[s.b] - p.previous[s.a];
    const Real qa = w * w * glm::dot(r, r);
    const Real qb = 2.0 * w * glm::dot(d, r);
    const Real qc = glm::dot(d, d) - target * target;
    const Real discriminant = qb * qb - 4.0 * qa * qc;
    if (qa > 0.0 && discriminant >= 0.0) {
      // The numerically stable pair of roots; keep the smaller in magnitude.
      const Real q = -0.5 * (qb + std::copysign(std::sqrt(discriminant), qb));
      Real g = 0.0;
      if (q != 0.0) {
        const Real g1 = q / qa, g2 = qc / q;
        g = std::abs(g1) < std::abs(g2) ? g1 : g2;
      }
      if (w1 != 0.0) p.position[s.a] -= (w1 * g) * r;
      if (w2 != 0.0) p.position[s.b] += (w2 * g) * r;
    } else if (length > 0.0) {
      project(p, s, m);
    }
  }
}

}  // namespace phys::detail
