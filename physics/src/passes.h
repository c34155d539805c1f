#pragma once
// The phases of one substep, each a free function over the world's arrays so that
// World::step reads like the algorithm and each phase can be timed and tested alone.
#include <span>

#include "physics/particles.h"
#include "physics/world.h"

namespace phys::detail {

/// Verlet with velocity-only damping: x' = x + (1 - d)(x - x*) + a h^2, with
/// d = 1 - exp(-damping h) so the decay per second does not depend on h (REFERENCES.md).
void integrate(Particles& p, const Vec3& gravity, Real damping, Real h);

/// One Gauss-Seidel pass over the sticks, each moved along its current direction in
/// proportion to the inverse masses (REFERENCES.md: the corrected form of Jakobsen's listing).
void relaxSticks(Particles& p, std::span<const Stick> sticks);

/// Projects every particle below the ground plane back onto it and records in depth[i] the
/// deepest penetration seen this substep (friction needs it: Jakobsen, "Friction").
void collideGround(Particles& p, Real groundHeight, std::span<Real> depth);

/// Cuts the tangential motion of each particle that touched the ground, in proportion to its
/// penetration depth: stops it when it is within mu_s * depth, else shortens it by mu_d * depth.
/// Never reverses it.
void applyGroundFriction(Particles& p, std::span<const Real> depth, Real staticFriction,
                         Real dynamicFriction);

}  // namespace phys::detail
