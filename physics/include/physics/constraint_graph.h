#pragma once
// The constraints between particles (sticks) and between bodies (links, the joints: between particle
// bodies, and with a rigid body at one end or both), and their
// layouts for the passes: the sticks by body (StickLayout) and the links by ragdoll (LinkLayout),
// in SIMD lanes. It owns the solver's scratch for them: XPBD's multipliers, Jacobi's per-particle
// sums, and the slack of links created outside their bounds.
#include <span>
#include <vector>

#include "physics/body.h"
#include "physics/constraints.h"
#include "physics/drives.h"
#include "physics/link_layout.h"
#include "physics/particles.h"
#include "physics/rigid_joints.h"
#include "physics/rigid_links.h"
#include "physics/settings.h"
#include "physics/stick_layout.h"
#include "physics/workers.h"

namespace phys {

/// The substep's passes, for ConstraintGraph::relaxSticks to run the chains' passes at once.
struct PassesAhead {
  int passes = 1;  ///< the substep's passes (SolverSettings::iterations)
  bool ground = false;
  Vec3 groundNormal{0.0, 1.0, 0.0};
  Real groundHeight = 0.0;  ///< unit: m
};

class ConstraintGraph {
 public:
  /// Makes room for one more particle's scratch.
  void addParticle();
  /// Adds a stick between existing particles; the layouts are stale until layOut().
  void addStick(const Stick& stick);
  /// Adds a link whose points are at `violation` (m, signed as detail::linkViolation) outside its
  /// bounds now: it closes that at most at maxDepenetrationSpeed (shrinkLinkSlack).
  void addLink(const Link& link, Real violation);
  /// Adds a link with a rigid end; it is solved as it stands (rigid links need no layout).
  void addRigidLink(const RigidLink& link) { rigidLinks_.push_back(link); }
  /// Adds a joint between two rigid bodies, solved as it stands too, with its drive (strength 0:
  /// none) and the drive's multiplier.
  void addRigidJoint(const RigidJoint& joint, const JointDrive& drive) {
    rigidJoints_.push_back(joint);
    drives_.push_back(drive);
    driveLambda_.push_back(0.0);
  }
  /// Replaces joint k's drive.
  void setDrive(std::size_t k, const JointDrive& drive) { drives_[k] = drive; }
  /// Adds what a drive needs of a joint between two particle bodies, with its drive and multiplier.
  void addParticleJoint(const ParticleJoint& joint, const JointDrive& drive) {
    particleJoints_.push_back(joint);
    particleDrives_.push_back(drive);
    particleDriveLambda_.push_back(0.0);
    particleDriveShare_.push_back(1.0);
  }
  /// Replaces particle joint k's drive.
  void setParticleDrive(std::size_t k, const JointDrive& drive) { particleDrives_[k] = drive; }
  /// Sets the most of particle joint k's drive's gap one pass closes (0 to 1; 1, the whole, unless
  /// a character turning in holds it: Character::turnIn).
  void setParticleDriveShare(std::size_t k, Real share) { particleDriveShare_[k] = share; }
  /// Sets a body's drive towards a pose (driven.drive), adding it when the body has none.
  void setBodyDrive(const DrivenBody& driven);
  /// Removes a body's drive, if it has one.
  void clearBodyDrive(BodyId body);
  /// Adds friction between two jointed particle bodies, with room for their spins.
  void addJointFriction(const JointFriction& friction);
  /// Once a step: each joint friction takes its share of its bodies' relative spin (JointFriction).
  /// `workers`, if given, run runs of frictions that share no body (frictionPieces_) at once.
  void dampJointFriction(Particles& particles, std::span<const Body> bodies, Real dt,
                         const Workers* workers = nullptr);
  /// True when sticks or links were added since the last layOut().
  bool stale() const { return stale_; }
  /// Lays the sticks out by body and the links by ragdoll. Allocates: after things were added.
  void layOut(std::span<const Body> bodies, std::size_t particleCount);
  /// Marks the lane groups of sticks and links that this step's passes skip (StickLayout::still),
  /// from the inverse masses with the sleeping islands masked; clearStill skips none.
  void markStill(std::span<const Real> inverseMass);
  void clearStill();

  std::span<const Stick> sticks() const { return sticks_; }
  std::span<const Link> links() const { return links_; }
  std::span<const RigidLink> rigidLinks() const { return rigidLinks_; }
  std::span<const RigidJoint> rigidJoints() const { return rigidJoints_; }
  /// Per rigid joint, its drive.
  std::span<const JointDrive> drives() const { return drives_; }
  /// XPBD's multipliers of the drives, per rigid joint.
  std::span<Real> driveLambda() { return driveLambda_; }
  std::span<const Real> driveLambda() const { return driveLambda_; }
  std::span<const ParticleJoint> particleJoints() const { return particleJoints_; }
  /// Per particle joint, its drive, and XPBD's multiplier of it.
  std::span<const JointDrive> particleDrives() const { return particleDrives_; }
  std::span<Real> particleDriveLambda() { return particleDriveLambda_; }
  std::span<const Real> particleDriveLambda() const { return particleDriveLambda_; }
  /// Per particle joint, the most of its drive's gap one pass closes.
  std::span<const Real> particleDriveShare() const { return particleDriveShare_; }
  /// The bodies' drives, in the order they were first set.
  std::span<const DrivenBody> bodyDrives() const { return bodyDrives_; }
  /// Their multipliers, two a drive: its centre's and its turn's.
  std::span<Real> bodyDriveLambda() { return bodyDriveLambda_; }
  std::span<const Real> bodyDriveLambda() const { return bodyDriveLambda_; }
  std::span<const JointFriction> jointFrictions() const { return jointFrictions_; }

  /// One pass over every stick by `method`; `firstPass` of the substep (XPBD zeroes its
  /// multipliers). `h` (s) and `compliance` (m/N) are XPBD's.
  /// `workers`, if given, run the lane groups of Gauss-Seidel and XPBD in pieces at once.
  /// `keepSpin` (SolverSettings::keepSpin; not SHAKE's, whose sticks keep it): the moment of each body
  /// laid out as a block or in lanes is kept through its sticks; the run bodies' (stickRunBodies) are
  /// the caller's.
  /// `ahead`: on the first pass of Gauss-Seidel or XPBD with more than one pass, every pass of the
  /// substep over the chains of loose particles at once (StickLayout::chains), the bits unchanged;
  /// the ground's plane, if there is one, says which chains the ground's passes may move between.
  void relaxSticks(Particles& particles, SolverMethod method, bool firstPass, Real h, Real compliance,
                   const Workers* workers = nullptr, bool keepSpin = false, const PassesAhead& ahead = {});
  /// StickLayout::runBodies.
  std::span<const std::uint32_t> stickRunBodies() const { return stickLayout_.runBodies(); }
  /// Each link's slack: the violation at x* it may keep this substep, less `step` (m). Returns the
  /// slack, empty when every link is within its bounds.
  std::span<const Real> shrinkLinkSlack(const Particles& particles, Real step);
  /// True while some link created outside its bounds has not yet been brought within them.
  bool linksApart() const { return linksApart_ > 0; }
  /// The slack as it is (empty when no link has any), without shrinking it.
  std::span<const Real> linkSlack() const;
  /// One pass over the links, each widened by its slack (may be empty).
  void solveLinks(Particles& particles, std::span<const Real> slack, const Workers* workers = nullptr) const;

 private:
  void relaxChainsAhead(Particles& particles, SolverMethod method, Real h, Real compliance,
                        const PassesAhead& ahead);

  std::vector<Stick> sticks_;
  std::vector<Link> links_;
  std::vector<RigidLink> rigidLinks_;
  std::vector<RigidJoint> rigidJoints_;
  std::vector<JointDrive> drives_;  // per rigid joint
  std::vector<Real> driveLambda_;   // per rigid joint: its drive's XPBD multiplier
  std::vector<ParticleJoint> particleJoints_;
  std::vector<JointDrive> particleDrives_;  // per particle joint
  std::vector<Real> particleDriveLambda_;   // per particle joint
  std::vector<Real> particleDriveShare_;    // per particle joint: of its gap, the most a pass closes
  std::vector<DrivenBody> bodyDrives_;
  std::vector<Real> bodyDriveLambda_;  // two per body drive
  std::vector<JointFriction> jointFrictions_;
  std::vector<BodySpin> spins_;  // per body: the joint friction's scratch
  // Where runs of joint frictions begin that share no body with the runs before (and the end):
  // in creation order, so one ragdoll's frictions are never cut apart. Found by layOut(); one run
  // of none before it.
  std::vector<std::size_t> frictionPieces_{0, 0};
  StickLayout stickLayout_;
  LinkLayout linkLayout_;
  bool stale_ = false;
  std::vector<Real> lambda_;       // per stick: XPBD multiplier
  std::vector<Real> linkSlack_;    // per link: violation it may keep this substep (m)
  int linksApart_ = 0;             // links whose slack is not yet 0
  std::vector<Vec3> jacobiDelta_;  // per particle
  std::vector<Vec3> chainSaved_;   // two per stick of the longest chain (relaxChainsAhead)
  std::vector<Real> laneSpin_;     // keepSpin: the lanes' levers, kLaneSpinValues per lane group
  std::vector<Real> degree_;       // per particle: sticks attached (Jacobi's scaling)
};

}  // namespace phys
