#pragma once
// Islands and sleeping (Stage::Islands; docs/physics.md, "Islands and sleeping"). A node is a body
// or a loose particle. Sticks, links and joints join nodes for good; a step's contacts join them for
// that step; the ground and pinned particles join nothing, as in Box2D and Jolt. The islands are a
// union-find rebuilt once a step from the lasting joins and the step's manifolds: a step's contacts
// come and go, and rebuilding them all costs a pass over the nodes and the manifolds
// (docs/performance.md, "Islands and sleeping").
//
// An island whose every node has been slower than SleepSettings::speed for SleepSettings::time,
// without speeding up step after step (Islands::speedingUp) or from one half of its rest to the next
// (Islands::fasterThanItsLastHalf), goes to sleep. The world then steps none of it
// (World::step: its particles and rigid bodies look pinned to the passes, and pairs of two sleeping bodies
// are not collided), so its state is kept to the bit. It wakes whole when an awake node joins it by a contact
// (in the step, as soon as the narrow phase finds it: wakeTouched), a stick, a link or a joint, when one of
// its nodes is dragged, and when the settings change.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat3x3.hpp>

#include "physics/body.h"
#include "physics/narrow_phase.h"
#include "physics/particles.h"
#include "physics/rigid_bodies.h"
#include "physics/settings.h"

namespace phys {

/// Index of a node: a body or a loose particle, in the order they were added.
using NodeId = Id<struct NodeTag>;

class World;

/// What Islands::update reads of the world once a step.
struct IslandInput {
  const Particles& particles;  ///< with their own inverse masses (none masked)
  const RigidBodies& rigid;
  std::span<const Body> bodies;
  std::span<const Manifold> manifolds;  ///< the step's, particle and rigid pairs alike
  Real h = 0.0;                         ///< unit: s; the last substep, over which x - x* was made
  Real dt = 0.0;                        ///< unit: s; the step
  SleepSettings sleep;
  /// Nodes kept awake this step (a drag's, the roots of characters whose drives move them, the
  /// bodies pushed), or none: their islands do not sleep.
  std::span<const NodeId> held;
};

class Islands {
 public:
  /// A loose particle's node; a pinned one (`fixed`) joins nothing and is never in an island.
  NodeId addParticle(bool fixed);
  /// A body's node; its `particleCount` particles, added just before, are its own.
  NodeId addBody(int particleCount);
  /// The two nodes are one island from now on (a stick, a link or a joint), unless one is fixed or
  /// they are one node. Wakes both whatever the join: a stick from a pin pulls on its body too.
  void join(NodeId a, NodeId b);
  /// The nodes of particles a and b, unless either is fixed.
  void joinParticles(ParticleId a, ParticleId b);

  /// Once a step, after its last substep: the islands of the lasting joins and the step's
  /// manifolds; wakes every sleeping island an awake node touched; times each node's rest; puts
  /// islands to sleep.
  void update(const IslandInput& in);
  /// The islands of the lasting joins and the manifolds, numbered and counted as update() does,
  /// without timing a rest, waking or putting anything to sleep: for a read between steps.
  void count(std::span<const Manifold> manifolds);
  /// False once a node, a lasting join or a node's sleep has changed since the islands were last
  /// numbered, or forgetCount() was called: islandCount(), sleepingIslands() and bodyIsland() are
  /// then out of date.
  bool counted() const { return counted_; }
  /// For a step that did not update() the islands (sleeping off): its contacts may have changed.
  void forgetCount() { counted_ = false; }
  /// Wakes every node (settings changed, or sleeping turned off).
  void wakeAll();
  /// Wakes the island of the node.
  void wake(NodeId node);

  /// Makes every sleeping node look pinned to the passes (inverse masses and inertias 0), keeping
  /// its own, which unmask() gives back: between the two, a step moves nothing of a sleeping
  /// island, through the same paths that leave a pinned particle or a frozen body alone. unmask()
  /// gives back exactly what mask() took, to the nodes it took it from: an island woken between
  /// the two stays pinned until the step's end.
  void mask(Particles& p, RigidBodies& r, std::span<const Body> bodies);
  void unmask(Particles& p, RigidBodies& r, std::span<const Body> bodies);
  /// True between mask() and unmask() when mask() took something.
  bool masked() const { return masking_; }

  /// In the step, once its manifolds are found: wakes every sleeping island that one of them joins
  /// to an awake node (speculative points included, as update() counts them), so that the passes
  /// move it rather than hold it as fixed. Returns the nodes it woke (empty when none), in node
  /// order, until the next call.
  std::span<const NodeId> wakeTouched(std::span<const Manifold> manifolds);
  /// Between mask() and unmask(): gives the nodes the last wakeTouched() woke their masses back now,
  /// so the rest of the step moves them; unmask() leaves them be.
  void unmaskWoken(Particles& p, RigidBodies& r, std::span<const Body> bodies);

  // The four queries below throw std::invalid_argument naming the call, the id and how many there
  // are for an id that does not exist: "bodyAsleep: body 7 does not exist (there are 2)".
  /// The node of a particle: its body's, or its own for a loose one.
  NodeId particleNode(ParticleId id) const;
  /// The node of a body.
  NodeId bodyNode(BodyId id) const;
  /// True when the node's island sleeps.
  bool asleep(NodeId node) const;
  /// True when the body's island sleeps.
  bool bodyAsleep(BodyId id) const;
  /// Per body: 1 once a stick, link or joint joined it to anything (a pin, another body, itself
  /// excepted: its own sticks), kept when that is removed; what the ground reads a free body by
  /// (GroundContacts::placeCapsulePoints).
  std::span<const std::uint8_t> bodiesJoined() const { return bodyJoined_; }
  /// Per body: 1 when asleep (what the narrow phase skips pairs by).
  std::span<const std::uint8_t> bodiesAsleep() const { return bodyAsleep_; }
  /// True when some node sleeps: the step masks their masses.
  bool anyAsleep() const { return sleepingNodes_ > 0; }
  /// True when every node that can move sleeps: the step has nothing to do.
  bool allAsleep() const { return sleepingNodes_ > 0 && sleepingNodes_ == movableNodes_; }
  /// The island of each body at the last update or count(), numbered from 0 in order of first body (for
  /// drawing); a body that joins nothing is an island of its own.
  std::span<const std::uint32_t> bodyIsland() const { return bodyIsland_; }
  /// At the last update or count(): islands with at least one node that can move, awake and asleep.
  std::size_t islandCount() const { return islandCount_; }
  std::size_t sleepingIslands() const { return sleepingIslands_; }
  /// Bodies awake and asleep now.
  std::size_t sleepingBodies() const;
  std::size_t awakeBodies() const { return bodyNode_.size() - sleepingBodies(); }

 private:
  // The queries above without their checks, for the world that owns the islands: its ids are its
  // own, and the step and the metrics ask for every particle and body.
  friend class World;
  NodeId nodeOf(ParticleId id) const { return particleNode_[id]; }
  NodeId nodeOf(BodyId id) const { return bodyNode_[id]; }
  bool sleeps(NodeId node) const { return asleep_[node] != 0; }
  bool bodySleeps(BodyId id) const { return asleep_[bodyNode_[id]] != 0; }

  NodeId addNode(bool fixed);
  void uniteForStep(std::span<const Manifold> manifolds);
  void number();
  void keepMaskRoom();
  NodeId root(NodeId node);
  void unite(NodeId a, NodeId b);
  void setAsleep(NodeId node, bool asleep);
  Real nodeSpeed(const IslandInput& in, NodeId node) const;
  Vec3 nodeCentre(const IslandInput& in, NodeId node) const;
  bool speedingUp(NodeId node, Real speed, const IslandInput& in);            // per node, once a step
  bool fasterThanItsLastHalf(NodeId node, Real rest, const IslandInput& in);  // per resting node

  std::vector<NodeId> particleNode_;        // per particle
  std::vector<NodeId> bodyNode_;            // per body
  std::vector<BodyId> nodeBody_;            // per node: its body, or kNoBody for a loose particle
  std::vector<ParticleId> nodeParticle_;    // per node: a loose particle's id
  std::vector<std::uint8_t> fixed_;         // per node: a pinned loose particle
  std::vector<NodeId> lasting_;             // per node: union-find parent over sticks, links, joints
  std::vector<NodeId> parent_;              // per node: this step's union-find parent
  std::vector<NodeId> sleepGroup_;          // per node: the island it fell asleep in (a node of it)
  std::vector<std::uint8_t> asleep_;        // per node
  std::vector<std::uint8_t> bodyAsleep_;    // per body
  std::vector<std::uint8_t> bodyJoined_;    // per body: see bodiesJoined
  std::vector<Real> rest_;                  // per node: unit: s; how long it has been slow
  std::vector<Real> lastSpeed_;             // per node: unit: m/s; its speed at the step before
  std::vector<Real> rising_;                // per node: unit: s; how long its speed has risen running
  std::vector<std::uint8_t> islandAwake_;   // per root: scratch
  std::vector<std::uint8_t> islandAsleep_;  // per root: scratch
  std::vector<Real> islandRest_;            // per root: scratch, the least rest of its nodes
  std::vector<std::uint32_t> bodyIsland_;
  std::vector<std::uint32_t> islandNumber_;  // per root: scratch
  // Per node, for fasterThanItsLastHalf, since its rest began: its centre at the last mark, its rest
  // then, the centre's mean speed between the two marks before, and how many marks (0 to 2).
  std::vector<Vec3> mark_;       // unit: m
  std::vector<Real> markRest_;   // unit: s
  std::vector<Real> halfSpeed_;  // unit: m/s
  std::vector<std::uint8_t> marks_;
  // What mask() took and from which nodes, in node order; room for every node, particle and body,
  // made as they are added.
  struct RigidMass {
    Real inverseMass = 0.0;
    Vec3 inverseInertia{0.0};
    glm::dmat3 inverseInertiaWorld{0.0};
  };
  std::vector<NodeId> maskedNodes_;
  std::vector<Real> maskedParticles_;
  std::vector<RigidMass> maskedRigid_;
  bool masking_ = false;                 // between a mask() that took something and unmask()
  std::vector<NodeId> woken_;            // the nodes the last wakeTouched() woke; room for every node
  std::vector<std::uint8_t> wakeGroup_;  // per node: scratch of wakeTouched, 1 for a group to wake
  std::size_t sleepingNodes_ = 0;
  std::size_t movableNodes_ = 0;
  std::size_t islandCount_ = 0;
  std::size_t sleepingIslands_ = 0;
  bool counted_ = false;
};

}  // namespace phys
