#pragma once
// A run of the method overlay: solver settings written as "key=value,key=value" with the
// <solver> element's attribute names (docs/scene-format.md), applied on top of the scene
// file's own. "method=xpbd", "iterations=8", "substeps=8,iterations=1".
#include <optional>
#include <string>
#include <string_view>

#include "physics/settings.h"

namespace sandbox {

inline constexpr int kMinOverlayRuns = 2;
inline constexpr int kMaxOverlayRuns = 4;

struct OverlaySpec {
  std::string text;  ///< as given, for the legend
  // Each override is applied only if given.
  std::optional<phys::SolverMethod> method;
  std::optional<int> iterations, substeps;
  std::optional<double> dt, bodyDamping, restitution, compliance, epsilon, slop, depenetrationSpeed;

  /// The scene's settings with these overrides.
  phys::SolverSettings applyTo(phys::SolverSettings base) const;
};

struct ParsedOverlaySpec {
  OverlaySpec spec;
  std::string error;  ///< empty on success; otherwise which key or value is wrong
};

ParsedOverlaySpec parseOverlaySpec(std::string_view text);

/// "gauss-seidel 3x1 dt 16.7 ms": method, iterations x substeps and dt, for legends.
std::string describeSolver(const phys::SolverSettings& s);

}  // namespace sandbox
