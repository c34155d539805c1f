#pragma once
// What the world can tell about itself: accuracy figures, and where the step's time went.
#include <cstdint>

#include "physics/types.h"

namespace phys {

/// Figures of the current state (World::metrics()).
struct Metrics {
  Real kineticEnergy = 0.0;       ///< unit: J; from Verlet velocities, pinned particles excluded
  Real potentialEnergy = 0.0;     ///< unit: J; m g h (uniform) or m s |x - p| (point gravity)
  Real maxConstraintError = 0.0;  ///< unitless; max over sticks of |violation| / rest length
  Real rmsConstraintError = 0.0;  ///< unitless; root mean square of the same
  Real maxJointError = 0.0;   ///< unit: m; max over links of the distance outside [min, max] (a pin's gap)
  Real maxPenetration = 0.0;  ///< unit: m; deepest point below the ground or inside another box now
  Real maxSpeed = 0.0;        ///< unit: m/s
  int contacts = 0;           ///< ground contact points pushed, and box-box contact points, in the last step
  int frozen = 0;             ///< particles frozen by the guard so far

  Real energy() const { return kineticEnergy + potentialEnergy; }
};

/// Wall-clock time of each phase of the last World::step(), summed over its substeps.
struct Profile {
  double integrate = 0.0;    ///< unit: ms
  double constraints = 0.0;  ///< unit: ms; relaxation of the sticks
  double collide = 0.0;      ///< unit: ms; box frames, broad phase and narrow phase
  double contacts = 0.0;     ///< unit: ms; contact projection (ground and box-box), all iterations
  double friction = 0.0;     ///< unit: ms; friction, and body damping (SolverSettings::bodyDamping)
  double guard = 0.0;        ///< unit: ms; NaN and bound checks
  double total = 0.0;        ///< unit: ms; the whole step
};

}  // namespace phys
