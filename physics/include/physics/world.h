#pragma once
// The world: particles, sticks between them, boxes made of particles, the ground, and the step
// that moves them. One step is Jakobsen's loop run `substeps` times: integrate (with the drag
// spring), relax the sticks and the contacts `iterations` times with friction after each pass,
// restitution, body damping, guard. Also the picking the sandbox needs: raycast and the drag.
#include <array>
#include <atomic>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "physics/body.h"
#include "physics/body_layout.h"
#include "physics/broad_phase.h"
#include "physics/character.h"
#include "physics/collision.h"
#include "physics/constraint_graph.h"
#include "physics/constraints.h"
#include "physics/contact_bins.h"
#include "physics/debug_draw.h"
#include "physics/ground_contacts.h"
#include "physics/guard.h"
#include "physics/islands.h"
#include "physics/joint_projection.h"
#include "physics/metrics.h"
#include "physics/motion.h"
#include "physics/narrow_phase.h"
#include "physics/particles.h"
#include "physics/parting.h"
#include "physics/push.h"
#include "physics/rigid_bodies.h"
#include "physics/rigid_contacts.h"
#include "physics/rigid_joints.h"
#include "physics/rigid_links.h"
#include "physics/settings.h"
#include "physics/tetra_volumes.h"
#include "physics/workers.h"

namespace phys {

/// A particle when it is created.
struct ParticleDesc {
  Vec3 position{0.0};   ///< unit: m
  Vec3 velocity{0.0};   ///< unit: m/s, at the time of creation
  Real mass = 1.0;      ///< unit: kg; > 0 unless pinned
  bool pinned = false;  ///< a pinned particle never moves (inverse mass 0)
  std::string name;     ///< for reports and dumps; may be empty
};

/// Defaults of the mouse spring (Drag): a 1 kg body follows about critically damped (1.1 times),
/// a 20 kg ragdoll torso swings a little, and a 70 kg ragdoll hung from its torso sags 0.35 m.
inline constexpr Real kDragStiffness = 2000.0;  ///< unit: N/m
inline constexpr Real kDragDamping = 100.0;     ///< unit: N s/m

/// A spring pulling one point (a particle, or a point of a box from World::anchor) towards a
/// target: force k (target - p) - b v on the point, v its velocity. It is applied implicitly
/// once per substep (docs/physics.md, "Drag"), so it is stable at any stiffness: an infinite
/// one would put the point on the target every substep. Pinned particles never move.
struct Drag {
  Embedding point;  ///< weights summing to 1 over existing particles (not for a rigid body)
  /// A rigid body's point instead: the body, and the point in its frame from its centre (unit: m).
  BodyId body = kNoBody;
  Vec3 local{0.0};
  Vec3 target{0.0};                 ///< unit: m
  Real stiffness = kDragStiffness;  ///< k, unit: N/m; finite, >= 0
  Real damping = kDragDamping;      ///< b, unit: N s/m (force per velocity); finite, >= 0
};

/// Radius of the sphere World::raycast tests a loose particle against: a particle is a point,
/// and a pick ray must be able to hit it.
inline constexpr Real kPickRadius = 0.1;  ///< unit: m

/// What World::raycast hit: a box or a loose particle (exactly one of the two is set).
struct RayHit {
  std::optional<BodyId> box;
  std::optional<ParticleId> particle;  ///< a particle that belongs to no box
  Real distance = 0.0;                 ///< unit: m; along the ray from its origin, 0 if it starts inside
  Vec3 point{0.0};                     ///< unit: m; where the ray enters (the origin if it starts inside)
};

class World {
 public:
  /// Throws std::invalid_argument when either settings struct fails validate().
  explicit World(const WorldSettings& world = {}, const SolverSettings& solver = {});

  /// Adds one particle; throws std::invalid_argument on a non-finite input or a bad mass.
  ParticleId addParticle(const ParticleDesc& desc);
  /// Adds a stick at the particles' current distance.
  void addStick(ParticleId a, ParticleId b, Real compliance = 0.0);
  /// Adds a stick of the given rest length (unit: m, finite and > 0).
  void addStick(ParticleId a, ParticleId b, Real length, Real compliance);
  /// Adds a range stick: no force while minLength <= |xb - xa| <= maxLength. minLength 0 or
  /// maxLength kNoMaxLength makes it one-sided. Needs 0 <= minLength <= maxLength, maxLength > 0.
  void addRange(ParticleId a, ParticleId b, Real minLength, Real maxLength, Real compliance = 0.0);
  /// Adds a box of the chosen model; throws std::invalid_argument on bad input and adds nothing.
  BodyId addBody(const BodyDesc& desc);

  /// Adds a joint between two embedded points (World::anchor gives them): a pin when maxLength
  /// is 0, else a range. Needs 0 <= minLength <= maxLength; throws std::invalid_argument on bad
  /// input and adds nothing.
  void addLink(const Embedding& a, const Embedding& b, Real minLength = 0.0, Real maxLength = 0.0);
  /// The same for points of any bodies (pointOn gives them): between two particle bodies' embedded
  /// points it is the link above; with a rigid end it is a RigidLink (rigidLinks()), which a rigid
  /// body's frame carries. Throws std::invalid_argument on bad input and adds nothing.
  void addLink(const BodyPoint& a, const BodyPoint& b, Real minLength = 0.0, Real maxLength = 0.0);
  /// The point at `worldPoint` (unit: m) carried by the box from now on: barycentric weights over
  /// the box's inscribed tetrahedron (its 4 particles, or corners 0, 3, 5, 6 of a corners box),
  /// which exist for any point, inside the box or not, with no matrix to invert.
  Embedding anchor(BodyId box, const Vec3& worldPoint) const;
  /// Adds a hinge or a cone between two rigid bodies (rigid_joints.h). Throws
  /// std::invalid_argument on bad input (bodies not rigid or the same, non-finite or zero vectors,
  /// a reference along the axis, stops outside [-pi, pi] or crossed, a swing outside (0, pi), a
  /// twist outside [0, pi], negative damping) and adds nothing.
  void addJoint(const JointDesc& joint);
  /// Adds friction in the joint between two particle bodies (JointFriction): once a step their
  /// relative spin decays by the share min(rate dt, 1). Throws std::invalid_argument on bad input
  /// (bodies not particle bodies or the same, a negative or non-finite rate) and adds nothing.
  void addJointFriction(BodyId a, BodyId b, Real rate);
  /// Adds what a drive needs of a joint between two particle bodies (ParticleJoint): the pivot
  /// (unit: m, in the world) and the turn they are at now, its drive's target, at strength 0. The
  /// links that hold the joint are addLink's. Returns its index. Throws std::invalid_argument on
  /// bad input (bodies not particle bodies or the same, a pivot not finite) and adds nothing.
  std::size_t addParticleJoint(BodyId parent, BodyId child, const Vec3& pivot);
  /// The same, as described: its pivots in the two bodies' frames and its rest given (a saved
  /// scene's); refuses a rest that is not a unit quaternion (within 1e-6) too.
  std::size_t addParticleJoint(const ParticleJoint& joint);
  /// The particle joint between two bodies as they lie now, the parent's pivot at `pivot` and the
  /// child's at `pivotB` (unit: m, in the world; the same point for a joint at rest), its rest the
  /// turn between them: what addParticleJoint(parent, child, pivot) adds. Checks only that
  /// both bodies exist.
  ParticleJoint particleJointAt(BodyId parent, BodyId child, const Vec3& pivot, const Vec3& pivotB) const;
  /// The point at `worldPoint` (unit: m) carried by the body from now on, whatever its model:
  /// anchor() for a particle body, fixed in its frame for a rigid one.
  BodyPoint pointOn(BodyId body, const Vec3& worldPoint) const;

  /// Starts pulling a point with a spring, replacing any drag set before. Throws
  /// std::invalid_argument (and keeps the old drag) on a bad embedding, a non-finite target or a
  /// negative or non-finite stiffness or damping.
  void setDrag(const Drag& drag);
  /// A drag of the point at `worldPoint` (unit: m) carried by the body from now on, whatever its
  /// model (anchor() for a particle body, its frame for a rigid one), with its target there.
  Drag dragAt(BodyId body, const Vec3& worldPoint) const;
  /// Where the drag's point is now (unit: m); throws std::invalid_argument if no drag is set.
  Vec3 dragPoint() const;
  /// Moves the target of the drag; throws std::invalid_argument if it is not finite or no drag is set.
  void setDragTarget(const Vec3& target);
  /// Stops the pull; does nothing if there is none.
  void clearDrag() { drag_.reset(); }
  const std::optional<Drag>& drag() const { return drag_; }

  /// The nearest box or loose particle along the ray from `origin` in `direction` (any length;
  /// distances are measured in metres along it) within maxDistance: boxes as their oriented box
  /// (bodyPose and half extents), loose particles as spheres of kPickRadius. A ray that starts
  /// inside a box or sphere hits it at distance 0. Throws std::invalid_argument on a non-finite
  /// origin, a zero or non-finite direction, or a negative or NaN maxDistance (infinity is fine).
  std::optional<RayHit> raycast(const Vec3& origin, const Vec3& direction, Real maxDistance) const;

  /// Keeps two boxes from colliding with each other (the parts of a ragdoll joined by a joint).
  void ignoreCollision(BodyId a, BodyId b);
  /// Every pair ignoreCollision() was given, as (smaller id, larger id), sorted.
  std::vector<std::pair<BodyId, BodyId>> ignoredCollisions() const;

  /// Advances the world by solverSettings().dt.
  void step();
  /// The same, unless `stop` is true before a substep: then it returns false at once, leaving the
  /// world part of the way through the step, fit only to be thrown away (the sandbox steps copies
  /// on another thread and drops them when a command comes; docs/sandbox.md, "Time budget").
  /// True when the step finished.
  bool step(const std::atomic<bool>& stop);

  /// Replaces the world settings; throws std::invalid_argument (and keeps the old ones) if bad.
  void setWorldSettings(const WorldSettings& settings);
  /// Replaces the solver settings; throws std::invalid_argument (and keeps the old ones) if bad.
  /// A new dt or substep count keeps every particle's velocity (exactly in free flight); more
  /// passes per step first relax the stored error without changing any velocity.
  void setSolverSettings(const SolverSettings& settings);
  /// Called once for each particle or body the guard freezes, at the end of the step (or of the
  /// setSolverSettings) that froze it, when the world is whole: the callback may change the world.
  void setFreezeCallback(std::function<void(const FreezeReport&)> callback);

  const WorldSettings& worldSettings() const { return world_; }
  const SolverSettings& solverSettings() const { return solver_; }
  const Particles& particles() const { return particles_; }
  std::span<const Stick> sticks() const { return constraints_.sticks(); }
  std::span<const Body> bodies() const { return bodies_; }
  std::span<const Link> links() const { return constraints_.links(); }
  /// The links with a rigid end, in the order they were added (after or among links()).
  std::span<const RigidLink> rigidLinks() const { return constraints_.rigidLinks(); }
  /// The joints between rigid bodies, in the order they were added.
  std::span<const RigidJoint> rigidJoints() const { return constraints_.rigidJoints(); }
  /// The friction of particle bodies' joints, in the order it was added.
  std::span<const JointFriction> jointFrictions() const { return constraints_.jointFrictions(); }
  /// Every joint of every kind: links(), rigidLinks() and rigidJoints().
  std::size_t jointCount() const { return links().size() + rigidLinks().size() + rigidJoints().size(); }
  /// What drives need of the joints between particle bodies, in the order they were added.
  std::span<const ParticleJoint> particleJoints() const { return constraints_.particleJoints(); }
  /// Particle joint k's drive, made at strength 0 with the joint's rest as its target.
  const JointDrive& particleJointDrive(std::size_t k) const;
  /// unit: N m; as jointDriveTorque, for particle joint k's drive.
  Real particleJointDriveTorque(std::size_t k) const;
  /// The most of particle joint k's drive's gap one pass closes now (0 to 1): kTurnInShare while its
  /// character turns in (Character::turnIn), else 1.
  Real particleJointDriveShare(std::size_t k) const;
  /// Replaces particle joint k's drive and wakes its island; refuses what setJointDrive refuses.
  void setParticleJointDrive(std::size_t k, const JointDrive& drive);
  /// Joint k as addJoint would take it to make it again as it is now: both bodies' pivots and frames.
  JointDesc jointDesc(std::size_t k) const;
  /// Joint k's angle now (rad): a hinge's about its axis, a cone's twist.
  Real jointAngle(std::size_t k) const;
  /// Joint k's drive (drives.h). A joint is made with strength 0 (no drive) and its rest as the
  /// target.
  const JointDrive& jointDrive(std::size_t k) const;
  /// unit: N m; the torque joint k's drive exerted in the last substep: XPBD's multiplier over the
  /// substep's passes / h^2 (drives.cpp), what the joint needed to follow its target. 0 for a joint
  /// without a drive, and before the first step.
  Real jointDriveTorque(std::size_t k) const;
  /// The body's drive towards a pose in the world (BodyDrive, the hand of god), if it has one.
  std::optional<BodyDrive> bodyDrive(BodyId id) const;
  /// The force (N) and torque (N m) body `id`'s drive exerted in the last substep, as
  /// jointDriveTorque; zeros for a body without one.
  DriveLoad bodyDriveLoad(BodyId id) const;
  /// Sets the body's drive, replacing any, and wakes its island. Throws std::invalid_argument (and
  /// keeps the old drive) for a body that does not exist, a position that is not
  /// finite, an orientation that is not a unit quaternion (within 1e-6; it is made unit), a
  /// strength outside [0, 1], a stiffness that is not finite and >= 0 or an angular stiffness that
  /// is not finite and > 0.
  void setBodyDrive(BodyId id, const BodyDrive& drive);
  /// Removes the body's drive, if it has one, and wakes its island.
  void clearBodyDrive(BodyId id);
  /// Every body drive, in the order the bodies were first given one.
  std::span<const DrivenBody> bodyDrives() const { return constraints_.bodyDrives(); }
  /// Joint k's rest: its child's orientation in its parent's frame when the joint's two frames are
  /// one, the target its drive is made with.
  Quat jointRest(std::size_t k) const;
  /// Replaces joint k's drive and wakes its island. Throws std::invalid_argument (and keeps the old
  /// drive) for a joint that does not exist, a target that is not a unit quaternion (within 1e-6;
  /// it is normalised), a strength outside [0, 1] or a stiffness that is not finite and > 0.
  void setJointDrive(std::size_t k, const JointDrive& drive);
  /// Adds a character: the ragdoll's joints driven along a clip (character.h), from the next step.
  /// Its frame is where the ragdoll's root part is now. Throws std::invalid_argument (and adds
  /// nothing) for a clip that clipProblem refuses or bindClip cannot bind, a strength outside
  /// [0, 1], a speed or scale that is not finite (speed >= 0, scale > 0). Returns its index.
  std::size_t addCharacter(const CharacterDesc& desc);
  std::span<const Character> characters() const { return characters_; }
  /// Fades character k from its clip to `playback` over blendTime (s, finite, >= 0; 0 cuts), the
  /// new clip's root path starting where the old one has got to. Throws std::invalid_argument (and
  /// changes nothing) as addCharacter would, or for a clip whose bones are not the character's.
  void playClip(std::size_t k, const Playback& playback, Real blendTime);
  /// Changes character k's clip to `playback` once its clip's clock reaches `at` (s), faded in over
  /// blendTime (s, >= 0), as playClip would then; replaces any clip queued before. Throws
  /// std::invalid_argument (and changes nothing) as playClip would, or for `at` not finite.
  void queueClip(std::size_t k, const Playback& playback, Real at, Real blendTime);
  /// Sets character k's strengths (0 to 1): its joints' drives and its root's, and what its
  /// reaction gives back; stops any reaction under way (CharacterState::Active). Throws
  /// std::invalid_argument (and changes nothing) out of range.
  void setCharacterStrength(std::size_t k, Real strength, Real rootStrength);
  /// Sets the share (0 to 1) of character k's strength that the joint of its bone `bone` (a clip's
  /// name) gets (CharacterDesc::partStrengths), from the next step. Throws std::invalid_argument (and
  /// changes nothing) for a bone the character has not, its root, or a share out of range.
  void setPartStrength(std::size_t k, const std::string& bone, Real share);
  /// Sets character k's balance (0 to 1, CharacterDesc::balance), now and as what its reaction
  /// gives back. Throws std::invalid_argument (and changes nothing) out of range.
  void setCharacterBalance(std::size_t k, Real balance);
  /// Replaces character k's reaction (Reaction), from the next step. Throws std::invalid_argument
  /// (and changes nothing) as addCharacter would for it.
  void setCharacterReaction(std::size_t k, const Reaction& reaction);
  /// Sets how long character k's turn-ins last (CharacterDesc::turnInTime; s, finite, >= 0), from
  /// the next one; a turn-in under way is held to it. Throws std::invalid_argument (and changes
  /// nothing) out of range.
  void setCharacterTurnIn(std::size_t k, Real seconds);
  /// What of character k changes as it steps (motion.h): its clips' clocks, fade, strengths now,
  /// reaction state and clip frame. Throws std::invalid_argument for a character that does not exist.
  CharacterMotion characterMotion(std::size_t k) const;
  /// Puts character k in `motion` (as characterMotion gives it, changed; a saved scene's reaction
  /// under way) and wakes its island. Throws std::invalid_argument (and changes nothing) for what
  /// setMotion would refuse in a character.
  void setCharacterMotion(std::size_t k, const CharacterMotion& motion);
  /// Pushes body `id` with `force` (N, world) for `duration` (s) at `worldPoint` (m; its centre if
  /// none), from the next substep, and wakes its island, held awake while the push lasts: the point is kept
  /// in the body's frame, the force in the world's. Pushes add up. Throws std::invalid_argument (and pushes
  /// nothing) for a body that does not exist, a force or point that is not finite, or a duration that is not
  /// finite and > 0.
  void push(BodyId id, const Vec3& force, Real duration, const std::optional<Vec3>& worldPoint = {});
  /// The pushes still acting.
  std::span<const Push> pushes() const { return pushes_; }
  /// Every particle body's corners, 8 per body from Body::firstCorner (a rigid body has none).
  std::span<const Embedding> corners() const { return corners_; }
  /// Corner k of any body now (bits as in Body), unit: m.
  Vec3 cornerPosition(BodyId id, int k) const;
  /// The rigid bodies' poses and velocities, indexed by Body::rigid.
  const RigidBodies& rigidBodies() const { return rigidBodies_; }
  /// Contacts with a rigid body on either side in the last substep: between bodies, then on the ground.
  std::span<const RigidContact> rigidBodyContacts() const { return narrowPhase_.rigidContacts(); }
  std::span<const RigidContact> rigidGroundContacts() const { return rigidGround_; }
  /// Every point that collides with the ground.
  std::span<const GroundContact> groundContacts() const { return ground_.points(); }
  /// Box-box contacts of the last substep.
  std::span<const BodyContact> bodyContacts() const { return narrowPhase_.contacts(); }
  /// What each of bodyContacts() carries that the passes seldom read, at the same index.
  std::span<const BodyContactExtra> bodyContactExtras() const { return narrowPhase_.contactExtras(); }
  /// The last substep's contacts of particle bodies as two threads took them (dealt() false: on
  /// one thread, or as one loop; docs/physics.md, "Threads").
  const ContactBins& contactBins() const { return contactBins_; }
  /// Each box as an oriented box, fitted at the start of the last substep.
  std::span<const Obb> bodyFrames() const { return frames_; }
  /// Box pairs whose bounds, grown by how far each can go in a step, overlapped at the start of
  /// the last step (the broad phase's output, which every substep's narrow phase tests), less the
  /// pairs of two sleeping bodies, which it does not look for.
  std::size_t broadPhasePairs() const { return broadPhase_.pairs().size(); }
  /// The name the particle was added with (ParticleDesc::name).
  const std::string& particleName(ParticleId id) const;
  /// Per particle: the body it belongs to, or kNoBody for a loose particle.
  std::span<const BodyId> particleBodies() const { return particleBody_; }
  /// Freezes so far, oldest first.
  std::span<const FreezeReport> freezes() const { return guard_.freezes(); }
  Real time() const { return time_; }  ///< unit: s; simulated time since creation
  long stepCount() const { return steps_; }
  /// Pairs the sweep (Stage::Sweep) stopped in the last step: bodies that would have passed
  /// through another within a substep.
  int sweptPairs() const { return swept_; }

  // The queries below that take an id or an index, and those above (joints, drives, characters,
  // pushes, corners, names), throw std::invalid_argument naming the call, the id and how many there
  // are for one that does not exist.

  /// Velocity of a particle over its last substep. unit: m/s
  Vec3 velocity(ParticleId id) const;
  /// Current position of an embedded point (a box corner, say). unit: m
  Vec3 position(const Embedding& point) const;
  /// Where a body point is now (unit: m).
  Vec3 position(const BodyPoint& point) const;
  /// The body that carries a point: a rigid body, or the body of its first particle (kNoBody for a
  /// loose particle).
  BodyId carrier(const BodyPoint& point) const;
  /// Centre and orientation of a body: a rigid body's own, a particle body's fitted to its
  /// particles (polar decomposition).
  BodyPose bodyPose(BodyId id) const;
  /// bodyPose(id).center, bit for bit, without fitting the orientation: for callers that read where
  /// bodies are every step (`lab stability`'s drift of every body of a pyramid). unit: m
  Vec3 bodyCentre(BodyId id) const;
  /// A body's mass and principal inertia (BodyMass).
  BodyMass bodyMass(BodyId id) const;
  /// Velocity of a body's centre (m/s) and its angular velocity (rad/s, world frame) over the last
  /// substep, as velocity() is a particle's (half a substep back): a rigid body's own; a particle
  /// body's the least-squares rigid motion of its particles, which keeps their momentum and
  /// angular momentum.
  std::pair<Vec3, Vec3> bodyVelocity(BodyId id) const;
  /// Velocity of a body's centre (m/s) and its spin (rad/s, world frame) at the pose's time, as a
  /// body placed at bodyPose() would start (what the lab gives the peer engines): each particle's
  /// velocity moved on half a substep (+ g h / 2), their mean by mass, and the spin that keeps
  /// their angular momentum about the pose's centre (0 for a body crushed flat). A rigid body's
  /// rigidDescVelocity. Zero for a fixed body (BodyMass::fixed).
  std::pair<Vec3, Vec3> poseVelocity(BodyId id) const;
  /// A rigid body's velocity and spin as a BodyDesc gives them, at the pose's time: bodyVelocity's
  /// moved on half a substep (v + g h / 2, and the spin by Euler's equations, the exact inverse of
  /// addBody's shift up to a radian a substep; a faster spin is not shifted), so that a body saved
  /// and reloaded goes on as it would have. Throws
  /// std::invalid_argument for a body of a particle model (their velocities are their particles').
  std::pair<Vec3, Vec3> rigidDescVelocity(BodyId id) const;
  /// Acceleration of gravity at a point, in the current mode. unit: m/s^2
  Vec3 gravityAt(const Vec3& x) const;

  Metrics metrics() const;
  /// Where the time of the last step() went.
  const Profile& profile() const { return profile_; }
  /// Whether step() times each of its stages into profile() (on by default). Off, its stages read
  /// no clock and profile() holds only the step's total: for a caller that times the steps itself
  /// and reads no stage (`lab stability`), whose runs at 10 x 16 read the clock some 60 times a
  /// substep. The state does not depend on it.
  void setStageTiming(bool on) { stageTiming_ = on; }
  bool stageTiming() const { return stageTiming_; }
  /// FNV-1a hash of every particle's position and previous position, every rigid body's pose and
  /// velocities and every character's clips, strengths and reaction (Motion::hash): equal hashes,
  /// equal states.
  std::uint64_t stateHash() const;
  /// The world's motion now (motion.h): what stateHash covers, and the clock.
  Motion motion() const;
  /// Puts the world in `motion`, taken from a world of the same structure (the same bodies,
  /// particles, rigid bodies and characters, in the same order). Only for a world that has not
  /// stepped: it then holds no contacts, warm starts or rest timers of its own, and goes on from the
  /// motion as a world built there would. Throws std::invalid_argument (and changes nothing) for a
  /// world that has stepped, arrays of other sizes, another number of characters, a character's
  /// clip of other bones than its own, or what Motion::problem finds.
  void setMotion(const Motion& motion);
  /// "" or why setMotion would refuse `motion` in a world that has not stepped.
  std::string motionProblem(const Motion& motion) const;
  /// The islands and which of them sleep (Islands; SolverSettings::sleep): as the last step left
  /// them, counted again here when asked after a body, a particle or a join was added or something
  /// woke since, and always here with sleeping off, which the step does not count them for.
  const Islands& islands() const;
  /// What the last step's joint projections did (SolverSettings::jointProjection): the solves of
  /// all its substeps, the widest error found before any, the widest left after the last; all zero
  /// when it is off or there are no rigid joints.
  const JointProjectionReport& lastJointProjection() const { return lastProjection_; }
  /// Draws what the flags ask for through the given interface.
  void debugDraw(DebugDraw& draw, const DebugDrawFlags& flags = {}) const;

 private:
  Real substepDt() const { return solver_.dt / solver_.substeps; }
  // The queries' work without their checks, for the step, the metrics and the drawing, whose ids
  // are the world's own: there a check would be paid for every body or link of every substep.
  BodyPose poseOf(BodyId id) const;
  Vec3 cornerOf(BodyId id, int k) const;
  Vec3 positionOf(const Embedding& point) const;
  Vec3 positionOf(const BodyPoint& point) const;
  Vec3 velocityOf(ParticleId id) const;
  bool stepUnless(const std::atomic<bool>* stop);
  void keepVelocities(Real hOld, Real hNew);
  ParticleId pushParticle(const ParticleDesc& desc);
  void settleWithoutVelocity();
  // The stages of a substep, in step()'s order (step.cpp); each times itself into profile_.
  void animate(Real h);
  void react();
  void noteBlows();
  Quat balanceTarget(const Character& c, const Quat& upright) const;
  void findSupports();
  bool standsOverSupport(const Character& c) const;
  /// Whether some part of c is further than kTurnInGap from its target orientation
  /// (characterTargets_, as animate has just found them).
  bool farFromTargets(const Character& c) const;
  void makeRootDrive(const Character& c, Real strength);
  /// Sets the character's root part's drive (a rigid or a particle body's).
  void setRootDrive(const Character& c, const BodyDrive& drive);
  struct PartMotion {
    Real mass = 0.0;  ///< unit: kg; 0 when the part cannot move (frozen, pinned, asleep)
    Vec3 centre{0.0};
    Vec3 velocity{0.0};
  };
  PartMotion partMotion(BodyId id) const;
  void placeAtRest(BodyId id, const BodyPose& pose);
  /// The root's drive, made now if the character's strengths or reaction will use it (addCharacter,
  /// setMotion), so that the step never allocates one.
  void makeRootDriveIfNeeded(const Character& c);
  /// Puts character c's ragdoll in its target pose, at rest (CharacterDesc::startInPose).
  void putInPose(const Character& c);
  bool anyCharacterActive() const;
  void integrateParticles(Real h);
  void applyPushes(Real h);
  void collectRigidGround();
  void placeRigidCapsulePoints();
  void startRigidContacts(Real h);
  void solveRigidContacts(Real h);
  void rigidVelocities(Real h);
  void guardRigidBodies();
  RigidPassInput rigidPassInput(Real h);
  Real lowestHeight(BodyId id, const Body& body) const;
  void fitBodyFrames();
  bool findPairs(bool firstSubstep);
  void stopFastBodies();
  void findContacts(bool newPairs, bool firstSubstep, Real h, bool again = false);
  void wakeTouched(bool firstSubstep, Real h);
  void dealContacts(bool newPairs);
  void partOverlaps();
  void measureApproaches(Real h);
  std::span<const Real> limitCorrections(Real h);
  void relax(Real h, std::span<const Real> linkSlack);
  void relaxContactBins(bool ground);
  void updateLayouts();
  void skipSleepers();
  void restitute(Real h);
  void dampBodies();
  void dampJoints();
  void projectJoints();
  void guard(bool shapes);
  bool restWhileAsleep();
  void updateIslands(std::size_t freezesBefore);
  void refreeze(const FreezeReport& freeze);
  struct HeldNodes {
    static constexpr std::size_t kMost = std::tuple_size_v<decltype(Embedding::particle)>;  // a drag's point
    std::array<NodeId, kMost> nodes{};
    int count = 0;
  };
  HeldNodes heldNodes() const;
  std::size_t holdMovingCharacters(std::span<NodeId> into) const;
  void guardParticles();
  GuardInput guardInput();
  void checkEmbedding(const Embedding& e, const std::string& who) const;
  void updateBodyFrames();
  void fitFrame(BodyId id);
  void joinBodies(ParticleId a, ParticleId b);
  BodyId addRigidBody(const BodyDesc& desc, const Quat& orientation);
  BodyId registerBody(const Body& body);
  NarrowPhaseInput narrowPhaseInput() const;
  Real gravityMagnitude() const;

  WorldSettings world_;
  SolverSettings solver_;
  Particles particles_;
  std::vector<std::string> particleName_;
  std::vector<BodyId> particleBody_;  // kNoBody for a loose particle
  ConstraintGraph constraints_;
  std::vector<Character> characters_;
  std::vector<Push> pushes_;
  std::vector<int> bodyCharacter_;                   // per body: the character whose part it is, or -1
  std::vector<std::array<BodyId, 2>> supportParts_;  // per character: scratch of findSupports
  std::vector<Quat> characterTargets_;               // scratch of animate(), sized to the longest skeleton
  // Scratch of updateIslands, sized (a copy keeps sizes, not capacities) for a drag's nodes and
  // every character's root: the nodes held awake.
  std::vector<NodeId> held_ = std::vector<NodeId>(HeldNodes::kMost);
  BodyLayout bodyLayout_;      // the bodies in lanes, for body damping (updateLayouts)
  bool layoutsStale_ = false;  // bodies or collision filters added since they were laid out
  std::vector<Body> bodies_;
  std::vector<Embedding> corners_;
  GroundContacts ground_;

  std::vector<Obb> frames_;                // per box, fitted in every substep
  std::vector<std::uint8_t> frameAsleep_;  // per box: 1 when its frame was fitted while it sleeps
  int swept_ = 0;                          // pairs stopFastBodies stopped in this step
  BroadPhase broadPhase_;
  NarrowPhase narrowPhase_;
  ContactBins contactBins_;  // on two or more threads: the contact stages in two bins at once
  Parting parting_;
  TetraVolumes tetraVolumes_;  // the tetra bodies' volumes, kept or floored before each pass over the sticks
  std::vector<RigidState> rigid_;     // per box: restitution's rigid-body view
  std::vector<StickSpin> stickSpin_;  // per box: keepSpin's scratch
  std::vector<SpinLever> spinLever_;  // per particle: keepSpin's m (x* - c*) and m, sized with the layouts
  std::vector<std::uint8_t> movedByBoxContact_;  // per particle: moved by a box-box contact in the last step

  RigidBodies rigidBodies_;
  std::vector<RigidContact> rigidGround_;  // per step: rigid bodies' points that may reach the ground
  RigidContactState rigidGroundState_;
  std::vector<ContactPatch> rigidPatches_;        // of narrowPhase_.rigidContacts(), in the passes' order
  std::vector<ContactPatch> rigidGroundPatches_;  // of rigidGround_

  std::optional<Drag> drag_;
  BodyId dragBody_ = kNoBody;  // the body carrying the drag's point, if one body does
  Guard guard_;
  JointProjection jointProjection_;  // SolverSettings::jointProjection
  JointProjectionReport lastProjection_;
  // Mutable for islands(), which counts them when the step did not (sleeping off): a cache.
  mutable Islands islands_;
  Workers workers_;  // SolverSettings::threads
  const Workers* workers() const { return workers_.threads() > 1 ? &workers_ : nullptr; }
  Profile profile_;
  bool stageTiming_ = true;
  // Where the stages time themselves: profile_, or nowhere (setStageTiming).
  Profile* stageProfile() { return stageTiming_ ? &profile_ : nullptr; }
  Real time_ = 0.0;
  long steps_ = 0;
};

}  // namespace phys
