#include "engine/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace engine {

FirstPersonCamera FirstPersonCamera::lookingAt(const glm::vec3& eye, const glm::vec3& target) {
  FirstPersonCamera camera;
  camera.position = eye;
  const glm::vec3 d = glm::normalize(target - eye);
  camera.yaw = glm::degrees(std::atan2(d.x, -d.z));
  camera.pitch = std::clamp(glm::degrees(std::asin(d.y)), -kMaxPitch, kMaxPitch);
  return camera;
}

glm::vec3 FirstPersonCamera::forward() const {
  const float y = glm::radians(yaw), p = glm::radians(pitch);
  return {std::sin(y) * std::cos(p), std::sin(p), -std::cos(y) * std::cos(p)};
}

glm::vec3 FirstPersonCamera::right() const {
  const float y = glm::radians(yaw);
  return {std::cos(y), 0.0f, std::sin(y)};
}

glm::mat4 FirstPersonCamera::view() const {
  return glm::lookAt(position, position + forward(), glm::vec3(0.0f, 1.0f, 0.0f));
}

glm::mat4 FirstPersonCamera::projection(float aspect) const {
  return glm::perspective(glm::radians(fovY), aspect, nearPlane, farPlane);
}

void FirstPersonCamera::move(float rightward, float upward, float forwardward) {
  position += right() * rightward + glm::vec3(0.0f, upward, 0.0f) + forward() * forwardward;
}

void FirstPersonCamera::turn(float yawDegrees, float pitchDegrees) {
  yaw = std::fmod(yaw + yawDegrees, 360.0f);
  pitch = std::clamp(pitch + pitchDegrees, -kMaxPitch, kMaxPitch);
}

}  // namespace engine
