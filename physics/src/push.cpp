// Pushes (physics/push.h): a force held on a body for a time, applied each substep with gravity.
#include "physics/push.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include "passes.h"
#include "physics/world.h"
#include "require.h"
#include "rigid_motion.h"

namespace phys {

using detail::require;

void World::push(BodyId body, const Vec3& force, Real duration, const std::optional<Vec3>& worldPoint) {
  detail::requireIndex(body, bodies_.size(), "push", "body");
  const std::string who = "push";
  require(finite(force), who + ": the force must be finite");
  require(std::isfinite(duration) && duration > 0.0, who + ": the duration must be finite and > 0");
  require(!worldPoint || finite(*worldPoint), who + ": the point must be finite");
  const BodyPose pose = poseOf(body);
  const Vec3 at = worldPoint ? *worldPoint - pose.center : Vec3(0.0);
  pushes_.push_back(Push{body, glm::conjugate(pose.orientation) * at, force, duration});
  // Held awake while the push lasts, as a drag's body is (updateIslands): asleep, its mass masked,
  // it would use up the push's time unmoved. Room for its node beside the characters' and a drag's.
  held_.resize(std::max(held_.size(), characters_.size() + HeldNodes::kMost + pushes_.size()));
  islands_.wake(islands_.nodeOf(body));
}

// Each substep, after the integration: the impulse F h at the point, as a velocity change and the
// position change it makes over the substep (as the mouse spring's). A particle box answers as a
// rigid body through its particles; a box that cannot (pinned, crushed) is pushed at its centre.
void World::applyPushes(Real h) {
  for (Push& p : pushes_) {
    const Real dt = std::min(h, p.remaining);
    p.remaining -= h;
    const Body& body = bodies_[p.body];
    const Vec3 impulse = p.force * dt;
    if (body.model == BodyModel::Rigid) {
      const Vec3 at = rigidBodies_.orientation[body.rigid] * p.local;
      detail::applyVelocityImpulse(rigidBodies_, body.rigid, at, impulse);
      detail::applyPositionalImpulse(rigidBodies_, body.rigid, at, impulse * h);
      continue;
    }
    detail::MassProperties m;
    Vec3 dv(0.0), dw(0.0), centre(0.0);
    if (detail::massProperties(particles_, body, m)) {
      const Vec3 at = poseOf(p.body).orientation * p.local;
      dv = impulse / m.mass;
      dw = glm::inverse(m.inertia) * glm::cross(at, impulse);
      centre = m.centre;
    } else {
      Real mass = 0.0;
      for (int j = 0; j < body.particleCount; ++j) {
        const Real w = particles_.inverseMass[body.firstParticle + j];
        mass += w > 0.0 ? 1.0 / w : 0.0;
      }
      if (mass == 0.0) continue;  // all pinned or frozen: nothing to move
      dv = impulse / mass;
    }
    detail::addBoxVelocity(particles_, body, centre, dv, dw, h);
  }
  std::erase_if(pushes_, [](const Push& p) { return p.remaining <= 0.0; });
}

}  // namespace phys
