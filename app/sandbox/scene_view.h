#pragma once
// Draws a world with the renderer: boxes with the box model, ragdoll parts (boxes held by a
// joint) with the limb model, capsules (Shape::Capsule bodies, jointed or not) with a capsule
// mesh built in code for their size, loose particles as lit spheres (sticks between them as
// lines), and the debug layers the draw options ask for. Models come from assets/models/ through assimp; a
// missing or broken file falls back to a cube built in code, with a warning.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "draw_options.h"
#include "engine/capsule_mesh_cache.h"
#include "engine/gpu_mesh.h"
#include "engine/renderer.h"
#include "physics/world.h"

namespace sandbox {

/// How one run is coloured: its own colours, or (in the method overlay) one translucent tint.
struct Tint {
  glm::vec3 color{1.0f};
  float alpha = 0.45f;
};

class SceneView {
 public:
  /// Needs a current GL context.
  SceneView(engine::Renderer& renderer, const std::filesystem::path& modelsDir);

  /// Meshes of the world, then its debug lines (flushed by the renderer's endFrame()).
  void draw(const phys::World& world, const glm::mat4& viewProjection, const DrawOptions& options,
            const std::optional<Tint>& tint = std::nullopt);

  /// Why a model could not be loaded and is drawn as the built-in cube; "" when both loaded.
  const std::string& modelWarnings() const { return modelWarnings_; }
  /// The capsule meshes, one per size drawn lately (tests look at how many there are).
  const engine::CapsuleMeshCache& capsuleMeshes() const { return capsuleMeshes_; }

 private:
  void findJointedBoxes(const phys::World& world);
  /// After the bodies are drawn: their poses are in poses_.
  void drawShadows(const phys::World& world, const glm::mat4& viewProjection);

  engine::Renderer& renderer_;
  std::string modelWarnings_;  // filled while the meshes below load: declared before them
  std::unique_ptr<engine::GpuMesh> boxMesh_;
  std::unique_ptr<engine::GpuMesh> limbMesh_;
  // Trimmed after each draw(): sizes no longer in any world drawn are freed beyond its capacity.
  engine::CapsuleMeshCache capsuleMeshes_;
  // Per-frame scratch, kept to avoid allocating each frame.
  std::vector<phys::BodyId> bodyOf_;   // per particle: its body, or kNoBody
  std::vector<std::uint8_t> jointed_;  // per box: held by a joint
  std::vector<std::uint32_t> groups_;  // per body, with BodyColoring::Body: jointGroups()
  std::vector<phys::BodyPose> poses_;  // per body, this frame's (a particle body's is a fit)
};

}  // namespace sandbox
