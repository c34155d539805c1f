#pragma once
// Penetration and joint gap measured from the bodies' poses alone (centre and orientation of
// each body of a Description), by one geometry code for every engine: our own narrow phase
// (physics/collision.h) on the peers' poses, so no engine is judged by its own contact report,
// which each engine defines differently (Bullet's includes its 4 cm margin, MuJoCo's its
// softness). The lab calls these outside the timed loop.
#include <vector>

#include "peer_scene.h"
#include "physics/collision.h"

namespace lab::peers {

/// Deepest overlap (m) of any two bodies that collide (Description::collides): the deepest
/// contact point our narrow phase finds between them (phys::collideBoxes, collideCapsules,
/// collideCapsuleBox), 0 when none touch. A sort-and-sweep on x over the bodies' bounding
/// boxes finds the pairs, so only pairs whose boxes overlap are tested, not all n^2 / 2 (1.1
/// million in the 136-ragdoll pile). Infinity when a body's pose is not finite (a peer that
/// blew up).
double bodyOverlap(const Description& scene, const std::vector<phys::Vec3>& centres,
                   const std::vector<phys::Quat>& orientations);

/// The penetration figure of a peer: the larger of bodyOverlap and groundPenetration, as ours
/// (Metrics::maxPenetration) is the deepest of its ground and box-box contacts.
double posePenetration(const Description& scene, const std::vector<phys::Vec3>& centres,
                       const std::vector<phys::Quat>& orientations);

/// The joint gap (m), as Metrics::maxJointError measures ours: the largest distance between the
/// two world points of any pin, and the most any range link (a joint stop, Distance::link) is
/// outside its [min, max]. Sticks are not joints (their error is stick-error). 0 with no
/// joints; infinity when a pose is not finite.
double jointGap(const Description& scene, const std::vector<phys::Vec3>& centres,
                const std::vector<phys::Quat>& orientations);

}  // namespace lab::peers
