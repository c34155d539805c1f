#pragma once
// What the physics can draw, declared here and implemented by whoever owns a renderer (the
// engine). The physics calls it; it never includes anything graphical.
#include "physics/types.h"

namespace phys {

struct Color {
  float r = 1.0f, g = 1.0f, b = 1.0f;  ///< linear RGB in [0, 1]
};

namespace colors {
inline constexpr Color kStick{0.90f, 0.10f, 0.10f};     ///< red: the seed's constraint colour
inline constexpr Color kRange{0.95f, 0.60f, 0.10f};     ///< orange: range sticks
inline constexpr Color kPin{1.00f, 0.90f, 0.20f};       ///< yellow: joint pins
inline constexpr Color kParticle{0.20f, 0.35f, 0.85f};  ///< blue
inline constexpr Color kContact{0.10f, 0.85f, 0.20f};   ///< green: the seed's collision markers
inline constexpr Color kBounds{0.60f, 0.60f, 0.60f};    ///< grey
inline constexpr Color kFrozen{0.85f, 0.10f, 0.85f};    ///< magenta
inline constexpr Color kTarget{0.35f, 0.95f, 1.00f};    ///< pale cyan: a character's target pose
/// Box-box contact points and normals, by ContactKind: face-face, face-edge, face-vertex,
/// edge-edge, edge-vertex, vertex-vertex.
inline constexpr Color kFeature[6] = {{0.10f, 0.85f, 0.85f}, {0.20f, 0.55f, 1.00f}, {0.60f, 0.40f, 1.00f},
                                      {1.00f, 0.85f, 0.10f}, {1.00f, 0.55f, 0.10f}, {1.00f, 1.00f, 1.00f}};
}  // namespace colors

class DebugDraw {
 public:
  virtual ~DebugDraw() = default;
  virtual void line(const Vec3& a, const Vec3& b, Color color) = 0;
  /// A marker of the given size (unit: m) centred on p.
  virtual void point(const Vec3& p, Real size, Color color) = 0;
  /// The edges of a box.
  virtual void box(const Vec3& center, const Quat& orientation, const Vec3& halfExtents, Color color) = 0;
};

/// What World::debugDraw draws.
struct DebugDrawFlags {
  bool constraints = true;  ///< sticks red, range sticks and joint limits orange, joint pins yellow
  bool particles = false;   ///< every particle; frozen ones magenta
  bool contacts = true;     ///< ground contact points that were pushed, box-box contact points and normals
  bool movedVertices =
      false;            ///< particles a box-box contact moved in the last step (the seed's green markers)
  bool bounds = false;  ///< each box's axis-aligned bounding box
  /// Each character's target pose as a ghost: its parts' outlines turned to their targets, placed
  /// from the root part where it is down the joints, and the skeleton through the joints' pivots.
  bool targets = false;
};

}  // namespace phys
