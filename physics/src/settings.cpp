#include "physics/settings.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

#include "physics/body.h"
#include "physics/types.h"
#include "require.h"

namespace phys {
namespace {

// Joins the reasons with "; " (the caller prefixes what was being checked).
std::string joined(const std::ostringstream& why) {
  std::string out = why.str();
  if (!out.empty()) out.resize(out.size() - 2);
  return out;
}

bool finiteNonNegative(Real v) {
  return std::isfinite(v) && v >= 0.0;
}

}  // namespace

std::string validate(const Material& m) {
  std::ostringstream why;
  if (!finiteNonNegative(m.staticFriction)) why << "static friction must be finite and >= 0; ";
  if (!finiteNonNegative(m.dynamicFriction)) why << "dynamic friction must be finite and >= 0; ";
  return joined(why);
}

Material combine(const Material& a, const Material& b) {
  return {std::sqrt(a.staticFriction * b.staticFriction), std::sqrt(a.dynamicFriction * b.dynamicFriction)};
}

bool groundWithinBound(const WorldSettings& s) {
  const Real n = glm::length(s.groundNormal);
  if (!s.ground || !std::isfinite(s.groundHeight) || !(n >= 1e-9 && std::isfinite(n))) return true;
  const Vec3 nearest = s.groundNormal * (s.groundHeight / n);
  return std::max({std::abs(nearest.x), std::abs(nearest.y), std::abs(nearest.z)}) <= s.bound;
}

std::string validate(const WorldSettings& s) {
  std::ostringstream why;
  if (s.gravityMode != GravityMode::Uniform && s.gravityMode != GravityMode::Point)
    why << "gravityMode must be Uniform or Point (is " << static_cast<int>(s.gravityMode) << "); ";
  if (!finite(s.gravity)) why << "gravity must be finite; ";
  if (!finite(s.gravityPoint)) why << "gravityPoint must be finite; ";
  if (!finiteNonNegative(s.gravityStrength)) why << "gravityStrength must be finite and >= 0 (m/s^2); ";
  if (!finiteNonNegative(s.damping)) why << "damping must be finite and >= 0 (1/s); ";
  // Its length too must be finite: 1e200 overflows it to inf, and normalising would make the normal 0.
  if (const Real n = glm::length(s.groundNormal); !finite(s.groundNormal) || !(n >= 1e-9 && std::isfinite(n)))
    why << "groundNormal must be non-zero and of finite length (is " << s.groundNormal.x << " "
        << s.groundNormal.y << " " << s.groundNormal.z << "); ";
  if (!std::isfinite(s.groundHeight)) why << "groundHeight must be finite; ";
  if (!groundWithinBound(s)) why << "groundHeight puts the ground beyond the bound of " << s.bound << " m; ";
  if (const std::string m = validate(s.groundMaterial); !m.empty()) why << "groundMaterial: " << m << "; ";
  if (!(s.bound > 0.0)) why << "bound must be > 0 (m); ";
  if (!(s.shapeCheckInterval > 0.0 && std::isfinite(s.shapeCheckInterval)))
    why << "shapeCheckInterval must be finite and > 0 (s); ";
  return joined(why);
}

std::string validate(const SolverSettings& s) {
  std::ostringstream why;
  // A value cast from outside the enum would relax no stick at all (ConstraintGraph::relaxSticks).
  if (static_cast<int>(s.method) < 0 || s.method > SolverMethod::Shake)
    why << "method must be one of SolverMethod's (is " << static_cast<int>(s.method) << "); ";
  if (!std::isfinite(s.dt) || s.dt < kMinDt || s.dt > kMaxDt) {
    why << "dt must be from " << kMinDt << " to " << kMaxDt << " (s); ";
  }
  if (s.substeps < 1 || s.substeps > kMaxSubsteps)
    why << "substeps must be from 1 to " << kMaxSubsteps << "; ";
  if (s.iterations < 1 || s.iterations > kMaxIterations)
    why << "iterations must be from 1 to " << kMaxIterations << "; ";
  if (!finiteNonNegative(s.featureEpsilon)) why << "featureEpsilon must be finite and >= 0 (m); ";
  if (!finiteNonNegative(s.contactSlop)) why << "contactSlop must be finite and >= 0 (m); ";
  if (!(s.bodyDamping >= 0.0 && s.bodyDamping <= 1.0)) why << "bodyDamping must be from 0 to 1; ";
  if (!(s.restitution >= 0.0 && s.restitution <= 1.0)) why << "restitution must be from 0 to 1; ";
  if (!(s.compliance >= 0.0 && s.compliance <= kMaxCompliance)) {
    why << "compliance must be from 0 to " << kMaxCompliance << " (m/N); ";
  }
  if (!(s.maxDepenetrationSpeed > 0.0)) {
    why << "maxDepenetrationSpeed must be > 0 (m/s; infinity for no limit); ";
  }
  const BroadPhaseSettings& b = s.broadPhase;
  if (b.maxStrips < 1 || b.maxStrips > kMaxStrips)
    why << "broadPhase.maxStrips must be from 1 to " << kMaxStrips << "; ";
  if (b.stripsPerBody < 1 || b.stripsPerBody > kMaxStrips)
    why << "broadPhase.stripsPerBody must be from 1 to " << kMaxStrips << "; ";
  if (b.maxStripsPerBody < 1 || b.maxStripsPerBody > kMaxStrips)
    why << "broadPhase.maxStripsPerBody must be from 1 to " << kMaxStrips << "; ";
  if (s.threads < 1 || s.threads > kMaxThreads) why << "threads must be from 1 to " << kMaxThreads << "; ";
  if (!finiteNonNegative(s.sleep.speed)) why << "sleep.speed must be finite and >= 0 (m/s); ";
  if (!finiteNonNegative(s.sleep.time)) why << "sleep.time must be finite and >= 0 (s); ";
  const JointProjectionSettings& j = s.jointProjection;
  if (!(j.tolerance > 0.0 && std::isfinite(j.tolerance)))
    why << "jointProjection.tolerance must be finite and > 0 (m); ";
  if (j.iterations < 1 || j.iterations > kMaxProjectionIterations)
    why << "jointProjection.iterations must be from 1 to " << kMaxProjectionIterations << "; ";
  const PartingSettings& p = s.parting;
  if (p.plainSweeps < 0 || p.plainSweeps > kMaxPartingSweeps)
    why << "parting.plainSweeps must be from 0 to " << kMaxPartingSweeps << "; ";
  if (p.overRelaxedSweeps < 0 || p.overRelaxedSweeps > kMaxPartingSweeps)
    why << "parting.overRelaxedSweeps must be from 0 to " << kMaxPartingSweeps << "; ";
  if (!(p.overRelaxation >= 1.0 && p.overRelaxation < 2.0))
    why << "parting.overRelaxation must be from 1 to below 2; ";
  if (!(p.tolerance > 0.0 && std::isfinite(p.tolerance)))
    why << "parting.tolerance must be finite and > 0 (m); ";
  if (p.progressSweeps < 1 || p.progressSweeps > kMaxPartingSweeps)
    why << "parting.progressSweeps must be from 1 to " << kMaxPartingSweeps << "; ";
  if (!finiteNonNegative(s.manifoldReuse.maxShift))
    why << "manifoldReuse.maxShift must be finite and >= 0 (m); ";
  if (!finiteNonNegative(s.manifoldReuse.maxTurn))
    why << "manifoldReuse.maxTurn must be finite and >= 0 (rad); ";
  return joined(why);
}

std::string_view toString(SolverMethod method) {
  detail::requireEnum(static_cast<int>(method), static_cast<int>(SolverMethod::Shake) + 1,
                      "toString(SolverMethod)", "method", "SolverMethod");
  static constexpr std::array<std::string_view, 4> kNames = {"gauss-seidel", "jacobi", "xpbd", "shake"};
  return kNames[static_cast<std::size_t>(method)];
}

std::optional<SolverMethod> parseSolverMethod(std::string_view name) {
  for (SolverMethod m :
       {SolverMethod::GaussSeidel, SolverMethod::Jacobi, SolverMethod::Xpbd, SolverMethod::Shake}) {
    if (name == toString(m)) return m;
  }
  return std::nullopt;
}

std::string_view toString(GravityMode mode) {
  detail::requireEnum(static_cast<int>(mode), static_cast<int>(GravityMode::Point) + 1,
                      "toString(GravityMode)", "mode", "GravityMode");
  return mode == GravityMode::Point ? "point" : "uniform";
}

std::optional<GravityMode> parseGravityMode(std::string_view name) {
  if (name == "uniform") return GravityMode::Uniform;
  if (name == "point") return GravityMode::Point;
  return std::nullopt;
}

}  // namespace phys
