#pragma once
// A rigid box made of its 8 corner particles braced by sticks (the seed's model).
#include <array>

#include "physics/types.h"

namespace phys {

/// What a box is when it is created.
struct BoxDesc {
  Vec3 center{0.0};                  ///< unit: m
  Vec3 size{1.0};                    ///< unit: m; full edge lengths, each > 0
  Quat orientation{1.0, 0.0, 0.0, 0.0};
  Vec3 velocity{0.0};                ///< unit: m/s; of every corner at creation
  Real mass = 1.0;                   ///< unit: kg; spread evenly over the corners
};

/// Where a box is: read back from its particles.
struct BoxPose {
  Vec3 center{0.0};  ///< unit: m
  Quat orientation{1.0, 0.0, 0.0, 0.0};
};

/// A box in the world. Corner k sits at (+-hx, +-hy, +-hz) in the body frame, with bit 0 of k
/// choosing the sign of x, bit 1 of y and bit 2 of z (set bit = positive).
struct Box {
  ParticleId firstCorner = 0;  ///< the 8 corners are consecutive particles from here
  Vec3 halfExtents{0.5};       ///< unit: m
};

/// Number of sticks that brace one box (see box.cpp for which ones and why).
inline constexpr int kBoxStickCount = 22;

/// Body-frame position of corner k of a box with the given half extents.
Vec3 boxCornerLocal(const Vec3& halfExtents, int k);

}  // namespace phys
