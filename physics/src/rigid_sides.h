#pragma once
// One side of a rigid constraint (a contact or a link) as the passes see it: a point fixed in a rigid
// body, a point carried by a particle body's particles (an embedding), or the ground. Each answers an
// impulse along a direction d with its point's inverse mass along it: a rigid body's
// 1/m + (r x d)^T I^-1 (r x d), a particle body's embedded point sum c_i^2 w_i (REFERENCES.md), the
// ground's 0.
#include "passes.h"
#include "physics/rigid_contacts.h"
#include "rigid_motion.h"

namespace phys::detail {

// One side of a contact as the passes see it for one correction: its point now and its lever arm.
struct SideView {
  ContactSide side;
  RigidId rigid;
  const Embedding* point;
  Vec3 at{0.0};        // Rigid: the point from the body's centre, world axes
  bool fixed = false;  // held still in this pass (shock propagation): takes no correction
};

/// The view of a side for one correction: `local` and `point` are read by the Rigid and the
/// Particles sides; the lever arm of a rigid one is taken from its orientation now.
inline SideView viewOf(const RigidPassInput& in, ContactSide side, RigidId rigid, const Vec3& local,
                       const Embedding& point, bool fixed = false) {
  SideView v{side, rigid, &point, Vec3(0.0), fixed};
  if (side == ContactSide::Rigid) v.at = in.rigid.orientation[rigid] * local;
  return v;
}

// The side's point now.
inline Vec3 positionOf(const RigidPassInput& in, const SideView& s) {
  switch (s.side) {
    case ContactSide::Rigid:
      return in.rigid.position[s.rigid] + s.at;
    case ContactSide::Particles:
      return embeddedPosition(in.particles.position, *s.point);
    case ContactSide::Ground:
      break;
  }
  return Vec3(0.0);
}

// The side's inverse mass along the unit direction d (1/kg).
inline Real inverseMassAlong(const RigidPassInput& in, const SideView& s, const Vec3& d) {
  if (s.fixed) return 0.0;
  switch (s.side) {
    case ContactSide::Rigid:
      return pointInverseMass(in.rigid, s.rigid, s.at, d);
    case ContactSide::Particles:
      return embeddedWeight(in.particles.inverseMass, *s.point);
    case ContactSide::Ground:
      break;
  }
  return 0.0;
}

// Moves the side's point by its inverse mass times the positional impulse p (kg m).
inline void push(RigidPassInput& in, const SideView& s, const Vec3& p) {
  if (s.fixed) return;
  if (s.side == ContactSide::Rigid) applyPositionalImpulse(in.rigid, s.rigid, s.at, p);
  if (s.side == ContactSide::Particles)
    shiftEmbedded(in.particles.position, in.particles.inverseMass, *s.point, p);
}

// The side's point's velocity (m/s): a particle body's over the substep so far.
inline Vec3 velocityOf(const RigidPassInput& in, const SideView& s) {
  switch (s.side) {
    case ContactSide::Rigid:
      return pointVelocity(in.rigid, s.rigid, s.at);
    case ContactSide::Particles:
      return (embeddedPosition(in.particles.position, *s.point) -
              embeddedPosition(in.particles.previous, *s.point)) /
             in.h;
    case ContactSide::Ground:
      break;
  }
  return Vec3(0.0);
}

// Changes the side's velocity by its inverse mass times the impulse p (N s); a particle body's
// through its particles' x*, which is where Verlet keeps velocity.
inline void kick(RigidPassInput& in, const SideView& s, const Vec3& p) {
  if (s.fixed) return;
  if (s.side == ContactSide::Rigid) applyVelocityImpulse(in.rigid, s.rigid, s.at, p);
  if (s.side == ContactSide::Particles)
    shiftEmbedded(in.particles.previous, in.particles.inverseMass, *s.point, -p * in.h);
}

}  // namespace phys::detail
