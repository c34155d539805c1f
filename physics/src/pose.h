#pragma once
#include <glm/mat3x3.hpp>

#include "physics/body.h"
#include "physics/particles.h"
#include "physics/types.h"

namespace phys::detail {

/// The rotation nearest to A (the orthogonal factor of its polar decomposition), by Higham's
/// iteration X <- (X + X^-T) / 2. A is the shape-matching matrix sum m (x - c) r^T of a body, so
/// it is R S with S symmetric positive definite while the body is not inverted; if it is
/// (det A <= 0), falls back to Gram-Schmidt on A's columns.
glm::dmat3 nearestRotation(const glm::dmat3& A);

/// A particle body's centre: the mean of its particles (they share its mass evenly).
Vec3 particleCentre(const Particles& p, const Body& body);

/// A particle body's pose read back from its particles: the centre their mean (a body's particles
/// share its mass evenly), the orientation the rotation that best takes their rest places to where
/// they are (shape matching, Müller et al. 2005).
BodyPose particleBodyPose(const Particles& p, const Body& body);

}  // namespace phys::detail
