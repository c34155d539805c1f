#include "scene_view.h"

#include <algorithm>
#include <cmath>
#include <iostream>

#include <glad/gl.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "body_colors.h"
#include "engine/error.h"
#include "engine/physics_debug_draw.h"

namespace sandbox {
namespace {

// A missing or broken model must not stop the sandbox: fall back to a cube built in code, and say
// why in `warnings`.
std::unique_ptr<engine::GpuMesh> loadModel(const std::filesystem::path& file, std::string& warnings) {
  try {
    return std::make_unique<engine::GpuMesh>(engine::loadMeshData(file));
  } catch (const engine::Error& e) {
    const std::string warning = std::string(e.what()) + "; drawing with the built-in cube instead";
    std::cerr << "sandbox: warning: " << warning << "\n";
    warnings += (warnings.empty() ? "" : "; ") + warning;
    return std::make_unique<engine::GpuMesh>(engine::unitCubeMesh());
  }
}

// Neighbouring boxes in one colour would merge into one block; each gets its own brightness,
// from 85% to 115% by the golden ratio, so the hue (what the tests look for) stays the same.
float boxShade(phys::BodyId id) {
  const float spread = std::fmod(static_cast<float>(id) * 0.618034f, 1.0f);
  return 0.85f + 0.3f * spread;
}

// Turned and placed by the pose fitted to the body's particles.
glm::mat4 poseMatrix(const phys::BodyPose& pose) {
  return glm::translate(glm::mat4(1.0f), glm::vec3(pose.center)) *
         glm::mat4_cast(glm::quat(pose.orientation));
}

// The box models are unit cubes about the origin: scaled by the box's size, then posed.
glm::mat4 boxModelMatrix(const phys::BodyPose& pose, const phys::Vec3& size) {
  return glm::scale(poseMatrix(pose), glm::vec3(size));
}

// In the method overlay every line of a run is drawn in the run's colour, so two runs' chains
// or constraints can be told apart where they part ways.
class TintedDraw : public phys::DebugDraw {
 public:
  TintedDraw(phys::DebugDraw& inner, const glm::vec3& tint) : inner_(inner), color_{tint.r, tint.g, tint.b} {}
  void line(const phys::Vec3& a, const phys::Vec3& b, phys::Color) override { inner_.line(a, b, color_); }
  void point(const phys::Vec3& p, phys::Real size, phys::Color) override { inner_.point(p, size, color_); }
  void box(const phys::Vec3& c, const phys::Quat& q, const phys::Vec3& h, phys::Color) override {
    inner_.box(c, q, h, color_);
  }

 private:
  phys::DebugDraw& inner_;
  phys::Color color_;
};

}  // namespace

SceneView::SceneView(engine::Renderer& renderer, const std::filesystem::path& modelsDir)
    : renderer_(renderer),
      boxMesh_(loadModel(modelsDir / "box.obj", modelWarnings_)),
      limbMesh_(loadModel(modelsDir / "limb.obj", modelWarnings_)) {}

// A soft dark disc on the ground where the key light throws each body's shadow, fainter the higher
// the body: what makes contact with the ground read in a picture. A flattened sphere, blended
// over the ground and hidden by the bodies in front of it.
void SceneView::drawShadows(const phys::World& world, const glm::mat4& viewProjection) {
  const phys::WorldSettings& w = world.worldSettings();
  const glm::vec3 n = glm::normalize(glm::vec3(w.groundNormal));
  const glm::vec3 towardsLight = renderer_.style().light.towardsLight;
  const float facing = glm::dot(n, towardsLight);
  if (facing < 0.1f) return;  // the light grazes the ground or is under it
  const engine::GpuMesh& disc = capsuleMeshes_.get(1.0f, 0.0f, engine::CapsuleMeshCache::kCoarse);
  const glm::mat4 turn = glm::mat4_cast(glm::quat(glm::vec3(0.0f, 1.0f, 0.0f), n));
  for (phys::BodyId id{}; id < world.bodies().size(); ++id) {
    const glm::vec3 centre(poses_[id].center);  // fitted by draw() for the body's mesh
    const float height = glm::dot(n, centre) - static_cast<float>(w.groundHeight);
    if (height < 0.0f) continue;
    const float radius = 0.75f * static_cast<float>(glm::length(world.bodies()[id].halfExtents));
    const float fade = std::clamp(1.0f - height / (4.0f * radius + 2.0f), 0.15f, 1.0f);
    const glm::vec3 at = centre - towardsLight * (height / facing) + n * 0.003f;  // above the ground
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), at) * turn *
                            glm::scale(glm::mat4(1.0f), glm::vec3(radius, 0.002f, radius));
    renderer_.drawMesh(disc, viewProjection, model, glm::vec3(0.0f), 0.4f * fade);
  }
}

void SceneView::findJointedBoxes(const phys::World& world) {
  const auto owner = world.particleBodies();
  bodyOf_.assign(owner.begin(), owner.end());
  jointed_.assign(world.bodies().size(), 0);
  for (const phys::Link& link : world.links()) {
    for (const phys::Embedding* e : {&link.a, &link.b}) {
      if (const phys::BodyId body = bodyOf_[e->particle[0]]; body != phys::kNoBody) jointed_[body] = 1;
    }
  }
  for (const phys::RigidJoint& j : world.rigidJoints())
    jointed_[world.rigidBodies().body[j.a]] = jointed_[world.rigidBodies().body[j.b]] = 1;
  for (const phys::RigidLink& link : world.rigidLinks()) {
    for (const phys::BodyPoint* end : {&link.a, &link.b}) {
      if (const phys::BodyId body = world.carrier(*end); body != phys::kNoBody) jointed_[body] = 1;
    }
  }
}

void SceneView::draw(const phys::World& world, const glm::mat4& viewProjection, const DrawOptions& options,
                     const std::optional<Tint>& tint) {
  findJointedBoxes(world);
  if (options.coloring == BodyColoring::Body) groups_ = jointGroups(world);
  const float alpha = tint ? tint->alpha : 1.0f;
  if (options.mode != DrawMode::Constraints) {
    const bool wireframe = options.mode == DrawMode::Wireframe;
    renderer_.setWireframe(wireframe);
    // Edges of the fine capsule mesh would crowd into a solid patch on a ragdoll's limbs.
    const auto capsuleDetail =
        wireframe ? engine::CapsuleMeshCache::kCoarse : engine::CapsuleMeshCache::kFine;
    const auto boxes = world.bodies();
    poses_.resize(boxes.size());
    for (phys::BodyId id{}; id < boxes.size(); ++id) {
      const phys::Body& box = boxes[id];
      const glm::vec3 color =
          tint ? tint->color : boxShade(id) * bodyColor(world, id, options.coloring, groups_);
      const phys::BodyPose& pose = poses_[id] = world.bodyPose(id);
      if (box.shape == phys::Shape::Capsule) {
        // Built at its own size: scaling one capsule to another would squash its caps.
        // Within what the cache takes, so that no size the physics allows can stop the drawing.
        using Cache = engine::CapsuleMeshCache;
        const float radius =
            std::clamp(static_cast<float>(box.capsuleRadius()), Cache::kResolution, Cache::kLargest);
        const float halfSegment =
            std::clamp(static_cast<float>(box.capsuleHalfSegment()), 0.0f, Cache::kLargest);
        const engine::GpuMesh& mesh = capsuleMeshes_.get(radius, halfSegment, capsuleDetail);
        renderer_.drawMesh(mesh, viewProjection, poseMatrix(pose), color, alpha);
      } else {
        const engine::GpuMesh& mesh = jointed_[id] != 0 ? *limbMesh_ : *boxMesh_;
        renderer_.drawMesh(mesh, viewProjection, boxModelMatrix(pose, box.halfExtents * 2.0), color, alpha);
      }
    }
    if (options.shadows && !wireframe && !tint && world.worldSettings().ground)
      drawShadows(world, viewProjection);
    if (options.particles) {
      // A sphere: a capsule with no core.
      using Cache = engine::CapsuleMeshCache;
      const float radius = std::clamp(options.particleRadius, Cache::kResolution, Cache::kLargest);
      const engine::GpuMesh* sphere = nullptr;  // made only for a world with loose particles
      for (std::size_t i = 0; i < world.particles().size(); ++i) {
        if (bodyOf_[i] != phys::kNoBody) continue;
        if (sphere == nullptr) sphere = &capsuleMeshes_.get(radius, 0.0f, capsuleDetail);
        const glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(world.particles().position[i]));
        renderer_.drawMesh(*sphere, viewProjection, model, tint ? tint->color : kParticleColor, alpha);
      }
    }
    renderer_.setWireframe(false);
    // Sticks between loose particles (a chain, a pendulum) have no mesh: lines show them.
    if (!options.sticks) {
      const glm::vec3 color = tint ? tint->color : kLooseStickColor;
      for (const phys::Stick& stick : world.sticks()) {
        if (bodyOf_[stick.a] != phys::kNoBody || bodyOf_[stick.b] != phys::kNoBody) continue;
        renderer_.lines().addLine(glm::vec3(world.particles().position[stick.a]),
                                  glm::vec3(world.particles().position[stick.b]), color);
      }
    }
  } else if (options.particles) {
    // Constraints mode draws lines only: a loose particle is a point, or a particle with no
    // stick (an orbit's body, a projectile) would not be drawn at all.
    for (std::size_t i = 0; i < world.particles().size(); ++i) {
      if (bodyOf_[i] != phys::kNoBody) continue;
      renderer_.lines().addPoint(glm::vec3(world.particles().position[i]), 2.0f * options.particleRadius,
                                 tint ? tint->color : kParticleColor);
    }
  }
  capsuleMeshes_.trim();
  engine::PhysicsDebugDraw debugDraw(renderer_.lines());
  phys::DebugDrawFlags flags;
  flags.constraints = options.mode == DrawMode::Constraints || options.sticks;
  flags.particles = false;  // the sticks show where the particles are; boxes on each would hide them
  flags.contacts = options.contacts;
  flags.movedVertices = options.markers;
  flags.bounds = options.bounds;
  flags.targets = options.targets;
  if (tint) {
    TintedDraw tinted(debugDraw, tint->color);
    world.debugDraw(tinted, flags);
  } else {
    world.debugDraw(debugDraw, flags);
  }
}

}  // namespace sandbox
