#pragma once
// The state hash World::stateHash and Motion::hash share, so that a motion saved from a world
// hashes as the world did.
#include <cstdint>
#include <span>

#include "physics/types.h"

namespace phys::detail {

/// FNV-1a, 64 bit, over the bytes of each array in turn; a quaternion counts as (w, x, y, z).
std::uint64_t stateHash(std::span<const Vec3> position, std::span<const Vec3> previous,
                        std::span<const Vec3> rigidPosition, std::span<const Vec3> rigidVelocity,
                        std::span<const Vec3> rigidAngularVelocity, std::span<const Quat> rigidOrientation);

}  // namespace phys::detail
