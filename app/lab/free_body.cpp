#include "free_body.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "physics/body.h"

namespace lab {
namespace {

using phys::Quat;
using phys::Vec3;

// The rotational state: orientation (body to world) and spin in body axes.
struct Spin {
  Quat q;
  Vec3 w;
};

// d/dt of the state: Euler's equations and the quaternion's kinematics.
Spin rate(const Spin& s, const Vec3& inertia) {
  const Vec3 momentum = inertia * s.w;  // componentwise: principal axes
  Spin d;
  d.w = glm::cross(momentum, s.w) / inertia;
  d.q = s.q * Quat(0.0, s.w.x, s.w.y, s.w.z) * 0.5;
  return d;
}

Spin add(const Spin& s, const Spin& d, double h) {
  return {Quat(s.q.w + h * d.q.w, s.q.x + h * d.q.x, s.q.y + h * d.q.y, s.q.z + h * d.q.z), s.w + h * d.w};
}

Spin rk4(const Spin& s, const Vec3& inertia, double h) {
  const Spin k1 = rate(s, inertia);
  const Spin k2 = rate(add(s, k1, h / 2), inertia);
  const Spin k3 = rate(add(s, k2, h / 2), inertia);
  const Spin k4 = rate(add(s, k3, h), inertia);
  // s + h/6 (k1 + 2 k2 + 2 k3 + k4), summed in that order.
  Spin out = add(s, add(add(add(k1, k2, 2.0), k3, 2.0), k4, 1.0), h / 6);
  // RK4 lets |q| drift by O(h^5) a step; putting it back on the unit sphere changes nothing else.
  out.q = glm::normalize(out.q);
  return out;
}

}  // namespace

std::optional<phys::Vec3> spinAtStart(const Vec3& kept, const Quat& orientation, const Vec3& inertia,
                                      double h) {
  const Vec3 body = glm::conjugate(orientation) * kept;
  Vec3 w = body;
  // w' is quadratic in w, so each pass shrinks the residual by about h |w'| / |w|: a few passes
  // reach round-off at any spin a substep can resolve; 50 is far beyond need and costs nothing.
  for (int k = 0; k < 50; ++k) {
    const Vec3 next = body + glm::cross(inertia * w, w) / inertia * (h / 2);
    const double size = glm::length(next);
    if (!std::isfinite(size)) return std::nullopt;  // diverged
    if (glm::length(next - w) <= 1e-14 * size) return orientation * next;
    w = next;
  }
  return std::nullopt;
}

std::vector<FreeBodyPose> freeBodyPoses(const FreeBodyStart& start, const std::vector<double>& times,
                                        double maxStep) {
  if (!(maxStep > 0.0)) throw std::invalid_argument("free body: the step must be positive");
  if (!(start.inertia.x > 0.0 && start.inertia.y > 0.0 && start.inertia.z > 0.0) ||
      !std::isfinite(start.inertia.x + start.inertia.y + start.inertia.z)) {
    throw std::invalid_argument("free body: the principal moments must be finite and positive");
  }
  Spin s{glm::normalize(start.orientation), glm::conjugate(start.orientation) * start.angularVelocity};
  double t = 0.0;
  std::vector<FreeBodyPose> poses;
  for (const double until : times) {
    if (!(until >= t)) throw std::invalid_argument("free body: the times must be ascending from 0");
    const double span = until - t;
    const int steps = std::max(1, static_cast<int>(std::ceil(span / maxStep)));
    const double h = span / steps;
    if (span > 0.0) {
      for (int i = 0; i < steps; ++i) s = rk4(s, start.inertia, h);
    }
    t = until;
    poses.push_back({start.centre + start.velocity * t, s.q});
  }
  return poses;
}

double cornerDistance(const FreeBodyPose& a, const FreeBodyPose& b, const Vec3& halfExtents) {
  double worst = 0.0;
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner = phys::boxCornerLocal(halfExtents, k);
    const double d = glm::length((a.centre + a.orientation * corner) - (b.centre + b.orientation * corner));
    if (std::isnan(d)) return d;  // std::max would drop it
    worst = std::max(worst, d);
  }
  return worst;
}

double freeBodyUncertainty(const FreeBodyStart& start, const std::vector<double>& times,
                           const Vec3& halfExtents) {
  const std::vector<FreeBodyPose> coarse = freeBodyPoses(start, times, kFreeBodyStep);
  const std::vector<FreeBodyPose> fine = freeBodyPoses(start, times, kFreeBodyStep / 2);
  double worst = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    worst = std::max(worst, cornerDistance(coarse[i], fine[i], halfExtents));
  }
  return worst;
}

}  // namespace lab
