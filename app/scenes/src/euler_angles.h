#pragma once
// The scene files' Euler angles: turns about the world x axis, then y, then z, in degrees, so
// q = qz qy qx. Both directions live here so the loader and the writer cannot disagree.
#include "physics/types.h"

namespace scenes::detail {

/// The orientation that the angles (degrees) describe.
phys::Quat orientationFromEuler(const phys::Vec3& degrees);

/// Angles (degrees) that orientationFromEuler turns back into q, to round-off, for any unit
/// quaternion: x and z in [-180, 180], y in [-90, 90]. Stays accurate near y = +-90 degrees
/// (gimbal lock), where x and z are no longer separately defined.
phys::Vec3 eulerFromOrientation(const phys::Quat& q);

}  // namespace scenes::detail
