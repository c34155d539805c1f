#pragma once
// What the view draws: the seed's three draw modes and the debug layers on top.
#include <optional>
#include <string_view>

namespace sandbox {

enum class DrawMode {
  Filled,       ///< lit meshes
  Wireframe,    ///< the meshes' edges
  Constraints,  ///< sticks and joints only: sticks red, ranges orange, pins yellow
};

/// What a body's colour says (Box2D's and Jolt's samples colour by island and by sleep alike).
enum class BodyColoring {
  Kind,    ///< boxes orange, particles blue, each body its own brightness
  Body,    ///< each body, or each set of bodies held by joints (a ragdoll), a colour of its own
  Island,  ///< each island a hue of its own
  Sleep,   ///< awake orange, asleep grey-blue
};

std::string_view toString(DrawMode mode);  ///< "filled", "wireframe", "constraints"
std::optional<DrawMode> parseDrawMode(std::string_view name);
std::string_view toString(BodyColoring coloring);                      ///< "kind", "body", "island", "sleep"
std::optional<BodyColoring> parseBodyColoring(std::string_view name);  ///< the names toString gives
/// The mode Tab goes to next.
DrawMode nextDrawMode(DrawMode mode);

struct DrawOptions {
  DrawMode mode = DrawMode::Filled;
  bool markers = false;   ///< green boxes on the vertices box-box contacts moved (the seed's C)
  bool sticks = false;    ///< constraints drawn over the meshes in the other modes
  bool contacts = false;  ///< contact points and normals
  bool bounds = false;    ///< each box's axis-aligned bounds
  bool particles = true;  ///< loose particles as lit spheres
  bool trails = false;    ///< the paths of loose particles and of the followed body (trails.h)
  bool targets = false;   ///< each character's target pose as a ghost (phys::DebugDrawFlags::targets)
  bool exact = true;      ///< the scene's exact answers (<expect kind="position">) as green crosses
  bool shadows = false;   ///< a soft shadow of each body on the ground (the sandbox starts with them)
  BodyColoring coloring = BodyColoring::Kind;  ///< the sandbox starts with Body (panels.h)
  /// Radius of a loose particle's sphere (unit: m), sized to the scene by particleRadiusFor.
  float particleRadius = 0.04f;
};

/// A loose particle's radius for a scene seen from `eye` looking at `target`: about 10 pixels
/// across at that distance in a 720-pixel-high window, never under half kParticleDrawSize.
float particleRadiusFor(float cameraDistance);

}  // namespace sandbox
