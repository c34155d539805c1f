#pragma once
// The phases of one substep, each a free function over the world's arrays, so World::step
// reads like the algorithm and each phase can be timed and tested alone. None allocates.
#include <span>

#include "physics/box.h"
#include "physics/constraints.h"
#include "physics/particles.h"
#include "physics/settings.h"

namespace phys::detail {

/// Verlet with velocity-only damping: x' = x + (1 - d)(x - x*) + a(x) h^2, x* = x, with
/// d = 1 - exp(-damping h) so the decay per second does not depend on h (REFERENCES.md).
void integrate(Particles& p, const WorldSettings& world, Real h);

/// The length a stick or range stick must be moved to, or a negative number when the current
/// length is within its bounds (nothing to do).
inline Real stickTarget(const Stick& s, Real length) {
  if (length < s.minLength) return s.minLength;
  if (length > s.maxLength) return s.maxLength;
  return -1.0;
}

/// Jakobsen: each stick in turn, along its current direction, in proportion to inverse mass.
void relaxGaussSeidel(Particles& p, std::span<const Stick> sticks);
/// Every stick's correction from the same positions, each pair scaled by 1 / the larger number
/// of sticks (`degree`) at its two ends, then summed per particle. delta is scratch, one per
/// particle.
void relaxJacobi(Particles& p, std::span<const Stick> sticks, std::span<const Real> degree, std::span<Vec3> delta);
/// XPBD (Macklin, Müller, Chentanez 2016): Gauss-Seidel with a multiplier per stick so that
/// compliance gives the same stiffness for any iteration count and step. lambda is per stick,
/// zeroed at the start of each substep.
void relaxXpbd(Particles& p, std::span<const Stick> sticks, std::span<Real> lambda, Real h);
/// SHAKE (Ryckaert, Ciccotti, Berendsen 1977): each stick moved along its direction at the
/// start of the substep (x* after integration), by the root of a scalar quadratic.
void relaxShake(Particles& p, std::span<const Stick> sticks);

/// Projects every contact point below the ground plane n . x = height back onto it, writing the
/// distance moved into push (0 for a point not moved; friction needs it: Jakobsen, "Friction").
void collideGround(Particles& p, std::span<const GroundContact> contacts, const Vec3& n, Real height,
                   std::span<Real> normalPush);
/// Cuts the tangential motion (x - x*) of each contact point the last ground pass pushed: stops
/// it when it is within mu_s * push, else shortens it by mu_d * push, by moving the point's
/// particles back along it; never reverses it. Run after each ground pass, so the sticks
/// relax what friction bends, and the cuts of all passes together stay within mu * the push.
void applyGroundFriction(Particles& p, std::span<const GroundContact> contacts, const Vec3& n,
                         std::span<const Real> normalPush);

/// Pushes each pair of contact points apart along its normal until n . (pB - pA) >= -slop, moving
/// both bodies' particles by their embedding weights and inverse masses; writes the distance
/// into push (0 when not pushed). `moved` marks the particles a correction touched.
void solveBodyContacts(Particles& p, std::span<const BodyContact> contacts, Real slop, std::span<Real> push,
                       std::span<std::uint8_t> moved);
/// Coulomb friction between the bodies of each contact the last pass pushed, as for the ground:
/// the tangential part of the relative motion this substep is stopped within mu_s * push, else
/// shortened by mu_d * push.
void applyBodyFriction(Particles& p, std::span<const BodyContact> contacts, std::span<const Real> push);

/// One pass over the joints, Gauss-Seidel in every method: each link's two points moved apart
/// or together along their separation by the weighted projection of REFERENCES.md, a pin's all
/// the way onto each other.
void solveLinks(Particles& p, std::span<const Link> links);

/// Pulls each box's particle velocities (x - x*) towards the box's rigid motion by `fraction`
/// (0 nothing, 1 all the way), keeping its linear and angular momentum; edits x* only.
void dampBodyMotion(Particles& p, std::span<const Box> boxes, Real fraction);

/// Current position of an embedded point.
Vec3 embeddedPosition(const std::vector<Vec3>& x, const Embedding& e);
/// sum c_i^2 w_i over the point's particles: what the weighted projection divides by.
Real embeddedWeight(const std::vector<Real>& inverseMass, const Embedding& e);
/// Moves each particle of the point by c_i w_i step (a pinned one not at all): the weighted
/// projection's update, without its division.
void shiftEmbedded(std::vector<Vec3>& x, const std::vector<Real>& inverseMass, const Embedding& e, const Vec3& step);
/// Moves an embedded point by D through its particles in `x` (positions or previous
/// positions), each in proportion to weight * inverse mass (REFERENCES.md).
void moveEmbedded(std::vector<Vec3>& x, const std::vector<Real>& inverseMass, const Embedding& e, const Vec3& D);

}  // namespace phys::detail
