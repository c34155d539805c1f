#pragma once
// The physics library's debug-draw interface, drawn with the engine's batched lines.
#include "engine/debug_lines.h"
#include "physics/debug_draw.h"

namespace engine {

class PhysicsDebugDraw : public phys::DebugDraw {
 public:
  /// Draws into `lines`, which must outlive this object.
  explicit PhysicsDebugDraw(DebugLines& lines) : lines_(lines) {}

  void line(const phys::Vec3& a, const phys::Vec3& b, phys::Color color) override;
  void point(const phys::Vec3& p, phys::Real size, phys::Color color) override;
  void box(const phys::Vec3& center, const phys::Quat& orientation, const phys::Vec3& halfExtents,
           phys::Color color) override;

 private:
  DebugLines& lines_;
};

}  // namespace engine
