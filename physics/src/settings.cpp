#include "physics/settings.h"

#include <cmath>
#include <sstream>

namespace phys {
namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

std::string validate(const WorldSettings& s) {
  std::ostringstream why;
  if (!finite(s.gravity)) why << "gravity must be finite; ";
  if (!std::isfinite(s.damping) || s.damping < 0.0) why << "damping must be finite and >= 0 (1/s); ";
  if (!std::isfinite(s.groundHeight)) why << "groundHeight must be finite; ";
  if (!std::isfinite(s.groundStaticFriction) || s.groundStaticFriction < 0.0)
    why << "groundStaticFriction must be finite and >= 0; ";
  if (!std::isfinite(s.groundDynamicFriction) || s.groundDynamicFriction < 0.0)
    why << "groundDynamicFriction must be finite and >= 0; ";
  std::string out = why.str();
  if (!out.empty()) out.resize(out.size() - 2);
  return out;
}

std::string validate(const SolverSettings& s) {
  std::ostringstream why;
  if (!std::isfinite(s.dt) || s.dt <= 0.0) why << "dt must be finite and > 0 (s); ";
  if (s.substeps < 1) why << "substeps must be >= 1; ";
  if (s.iterations < 1) why << "iterations must be >= 1; ";
  std::string out = why.str();
  if (!out.empty()) out.resize(out.size() - 2);
  return out;
}

}  // namespace phys
