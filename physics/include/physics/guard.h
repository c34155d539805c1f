#pragma once
// The guard (Stage::Guard): after every substep, a particle gone non-finite or out of the world's
// bound, and every few substeps a body crushed past recovery, is frozen, put back whole where the
// guard last found it good, and reported. Nothing non-finite leaves the step.
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "physics/body.h"
#include "physics/constraints.h"
#include "physics/particles.h"
#include "physics/rigid_bodies.h"
#include "physics/workers.h"

namespace phys {

/// What the guard did to a particle that went bad.
struct FreezeReport {
  std::string name;       ///< the box's name, else the particle's, else "particle N"
  std::string reason;     ///< "non-finite position", "left the world bound of B m", "crushed: ...", ...
  ParticleId particle;    ///< the first bad particle (0 for a rigid body, which has none)
  Real time;              ///< unit: s; simulated time of the substep that caught it
  BodyId body = kNoBody;  ///< the body frozen whole, or kNoBody for a loose particle
};

/// What the guard reads of the world; it writes only the particles of what it freezes.
struct GuardInput {
  Particles& particles;
  std::span<const Body> bodies;
  std::span<const Stick> sticks;
  std::span<const std::string> particleNames;
  std::span<const BodyId> particleBodies;  ///< per particle: its body, or kNoBody
  Real time = 0.0;                         ///< unit: s; of the substep
};

class Guard {
 public:
  /// A new particle, good where it was created.
  void addParticle(const Vec3& position) { checked_.push_back(position); }
  /// A new body, not crushed.
  void addBody();
  /// Per particle, where the guard last found it good: the integration writes x there before it
  /// moves a particle, so a body frozen in a substep goes back to where that substep started.
  std::span<Vec3> checked() { return checked_; }
  /// The same per rigid body, its pose: written by its integration, so that a rigid body frozen in
  /// a substep goes back to where that substep started, not to its previous pose, which the
  /// parting moves with it.
  void addRigidBody(const Vec3& position, const Quat& orientation) {
    checkedRigidPosition_.push_back(position);
    checkedRigidOrientation_.push_back(orientation);
  }
  std::span<Vec3> checkedRigidPositions() { return checkedRigidPosition_; }
  std::span<Quat> checkedRigidOrientations() { return checkedRigidOrientation_; }
  void setCallback(std::function<void(const FreezeReport&)> callback) { onFreeze_ = std::move(callback); }
  /// Gives the callback each freeze it has not been given, oldest first. The world calls it once it
  /// is whole again (after a step, not inside one), so that the callback may change the world.
  void report();
  std::span<const FreezeReport> freezes() const { return freezes_; }

  /// Freezes every particle (and its whole body) that is non-finite or beyond `bound` (m) on an
  /// axis. The look for any such particle runs in ranges on `workers`, when given.
  void checkParticles(const GuardInput& in, Real bound, const Workers* workers = nullptr);
  /// Freezes each rigid body whose pose or velocities are non-finite or whose centre is beyond
  /// `bound` (m) on an axis: put back at the pose its substep started from (finite, as the last
  /// check found it), at rest, with no inverse mass or inertia, so nothing moves it again.
  void checkRigidBodies(RigidBodies& rigid, std::span<const Body> bodies, Real bound, Real time);
  /// True when the shapes are due a look (every `interval` s of simulated time).
  bool shapesDue(Real time) const { return time >= nextShapeCheck_; }
  /// Freezes each body whose worst stick has been more than kCrushedStickError off its length for
  /// kCrushedTime running; the next look is `interval` (s) from now.
  void checkShapes(const GuardInput& in, Real interval);

 private:
  void freeze(const GuardInput& in, ParticleId bad, const std::string& reason);
  static Real worstStickError(const GuardInput& in, const Body& box);

  std::vector<Vec3> checked_;                  // per particle
  std::vector<Vec3> checkedRigidPosition_;     // per rigid body
  std::vector<Quat> checkedRigidOrientation_;  // per rigid body
  std::vector<Real> crushedSince_;  // per body: time it went past kCrushedStickError, infinity if not
  Real nextShapeCheck_ = 0.0;       // s
  std::function<void(const FreezeReport&)> onFreeze_;
  std::vector<FreezeReport> freezes_;
  std::size_t reported_ = 0;  // freezes_ given to the callback (report)
};

}  // namespace phys
