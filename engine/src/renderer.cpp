#include "engine/renderer.h"

#include <algorithm>
#include <cmath>

#include <glad/gl.h>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace engine {
namespace {

MeshData unitQuadXZ() {
  MeshData quad;
  quad.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  quad.normals.assign(4, glm::vec3(0, 1, 0));
  quad.indices = {0, 2, 1, 0, 3, 2};
  quad.boundsMin = {-1, 0, -1};
  quad.boundsMax = {1, 0, 1};
  return quad;
}

// The shortest rotation taking (0, 1, 0) to the unit vector n.
glm::mat3 rotationFromUp(const glm::vec3& n) {
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  const float c = glm::dot(up, n);
  if (c > 0.999999f) return glm::mat3(1.0f);
  if (c < -0.999999f) return glm::mat3_cast(glm::angleAxis(glm::pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f)));
  return glm::mat3_cast(glm::angleAxis(std::acos(c), glm::normalize(glm::cross(up, n))));
}

}  // namespace

glm::vec3 shade(const glm::vec3& albedo, const glm::vec3& normal, const Light& light) {
  return albedo * (light.ambient + light.diffuse * std::max(glm::dot(normal, light.towardsLight), 0.0f));
}

Renderer::Renderer(const std::filesystem::path& shaderDir, const RenderStyle& style)
    : style_(style),
      meshProgram_(shaderDir / "mesh.vert", shaderDir / "mesh.frag"),
      groundProgram_(shaderDir / "ground.vert", shaderDir / "ground.frag"),
      groundQuad_(unitQuadXZ()),
      lines_(shaderDir) {}

void Renderer::beginFrame(const glm::ivec2& framebufferSize) {
  beginFrame(framebufferSize, glm::ivec4(0, 0, framebufferSize.x, framebufferSize.y));
}

void Renderer::beginFrame(const glm::ivec2& framebufferSize, const glm::ivec4& viewport) {
  glViewport(0, 0, framebufferSize.x, framebufferSize.y);
  const glm::vec3& c = style_.clearColor;
  glClearColor(c.r, c.g, c.b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glViewport(viewport.x, viewport.y, viewport.z, viewport.w);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

void Renderer::drawGround(const glm::mat4& viewProjection, const glm::vec3& eye, const glm::vec3& normal,
                          float height) {
  // The plane's frame: the rotation taking world up to its normal carries x and z into it.
  const glm::mat3 rotation = rotationFromUp(normal);
  const glm::vec3 origin = normal * height;
  const glm::vec3 overEye = eye - (glm::dot(normal, eye) - height) * normal;
  // Snap the quad's centre to the grid so the lines stay put as the camera moves.
  const float snap = style_.gridSpacing;
  const glm::vec2 planeCentre{std::floor(glm::dot(rotation[0], overEye - origin) / snap) * snap,
                              std::floor(glm::dot(rotation[2], overEye - origin) / snap) * snap};
  const glm::vec3 centre = origin + rotation[0] * planeCentre.x + rotation[2] * planeCentre.y;
  const glm::mat4 model = glm::scale(glm::translate(glm::mat4(1.0f), centre) * glm::mat4(rotation),
                                     glm::vec3(style_.groundExtent, 1.0f, style_.groundExtent));
  groundProgram_.use();
  groundProgram_.set("uViewProjection", viewProjection);
  groundProgram_.set("uModel", model);
  groundProgram_.set("uNormal", normal);
  groundProgram_.set("uPlaneOffset", glm::vec3(planeCentre.x, 0.0f, planeCentre.y));
  groundProgram_.set("uExtent", style_.groundExtent);
  groundProgram_.set("uColor", style_.groundColor);
  groundProgram_.set("uGridColor", style_.gridColor);
  groundProgram_.set("uGridSpacing", style_.gridSpacing);
  groundProgram_.set("uTowardsLight", style_.light.towardsLight);
  groundProgram_.set("uAmbient", style_.light.ambient);
  groundProgram_.set("uDiffuse", style_.light.diffuse);
  groundQuad_.draw();
}

void Renderer::drawMesh(const GpuMesh& mesh, const glm::mat4& viewProjection, const glm::mat4& model,
                        const glm::vec3& albedo, float alpha) {
  const bool translucent = alpha < 1.0f;
  if (translucent) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
  }
  meshProgram_.use();
  meshProgram_.set("uViewProjection", viewProjection);
  meshProgram_.set("uModel", model);
  meshProgram_.set("uColor", albedo);
  meshProgram_.set("uAlpha", alpha);
  meshProgram_.set("uTowardsLight", style_.light.towardsLight);
  meshProgram_.set("uAmbient", style_.light.ambient);
  meshProgram_.set("uDiffuse", style_.light.diffuse);
  mesh.draw();
  if (translucent) {
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
  }
}

void Renderer::setWireframe(bool on) {
  glPolygonMode(GL_FRONT_AND_BACK, on ? GL_LINE : GL_FILL);
  // Back faces would hide nothing in wireframe, and culling them loses half the edges.
  if (on)
    glDisable(GL_CULL_FACE);
  else
    glEnable(GL_CULL_FACE);
}

void Renderer::endFrame(const glm::mat4& viewProjection) {
  lines_.flush(viewProjection);
}

}  // namespace engine
