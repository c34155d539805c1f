#include "engine/physics_debug_draw.h"

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

namespace engine {
namespace {

glm::vec3 rgb(phys::Color c) {
  return {c.r, c.g, c.b};
}

}  // namespace

void PhysicsDebugDraw::line(const phys::Vec3& a, const phys::Vec3& b, phys::Color color) {
  lines_.addLine(glm::vec3(a), glm::vec3(b), rgb(color));
}

void PhysicsDebugDraw::point(const phys::Vec3& p, phys::Real size, phys::Color color) {
  // A small box rather than a cross: the seed's collision markers were green boxes.
  lines_.addBody(glm::vec3(p), glm::mat3(1.0f), glm::vec3(static_cast<float>(size) * 0.5f), rgb(color));
}

void PhysicsDebugDraw::box(const phys::Vec3& center, const phys::Quat& orientation,
                           const phys::Vec3& halfExtents, phys::Color color) {
  lines_.addBody(glm::vec3(center), glm::mat3_cast(glm::quat(orientation)), glm::vec3(halfExtents),
                 rgb(color));
}

}  // namespace engine
