#pragma once
// The phases of one substep, each a free function over the world's arrays, so World::step
// reads like the algorithm and each phase can be timed and tested alone. None allocates.
#include <algorithm>
#include <span>

#include <glm/mat3x3.hpp>

#include "physics/body.h"
#include "physics/body_layout.h"
#include "physics/collision.h"
#include "physics/constraints.h"
#include "physics/drives.h"
#include "physics/link_layout.h"
#include "physics/particles.h"
#include "physics/rigid_bodies.h"
#include "physics/settings.h"
#include "physics/stick_layout.h"
#include "physics/workers.h"

namespace phys::detail {

/// The point at u (in units of the half extents, in the body frame; inside the box or not) carried
/// rigidly by the box: barycentric weights over its inscribed tetrahedron (its 4 particles, or
/// corners 0, 3, 5, 6 of a corners box), exact for any point while the box keeps its shape.
Embedding rigidEmbedding(const Body& box, const Vec3& u);
/// The same point carried by a corners box's other inscribed tetrahedron (corners 1, 2, 4, 7), from
/// its rigidEmbedding over corners 0, 3, 5, 6: the two together carry a point symmetrically, as the
/// box's 8 corners do (docs/physics.md, "A capsule on a slope").
Embedding otherTetrahedron(const Embedding& a);

/// A world point in the body's frame `frame` (of this substep), in units of its half extents.
Vec3 frameCoordinates(const Body& body, const Obb& frame, const Vec3& point);
/// A world point carried rigidly by the body as it lies in its frame (rigidEmbedding).
Embedding rigidPoint(const Body& body, const Obb& frame, const Vec3& point);
/// A point of the body's surface (a contact's), embedded where the body's particles hold it: a
/// box's on the face it lies on, by that face's 4 corners (corners model) or the tetrahedron; a
/// tetra capsule's rigidly; a corners capsule's on the nearest face of its box. `moved`, if not
/// null, gets how far the embedding carries the point off where it was (a capsule's: its face).
Embedding surfacePoint(const Body& body, const Obb& frame, const Vec3& point, Vec3* moved = nullptr);
/// The frame to embed a particle body's contact points in (rigidPoint, surfacePoint): its fitted
/// frame, or, for a body turned inside out by more than half its thickness, that frame with its z
/// axis reversed, so that a point goes on the face whose particles lie there. `position` is every
/// particle's position, as the frame was fitted from. A rigid body's frame is its pose, unchanged.
Obb embeddingFrame(const Body& body, const Obb& frame, std::span<const Vec3> position);

/// A particle body's mean move in this substep, from x* to x (unit: m): what the sweep and the
/// start overlaps take for the body's move when they put its frame back where the substep began.
inline Vec3 meanParticleMove(const Particles& p, const Body& body) {
  Vec3 sum(0.0);
  for (int j = 0; j < body.particleCount; ++j) {
    const ParticleId i = body.firstParticle + j;
    sum += p.position[i] - p.previous[i];
  }
  return sum / static_cast<Real>(body.particleCount > 0 ? body.particleCount : 1);
}

/// Any body's move in this substep (unit: m): a rigid body's centre's, from its previous pose to
/// now; a particle body's mean particle move.
inline Vec3 bodyMove(const Particles& p, const RigidBodies& rigid, const Body& body) {
  if (body.model == BodyModel::Rigid) return rigid.position[body.rigid] - rigid.previousPosition[body.rigid];
  return meanParticleMove(p, body);
}

/// The thinnest half extent of two bodies' frames (unit: m): neither can be past the other's middle
/// without moving at least this far, so a pair that moved less in a substep cannot have crossed.
inline Real thinnestHalfExtent(const Obb& a, const Obb& b) {
  const Vec3 &ha = a.halfExtents, &hb = b.halfExtents;
  return std::min({ha.x, ha.y, ha.z, hb.x, hb.y, hb.z});
}

/// Verlet with velocity-only damping: x' = x + (1 - d)(x - x*) + a(x) h^2, x* = x, with
/// d = 1 - exp(-damping h) so the decay per second does not depend on h (REFERENCES.md).
/// `checked` (per particle) is given x too: what the guard found good at the end of the last
/// substep, and puts back if it freezes the body in this one (later phases edit x*).
/// `workers`, if given, integrate ranges of particles at once (SolverSettings::threads).
void integrate(Particles& p, const WorldSettings& world, Real h, std::span<Vec3> checked,
               const Workers* workers = nullptr);
/// The same for the particles [begin, end) alone: what integrate() does to each of them, bit for bit.
void integrateRange(Particles& p, const WorldSettings& world, Real h, std::span<Vec3> checked,
                    std::size_t begin, std::size_t end);

/// Pulls an embedded point towards `target` by a spring of the given stiffness (N/m) and
/// damping (N s/m), stepped implicitly over the substep h, so it is stable at any stiffness:
/// the point at most reaches the target. `box` is the box that carries the point, which then
/// answers as a rigid body, or null (a loose particle): the point's carriers answer alone.
/// Pinned and frozen particles do not move.
void applyDrag(Particles& p, const Body* box, const Embedding& point, const Vec3& target, Real stiffness,
               Real damping, Real h);

/// The length a stick or range stick must be moved to, or a negative number when the current
/// length is within its bounds (nothing to do).
inline Real stickTarget(const Stick& s, Real length) {
  if (length < s.minLength) return s.minLength;
  if (length > s.maxLength) return s.maxLength;
  return -1.0;
}

/// keepSpin's part in a pass over the sticks: `laneLevers`, kLaneSpinValues (relax_lanes.h) per
/// lane group of the layout, the lanes' levers, computed on the substep's `firstPass` and read on
/// the others.
struct SpinPass {
  std::span<Real> laneLevers;
  bool firstPass = false;
};

// Each pass runs over `layout` (StickLayout): the same result as one loop over `sticks` in
// creation order, faster.
/// Jakobsen: each stick in turn, along its current direction, in proportion to inverse mass.
/// `workers`, if given, relax the lane groups in pieces at once (they share no particle); the blocks
/// and runs follow on the calling thread, as they would in one loop. `spin`, if given (keepSpin),
/// keeps each lane's and block's body's moment through its sticks (keepStickMoment); the runs'
/// bodies are the caller's (restoreStickSpin). Jacobi and XPBD take it alike.
void relaxGaussSeidel(Particles& p, std::span<const Stick> sticks, const StickLayout& layout,
                      const Workers* workers = nullptr, const SpinPass* spin = nullptr);
/// The ground plane n . x = height, for the chains' passes at once.
struct GroundPlane {
  Vec3 normal{0.0, 1.0, 0.0};
  Real height = 0.0;
};
/// `passes` passes of Gauss-Seidel over each chain of `layout` (StickLayout::chains) at once, on
/// the substep's first pass, with the bits of one pass after the other; the chains done so are
/// marked ahead, and the passes skip them. A chain with a particle at or below `ground` (if given)
/// at any point of them, which the ground's passes between would have moved, is put back as it
/// was and left to the passes. `saved` is scratch: two per stick of the longest chain.
void relaxChainsAhead(Particles& p, std::span<const Stick> sticks, StickLayout& layout, int passes,
                      const GroundPlane* ground, std::span<Vec3> saved);
/// The same for XPBD, whose multipliers `lambda` were zeroed for the substep.
void relaxChainsAheadXpbd(Particles& p, std::span<const Stick> sticks, StickLayout& layout, int passes,
                          const GroundPlane* ground, std::span<Vec3> saved, std::span<Real> lambda, Real h,
                          Real compliance);
/// Every stick's correction from the same positions, each pair scaled by 1 / the larger number
/// of sticks (`degree`) at its two ends, then summed per particle. delta is scratch, one per
/// particle. `workers` as for Gauss-Seidel: a lane group's bodies sum and apply their own.
void relaxJacobi(Particles& p, std::span<const Stick> sticks, const StickLayout& layout,
                 std::span<const Real> degree, std::span<Vec3> delta, const Workers* workers = nullptr,
                 const SpinPass* spin = nullptr);
/// XPBD (Macklin, Müller, Chentanez 2016): Gauss-Seidel with a multiplier per stick so that
/// compliance gives the same stiffness for any iteration count and step. lambda is per stick,
/// zeroed at the start of each substep.
/// `compliance` (m/N, SolverSettings::compliance) is added to every stick's own.
void relaxXpbd(Particles& p, std::span<const Stick> sticks, const StickLayout& layout, std::span<Real> lambda,
               Real h, Real compliance, const Workers* workers = nullptr, const SpinPass* spin = nullptr);
/// SHAKE (Ryckaert, Ciccotti, Berendsen 1977): each stick moved along its direction at the
/// start of the substep (x* after integration), by the root of a scalar quadratic. `workers` as
/// for Gauss-Seidel.
void relaxShake(Particles& p, std::span<const Stick> sticks, const StickLayout& layout,
                const Workers* workers = nullptr);

/// SolverSettings::keepSpin (stick_spin.cpp). A pass keeps a body's moment sum m (x*_i - c*) x x_i
/// (h times its angular momentum about its centre) through its sticks by `stickMoment` before them
/// and `keepStickMoment` after, which turns the body's particles rigidly about its centre back to
/// that moment: what the sticks did to its angular momentum is undone and its momentum kept. The
/// lanes, blocks and tetra volumes do it on their copies of a body (relax.cpp, tetra_volumes.cpp);
/// `startStickSpin` (once a substep, before its passes), `measureStickSpin` and `restoreStickSpin`
/// do it around a whole pass for the bodies `which` lists (StickLayout::runBodies, those relaxed in
/// the world's arrays), with `spin` indexed by body and `lever` by particle. A body with a pinned,
/// frozen or sleeping particle, a rigid one, or one crushed flat, is left alone.
/// `spinLevers`: a body's levers m (x*_i - c*) and masses from its `count` particles from `first`;
/// false, and zeros, for a body with a particle that cannot move.
bool spinLevers(const Particles& p, ParticleId first, int count, SpinLever* lever);
/// sum lever_i x (x_i - x_0) over a body's `count` particles.
Vec3 stickMoment(const Vec3* x, const SpinLever* lever, int count);
/// Turns the body's `count` particles about their centre back to the moment `before`.
void keepStickMoment(Vec3* x, const SpinLever* lever, int count, const Vec3& before);
/// keepSpin around a pass over one body held in `x` (a block's copy, or a tetra volume's particles in
/// place), its `count` (up to kMaxBlockParticles) particles from `first`: the levers and the moment
/// when made, the turn back to that moment in `keep`; nothing when `on` is false.
class KeptMoment {
 public:
  KeptMoment(const Particles& p, ParticleId first, int count, const Vec3* x, bool on)
      : on_(on), count_(count) {
    if (!on_) return;
    spinLevers(p, first, count, lever_);
    moment_ = stickMoment(x, lever_, count);
  }
  void keep(Vec3* x) const {
    if (on_) keepStickMoment(x, lever_, count_, moment_);
  }

 private:
  SpinLever lever_[kMaxBlockParticles];
  Vec3 moment_{0.0};
  bool on_;
  int count_;
};
void startStickSpin(const Particles& p, std::span<const Body> bodies, std::span<const std::uint32_t> which,
                    std::span<SpinLever> lever, std::span<StickSpin> spin);
void measureStickSpin(const Particles& p, std::span<const Body> bodies, std::span<const std::uint32_t> which,
                      std::span<const SpinLever> lever, std::span<StickSpin> spin);
void restoreStickSpin(Particles& p, std::span<const Body> bodies, std::span<const std::uint32_t> which,
                      std::span<const SpinLever> lever, std::span<const StickSpin> spin);

/// Projects every contact point below the ground plane n . x = height back onto it, writing the
/// distance moved into push (0 for a point not moved; friction needs it: Jakobsen, "Friction").
/// `allowance`, if not empty, is per point the depth it may keep in this substep
/// (toAllowance): the point is moved up to that depth, not onto the plane.
/// `still`, if not empty, is per point 1 for a point to leave as it is (GroundContacts::markStill),
/// here and in the other ground passes. `far`, if not empty, is per point 1 for a point known to be
/// far above the plane (GroundContacts::far): not pushed.
void collideGround(Particles& p, std::span<const GroundContact> contacts, const Vec3& n, Real height,
                   std::span<Real> normalPush, std::span<const Real> allowance = {},
                   std::span<const std::uint8_t> still = {}, std::span<const std::uint8_t> far = {});
/// Depth (m) of each contact point below the plane at x*, where the substep started; negative above.
void measureGroundStartDepth(const Particles& p, std::span<const GroundContact> contacts, const Vec3& n,
                             Real height, std::span<Real> depth);

/// Depenetration limit (SolverSettings::maxDepenetrationSpeed): turns each contact's overlap at
/// the start of the substep (ground depth, or box-box overlap beyond the slop, at x*) into the
/// overlap it may keep at the end, max(0, overlap - step), step = the speed limit times h. A
/// contact that started apart gets 0, so its approach is stopped in full; one that started deeper
/// than step sheds `step` of it, and so parts at most at that speed.
inline void toAllowance(std::span<Real> startOverlap, Real step) {
  for (Real& v : startOverlap) v = v > step ? v - step : 0.0;
}
/// Cuts the tangential motion (x - x*) of each contact point the last ground pass pushed: stops
/// it when it is within mu_s * push, else shortens it by mu_d * push, by moving the point's
/// particles back along it; never reverses it. Run after each ground pass, so the sticks
/// relax what friction bends, and the cuts of all passes together stay within mu * the push.
/// `freeTetraBoxes` (GroundContacts::anyFreeTetraBox): whether some box's corners are marked to be cut
/// as one rigid body; when not, a point with no push is passed over without reading its contact.
void applyGroundFriction(Particles& p, std::span<const GroundContact> contacts, const Vec3& n,
                         std::span<const Real> normalPush, std::span<const std::uint8_t> still,
                         bool freeTetraBoxes);

/// Pushes each pair of contact points apart along its normal until n . (pB - pA) >= -slop, moving
/// both bodies' particles by their embedding weights and inverse masses; writes the distance
/// into push (0 when not pushed). `allowance`, if not empty, is per contact the overlap beyond
/// the slop it may keep in this substep (toAllowance).
void solveBodyContacts(Particles& p, std::span<const BodyContact> contacts, Real slop, std::span<Real> push,
                       std::span<const Real> allowance = {});
/// Marks in `moved` the particles of every contact `touched` says a pass pushed (for the debug
/// draw): once a substep, not in every pass.
void markPushedParticles(std::span<const BodyContact> contacts, std::span<const std::uint8_t> touched,
                         std::span<std::uint8_t> moved);
/// Coulomb friction between the bodies of each contact the last pass pushed, as for the ground:
/// the tangential part of the relative motion this substep (of an anchored point, since its
/// anchor: BodyContact::anchor) is stopped within mu_s * push, else shortened by mu_d * push.
/// `extras` are the contacts' own (NarrowPhase::contactExtras), at the same index.
void applyBodyFriction(Particles& p, std::span<BodyContact> contacts,
                       std::span<const BodyContactExtra> extras, std::span<const Real> push);

/// What restitution needs to know in a substep (SolverSettings::restitution).
struct Restitution {
  Real coefficient = 0.0;  // e, 0 to 1
  Real minSpeed = 0.0;     // m/s: slower impacts do not bounce
  Real h = 0.0;            // s: the substep
};

/// The change of a contact's normal separation speed (m/s, positive apart) that restitution asks
/// for, from its separation speed now and its approach speed at the start of the substep. A fast
/// impact leaves at e times its approach speed. A slow one only stops closing: then the box under
/// a box that bounces, pushed down by the bounce, hands it back from the ground instead of
/// carrying half of it into the ground.
inline Real restitutionChange(Real separation, Real approach, const Restitution& r) {
  if (approach > r.minSpeed) return r.coefficient * approach - separation;
  return separation < 0.0 ? -separation : 0.0;
}

/// Normal speed (m/s) at which each ground contact point approaches the ground, from x - x*.
void measureGroundApproach(const Particles& p, std::span<const GroundContact> contacts, const Vec3& n, Real h,
                           std::span<Real> approach);
/// Normal speed (m/s) at which the two points of each box-box contact approach each other.
void measureBodyApproach(const Particles& p, std::span<const BodyContact> contacts, Real h,
                         std::span<Real> approach);
/// Fills each box's rigid state (RigidState) from its particles, with no changes yet.
void measureRigidStates(const Particles& p, std::span<const Body> boxes, Real h, std::span<RigidState> rigid);
/// One Gauss-Seidel pass of restitution over the ground contact points `pushed` in this substep:
/// an impulse along n on each point's body gives the point the separation speed
/// restitutionChange asks for. A box takes it in its rigid state, a loose particle in its x*.
void restituteGround(Particles& p, std::span<RigidState> rigid, std::span<const GroundContact> contacts,
                     const Vec3& n, std::span<const Real> approach, std::span<const std::uint8_t> pushed,
                     const Restitution& r);
/// restituteGround for box-box contacts: equal and opposite impulses on the two boxes.
void restituteBodyContacts(const Particles& p, std::span<RigidState> rigid,
                           std::span<const BodyContact> contacts, std::span<const Real> approach,
                           std::span<const std::uint8_t> pushed, const Restitution& r);
/// Writes each box's velocity and spin changes into its particles' x*: x*_i -= (dv + dw x r_i) h.
void applyRigidChanges(Particles& p, std::span<const Body> boxes, std::span<const RigidState> rigid, Real h);

/// A box's mass (kg), centre of mass (m) and inertia tensor about it (kg m^2), from its particles now.
struct MassProperties {
  Real mass = 0.0;
  Vec3 centre{0.0};
  glm::dmat3 inertia{0.0};
};
/// False when the box cannot move as a rigid body: a particle pinned or frozen, or the box crushed
/// flat (four or more particles not in one plane make the inertia positive definite).
bool massProperties(const Particles& p, const Body& box, MassProperties& out);
/// Changes a particle box's velocity by dv (m/s) at `centre` and dw (rad/s) about it, as its
/// particles' x - x* over the substep h (the Verlet velocity): each free particle moves by
/// (dv + dw x r_i) h; a pinned or frozen one stays.
void addBoxVelocity(Particles& p, const Body& box, const Vec3& centre, const Vec3& dv, const Vec3& dw,
                    Real h);
/// A box's rigid motion over the substep, from its particles' x - x*: the centre's (m), and the
/// rotation (rad, about the centre) that keeps the particles' angular momentum. Velocities times h.
struct RigidMotion {
  Vec3 linear{0.0};
  Vec3 angular{0.0};
};
RigidMotion rigidMotion(const Particles& p, const Body& box, const MassProperties& m);
/// Each friction takes the share min(rate dt, 1) of its two bodies' relative spin over the last
/// substep away (JointFriction), by turning each body's particles' motion about its centre.
/// `spins` holds one per body a friction joins (indexed by body id), any state on entry.
void dampJointFriction(Particles& p, std::span<const Body> bodies, std::span<const JointFriction> frictions,
                       Real dt, std::span<BodySpin> spins);

/// One pass over the particle joints' drives (drives.h), drives[k], lambda[k] and share[k] joint k's,
/// each body turned about its centre as a rigid body of its particles' inertia, the pass closing at
/// most share[k] of the drive's gap (1: as XPBD has it); the first pass of a substep zeroes the
/// multipliers. h: the substep (s).
void driveParticleJoints(Particles& p, std::span<const Body> bodies, std::span<const ParticleJoint> joints,
                         std::span<const JointDrive> drives, std::span<Real> lambda,
                         std::span<const Real> share, bool firstPass, Real h);
/// One pass over the drives of particle bodies among `driven` (the rigid ones are driveRigidBodies'),
/// lambda holding two multipliers a drive, as driveRigidBodies'.
void driveParticleBodies(Particles& p, std::span<const Body> bodies, std::span<const DrivenBody> driven,
                         std::span<Real> lambda, bool firstPass, Real h);

/// How far the link is outside its bounds with the particles at x (positions or previous
/// positions): > 0 beyond max (a pin's whole gap), < 0 short of min, 0 within. unit: m
Real linkViolation(const std::vector<Vec3>& x, const Link& link);
/// The depenetration limit for links created outside their bounds (World::addLink): `slack` is
/// per link the violation it may keep, signed as linkViolation's, 0 for a link that has been
/// within its bounds. Each substep it becomes the violation at x* (where the substep starts),
/// if smaller, less `step` (maxDepenetrationSpeed times h), and never changes sign. Returns how
/// many links still have slack.
int shrinkLinkSlack(const Particles& p, std::span<const Link> links, Real step, std::span<Real> slack);
/// One pass over the joints, Gauss-Seidel in every method: each link's two points moved apart
/// or together along their separation by the weighted projection of REFERENCES.md, a pin's all
/// the way onto each other. `slack`, if not empty, is per link what shrinkLinkSlack allows it
/// to keep: its bounds are widened by that much on the side it is outside. With no slack the pass
/// runs over `layout` (LinkLayout), in lanes, to the same result.
void solveLinks(Particles& p, std::span<const Link> links, const LinkLayout& layout,
                std::span<const Real> slack = {}, const Workers* workers = nullptr);

/// Pulls each box's particle velocities (x - x*) towards the box's rigid motion by `fraction`
/// (0 nothing, 1 all the way), keeping its linear and angular momentum; edits x* only.
/// `layout` (BodyLayout) groups the bodies; every body of `boxes` is in it once.
void dampBodyMotion(Particles& p, std::span<const Body> boxes, const BodyLayout& layout, Real fraction,
                    const Workers* workers = nullptr);

// The next three are inline: the contact passes call them for every point of every pass, and
// out of line (even under link-time optimisation) the calls took 29% of a pyramid's step.

/// Current position of an embedded point.
inline Vec3 embeddedPosition(const std::vector<Vec3>& x, const Embedding& e) {
  Vec3 p(0.0);
  for (int i = 0; i < e.count; ++i) p += e.weight[i] * x[e.particle[i]];
  return p;
}

/// sum c_i^2 w_i over the point's particles: what the weighted projection divides by.
inline Real embeddedWeight(const std::vector<Real>& inverseMass, const Embedding& e) {
  Real sum = 0.0;
  for (int i = 0; i < e.count; ++i) sum += e.weight[i] * e.weight[i] * inverseMass[e.particle[i]];
  return sum;
}

/// Moves each particle of the point by c_i w_i step (a pinned one not at all): the weighted
/// projection's update, without its division.
inline void shiftEmbedded(std::vector<Vec3>& x, const std::vector<Real>& inverseMass, const Embedding& e,
                          const Vec3& step) {
  for (int i = 0; i < e.count; ++i) {
    const Real w = inverseMass[e.particle[i]];
    if (w != 0.0) x[e.particle[i]] += (e.weight[i] * w) * step;  // a pinned one never moves
  }
}

/// Moves an embedded point by D through its particles in `x` (positions or previous
/// positions), each in proportion to weight * inverse mass (REFERENCES.md).
void moveEmbedded(std::vector<Vec3>& x, const std::vector<Real>& inverseMass, const Embedding& e,
                  const Vec3& D);

/// A point as friction reads and moves it: its embedding, or, for a corners capsule's surface point
/// (GroundContact::surface, BodyContactExtra::surfaceA, B), the mean of that point carried by each
/// of its box's two inscribed tetrahedra (otherTetrahedron). The one tetrahedron alone is chiral,
/// and its cuts along a capsule's core twisted the box about the vertical, so that one held on a
/// slope turned off the fall line and rolled; the two together are symmetric, as a box's corners
/// are (docs/physics.md, "Capsules", "A capsule on a slope"). Their particles are disjoint, so the
/// mean point's K is (K_1 + K_2) / 4, and an impulse on it is split evenly between the two: Coulomb's
/// bound then holds when one side's particles weigh more (a pinned or frozen corner).
struct FrictionPoint {
  const Embedding* point;
  Embedding mirror;  // count 0 unless carried by both tetrahedra

  static FrictionPoint of(const Embedding& e, bool bothTetrahedra) {
    return {&e, bothTetrahedra ? otherTetrahedron(e) : Embedding{}};
  }
  Vec3 at(const std::vector<Vec3>& x) const {
    const Vec3 first = embeddedPosition(x, *point);
    return mirror.count == 0 ? first : 0.5 * (first + embeddedPosition(x, mirror));
  }
  Real weight(const std::vector<Real>& inverseMass) const {
    const Real first = embeddedWeight(inverseMass, *point);
    return mirror.count == 0 ? first : 0.25 * (first + embeddedWeight(inverseMass, mirror));
  }
  /// The point moved by an impulse `lambda` (position units per unit of weight, as shiftEmbedded).
  void shift(std::vector<Vec3>& x, const std::vector<Real>& inverseMass, const Vec3& lambda) const {
    if (mirror.count == 0) {
      shiftEmbedded(x, inverseMass, *point, lambda);
      return;
    }
    shiftEmbedded(x, inverseMass, *point, 0.5 * lambda);
    shiftEmbedded(x, inverseMass, mirror, 0.5 * lambda);
  }
};

}  // namespace phys::detail
