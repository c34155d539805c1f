#pragma once
// Every tunable of the world and the solver, with its default and unit. The sandbox's panels,
// the scene loader and the tests read the defaults from here and nowhere else.
#include <string>

#include "physics/types.h"

namespace phys {

/// Forces and the ground: what the world is like.
struct WorldSettings {
  Vec3 gravity{0.0, -9.81, 0.0};  ///< unit: m/s^2
  /// The seed's "wind resistance": velocity decays as exp(-damping * t). It acts on velocity
  /// only (REFERENCES.md: Jakobsen's "1.99" form pulls resting particles towards the origin).
  Real damping = 0.0;               ///< unit: 1/s
  bool ground = true;               ///< false: nothing below, bodies fall for ever
  Real groundHeight = 0.0;          ///< unit: m; the ground is the plane y = groundHeight
  Real groundStaticFriction = 0.8;  ///< unitless; tangential motion up to mu_s * depth stops
  Real groundDynamicFriction = 0.6; ///< unitless; otherwise it is cut by mu_d * depth
};

/// How the equations are stepped and relaxed.
struct SolverSettings {
  Real dt = 1.0 / 60.0;  ///< unit: s; time advanced by one World::step()
  int substeps = 1;      ///< integrations per step, each of dt / substeps
  int iterations = 3;    ///< relaxation passes per substep (the seed's 3)
};

/// Empty when the settings can be stepped; otherwise says which field is wrong and why.
std::string validate(const WorldSettings& settings);
/// Empty when the settings can be stepped; otherwise says which field is wrong and why.
std::string validate(const SolverSettings& settings);

}  // namespace phys
