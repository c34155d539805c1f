#pragma once
// The exact motion of a free rigid body, for `lab converge` (docs/lab.md, "lab converge"): no
// force, no torque, so its centre moves in a straight line and its spin obeys Euler's equations,
//   I w' = (I w) x w   (w and I in the body's principal axes),   q' = q (0, w) / 2,
// integrated here by classical Runge-Kutta at a step small enough that the answer is good to
// about 1e-12 m over seconds (FreeBodyReference::uncertainty measures it). This is the lab's own
// code, apart from the physics it measures, so that a rigid or particle box is checked against
// something that shares none of its integrator.
#include <optional>
#include <vector>

#include "physics/types.h"

namespace lab {

/// A free body at time 0.
struct FreeBodyStart {
  phys::Vec3 centre{0.0};              ///< unit: m
  phys::Quat orientation{1, 0, 0, 0};  ///< body to world, unit quaternion
  phys::Vec3 velocity{0.0};            ///< unit: m/s; of the centre
  phys::Vec3 angularVelocity{0.0};     ///< unit: rad/s; world frame
  /// unit: kg m^2; principal moments along the body's x, y, z. Only their ratios matter.
  phys::Vec3 inertia{1.0};
};

/// The spin w(0) of a body whose World keeps w(-h/2), its spin half a substep h back (the physics
/// keeps velocities of the substep's middle, docs/physics.md, "Rigid bodies"): the root of
/// w = kept + w'(w) h / 2 under Euler's equations, by fixed-point iteration to round-off.
/// `orientation` and `inertia` as in FreeBodyStart; kept in world frame. unit: rad/s. None where
/// the iteration does not converge: beyond about h |w| = 2, where a substep cannot resolve the spin.
std::optional<phys::Vec3> spinAtStart(const phys::Vec3& kept, const phys::Quat& orientation,
                                      const phys::Vec3& inertia, double h);

/// A body's pose at some time.
struct FreeBodyPose {
  phys::Vec3 centre{0.0};
  phys::Quat orientation{1, 0, 0, 0};
};

/// The body's poses at the given times (s, ascending, >= 0), integrated with steps of at most
/// `maxStep` seconds (each interval between times is cut into equal steps).
std::vector<FreeBodyPose> freeBodyPoses(const FreeBodyStart& start, const std::vector<double>& times,
                                        double maxStep);

/// The reference's step, unit: s. 1e-4 s at spins of a few turns a second makes RK4's error per
/// unit time about (w h)^4 ~ 1e-13; the uncertainty below is measured, not assumed.
inline constexpr double kFreeBodyStep = 1.0e-4;

/// The largest distance, over the times and the eight corners (+-halfExtents) of the body, between
/// the poses at kFreeBodyStep and at half of it: how far the reference itself may be off. unit: m
double freeBodyUncertainty(const FreeBodyStart& start, const std::vector<double>& times,
                           const phys::Vec3& halfExtents);

/// The largest distance between the eight corners of a box of `halfExtents` placed at `a` and at
/// `b`. unit: m
double cornerDistance(const FreeBodyPose& a, const FreeBodyPose& b, const phys::Vec3& halfExtents);

}  // namespace lab
