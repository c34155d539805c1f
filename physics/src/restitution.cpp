// Restitution (SolverSettings::restitution): a velocity pass after the position passes, as in
// Müller et al. 2020. Verlet's x - x* is the velocity times h, so a velocity change dv moves x*
// by -dv h and the positions the passes reached stay. A contact's velocity change is an impulse
// on the bodies it touches, each box taken as a rigid body (mass, centre and inertia from its
// particles now): moving only the contact particles' x* would send a landing box's bottom
// corners up while its top kept falling, and its sticks would cancel the bounce in the next
// substep. The impulses change the boxes' rigid states, and reach the particles once, at the end.
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "passes.h"

namespace phys::detail {
namespace {

// The rigid body's velocity at a point. A box's own particles may also be moving apart or
// together, the passes having left it squeezed by the impact; that motion is internal, and the
// sticks turn it back without changing the box's momentum, so the bounce is set on the rigid
// motion alone. (Set on the contact point's own x - x* instead, a box dropped flat kept 4%
// less of its speed: the squeeze of the impact substep, 0.6 mm, came out of the bounce.)
Vec3 velocityAt(const RigidState& body, const Vec3& point) {
  return body.velocity + glm::cross(body.spin, point - body.centre);
}

// How much an impulse of 1 N s along n at `point` changes that point's speed along n:
// 1/M + (r x n) . I^-1 (r x n), r from the centre to the point. unit: 1/kg
Real inverseMassAt(const RigidState& body, const Vec3& point, const Vec3& n) {
  const Vec3 rn = glm::cross(point - body.centre, n);
  return body.inverseMass + glm::dot(rn, body.inverseInertia * rn);
}

// The impulse (N s) at `point` changes the body's velocity by J / M and its spin by I^-1 (r x J).
void applyImpulse(RigidState& body, const Vec3& point, const Vec3& impulse) {
  const Vec3 dv = body.inverseMass * impulse;
  const Vec3 dw = body.inverseInertia * glm::cross(point - body.centre, impulse);
  body.velocity += dv;
  body.spin += dw;
  body.velocityChange += dv;
  body.spinChange += dw;
}

// n . (motion of pB - motion of pA) over this substep: the relative normal velocity times h.
Real relativeNormalMotion(const Particles& p, const BodyContact& c) {
  const Vec3 motionA = embeddedPosition(p.position, c.pointA) - embeddedPosition(p.previous, c.pointA);
  const Vec3 motionB = embeddedPosition(p.position, c.pointB) - embeddedPosition(p.previous, c.pointB);
  return glm::dot(c.normal, motionB - motionA);
}

// A loose particle is its own body: its velocity is x - x*, and an impulse changes it by w J.
void restituteParticle(Particles& p, ParticleId i, const Vec3& n, Real approach, const Restitution& r) {
  if (p.inverseMass[i] == 0.0) return;  // pinned or frozen
  const Real change = restitutionChange(glm::dot(n, p.position[i] - p.previous[i]) / r.h, approach, r);
  p.previous[i] -= (change * r.h) * n;
}

}  // namespace

void measureGroundApproach(const Particles& p, std::span<const GroundContact> contacts, const Vec3& n, Real h,
                           std::span<Real> approach) {
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Embedding& e = contacts[c].point;
    approach[c] = -glm::dot(n, embeddedPosition(p.position, e) - embeddedPosition(p.previous, e)) / h;
  }
}

void measureBodyApproach(const Particles& p, std::span<const BodyContact> contacts, Real h,
                         std::span<Real> approach) {
  for (std::size_t k = 0; k < contacts.size(); ++k) approach[k] = -relativeNormalMotion(p, contacts[k]) / h;
}

void measureRigidStates(const Particles& p, std::span<const Body> boxes, Real h,
                        std::span<RigidState> rigid) {
  MassProperties m;
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    RigidState& s = rigid[k];
    s = {};
    if (!massProperties(p, boxes[k], m)) continue;  // inverse mass 0 or crushed flat: impulses leave it alone
    const RigidMotion motion = rigidMotion(p, boxes[k], m);
    s.inverseMass = 1.0 / m.mass;
    s.centre = m.centre;
    s.inverseInertia = glm::inverse(m.inertia);
    s.velocity = motion.linear / h;
    s.spin = motion.angular / h;
  }
}

void restituteGround(Particles& p, std::span<RigidState> rigid, std::span<const GroundContact> contacts,
                     const Vec3& n, std::span<const Real> approach, std::span<const std::uint8_t> pushed,
                     const Restitution& r) {
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    if (pushed[c] == 0) continue;
    const GroundContact& contact = contacts[c];
    if (contact.body == kNoBody) {
      restituteParticle(p, contact.point.particle[0], n, approach[c], r);
      continue;
    }
    RigidState& body = rigid[static_cast<std::size_t>(contact.body)];
    const Vec3 x = embeddedPosition(p.position, contact.point);
    const Real change = restitutionChange(glm::dot(n, velocityAt(body, x)), approach[c], r);
    const Real k = inverseMassAt(body, x, n);
    if (change != 0.0 && k > 0.0) applyImpulse(body, x, (change / k) * n);
  }
}

void restituteBodyContacts(const Particles& p, std::span<RigidState> rigid,
                           std::span<const BodyContact> contacts, std::span<const Real> approach,
                           std::span<const std::uint8_t> pushed, const Restitution& r) {
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    if (pushed[k] == 0) continue;
    const BodyContact& c = contacts[k];
    RigidState& a = rigid[static_cast<std::size_t>(c.bodyA)];
    RigidState& b = rigid[static_cast<std::size_t>(c.bodyB)];
    const Vec3 xa = embeddedPosition(p.position, c.pointA), xb = embeddedPosition(p.position, c.pointB);
    const Real change =
        restitutionChange(glm::dot(c.normal, velocityAt(b, xb) - velocityAt(a, xa)), approach[k], r);
    const Real w = inverseMassAt(a, xa, c.normal) + inverseMassAt(b, xb, c.normal);
    if (change == 0.0 || w == 0.0) continue;
    const Vec3 impulse = (change / w) * c.normal;  // on B; A takes the opposite
    applyImpulse(a, xa, -impulse);
    applyImpulse(b, xb, impulse);
  }
}

void applyRigidChanges(Particles& p, std::span<const Body> boxes, std::span<const RigidState> rigid, Real h) {
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const RigidState& s = rigid[k];
    if (s.velocityChange == Vec3(0.0) && s.spinChange == Vec3(0.0)) continue;
    const Body& box = boxes[k];
    for (ParticleId i = box.firstParticle; i < box.firstParticle + static_cast<ParticleId>(box.particleCount);
         ++i) {
      // A particle the guard froze since the states were measured is never written again.
      if (p.inverseMass[i] == 0.0) continue;
      p.previous[i] -= (s.velocityChange + glm::cross(s.spinChange, p.position[i] - s.centre)) * h;
    }
  }
}

}  // namespace phys::detail
