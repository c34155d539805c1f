#pragma once
// Parting without velocity (Stage::Parting): overlaps deeper than the feature epsilon that a
// substep starts with are removed by moving bodies whole, x and x* alike (a rigid body's position
// and previous position), solved together for all pairs and the ground (docs/physics.md, "Where
// energy could come from nowhere"). Bodies joined by sticks, links or joints move as one group; the
// groups are a union-find over the bodies it owns.
#include <span>
#include <vector>

#include "physics/body.h"
#include "physics/constraints.h"
#include "physics/narrow_phase.h"
#include "physics/particles.h"
#include "physics/rigid_bodies.h"
#include "physics/rigid_contacts.h"
#include "physics/settings.h"

namespace phys {

/// The ground as the parting sees it: its contact points and their start depths.
struct PartingGround {
  bool enabled = false;
  Vec3 normal{0.0, 1.0, 0.0};
  std::span<const GroundContact> contacts;
  std::span<Real> allowance;  ///< unit: m; per contact, its depth at x*: moves with the bodies
};

/// The rigid bodies as the parting sees them: their poses, which it moves, and the start overlaps of
/// their contacts, which move with them.
struct PartingRigid {
  RigidBodies& bodies;
  std::span<Real>
      contactOverlap;  ///< unit: m; per NarrowPhase::rigidContacts() point, its overlap at the start
  std::span<const RigidContact> ground;
  std::span<Real> groundOverlap;  ///< unit: m; per rigid ground contact, its depth at the start
};

class Parting {
 public:
  /// Makes room for one more body, a group of its own, whose id is the number of bodies before it.
  void addBody();
  /// The two bodies move as one from now on (a stick or a link joins them).
  void join(BodyId a, BodyId b);
  /// Makes room for the pairs' scratch (room.h), so that the step does not allocate.
  void reserve(std::size_t pairs, std::size_t bodies);
  /// Parts the overlaps deeper than `featureEpsilon` (m) that the manifolds and the ground start
  /// the substep with, moving particle bodies' x and x* and rigid bodies' position and previous
  /// position alike; the contacts' start overlaps (`contactAllowance`, the ground's, the rigid
  /// ones) and the kept points' friction anchors (`contacts`) move with the bodies.
  void part(Particles& particles, std::span<const Body> bodies, std::span<const Manifold> manifolds,
            std::span<BodyContact> contacts, std::span<Real> contactAllowance, const PartingGround& ground,
            const PartingRigid& rigid, Real featureEpsilon, const PartingSettings& settings);

 private:
  BodyId group(BodyId id);

  std::vector<BodyId> parent_;    // per body: union-find parent over links and sticks
  std::vector<BodyId> root_;      // per body: its group's root, this substep
  std::vector<Vec3> shift_;       // per body: translation (m)
  std::vector<Real> weight_;      // per body: inverse mass (1/kg), 0 if it cannot move
  std::vector<Real> groundNeed_;  // per body: n_g . shift it needs (m)
  std::vector<Real> groundPush_;  // per body: the ground's push, accumulated (m)
  std::vector<Real> need_;        // per manifold: the least n . (t_b - t_a) the parting must reach (m)
  std::vector<Real> push_;        // per manifold: accumulated by the sweeps (shift x mass, kg m), >= 0
};

}  // namespace phys
