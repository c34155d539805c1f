// World::debugDraw: what the physics knows, through the interface the renderer implements.
#include <algorithm>
#include <vector>

#include "physics/character.h"
#include "physics/world.h"

namespace phys {

void World::debugDraw(DebugDraw& draw, const DebugDrawFlags& flags) const {
  const auto& x = particles_.position;
  if (flags.constraints) {
    for (const Stick& s : constraints_.sticks())
      draw.line(x[s.a], x[s.b], s.isRange() ? colors::kRange : colors::kStick);
    auto drawLink = [&](const Vec3& a, const Vec3& b, bool pin) {
      if (pin)
        draw.point(a, 0.03, colors::kPin);
      else
        draw.line(a, b, colors::kRange);
    };
    for (const Link& link : constraints_.links())
      drawLink(positionOf(link.a), positionOf(link.b), link.isPin());
    for (const RigidLink& link : constraints_.rigidLinks())
      drawLink(positionOf(link.a), positionOf(link.b), link.isPin());
    for (const RigidJoint& j : constraints_.rigidJoints())
      drawLink(rigidBodies_.position[j.a] + rigidBodies_.orientation[j.a] * j.pivotA, Vec3(0.0), true);
  }
  if (flags.particles) {
    for (std::size_t i = 0; i < particles_.size(); ++i) {
      const bool frozen = particles_.inverseMass[i] == 0.0 &&
                          std::any_of(freezes().begin(), freezes().end(), [&](const FreezeReport& f) {
                            if (f.body != kNoBody) return f.body == particleBody_[i];
                            return f.particle == i;
                          });
      draw.point(x[i], 0.05, frozen ? colors::kFrozen : colors::kParticle);
    }
  }
  if (flags.contacts) {
    const std::span<const GroundContact> groundPoints = ground_.points();
    for (std::size_t c = 0; c < groundPoints.size(); ++c) {
      if (ground_.state().touched[c] != 0)
        draw.point(positionOf(groundPoints[c].point), 0.08, colors::kContact);
    }
    for (std::size_t k = 0; k < narrowPhase_.contacts().size(); ++k) {
      if (narrowPhase_.state().touched[k] == 0) continue;  // speculative: not touching in the last substep
      const BodyContact& c = narrowPhase_.contacts()[k];
      const Vec3 p = positionOf(c.pointA);
      const Color color = colors::kFeature[c.kind % 6];
      draw.point(p, 0.05, color);
      draw.line(p, p + 0.25 * c.normal, color);
    }
    // Contacts with a rigid body, where the rigid body's point is (B's on the ground).
    auto drawRigid = [&](std::span<const RigidContact> list, const RigidContactState& state) {
      for (std::size_t k = 0; k < list.size() && k < state.touched.size(); ++k) {
        if (state.touched[k] == 0) continue;
        const RigidContact& c = list[k];
        const bool onA = c.sideA != ContactSide::Ground;
        const Vec3 p =
            onA ? detail::sidePosition(particles_, rigidBodies_, c.sideA, c.rigidA, c.localA, c.pointA, false)
                : detail::sidePosition(particles_, rigidBodies_, c.sideB, c.rigidB, c.localB, c.pointB,
                                       false);
        if (!onA) {
          draw.point(p, 0.08, colors::kContact);
          continue;
        }
        const Color color = colors::kFeature[c.kind % 6];
        draw.point(p, 0.05, color);
        draw.line(p, p + 0.25 * c.normal, color);
      }
    };
    drawRigid(narrowPhase_.rigidContacts(), narrowPhase_.rigidState());
    drawRigid(rigidGround_, rigidGroundState_);
  }
  if (flags.movedVertices) {
    for (std::size_t i = 0; i < particles_.size(); ++i) {
      if (movedByBoxContact_[i] != 0) draw.point(x[i], 0.1, colors::kContact);
    }
  }
  if (flags.targets) {
    // Drawn, not stepped: allocating here costs the step nothing.
    std::vector<Quat> turned;
    std::vector<Vec3> centres;
    for (const Character& c : characters_) {
      turned.resize(c.bones.size());
      centres.resize(c.bones.size());
      targetOrientations(c, c.pose, turned);
      targetCentres(*this, c, turned, poseOf(c.bones[0].body).center, centres);
      for (std::size_t b = 0; b < c.bones.size(); ++b) {
        const CharacterBone& bone = c.bones[b];
        draw.box(centres[b], turned[b], bodies_[bone.body].halfExtents, colors::kTarget);
        if (bone.parent < 0) continue;
        const Vec3 pivot = centres[b] + turned[b] * bonePivots(*this, c, b).second;
        draw.line(centres[static_cast<std::size_t>(bone.parent)], pivot, colors::kTarget);
        draw.line(pivot, centres[b], colors::kTarget);
      }
    }
  }
  if (flags.bounds) {
    for (BodyId id{}; id < bodies_.size(); ++id) {
      const Body& box = bodies_[id];
      Vec3 lo(std::numeric_limits<Real>::max()), hi(-std::numeric_limits<Real>::max());
      for (int k = 0; k < 8; ++k) {
        const Vec3 p = cornerOf(id, k);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
      if (box.shape == Shape::Capsule) {
        // A capsule's own bounds: its core's ends, out by the radius on every axis.
        const Vec3 centre = (lo + hi) * 0.5;
        const Vec3 corner0 = cornerOf(id, 0), corner2 = cornerOf(id, 2);
        const Vec3 axis = glm::normalize(corner2 - corner0) * box.capsuleHalfSegment();
        lo = glm::min(centre - axis, centre + axis) - Vec3(box.capsuleRadius());
        hi = glm::max(centre - axis, centre + axis) + Vec3(box.capsuleRadius());
      }
      draw.box((lo + hi) * 0.5, Quat(1.0, 0.0, 0.0, 0.0), (hi - lo) * 0.5, colors::kBounds);
    }
  }
}

}  // namespace phys
