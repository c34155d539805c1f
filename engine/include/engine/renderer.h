#pragma once
// Draws the lit scene: a ground plane with a grid, meshes under one directional light, and the
// debug lines on top. The colours and the light live in RenderStyle, one place, so tests can
// predict what a pixel should be.
#include <filesystem>
#include <memory>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "engine/debug_lines.h"
#include "engine/gpu_mesh.h"
#include "engine/shader.h"

namespace engine {

/// One directional light plus ambient: colour = albedo * (ambient + diffuse * max(n.l, 0)).
struct Light {
  glm::vec3 towardsLight{0.37139068f, 0.74278135f, 0.55708601f};  ///< unit vector (0.4, 0.8, 0.6)
  float ambient = 0.35f;
  float diffuse = 0.65f;
};

struct RenderStyle {
  glm::vec3 clearColor{0.62f, 0.74f, 0.86f};  ///< the sky, linear RGB in [0, 1]
  glm::vec3 groundColor{0.44f, 0.47f, 0.42f};
  glm::vec3 gridColor{0.30f, 0.32f, 0.29f};
  float gridSpacing = 1.0f;     ///< unit: m; lines at every multiple
  float groundExtent = 250.0f;  ///< unit: m; half the side of the ground quad
  Light light;
};

/// The colour the lighting model gives a surface of this albedo and unit normal.
glm::vec3 shade(const glm::vec3& albedo, const glm::vec3& normal, const Light& light);

class Renderer {
 public:
  /// Needs a current GL context; loads its programs from shaderDir (throws engine::Error).
  explicit Renderer(const std::filesystem::path& shaderDir, const RenderStyle& style = {});

  /// Sets the viewport, clears colour and depth, enables depth testing.
  void beginFrame(const glm::ivec2& framebufferSize);
  /// The same, drawing into part of the framebuffer only: x, y (from the bottom-left corner),
  /// width and height in framebuffer pixels. The whole framebuffer is cleared.
  void beginFrame(const glm::ivec2& framebufferSize, const glm::ivec4& viewport);
  /// The ground plane { x : normal . x = height } (normal of unit length), centred under the
  /// camera so it never ends. For the normal (0, 1, 0) the grid lines lie on whole x and z.
  void drawGround(const glm::mat4& viewProjection, const glm::vec3& eye, const glm::vec3& normal,
                  float height);
  /// Draws a lit mesh. alpha < 1 blends it over what is drawn (without writing depth, so the
  /// runs of the method overlay all show through each other).
  void drawMesh(const GpuMesh& mesh, const glm::mat4& viewProjection, const glm::mat4& model,
                const glm::vec3& albedo, float alpha = 1.0f);
  /// Meshes drawn from now on show only their triangles' edges (the seed's wireframe mode).
  void setWireframe(bool on);
  /// Lines collected this frame; drawn by endFrame().
  DebugLines& lines() { return lines_; }
  void endFrame(const glm::mat4& viewProjection);

  RenderStyle& style() { return style_; }

 private:
  RenderStyle style_;
  ShaderProgram meshProgram_;
  ShaderProgram groundProgram_;
  GpuMesh groundQuad_;
  DebugLines lines_;
};

}  // namespace engine
